#include "linf/io/csv.hpp"

#include <algorithm>
#include <charconv>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <memory>
#include <stdexcept>

#include "util/parallel.hpp"

namespace linf {

namespace {
// The digits of 00 .. 99, two at a time: half the divisions of one digit at a time (a CSV line
// has 14 numbers).
constexpr char kPairs[] =
    "00010203040506070809101112131415161718192021222324252627282930313233343536373839"
    "40414243444546474849505152535455565758596061626364656667686970717273747576777879"
    "8081828384858687888990919293949596979899";
constexpr std::size_t kFixed6Room = 400;

// Writes x with six decimals at s (room for kFixed6Room characters), returns the end.
char* put_fixed6(char* s, double x) {
  // Most values need no general conversion: x * 10^6 rounded to an integer is x to six places
  // unless the product lies within its rounding error of a half (then to_chars decides).
  const double a = std::fabs(x), p = a * 1e6;
  if (a < 1e9) {
    const double whole = std::floor(p), frac = p - whole;  // both exact
    if (std::fabs(frac - 0.5) > 4.5e-16 * p) {
      std::uint64_t n = std::uint64_t(whole) + (frac > 0.5);
      char buf[32];
      char* const end = buf + sizeof buf;
      char* d = end;
      auto two = [&](unsigned v) { d -= 2, d[0] = kPairs[2 * v], d[1] = kPairs[2 * v + 1]; };  // 00 .. 99
      for (int i = 0; i < 3; ++i) two(unsigned(n % 100)), n /= 100;
      *--d = '.';
      for (; n >= 100; n /= 100) two(unsigned(n % 100));
      if (n >= 10) two(unsigned(n));
      else *--d = char('0' + n);
      if (std::signbit(x)) *--d = '-';
      const std::size_t len = std::size_t(end - d);
      std::memcpy(s, d, len);
      return s + len;
    }
  }
  // std::to_chars with a precision is specified as printf's "%.6f"; the largest double has
  // 309 digits before the point.
  return std::to_chars(s, s + kFixed6Room, x, std::chars_format::fixed, 6).ptr;
}
}  // namespace

void append_fixed6(std::string& out, double x) {
  char num[kFixed6Room];
  out.append(num, std::size_t(put_fixed6(num, x) - num));
}

namespace {
void append_field(std::string& line, double x) {
  line.push_back(',');
  append_fixed6(line, x);
}

using File = std::unique_ptr<FILE, int (*)(FILE*)>;

File gauges_csv(const std::string& path, bool with_context = false) {
  File f(std::fopen(path.c_str(), "w"), &std::fclose);
  if (!f) throw std::runtime_error("cannot write " + path);
  std::fputs(with_context ? "id,type,x1,y1,x2,y2,cx,cy,cd,score,norm_score,tiebreak,rank,context,count\r\n"
                          : "id,type,x1,y1,x2,y2,cx,cy,cd,score,norm_score,tiebreak,rank\r\n",
             f.get());
  return f;
}

// One gauge's line into `line`; r: its reals in the gauge table's order (x1 .. tiebreak, DBU
// but norm_score), the subsets' source and the whole layer's alike, so that both write the
// same bytes for a gauge.
void gauge_line(std::string& line, std::int64_t rank, GaugeType type, const double* r, double dbu) {
  const std::string id = std::to_string(rank);
  line.assign(id);
  line.push_back(',');
  line.append(gauge_type_name(type));
  for (int i = 0; i < 8; ++i) append_field(line, r[i] * dbu);
  append_field(line, r[8]);
  append_field(line, r[9] * dbu);
  line.push_back(',');
  line.append(id);
}

// ",context,count" of a plan's gauge: the context id as 16 hex digits, the count in decimal.
void append_context(std::string& line, std::uint64_t context, std::uint64_t count) {
  char text[48];
  const int n = std::snprintf(text, sizeof text, ",%016llx,%llu", static_cast<unsigned long long>(context),
                              static_cast<unsigned long long>(count));
  line.append(text, std::size_t(n));
}
}  // namespace

void write_gauges_csv(const Sites& sites, const Gauges& gauges, double dbu, const std::string& path) {
  const File f = gauges_csv(path);
  std::string line;
  std::int64_t rank = 0;
  for (const Gauge& g : gauges.gauges) {
    const MeasurementLine m = measurement_line(sites, g);
    const double r[kGaugeReals] = {m.p.x, m.p.y, m.q.x, m.q.y, g.at.x, g.at.y,
                                   g.cd, g.score, gauges.norm_score(g), g.tiebreak};
    gauge_line(line, ++rank, g.type, r, dbu);
    line.append("\r\n");
    std::fwrite(line.data(), 1, line.size(), f.get());
  }
  if (std::ferror(f.get())) throw std::runtime_error("error writing " + path);
}

void write_gauges_csv_rows(const GaugeTableView& table, const std::vector<std::size_t>& rows, double dbu,
                           const std::string& path, const GaugeContexts* contexts) {
  for (std::size_t i : rows)
    if (i >= table.count) throw std::out_of_range("gauge row beyond the table");
  if (contexts && (contexts->ids.size() != rows.size() || contexts->counts.size() != rows.size()))
    throw std::invalid_argument("one context id and one count a row");
  const File f = gauges_csv(path, contexts != nullptr);
  std::string line;
  for (std::size_t j = 0; j < rows.size(); ++j) {
    const std::size_t i = rows[j];
    const std::int32_t* k = table.ints + i * kGaugeInts;
    if (k[12] < 0 || k[12] > int(GaugeType::T)) throw std::out_of_range("gauge type index out of range");
    gauge_line(line, k[0], GaugeType(k[12]), table.reals + i * kGaugeReals, dbu);
    if (contexts) append_context(line, contexts->ids[j], contexts->counts[j]);
    line.append("\r\n");
    std::fwrite(line.data(), 1, line.size(), f.get());
  }
  if (std::ferror(f.get())) throw std::runtime_error("error writing " + path);
}

PiecesCsv::PiecesCsv(const std::string& path, double dbu) : path_(path), dbu_(dbu) {
  f_ = std::fopen(path.c_str(), "w");
  if (!f_) throw std::runtime_error("cannot write " + path);
  std::fputs("kind,x1,y1,x2,y2,d1,d2,a_x1,a_y1,a_x2,a_y2,b_x1,b_y1,b_x2,b_y2\r\n", f_);
}

PiecesCsv::~PiecesCsv() {
  if (f_) std::fclose(f_);
}

void PiecesCsv::add(const Sites& sites, const Piece* pieces, std::size_t n) {
  // Formatting is most of the writer's time (14 numbers a piece): chunks of the batch are
  // formatted side by side, written in order.
  constexpr std::size_t kChunk = 8192;
  const std::size_t chunks = (n + kChunk - 1) / kChunk;
  text_.resize(std::max(text_.size(), chunks));
  detail::parallel_for(chunks, 0, [&](unsigned, std::size_t c) {
    std::string& out = text_[c];
    out.clear();
    const auto& S = sites.sites;
    for (std::size_t i = c * kChunk, end = std::min(n, i + kChunk); i < end; ++i) {
      const Piece& p = pieces[i];
      const Site& a = S[p.a];
      const Site& b = S[p.b];
      const double v[14] = {p.p.x, p.p.y, p.q.x, p.q.y, p.d1, p.d2,
                            double(a.a.x), double(a.a.y), double(a.b.x), double(a.b.y),
                            double(b.a.x), double(b.a.y), double(b.b.x), double(b.b.y)};
      // The line is made in place and appended once (an append a field cost as much again).
      char line[16 + 14 * (1 + kFixed6Room)];
      const char* kind = kind_name(p.kind);
      const std::size_t kl = std::strlen(kind);
      std::memcpy(line, kind, kl);
      char* at = line + kl;
      for (double x : v) *at++ = ',', at = put_fixed6(at, x * dbu_);
      *at++ = '\r', *at++ = '\n';
      out.append(line, std::size_t(at - line));
    }
  });
  for (std::size_t c = 0; c < chunks; ++c) std::fwrite(text_[c].data(), 1, text_[c].size(), f_);
}

void PiecesCsv::close() {
  const bool bad = std::ferror(f_) != 0;
  const bool failed = std::fclose(f_) != 0;
  f_ = nullptr;
  if (bad || failed) throw std::runtime_error("error writing " + path_);
}

void write_pieces_csv(Diagram& d, double dbu, const std::string& path) {
  const auto t0 = std::chrono::steady_clock::now();
  PiecesCsv csv(path, dbu);
  // In batches, as the streamed stage gives them: the formatted text is held a batch at a time.
  for (std::size_t i = 0; i < d.pieces.size(); i += std::size_t(1) << 16)
    csv.add(d.sites, d.pieces.data() + i, std::min(d.pieces.size() - i, std::size_t(1) << 16));
  csv.close();
  d.seconds_csv = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace linf
