#include "linf/io/gauge_table.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <climits>
#include <cstdio>
#include <cstring>
#include <stdexcept>

#include "linf/io/gds.hpp"
#include "linf/util/pages.hpp"
#include "util/parallel.hpp"

namespace linf {

namespace {
// Rows a file batch holds before they go out.
constexpr std::size_t kBatch = std::size_t(1) << 14;
// Gauges written before their pages are given back.
constexpr std::size_t kReleaseEvery = std::size_t(1) << 16;

std::runtime_error write_error(const std::string& file, const char* why) {
  const int e = errno;
  return std::runtime_error("cannot write the gauge columns to " + file + why + std::strerror(e));
}
}  // namespace

GaugeTableWriter::GaugeTableWriter(std::size_t count, char* reals, char* ints)
    : count_(count), rd_(reals), id_(ints) {}

GaugeTableWriter::GaugeTableWriter(std::size_t count, const std::string& file) : count_(count), file_(file) {
  fd_ = ::open(file_.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0600);
  if (fd_ < 0) throw write_error(file_, ": ");
  buf_r_.resize(kGaugeRealBytes * kBatch);
  buf_i_.resize(kGaugeIntBytes * kBatch);
  rd_ = buf_r_.data(), id_ = buf_i_.data();
}

GaugeTableWriter::~GaugeTableWriter() {
  if (fd_ >= 0) ::close(fd_);
}

namespace {
// One gauge's row at `rd` (its reals) and `id` (its ints).
void put_row(const Sites& sites, const Gauges& gauges, const Gauge& x, std::size_t rank, char* rd, char* id) {
  const MeasurementLine m = measurement_line(sites, x);
  for (double v : {m.p.x, m.p.y, m.q.x, m.q.y, x.at.x, x.at.y, x.cd, x.score, gauges.norm_score(x), x.tiebreak}) {
    std::memcpy(rd, &v, sizeof v);
    rd += sizeof v;
  }
  const Site& a = sites.sites[x.a];
  const Site& b = sites.sites[x.b];
  for (Coord v : {Coord(rank), Coord(x.teeth), Coord(x.a), Coord(x.b), a.a.x, a.a.y, a.b.x, a.b.y, b.a.x, b.a.y,
                  b.b.x, b.b.y, Coord(x.type)}) {
    if (v < INT32_MIN || v > INT32_MAX) throw std::range_error("coordinates beyond 32 bits (layouts have 32)");
    const std::int32_t w = std::int32_t(v);
    std::memcpy(id, &w, sizeof w);
    id += sizeof w;
  }
}
}  // namespace

void GaugeTableWriter::add(const Sites& sites, const Gauges& gauges, const Gauge& x) { add(sites, gauges, &x, 1, 1); }

void GaugeTableWriter::add(const Sites& sites, const Gauges& gauges, const Gauge* g, std::size_t n, int threads) {
  while (n > 0) {
    // In memory every row has its place; a file's rows go through the batch, a batch at a time.
    const std::size_t k = fd_ >= 0 ? std::min(n, kBatch - in_batch_) : n;
    // Blocks of rows a thread: a row is about half a microsecond, a thread's start far more.
    constexpr std::size_t kBlock = std::size_t(1) << 12;
    const std::size_t blocks = (k + kBlock - 1) / kBlock;
    auto rows = [&](std::size_t b) {
      for (std::size_t i = b * kBlock; i < std::min(k, (b + 1) * kBlock); ++i)
        put_row(sites, gauges, g[i], rows_ + i + 1, rd_ + i * kGaugeRealBytes, id_ + i * kGaugeIntBytes);
    };
    // One block (a gauge at a time, as the editor's paths take them) on this thread directly.
    if (blocks == 1) rows(0);
    else detail::parallel_for(blocks, threads, [&](unsigned, std::size_t b) { rows(b); });
    rd_ += k * kGaugeRealBytes, id_ += k * kGaugeIntBytes;
    rows_ += k, g += k, n -= k;
    if (fd_ >= 0 && (in_batch_ += k) == kBatch) flush();
  }
}

void GaugeTableWriter::close() {
  if (fd_ < 0) return;
  flush();
  const int fd = fd_;
  fd_ = -1;
  if (::close(fd) != 0) throw write_error(file_, ": ");
}

void GaugeTableWriter::put(const char* p, std::size_t left, std::uint64_t at) {
  while (left > 0) {
    const ssize_t k = pwrite(fd_, p, left, off_t(at));
    if (k < 0 && errno == EINTR) continue;
    if (k <= 0) throw write_error(file_, " (disk full?): ");
    p += k, left -= std::size_t(k), at += std::uint64_t(k);
  }
}

void GaugeTableWriter::flush() {
  put(buf_r_.data(), kGaugeRealBytes * in_batch_, kGaugeRealBytes * flushed_);
  put(buf_i_.data(), kGaugeIntBytes * in_batch_, kGaugeRealBytes * count_ + kGaugeIntBytes * flushed_);
  flushed_ += in_batch_, in_batch_ = 0;
  rd_ = buf_r_.data(), id_ = buf_i_.data();
}

void write_gauge_table(const Sites& sites, Gauges& g, GaugeTableWriter& table,
                       const std::function<void(const Gauge&)>& each, int threads) {
  const std::size_t n = g.gauges.size();
  for (std::size_t done = 0; done < n;) {
    const std::size_t k = std::min(kReleaseEvery, n - done);
    const Gauge* first = g.gauges.data() + done;
    if (each) {
      for (std::size_t i = 0; i < k; ++i) {
        table.add(sites, g, first[i]);
        each(first[i]);
      }
    } else {
      table.add(sites, g, first, k, threads);
    }
    detail::release_pages(first, first + k);
    done += k;
  }
  g.gauges = Paged<Gauge>();
  table.close();
}

std::string gauge_label(std::int32_t rank, GaugeType type, double cd_um) {
  char label[96];
  std::snprintf(label, sizeof label, "#%d %s %.4g", rank, gauge_type_name(type), cd_um);
  return label;
}

void write_gauges_gds(const GaugeTableView& table, const std::string& path, double dbu, int layer, int datatype,
                      const std::string& cell) {
  GdsWriter w(path, dbu, cell);
  const double* r = table.reals;
  const std::int32_t* k = table.ints;
  for (std::size_t i = 0; i < table.count; ++i, r += kGaugeReals, k += kGaugeInts) {
    w.path(layer, datatype, r[0], r[1], r[2], r[3]);
    if (k[12] < 0 || k[12] > int(GaugeType::T)) throw std::out_of_range("gauge type index out of range");
    w.text(layer, datatype, r[4], r[5], gauge_label(k[0], GaugeType(k[12]), r[6] * dbu));
  }
  w.close();
}

}  // namespace linf
