#include "linf/pipeline/stream.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <condition_variable>
#include <exception>
#include <functional>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <mutex>
#include <queue>
#include <stdexcept>
#include <system_error>
#include <thread>
#include <utility>

#include "linf/diagram/builder.hpp"
#include "linf/diagram/classify.hpp"
#include "linf/diagram/sweep.hpp"
#include "linf/io/csv.hpp"
#include "linf/pipeline/tile_task.hpp"
#include "linf/geometry/sites.hpp"
#include "util/parallel.hpp"
#include "util/progress_meter.hpp"

namespace linf {

namespace {

double since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// Sorted runs of pieces, one after the other in a temporary file that is unlinked at once (it
// goes when it is closed, also when the process dies).
class Runs {
 public:
  Runs() {
    const char* env = std::getenv("TMPDIR");
    const std::string dir = env && *env ? env : "/tmp";
    std::string name = dir + "/linf_opc_pieces_XXXXXX";
    fd_ = mkstemp(name.data());
    if (fd_ < 0) throw std::runtime_error("cannot create a temporary file in " + dir + ": " + std::strerror(errno));
    unlink(name.c_str());
  }
  ~Runs() { ::close(fd_); }
  Runs(const Runs&) = delete;
  Runs& operator=(const Runs&) = delete;

  void add(const std::vector<Piece>& part) {
    if (part.empty()) return;
    const char* p = reinterpret_cast<const char*>(part.data());
    std::size_t left = part.size() * sizeof(Piece);
    off_t at = off_t(pieces_ * sizeof(Piece));
    while (left > 0) {
      const ssize_t k = pwrite(fd_, p, left, at);
      if (k < 0 && errno == EINTR) continue;
      if (k <= 0)
        throw std::runtime_error(std::string("cannot write the diagram's pieces to a temporary file (disk full?): ") +
                                 std::strerror(errno));
      p += k, left -= std::size_t(k), at += k;
    }
    runs_.push_back({pieces_, pieces_ + part.size()});
    pieces_ += part.size();
  }

  void read(std::uint64_t first, std::size_t n, Piece* out) const {
    char* p = reinterpret_cast<char*>(out);
    std::size_t left = n * sizeof(Piece);
    off_t at = off_t(first * sizeof(Piece));
    while (left > 0) {
      const ssize_t k = pread(fd_, p, left, at);
      if (k < 0 && errno == EINTR) continue;
      if (k <= 0) throw std::runtime_error(std::string("cannot read the diagram's temporary file: ") + std::strerror(errno));
      p += k, left -= std::size_t(k), at += k;
    }
  }

  struct Run { std::uint64_t first, end; };
  const std::vector<Run>& runs() const { return runs_; }

 private:
  int fd_ = -1;
  std::uint64_t pieces_ = 0;
  std::vector<Run> runs_;
};

// The runs merged in join_order; each owner pair's pieces, from every run, handed to `pair`.
// A buffer a run, of 1024 pieces (64 KB) while the buffers together stay under 16 MB, fewer
// (down to 64) past that: a run is a tile, and a layer of millions of shapes has thousands.
template <class Pair>
void merge(const Runs& runs, const Pair& pair) {
  struct Cursor {
    std::uint64_t next, end;
    std::vector<Piece> buf;
    std::size_t at = 0;
  };
  std::vector<Cursor> cs;
  for (const Runs::Run& r : runs.runs()) cs.push_back({r.first, r.end, {}, 0});
  const std::size_t each =
      std::clamp<std::size_t>((std::size_t(16) << 20) / sizeof(Piece) / std::max<std::size_t>(1, cs.size()), 64, 1024);
  auto fill = [&](Cursor& c) {
    const std::size_t n = std::size_t(std::min<std::uint64_t>(each, c.end - c.next));
    c.buf.resize(n);
    if (n) runs.read(c.next, n, c.buf.data());
    c.next += n, c.at = 0;
    return n > 0;
  };
  auto later = [&](std::size_t x, std::size_t y) { return join_order(cs[y].buf[cs[y].at], cs[x].buf[cs[x].at]); };
  std::priority_queue<std::size_t, std::vector<std::size_t>, decltype(later)> heap(later);
  for (std::size_t i = 0; i < cs.size(); ++i)
    if (fill(cs[i])) heap.push(i);
  std::vector<Piece> group;
  while (!heap.empty()) {
    const std::size_t i = heap.top();
    heap.pop();
    Cursor& c = cs[i];
    const Piece& p = c.buf[c.at];
    if (!group.empty() && (group[0].a != p.a || group[0].b != p.b)) {
      pair(group);
      group.clear();
    }
    group.push_back(p);
    if (++c.at < c.buf.size() || fill(c)) heap.push(i);
  }
  if (!group.empty()) pair(group);
}

// Joined pieces on their way to the checker, the writers and the stretches: whole owner pairs,
// each pair's first piece at its entry of `starts`.
struct Batch {
  std::vector<Piece> pieces;
  std::vector<std::size_t> starts;
  void clear() { pieces.clear(), starts.clear(); }
};

// Hands batches to `work` in order: on a thread of its own, one batch behind the caller, or at
// once on the caller's thread. Merging and joining the next batch then overlaps the checker and
// the stretches taking this one, which are most of the pass after the tiles. The first
// exception `work` throws is rethrown by the next give() or by finish().
class Behind {
 public:
  Behind(bool threaded, std::function<void(Batch&)> work) : work_(std::move(work)) {
    try {
      if (threaded) thread_ = std::thread([this] { run(); });
    } catch (const std::system_error&) {
      // No thread to be had (EAGAIN): the batches are taken on the caller's.
    }
  }
  ~Behind() { stop(); }
  Behind(const Behind&) = delete;
  Behind& operator=(const Behind&) = delete;

