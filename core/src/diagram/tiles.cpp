#include "tiles.hpp"

#include <algorithm>
#include <cmath>
#include <condition_variable>
#include <cstdint>
#include <exception>
#include <memory>
#include <mutex>
#include <stdexcept>
#include <string>
#include <thread>
#include <utility>

#include "linf/diagram/sweep.hpp"
#include "linf/geometry/distance.hpp"
#include "linf/util/paged.hpp"
#include "tile_jobs.hpp"
#include "util/ahead.hpp"
#include "util/progress_meter.hpp"

namespace linf::detail {

namespace {

// The quadtree boxes of `root` at `level`, by the same halving as the subdivision itself, so
// that a task is exactly the box the recursion would reach; index j * 2^level + i.
std::vector<Box> grid_boxes(const Box& root, int level) {
  std::vector<Box> cur{root};
  for (int l = 0; l < level; ++l) {
    const std::size_t n = std::size_t(1) << l, m = 2 * n;
    std::vector<Box> next(m * m);
    for (std::size_t j = 0; j < n; ++j)
      for (std::size_t i = 0; i < n; ++i) {
        const std::array<Box, 4> q = quarters(cur[j * n + i]);
        next[(2 * j) * m + 2 * i] = q[0];
        next[(2 * j) * m + 2 * i + 1] = q[1];
        next[(2 * j + 1) * m + 2 * i] = q[2];
        next[(2 * j + 1) * m + 2 * i + 1] = q[3];
      }
    cur.swap(next);
  }
  return cur;
}

// Site ids bucketed by bounding box over a uniform grid of the root (compressed rows), in the
// builder's coordinates (relative to `origin`).
class SiteGrid {
 public:
  SiteGrid(const SiteList& s, const Box& root, int level, const Point& origin)
      : s_(s), root_(root), n_(std::size_t(1) << level), o_(origin) {
    cw_ = (root.x2 - root.x1) / double(n_), ch_ = (root.y2 - root.y1) / double(n_);
    start_.resize(n_ * n_ + 1);
    for (int pass = 0; pass < 2; ++pass) {
      std::vector<std::size_t> fill(start_.begin(), start_.end() - 1);
      for (std::size_t t = 0; t < s.size(); ++t) {
        std::size_t i1, i2, j1, j2;
        range(box_of(shifted(s[t], o_)), 0, i1, i2, j1, j2);
        for (std::size_t j = j1; j <= j2; ++j)
          for (std::size_t i = i1; i <= i2; ++i) {
            if (pass == 0) ++start_[j * n_ + i + 1];
            else ids_[fill[j * n_ + i]++] = int(t);
          }
      }
      if (pass == 0) {
        for (std::size_t k = 1; k < start_.size(); ++k) start_[k] += start_[k - 1];
        ids_.resize(start_.back());
      }
    }
  }

  // Sites whose bounding box comes within L-inf distance r of b (a superset of the sites
  // within r of b), each once, ascending if `sorted`. `seen` is the caller's scratch, one entry
  // a site.
  void near(const Box& b, double r, std::vector<int>& out, Paged<std::uint32_t>& seen, std::uint32_t& stamp,
            bool sorted = true) const {
    out.clear();
    if (seen.size() != s_.size()) seen.clear(), seen.resize(s_.size()), stamp = 0;
    if (++stamp == 0) std::fill(seen.begin(), seen.end(), 0), stamp = 1;
    std::size_t i1, i2, j1, j2;
    range(b, r, i1, i2, j1, j2);
    for (std::size_t j = j1; j <= j2; ++j)
      for (std::size_t k = start_[j * n_ + i1]; k < start_[j * n_ + i2 + 1]; ++k) {
        const int t = ids_[k];
        if (seen[t] == stamp) continue;
        seen[t] = stamp;
        const Box c = box_of(shifted(s_[t], o_));
        if (std::max({c.x1 - b.x2, b.x1 - c.x2, c.y1 - b.y2, b.y1 - c.y2}) <= r) out.push_back(t);
      }
    if (sorted) std::sort(out.begin(), out.end());
  }

