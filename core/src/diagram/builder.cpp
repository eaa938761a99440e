#include "linf/diagram/builder.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <tuple>

#include "far_field.hpp"
#include "linf/diagram/sweep.hpp"
#include "subdivision.hpp"
#include "tiles.hpp"
#include "util/huge_pages.hpp"
#include "util/progress_meter.hpp"

namespace linf {

namespace {
using namespace detail;

// One pass of the subdivision over `root` with the sites `ids`, skipping boxes inside `hole`
// and the parts of pieces there: the far field, or everything in one pass. The top levels,
// breadth first, become the workers' tasks, counted as the `stage`'s parts. Boxes and pieces
// are relative to `origin`.
std::vector<Piece> run(const SiteList& sites, const Point& origin, std::vector<int> ids, const Box& root,
                       const Box* hole, const BuildOptions& opt, double tau, BuildStats& st, const ProgressFn& progress,
                       const char* stage) {
  const Model model(sites, std::move(ids), opt, tau, origin);
  std::vector<int> all(model.S.size());
  for (std::size_t i = 0; i < all.size(); ++i) all[i] = int(i);
  std::vector<std::pair<Box, std::vector<int>>> tasks, next;
  tasks.emplace_back(root, std::move(all));
  const Builder top(model, root, hole);
  for (int level = 0; level < 3; ++level) {
    next.clear();
    for (auto& [b, c] : tasks) {
      for (const Box& q : quarters(b)) {
        if (hole && q.x1 >= hole->x1 && q.x2 <= hole->x2 && q.y1 >= hole->y1 && q.y2 <= hole->y2) continue;
        std::vector<int> keep = top.candidates(q, c);
        if (keep.size() > 1) next.emplace_back(q, std::move(keep));
      }
    }
    tasks.swap(next);
  }
  std::vector<Builder> workers(worker_count(tasks.size(), opt.threads), Builder(model, root, hole));
  ProgressMeter meter(progress, stage, tasks.size());
  parallel_for(tasks.size(), opt.threads, [&](unsigned w, std::size_t i) {
    workers[w].process(tasks[i].first, tasks[i].second);
    meter.step();
  });
  std::vector<Piece> part;
  collect(model, workers, st, part);
  return part;
}

// Rounding allowance of the pruning decisions, from the coordinate scale relative to the
// origin (the local clip box `c` holds every site): one value for the whole input, whatever
// the tiles.
double allowance(const Box& c) {
  return 1e-12 * std::max({1.0, std::fabs(c.x1), std::fabs(c.x2), std::fabs(c.y1), std::fabs(c.y2)});
}

Box shifted(const Box& b, double dx, double dy) { return {b.x1 + dx, b.y1 + dy, b.x2 + dx, b.y2 + dy}; }

// Pieces from the builder's coordinates back to the layout's (shifted, bounds.hpp).
void to_layout(std::vector<Piece>& part, const Point& o) {
  const double dx = double(o.x), dy = double(o.y);
  for (Piece& p : part) p.p.x += dx, p.p.y += dy, p.q.x += dx, p.q.y += dy;
}

}  // namespace

void build_parts(const Sites& sites, const Box& clip, const BuildOptions& opt, BuildStats* stats,
                 const PartSink& sink) {
  build_parts(sites, clip, opt, stats, sink, TileRunner{});
}

void build_parts(const Sites& sites, const Box& clip, const BuildOptions& opt, BuildStats* stats,
                 const PartSink& sink, const TileRunner& runner, const ProgressFn& progress) {
  build_parts(sites, clip, opt, stats, PartPrepare{},
              [&](std::vector<Piece>& part, const Box& frame, std::any&) { sink(part, frame); }, runner, progress, 0);
}

void build_parts(const Sites& sites, const Box& clip, const BuildOptions& opt, BuildStats* stats,
                 const PartPrepare& prepare, const PreparedSink& prepared_sink, const TileRunner& runner,
                 const ProgressFn& progress, std::uint32_t remote) {
  // Where a part is not prepared on the thread that built it, it is prepared here, unless the
  // tile's task prepared it (`done`: its bytes, handed on as a std::string).
  auto deliver = [&](std::vector<Piece>& part, const Box& frame, std::string* done) {
    std::any prepared;
    if (done && !done->empty()) prepared = std::move(*done);
    else if (prepare) prepared = prepare(part, frame);
    prepared_sink(part, frame, prepared);
  };
  const PartSink sink = [&](std::vector<Piece>& part, const Box& frame) { deliver(part, frame, nullptr); };
  if (sites.sites.size() < 2) return;
  Coord ox1 = INT64_MAX, oy1 = INT64_MAX, ox2 = INT64_MIN, oy2 = INT64_MIN;
  for (const Site& t : sites.sites) {
    ox1 = std::min({ox1, t.a.x, t.b.x}), ox2 = std::max({ox2, t.a.x, t.b.x});
    oy1 = std::min({oy1, t.a.y, t.b.y}), oy2 = std::max({oy2, t.a.y, t.b.y});
  }
  const Point origin{(ox1 + ox2) / 2, (oy1 + oy2) / 2};
  const Box lclip = shifted(clip, -double(origin.x), -double(origin.y));
  const double tau = allowance(lclip);
  std::vector<int> all(sites.sites.size());
  for (std::size_t i = 0; i < all.size(); ++i) all[i] = int(i);
  BuildStats st;
  // Two passes. Beyond the sites' bounding box lies the far field, where large groups of
  // sites tie in L-inf and boxes stay crowded (most of the work in one pass over the clip box).
  // Only sites that are L-inf nearest (tied or not) at a point of the inner box's border can
  // own a point outside it (far_field.hpp). So the inner box is built with every site, the far
  // field with those sites only.
  // The margin is off the integer and half-integer grid, so that no piece runs along the
  // inner box's border, and dyadic (5/16), so that halving boxes stays exact.
  const double x1 = double(ox1 - origin.x), y1 = double(oy1 - origin.y), x2 = double(ox2 - origin.x),
               y2 = double(oy2 - origin.y);
  const double margin = std::floor(std::max({x2 - x1, y2 - y1, 64.0}) / 64) + 0.3125;
  const Box inner{x1 - margin, y1 - margin, x2 + margin, y2 + margin};
  const bool sweep = opt.sweep;
  const bool one_pass = !opt.far_field_pass || inner.x1 <= lclip.x1 || inner.y1 <= lclip.y1 ||
                        inner.x2 >= lclip.x2 || inner.y2 >= lclip.y2;
  if (sweep && (one_pass || opt.tile_size == 0)) {  // one tile: the whole layer in one sweep
    if (progress) progress("building the diagram", 0, 0);
    std::vector<Piece> part = sweep_part(sites.sites, all, clip);
    st.tiles = 1, st.largest_tile_sites = all.size();
    if (stats) *stats = st;
    sink(part, clip);
    return;
  }
  if (one_pass) {
    std::vector<Piece> part =
        run(sites.sites, origin, all, lclip, nullptr, opt, tau, st, progress, "building the diagram");
    if (stats) *stats = st;
    to_layout(part, origin);
    sink(part, clip);
    return;
  }
  std::vector<int> border;
  std::vector<BorderMark> marks;
  const double eps = 1e-9 * std::max({1.0, std::fabs(inner.x1), std::fabs(inner.x2), std::fabs(inner.y1),
                                      std::fabs(inner.y2)});
  auto on_border = [&](const Vec2& v) {
    return std::fabs(v.x - inner.x1) <= eps || std::fabs(v.x - inner.x2) <= eps || std::fabs(v.y - inner.y1) <= eps ||
           std::fabs(v.y - inner.y2) <= eps;
  };
  // The border's marks and owners from a part's pieces, `o` their offset from the builder's
  // coordinates (the sweep's parts come in layout coordinates: its vertices as it computed them).
  auto note_border = [&](const std::vector<Piece>& part, const Vec2& o) {
    for (const Piece& p : part) {
      const Vec2 u{p.p.x - o.x, p.p.y - o.y}, v{p.q.x - o.x, p.q.y - o.y};
      const bool at_u = on_border(u), at_v = on_border(v);
      if (at_u) marks.push_back({u, p.d1});
      if (at_v) marks.push_back({v, p.d2});
      if (at_u || at_v) border.push_back(p.a), border.push_back(p.b);
    }
  };
  const Vec2 o{double(origin.x), double(origin.y)};
  const JobSink inner_job = [&](std::vector<Piece>& part, const Box& frame, std::string& done) {
    note_border(part, {0, 0});
    to_layout(part, origin);
    deliver(part, shifted(frame, o.x, o.y), &done);
  };
  const JobSink swept_job = [&](std::vector<Piece>& part, const Box& frame, std::string& done) {
    note_border(part, o);
    deliver(part, frame, &done);
  };
  const PartSink inner_sink = [&](std::vector<Piece>& part, const Box& frame) {
    std::string none;
    inner_job(part, frame, none);
  };
  if (sweep && !runner) {
    // The far field is swept beside the tiles, from its own walk along the inner box's border
    // (tiles.hpp): nothing of the tiles is waited for, and it costs no thread time at the end.
    std::vector<Piece> far;
    sweep_tiled(sites.sites, origin, inner, opt, tau, st, prepare, prepared_sink, progress, &clip, &far);
    if (progress) progress("building the far field", 0, 0);
    if (stats) *stats = st;
    sink(far, shifted(inner, o.x, o.y));
    return;
  }
  // The tiles here or by the runner (same parts, same order); the far field is built here.
  // A task prepares a sweep's tile only: its pieces come in layout coordinates, as the sink
  // takes them (the subdivision's are shifted here first).
  if (runner) build_tiled_jobs(sites.sites, origin, inner, opt, tau, st, sweep ? swept_job : inner_job, runner, progress,
                               sweep ? remote : 0);
  else build_tiled(sites.sites, origin, inner, opt, tau, st, inner_sink, progress);
  // The border's owners, and the sites L-inf-tied with them there (far_field.hpp).
  std::vector<int> near = far_field_sites(sites.sites, origin, inner, marks);
  border.insert(border.end(), near.begin(), near.end());
  std::sort(border.begin(), border.end());
  border.erase(std::unique(border.begin(), border.end()), border.end());
  if (border.size() < 2) border = all;  // one site owns the whole border: let the pass decide
  if (sweep) {
    for (std::size_t k = 0, n = border.size(); k < n; ++k)  // the sweep takes a segment with its ends
      if (!sites.sites[border[k]].is_point())
        border.push_back(sites.sites[border[k]].end0), border.push_back(sites.sites[border[k]].end1);
    std::sort(border.begin(), border.end());
    border.erase(std::unique(border.begin(), border.end()), border.end());
    if (progress) progress("building the far field", 0, 0);
    const Box hole = shifted(inner, o.x, o.y);
    std::vector<Piece> far = sweep_part(sites.sites, border, clip, &hole);
    if (stats) *stats = st;
    sink(far, hole);
    return;
  }
  std::vector<Piece> far =
      run(sites.sites, origin, std::move(border), lclip, &inner, opt, tau, st, progress,
          "building the far field");
  if (stats) *stats = st;
  // The far field's pieces lie outside the inner box; its vertices on that box are shared.
  to_layout(far, origin);
  sink(far, shifted(inner, double(origin.x), double(origin.y)));
}

bool join_order(const Piece& x, const Piece& y) { return detail::piece_order(x, y); }

void join_pair(std::vector<Piece>& pieces) {
  std::vector<char> used;
  std::vector<Piece> joined;
  detail::join_run(pieces.data(), pieces.data() + pieces.size(), used, joined);
  pieces.swap(joined);
}

std::vector<Piece> build_pieces(const Sites& sites, const Box& clip, const BuildOptions& opt, BuildStats* stats,
                               const ProgressFn& progress) {
  // Every tile's joined pieces are appended to one vector with room for the usual 3-3.5 pieces
  // a site reserved at once: its pages are committed only as pieces are written, so nothing is
  // ever copied or held twice (a growing vector would hold up to three times the pieces while
  // it reallocates, a concatenation of per-tile vectors twice).
  std::vector<Piece> raw;
  if (sites.sites.size() < 2) return raw;
  raw.reserve(std::size_t(4.5 * double(sites.sites.size())) + 64);
  huge_pages(raw);
  build_parts(sites, clip, opt, stats,
              [&](std::vector<Piece>& part, const Box&) { raw.insert(raw.end(), part.begin(), part.end()); },
              TileRunner{}, progress);
  join_pieces(raw, opt.threads);
  return raw;
}

}  // namespace linf