  // Takes b's contents and leaves it empty.
  void give(Batch& b) {
    if (!thread_.joinable()) {
      work_(b);
      b.clear();
      return;
    }
    std::unique_lock<std::mutex> lock(m_);
    cv_.wait(lock, [&] { return !full_ || failed_; });
    if (failed_) std::rethrow_exception(failed_);
    std::swap(slot_, b);
    full_ = true;
    b.clear();
    cv_.notify_all();
  }
  // Waits for every batch given to be taken.
  void finish() {
    stop();
    if (failed_) std::rethrow_exception(failed_);
  }

 private:
  void run() {
    Batch mine;
    for (;;) {
      {
        std::unique_lock<std::mutex> lock(m_);
        cv_.wait(lock, [&] { return full_ || done_; });
        if (!full_) return;
        std::swap(mine, slot_);
        full_ = false;
        cv_.notify_all();
      }
      try {
        work_(mine);
        mine.clear();
      } catch (...) {
        std::lock_guard<std::mutex> lock(m_);
        failed_ = std::current_exception();
        cv_.notify_all();
        return;
      }
    }
  }
  void stop() {
    if (!thread_.joinable()) return;
    {
      std::lock_guard<std::mutex> lock(m_);
      done_ = true;
      cv_.notify_all();
    }
    thread_.join();
  }