 private:
  static Box box_of(const Site& t) {
    return {double(std::min(t.a.x, t.b.x)), double(std::min(t.a.y, t.b.y)), double(std::max(t.a.x, t.b.x)),
            double(std::max(t.a.y, t.b.y))};
  }
  // Buckets meeting b enlarged by r, one bucket of slack for rounding (near() filters exactly).
  void range(const Box& b, double r, std::size_t& i1, std::size_t& i2, std::size_t& j1, std::size_t& j2) const {
    auto cell = [&](double v, double lo, double w) {
      const double k = std::floor((v - lo) / w);
      return std::size_t(std::clamp(k, 0.0, double(n_ - 1)));
    };
    i1 = cell(b.x1 - r, root_.x1, cw_) > 0 ? cell(b.x1 - r, root_.x1, cw_) - 1 : 0;
    j1 = cell(b.y1 - r, root_.y1, ch_) > 0 ? cell(b.y1 - r, root_.y1, ch_) - 1 : 0;
    i2 = std::min(n_ - 1, cell(b.x2 + r, root_.x1, cw_) + 1);
    j2 = std::min(n_ - 1, cell(b.y2 + r, root_.y1, ch_) + 1);
  }

  const SiteList& s_;
  Box root_;
  std::size_t n_;
  Point o_;
  double cw_ = 1, ch_ = 1;
  // Whole-layer arrays (a site's id once or more): Paged, as the sites are.
  Paged<std::size_t> start_;
  Paged<int> ids_;
};

// The task's halo: every site that can own a point of b. With U the least upper bound of the
// distance over b among the sites found, every owner lies within U of b; the search radius
// grows to U (+ the rounding allowance) until it covers it. The site attaining U is then
// found too, so the builder's first pruning gives what it gives with every site.
void gather(const SiteGrid& grid, const SiteList& sites, const Point& origin, const Box& b, const Box& root,
            double tau, std::vector<int>& out, Paged<std::uint32_t>& seen, std::uint32_t& stamp) {
  double r = std::max(b.x2 - b.x1, b.y2 - b.y1);
  const double span = std::max(root.x2 - root.x1, root.y2 - root.y1);
  for (;;) {
    grid.near(b, r, out, seen, stamp);
    if (out.empty()) {
      if (r > 2 * span) return;  // no sites at all
      r *= 2;
      continue;
    }
    double U = INFINITY;
    for (int t : out) {
      const Site s = shifted(sites[t], origin);
      U = std::min(U, rectilinear(s) ? far_side(s, b, false) : max_over(make_distfn(s, Norm::Linf), b));
    }
    if (U + tau <= r) return;
    r = U + tau;
  }
}

// Task level: a few hundred sites a task on average, from the site count only (never from
// the tile size): enough tasks to share among threads, few enough that gathering is cheap.
int task_level(std::size_t n) {
  int level = 2;
  while (level < 10 && (std::size_t(1) << (2 * level)) * 256 < n) ++level;
  return level;
}

// A tile's own sites; its halo adds a third to a half more (a block of tracks).
constexpr std::size_t kAutoTileSites = std::size_t(1) << 15;

// The sites (by their box's centre) in each of the n x n tasks of root, row by row.
std::vector<std::uint32_t> sites_per_task(const SiteList& sites, const Point& origin, const Box& root, std::size_t n) {
  std::vector<std::uint32_t> count(n * n, 0);
  const double cw = (root.x2 - root.x1) / double(n), ch = (root.y2 - root.y1) / double(n);
  auto cell = [&](double v, double lo, double w) {
    return std::size_t(std::clamp(std::floor((v - lo) / w), 0.0, double(n - 1)));
  };
  for (const Site& s : sites) {
    const Site t = shifted(s, origin);
    ++count[cell(0.5 * (double(t.a.y) + double(t.b.y)), root.y1, ch) * n +
            cell(0.5 * (double(t.a.x) + double(t.b.x)), root.x1, cw)];
  }
  return count;
}

// The most sites in one block of k x k tasks: the fullest tile's own sites, before its halo.
std::size_t fullest_tile(const std::vector<std::uint32_t>& per_task, std::size_t n, std::size_t k) {
  std::size_t most = 0;
  for (std::size_t bj = 0; bj < n; bj += k)
    for (std::size_t bi = 0; bi < n; bi += k) {
      std::size_t in = 0;
      for (std::size_t j = bj; j < bj + k; ++j)
        for (std::size_t i = bi; i < bi + k; ++i) in += per_task[j * n + i];
      most = std::max(most, in);
    }
  return most;
}

// The fixed grid of tasks and its tiles, and each tile's sites: what the local pass and the
// tile jobs share, so that both give a tile the same sites, boxes and halos.
class Plan {
  // First, as the public members below are initialised from them.
  const SiteList& sites_;
  Point origin_;
  Box root_;
  BuildOptions opt_;
  double tau_;
  int T_;  // task level