  std::function<void(Batch&)> work_;
  std::mutex m_;
  std::condition_variable cv_;
  Batch slot_;
  bool full_ = false, done_ = false;
  std::exception_ptr failed_;
  std::thread thread_;  // last: started once the rest is ready
};

}  // namespace

StreamResult stream_voronoi(const FlatPolygons& polygons, const DiagramOptions& opt, const StreamOutputs& out,
                            const TileRunner& tiles) {
  StreamResult r;
  Diagram& d = r.diagram;
  auto t0 = std::chrono::steady_clock::now();
  if (opt.progress) opt.progress("merging the polygons", 0, 0);
  d.sites = sites_of_polygons(merge_polygons(polygons, std::size_t(1) << 16, opt.build.threads).view());
  d.seconds_merge = since(t0);
  d.clip = clip_box(d.sites);
  d.attempts = 1;

  std::unique_ptr<StretchStream> stretches;
  if (out.keep) {
    const Sites& sites = d.sites;
    const auto& keep = out.keep;
    stretches = std::make_unique<StretchStream>(
        d.sites, [&sites, &keep](std::int32_t a, std::int32_t b, PieceKind k) { return keep(sites, a, b, k); },
        std::size_t(4.5 * double(d.sites.sites.size())));
  }
  double t_stretches = 0;

  // Build: every tile's pieces classified, their vertices given to the stretches, spilled.
  Runs runs;
  std::vector<double> clear;  // a sample of clearances: where the checker draws its pairs
  BuildStats st;
  t0 = std::chrono::steady_clock::now();
  // A part's own work — its kinds, its vertices' stretches — on the thread that built it (the
  // sweep's tiles: several at once); the rest in the parts' order.
  using Reading = std::shared_ptr<const StretchStream::Reading>;
  auto prepare = [&](std::vector<Piece>& part, const Box& frame) -> std::any {
    for (Piece& p : part) p.kind = classify(d.sites, p);
    return stretches ? stretches->read(part, frame) : Reading{};
  };
  auto take = [&](std::vector<Piece>& part, const Box&, std::any& prepared) {
    for (std::size_t i = 0; i < part.size(); i += 1 + part.size() / 64) clear.push_back(part[i].d1);
    if (stretches) {
      const auto t = std::chrono::steady_clock::now();
      // Prepared by the tile's task (run_tile_job): its bytes; else by `prepare`.
      if (const std::string* bytes = std::any_cast<std::string>(&prepared))
        stretches->add(*StretchStream::reading(*bytes));
      else
        stretches->add(*std::any_cast<Reading&>(prepared));
      t_stretches += since(t);
    }
    runs.add(part);
  };
  BuildOptions build = opt.build;
  build.sweep = d.swept = opt.sweep && sweep_handles(d.sites);  // a cluster's tiles too (tile_jobs.hpp)
  build_parts(d.sites, d.clip, build, &st, prepare, take, tiles, opt.progress,
              stretches && out.keep_measurable ? kGaugeReadings : 0);
  d.seconds_build = since(t0) - t_stretches;
  d.tiles = st.tiles, d.tile_tasks = st.tasks, d.largest_tile_sites = st.largest_tile_sites;

  // Merge: each pair's pieces joined, in build_pieces' order, to every consumer in batches.
  std::unique_ptr<Checker> checker;
  if (opt.check) {
    CheckOptions co = opt.checker;
    co.threads = opt.build.threads;
    checker = std::make_unique<Checker>(d.sites, d.clip, median_clearance(std::move(clear)), co);
  }
  std::unique_ptr<PiecesCsv> csv;
  if (!out.csv.empty()) csv = std::make_unique<PiecesCsv>(out.csv, out.dbu);
  std::unique_ptr<GdsWriter> gds;
  if (!out.gds.empty()) gds = std::make_unique<GdsWriter>(out.gds, out.layers.dbu, out.layers.cell);
  Behind behind(detail::worker_count(2, opt.build.threads) > 1, [&](Batch& b) {
    for (const Piece& p : b.pieces) ++r.counts[std::size_t(p.kind)];
    r.pieces += b.pieces.size();
    auto t = std::chrono::steady_clock::now();
    if (checker) checker->add(b.pieces.data(), b.pieces.size());
    d.seconds_check += since(t);
    t = std::chrono::steady_clock::now();
    if (csv) csv->add(d.sites, b.pieces.data(), b.pieces.size());
    if (gds) draw_pieces(*gds, out.layers, b.pieces.data(), b.pieces.size(), r.drawn);
    d.seconds_csv += since(t);
    if (stretches) {
      t = std::chrono::steady_clock::now();
      b.starts.push_back(b.pieces.size());
      for (std::size_t g = 0; g + 1 < b.starts.size(); ++g)
        stretches->pair(b.pieces.data() + b.starts[g], b.starts[g + 1] - b.starts[g]);
      t_stretches += since(t);
    }
  });
  Batch batch;
  t0 = std::chrono::steady_clock::now();
  std::uint64_t raw = 0;
  for (const Runs::Run& run : runs.runs()) raw += run.end - run.first;
  detail::ProgressMeter meter(opt.progress, opt.check ? "joining and checking the pieces" : "joining the pieces", raw);
  merge(runs, [&](std::vector<Piece>& group) {
    meter.step(group.size());
    join_pair(group);
    batch.starts.push_back(batch.pieces.size());
    for (Piece p : group) {
      // Again after the join: a piece's kind is decided at its own midpoint, as the in-memory
      // stage decides it on the joined pieces (the tiles' kinds served the point stretches).
      p.kind = classify(d.sites, p);
      batch.pieces.push_back(p);
    }
    if (batch.pieces.size() >= (std::size_t(1) << 16)) behind.give(batch);
  });
  behind.give(batch);
  behind.finish();

  if (checker) {
    if (opt.progress) opt.progress("checking the diagram", 0, 0);
    const auto t = std::chrono::steady_clock::now();
    r.check = checker->finish();
    d.seconds_check += since(t);
  }
  const auto t = std::chrono::steady_clock::now();
  if (csv) csv->close();
  if (gds) gds->close();
  d.seconds_csv += since(t);
  if (checker && !r.check.ok()) {
    // Never handed on: what was written goes.
    if (!out.csv.empty()) std::remove(out.csv.c_str());
    if (!out.gds.empty()) std::remove(out.gds.c_str());
    std::string what = "the L-inf Voronoi diagram failed its check";
    if (!r.check.messages.empty()) what += ": " + r.check.messages.front();
    throw DiagramError(what, r.check);
  }
  if (stretches) {
    if (opt.progress) opt.progress("joining the stretches", 0, 0);
    const auto t1 = std::chrono::steady_clock::now();
    r.stretches = stretches->finish();
    t_stretches += since(t1);
  }
  r.seconds_stretches = t_stretches;
  return r;
}

StreamResult stream_voronoi(const std::vector<Polygon>& polygons, const DiagramOptions& opt, const StreamOutputs& out,
                            const TileRunner& tiles) {
  return stream_voronoi(flat_of(polygons).view(), opt, out, tiles);
}

}  // namespace linf