 public:
  // sweep: planned for sweep_sites (a finer grid, no local ids), not for gather_tile.
  Plan(const SiteList& sites, const Point& origin, const Box& root, const BuildOptions& opt, double tau,
       bool sweep = false)
      : sites_(sites), origin_(origin), root_(root), opt_(opt), tau_(tau), T_(task_level(sites.size())),
        nt(std::size_t(1) << T_), per(side_tasks()), ntiles(nt / per), tasks(grid_boxes(root, T_)),
        level_(sweep ? fine_level() : T_ + 1),  // buckets finer than tasks: tighter halos
        grid_(sites, root, level_, origin),
        scratch_(worker_count(sweep ? ntiles * ntiles + 1 : per * per, opt.threads)) {  // + 1: the far field
    if (sweep) return;
    local_.resize(sites.size());
    std::fill(local_.begin(), local_.end(), -1);
  }

  const std::size_t nt;      // tasks along the root's side
  const std::size_t per;     // tasks along a tile's side
  const std::size_t ntiles;  // tiles along the root's side
  const std::vector<Box> tasks;

  // Tile (tj, ti)'s task k (row by row within the tile): its index in `tasks`.
  std::size_t task_of(std::size_t tj, std::size_t ti, std::size_t k) const {
    return (tj * per + k / per) * nt + ti * per + k % per;
  }
  Box frame(std::size_t tj, std::size_t ti) const {
    Box f = tasks[task_of(tj, ti, 0)];
    const Box& last = tasks[task_of(tj, ti, per * per - 1)];
    f.x2 = last.x2, f.y2 = last.y2;
    return f;
  }
  // The same frame in layout coordinates, where the sweep works.
  Box layout_frame(std::size_t tj, std::size_t ti) const { return in_layout(frame(tj, ti)); }
  Box layout_root() const { return in_layout(root_); }
  // The tile's sites for the sweep (safe on several threads, each with its own `worker`). A
  // site that owns a point p of the frame F and does not meet F is an L-inf nearest site, tied
  // or not, at the point q where the segment from p to the site's nearest point leaves F (as in
  // far_field.hpp). So the sites meeting F and those meeting the square of radius f(q) about
  // each border point q (f: the distance to the nearest site) are enough. The border is walked
  // in steps of length l from sample points c: over a step f <= f(c) + l (f is 1-Lipschitz), so
  // the sites within f(c) + l of the step are taken. A square there reaches at most l beyond
  // the nearest site: l = f(c) / 32 (or a 256th of the frame) keeps that slack small, where a
  // border far from every site would otherwise take rows of sites behind the nearest. The
  // next sample's nearest site is among a step's catch.
  // Every segment's end sites are added (the sweep takes a segment with them). Tighter than
  // the tasks' halos, which take a task's whole least upper bound of f around it.
  std::vector<int> sweep_sites(std::size_t tj, std::size_t ti, unsigned worker) {
    return walked(frame(tj, ti), worker, true);
  }
  // The sites L-inf nearest, tied or not, at a point of the root's border, and every segment's
  // end sites: the only sites that own a point outside the root (far_field.hpp), found by the
  // same walk, so that the far field needs nothing of the tiles and is swept beside them.
  std::vector<int> far_field_sites(unsigned worker) { return walked(root_, worker, false); }
  // The sweep's grid: about 8 sites a bucket, for sweep_sites' many small queries.
  int fine_level() const {
    int level = T_ + 1;
    while (level < 12 && (std::size_t(1) << (2 * level)) * 8 < sites_.size()) ++level;
    return level;
  }

 private:
  // The border walk of sweep_sites over F; with `inside`, also the sites meeting F.
  std::vector<int> walked(const Box& F, unsigned worker, bool inside) {
    Scratch& sc = scratch_[worker];
    std::vector<int> ids, h;
    // The steps' catches overlap (a step is a 32nd of the radius it searches): each site is
    // taken once, and the catches are left unsorted.
    if (sc.taken.size() != sites_.size()) sc.taken.clear(), sc.taken.resize(sites_.size()), sc.taken_stamp = 0;
    if (++sc.taken_stamp == 0) std::fill(sc.taken.begin(), sc.taken.end(), 0), sc.taken_stamp = 1;
    auto take = [&](int t) {
      if (sc.taken[t] != sc.taken_stamp) sc.taken[t] = sc.taken_stamp, ids.push_back(t);
    };
    if (inside) {
      grid_.near(F, 0, h, sc.seen, sc.stamp, false);
      for (int t : h) take(t);
    }
    const double side = std::max(F.x2 - F.x1, F.y2 - F.y1);
    // At most 4 x 256 samples a tile: a step of a 256th of the side takes at most that much
    // more of the border's band, about 4 x N / 256 sites of a tile of N (0.7% more on 10^6
    // wires), and the walk took a sixth of the one-thread build with 2048 (docs/design.md).
    const double floor_step = std::max(1.0, side / 256);
    for (int e = 0; e < 4; ++e) {
      const bool horizontal = e < 2;  // y = y1, y = y2, x = x1, x = x2
      const double at = e == 0 ? F.y1 : e == 1 ? F.y2 : e == 2 ? F.x1 : F.x2;
      const double lo = horizontal ? F.x1 : F.y1, hi = horizontal ? F.x2 : F.y2;
      double f = nearest(horizontal ? Vec2{lo, at} : Vec2{at, lo}, sc, h);
      if (f == INFINITY) return {};  // no sites
      for (double u = lo; u < hi;) {
        const double l = std::min(hi - u, std::max(floor_step, f / 32));
        const Box step = horizontal ? Box{u, at, u + l, at} : Box{at, u, at, u + l};
        grid_.near(step, f + l + tau_, h, sc.seen, sc.stamp, false);  // f(c) + l bounds f over the step
        for (int t : h) take(t);
        u += l;
        // The next sample's nearest site is among these: f there is at most f + l.
        f = distance(horizontal ? Vec2{u, at} : Vec2{at, u}, h);
      }
    }
    const std::size_t n = ids.size();
    for (std::size_t k = 0; k < n; ++k)
      if (!sites_[ids[k]].is_point()) take(sites_[ids[k]].end0), take(sites_[ids[k]].end1);
    std::sort(ids.begin(), ids.end());
    return ids;
  }

 public:
  // The tile's sites (global ids, ascending) and each task's halo in local ids (into them).
  std::vector<int> gather_tile(std::size_t tj, std::size_t ti, std::vector<std::vector<int>>& halo) {
    halo.resize(per * per);
    parallel_for(per * per, opt_.threads, [&](unsigned w, std::size_t k) {
      gather(grid_, sites_, origin_, tasks[task_of(tj, ti, k)], root_, tau_, halo[k], scratch_[w].seen,
             scratch_[w].stamp);
    });
    std::vector<int> ids;
    for (auto& h : halo)
      for (int t : h)
        if (local_[t] < 0) local_[t] = 0, ids.push_back(t);
    std::sort(ids.begin(), ids.end());
    for (std::size_t i = 0; i < ids.size(); ++i) local_[ids[i]] = int(i);
    for (auto& h : halo)
      for (int& t : h) t = local_[t];
    for (int t : ids) local_[t] = -1;
    return ids;
  }

 private:
  Box in_layout(const Box& f) const {
    const double ox = double(origin_.x), oy = double(origin_.y);
    return {f.x1 + ox, f.y1 + oy, f.x2 + ox, f.y2 + oy};
  }
  // Tasks along a tile's side: 2^(T - Lt), Lt the tile level.
  std::size_t side_tasks() const {
    int Lt = 0;  // tile level: the coarsest whose boxes are no larger than the tile size
    const double side = std::max(root_.x2 - root_.x1, root_.y2 - root_.y1);
    if (opt_.tile_size > 0)
      while (Lt < T_ && side / double(std::size_t(1) << Lt) > opt_.tile_size) ++Lt;
    else if (opt_.tile_size < 0) {
      // Automatic: the coarsest level whose fullest tile holds at most kAutoTileSites sites of
      // its own. A tile's working memory grows with its sites (about 2 KB a site), so the
      // fullest one sets the stage's peak; 2^16 sites a tile on average over the layer's box let
      // it double with the layer's shape and with where its size fell between two levels (the
      // half of a block, twice as tall as wide: 77,645 sites in its fullest tile with the halo
      // and 254 MB over the stage's base, where the whole block's fullest tile had 34,950 and
      // 154 MB).
      const std::size_t n = std::size_t(1) << T_;
      const std::vector<std::uint32_t> per_task = sites_per_task(sites_, origin_, root_, n);
      while (Lt < T_ && fullest_tile(per_task, n, std::size_t(1) << (T_ - Lt)) > kAutoTileSites) ++Lt;
    }
    return std::size_t(1) << (T_ - Lt);
  }

  struct Scratch {  // one entry a site in each
    Paged<std::uint32_t> seen, taken;
    std::uint32_t stamp = 0, taken_stamp = 0;
  };

  // The L-inf distance from c to the nearest of `among` (points and axis-parallel segments:
  // their boxes; a 45-degree segment's box lies nearer than the segment), INFINITY if none.
  double distance(const Vec2& c, const std::vector<int>& among) const {
    double f = INFINITY;
    for (int t : among) {
      const Site u = shifted(sites_[t], origin_);
      if (!rectilinear(u)) {  // a 45-degree edge: its box is nearer than it
        f = std::min(f, dist_segment(c.x, c.y, u.a, u.b));
        continue;
      }
      f = std::min(f, std::max({double(std::min(u.a.x, u.b.x)) - c.x, c.x - double(std::max(u.a.x, u.b.x)),
                                double(std::min(u.a.y, u.b.y)) - c.y, c.y - double(std::max(u.a.y, u.b.y)), 0.0}));
    }
    return f;
  }
  // The distance from c to its nearest site, INFINITY if there are none. `h` is scratch.
  double nearest(const Vec2& c, Scratch& sc, std::vector<int>& h) const {
    const double span = std::max(root_.x2 - root_.x1, root_.y2 - root_.y1);
    const double cell = span / double(std::size_t(1) << level_);
    for (double r = std::max(1.0, cell / 2);; r *= 2) {
      grid_.near({c.x, c.y, c.x, c.y}, r, h, sc.seen, sc.stamp);
      const double f = distance(c, h);
      if (f <= r) return f;
      if (r > 4 * span) return INFINITY;
    }
  }

  int level_;  // the grid's
  SiteGrid grid_;
  std::vector<Scratch> scratch_;
  Paged<int> local_;  // global id -> id in the current tile
};

}  // namespace

void build_tiled(const SiteList& sites, const Point& origin, const Box& root, const BuildOptions& opt, double tau,
                 BuildStats& st, const PartSink& sink, const ProgressFn& progress) {
  Plan plan(sites, origin, root, opt, tau);
  const std::size_t per = plan.per, ntiles = plan.ntiles;
  const std::vector<Box>& tasks = plan.tasks;
  std::vector<std::vector<int>> halo(per * per);
  // A tile's end — its pieces collected and joined, then handed to the sink — runs on a thread
  // of its own while the next tile is gathered and built: done in line, it left all cores but
  // one idle. Tiles still reach the sink one at a time and in order. The workers' raw pieces
  // live in two sets of buffers, one for the tile being built and one for the tile ending, and
  // the joined pieces in one; all are kept from tile to tile: fresh ones would be fresh pages,
  // and faulting them in cost about a tenth of the build.
  const bool overlap = worker_count(2, opt.threads) > 1;
  const std::size_t nw = worker_count(per * per, opt.threads);
  std::array<std::vector<std::vector<Piece>>, 2> raw{std::vector<std::vector<Piece>>(nw),
                                                     std::vector<std::vector<Piece>>(nw)};
  std::vector<Piece> part;
  BuildStats ended;  // what collect() counts, written by the ending tile's thread
  std::thread ending;
  std::exception_ptr failed;
  auto wait_for_ending = [&] {
    if (ending.joinable()) ending.join();
    if (failed) std::rethrow_exception(std::exchange(failed, nullptr));
  };
  int slot = 0;
  ProgressMeter meter(progress, "building the diagram", ntiles * ntiles * per * per);
  try {
    for (std::size_t tj = 0; tj < ntiles; ++tj)
      for (std::size_t ti = 0; ti < ntiles; ++ti) {
        auto task_of = [&](std::size_t k) { return plan.task_of(tj, ti, k); };
        std::vector<int> ids = plan.gather_tile(tj, ti, halo);
        if (ids.size() < 2) {
          meter.step(per * per);
          continue;
        }
        auto model = std::make_unique<const Model>(sites, std::move(ids), opt, tau, origin);
        std::vector<Builder> workers(nw, Builder(*model, root, nullptr));
        for (std::size_t w = 0; w < nw; ++w) workers[w].out.swap(raw[slot][w]);
        parallel_for(per * per, opt.threads, [&](unsigned w, std::size_t k) {
          workers[w].process(tasks[task_of(k)], halo[k]);
          meter.step();
        });
        const Box frame = plan.frame(tj, ti);
        ++st.tiles;
        st.tasks += per * per;
        st.largest_tile_sites = std::max(st.largest_tile_sites, model->S.size());
        wait_for_ending();  // the previous tile's pieces reach the sink first
        auto end_tile = [&, model = std::move(model), workers = std::move(workers), frame, s = slot]() mutable {
          try {
            collect(*model, workers, ended, part);
            for (std::size_t w = 0; w < nw; ++w) raw[s][w].swap(workers[w].out), raw[s][w].clear();
            workers.clear();  // they refer to the model
            model.reset();
            sink(part, frame);
          } catch (...) {
            failed = std::current_exception();
          }
        };
        if (overlap) ending = std::thread(std::move(end_tile));
        else end_tile();
        slot ^= 1;
      }
    wait_for_ending();
  } catch (...) {
    if (ending.joinable()) ending.join();
    throw;
  }
  add_work(st, ended);
}

void sweep_tiled(const SiteList& sites, const Point& origin, const Box& root, const BuildOptions& opt, double tau,
                 BuildStats& st, const PartPrepare& prepare, const PreparedSink& sink, const ProgressFn& progress,
                 const Box* clip, std::vector<Piece>* far) {
  Plan plan(sites, origin, root, opt, tau, true);
  const std::size_t count = plan.ntiles * plan.ntiles;
  const unsigned nw = worker_count(count, opt.threads);
  // The far field: job 0, taken first, as it is one of the longest; the tiles are jobs 1 to count.
  const std::size_t first = far ? 1 : 0;
  auto far_field = [&](unsigned w) {
    std::vector<int> ids = plan.far_field_sites(w);
    if (ids.size() < 2) {  // one site owns the whole border: let the sweep decide among all
      ids.resize(sites.size());
      for (std::size_t i = 0; i < ids.size(); ++i) ids[i] = int(i);
    }
    const Box hole = plan.layout_root();
    *far = sweep_part(sites, ids, *clip, &hole);
  };
  ProgressMeter meter(progress, "building the diagram", count);
  // Each worker takes the next tile, gathers its sites and sweeps it; whoever finds the next
  // tile in order ready hands it and those after it to the sink, one thread at a time. At most
  // `window` tiles are ahead of the sink: their pieces are what the pass holds at once.
  const std::size_t window = 2 * std::size_t(nw);
  struct Slot {
    bool ready = false;
    std::size_t sites = 0;
    Box frame;
    std::vector<Piece> part;
    std::any prepared;
  };
  std::vector<Slot> slots(window);
  std::mutex m;
  std::condition_variable cv;
  std::size_t delivered = 0;
  bool delivering = false, stop = false;
  parallel_for(count + first, opt.threads, [&](unsigned w, std::size_t job) {
    if (job < first) {
      try {
        far_field(w);
      } catch (...) {
        std::lock_guard<std::mutex> lock(m);
        stop = true;
        cv.notify_all();
        throw;
      }
      return;
    }
    const std::size_t i = job - first;
    try {
      {
        std::unique_lock<std::mutex> lock(m);
        cv.wait(lock, [&] { return i < delivered + window || stop; });
        if (stop) return;
      }
      const std::size_t tj = i / plan.ntiles, ti = i % plan.ntiles;
      const std::vector<int> ids = plan.sweep_sites(tj, ti, w);
      Slot done{true, ids.size(), plan.layout_frame(tj, ti), {}, {}};
      if (ids.size() >= 2) {
        done.part = sweep_part(sites, ids, done.frame);
        if (prepare) done.prepared = prepare(done.part, done.frame);
      }
      meter.step();
      std::unique_lock<std::mutex> lock(m);
      slots[i % window] = std::move(done);
      if (delivering) return;  // the thread handing tiles over will find it
      delivering = true;
      while (delivered < count && slots[delivered % window].ready) {
        Slot s = std::move(slots[delivered % window]);
        slots[delivered % window] = Slot{};
        lock.unlock();
        if (s.sites >= 2) {  // as build_tiled: a tile of fewer sites has no pieces
          ++st.tiles;
          st.tasks += plan.per * plan.per;
          st.largest_tile_sites = std::max(st.largest_tile_sites, s.sites);
          sink(s.part, s.frame, s.prepared);
        }
        lock.lock();
        ++delivered;
        cv.notify_all();
      }
      delivering = false;
    } catch (...) {
      std::lock_guard<std::mutex> lock(m);
      stop = true;
      cv.notify_all();
      throw;
    }
  });
}

void build_tiled_jobs(const SiteList& sites, const Point& origin, const Box& root, const BuildOptions& opt,
                      double tau, BuildStats& st, const JobSink& sink, const TileRunner& runner,
                      const ProgressFn& progress, std::uint32_t prepare) {
  // The sweep's tiles as sweep_tiled gathers them (its finer plan, a frame in layout
  // coordinates, no tasks); the subdivision's with their tasks and halos.
  const bool sweep = opt.sweep;
  Plan plan(sites, origin, root, opt, tau, sweep);
  const std::size_t count = plan.ntiles * plan.ntiles;
  ProgressMeter meter(progress, "building the diagram's tiles", count);
  // Tile i (row by row, as the local pass) as a job's bytes; empty if it has no pieces.
  auto make = [&](unsigned worker, std::size_t i) -> std::string {
    const std::size_t tj = i / plan.ntiles, ti = i % plan.ntiles;
    TileJob job;
    job.ids = sweep ? plan.sweep_sites(tj, ti, worker) : plan.gather_tile(tj, ti, job.halos);
    if (job.ids.size() < 2) return {};  // as the local pass: no pieces
    job.opt = opt;
    job.origin = origin, job.root = root, job.tau = tau;
    job.frame = sweep ? plan.layout_frame(tj, ti) : plan.frame(tj, ti);
    job.sites.reserve(job.ids.size());
    for (int t : job.ids) job.sites.push_back(sites[t]);
    if (!sweep)
      for (std::size_t k = 0; k < plan.per * plan.per; ++k) job.tasks.push_back(plan.tasks[plan.task_of(tj, ti, k)]);
    job.prepare = prepare;
    if (prepare) {
      for (int t : job.ids) {
        const Site& v = sites[t];
        if (!v.is_point()) continue;
        for (std::int32_t k : {v.end0, v.end1})
          if (k >= 0 && !std::binary_search(job.ids.begin(), job.ids.end(), k)) job.near_ids.push_back(k);
      }
      std::sort(job.near_ids.begin(), job.near_ids.end());
      job.near_ids.erase(std::unique(job.near_ids.begin(), job.near_ids.end()), job.near_ids.end());
      for (int t : job.near_ids) job.near.push_back(sites[t]);
    }
    return encode_job(job);
  };
  // The sweep's tiles are planned ahead on the host's other threads (sweep_sites keeps a
  // scratch a worker), while the runner's thread sends and gathers: on a farm this host plans
  // for every worker. The subdivision's gather_tile shares its scratch, so its jobs are planned
  // as they are taken; so are all with one thread.
  const unsigned planners = sweep ? worker_count(count, opt.threads) - 1 : 0;
  Ahead<std::string> ahead(count, planners, 2 * std::size_t(planners), make);
  std::size_t planned = 0;
  auto next = [&](std::string& bytes) {
    while (ahead.take(bytes)) {
      ++planned;
      if (!bytes.empty()) return true;
      meter.step();
    }
    return false;
  };
  std::size_t taken = 0, received = 0;
  auto counted_next = [&](std::string& bytes) {
    const bool more = next(bytes);
    taken += more;
    return more;
  };
  BuildStats work;
  auto done = [&](std::string_view bytes) {
    TileResult r = decode_result(bytes);
    ++received;
    meter.step();
    st.tiles += r.stats.tiles;
    st.tasks += sweep ? plan.per * plan.per : r.stats.tasks;  // as sweep_tiled counts them
    st.largest_tile_sites = std::max(st.largest_tile_sites, r.stats.largest_tile_sites);
    add_work(work, r.stats);
    sink(r.pieces, r.frame, r.prepared);
  };
  runner(counted_next, done);
  // A runner that stops early would leave tiles out: never a partial diagram.
  if (received != taken || planned < count)
    throw std::runtime_error("the tile runner returned " + std::to_string(received) + " results for " +
                             std::to_string(taken) + " jobs taken, of all the tiles' jobs");
  add_work(st, work);
}

}  // namespace linf::detail
