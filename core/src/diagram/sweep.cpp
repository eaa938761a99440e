// The sweep-line builder (sweep.hpp): Boost.Polygon's voronoi_builder with our predicates
// (sweep/predicates.hpp) records the diagram's topology as half-edges; each edge is then the
// part of its two sites' bisector (sweep/bisector.hpp) between its vertices, cut where the
// bisector bends and clipped to the box.
#include "linf/diagram/sweep.hpp"

#include <algorithm>
#include <boost/polygon/voronoi_builder.hpp>
#include <cmath>
#include <deque>
#include <stdexcept>
#include <tuple>

#include "linf/diagram/builder.hpp"
#include "diagram/sweep/bisector.hpp"
#include "diagram/sweep/predicates.hpp"

namespace linf {
namespace {

using sweep::Ratio;

// What the builder reports (the OUTPUT interface of voronoi_builder::construct): half-edges
// in twin pairs, each with its cell's site and the vertex it starts from; a cell lies on the
// left of its half-edges.
struct Topology {
  struct Half {
    std::int32_t site;
    std::int32_t vertex0 = -1;
  };
  std::deque<Half> halves;  // twins are 2i and 2i + 1; a deque keeps them in place
  std::vector<Vec2> vertices;

  void _reserve(std::size_t) {}
  template <typename Site>
  void _process_single_site(const Site&) {}
  template <typename Site>
  std::pair<void*, void*> _insert_new_edge(const Site& s1, const Site& s2) {
    halves.push_back({std::int32_t(s1.initial_index())});
    Half* h1 = &halves.back();
    halves.push_back({std::int32_t(s2.initial_index())});
    return {h1, &halves.back()};
  }
  template <typename Site, typename Circle>
  std::pair<void*, void*> _insert_new_edge(const Site& s1, const Site& s3, const Circle& c, void* e12, void* e23) {
    const std::int32_t v = std::int32_t(vertices.size());
    vertices.push_back({c.x().limit(), c.y().limit()});
    static_cast<Half*>(e12)->vertex0 = v;
    static_cast<Half*>(e23)->vertex0 = v;
    auto e = _insert_new_edge(s1, s3);
    static_cast<Half*>(e.second)->vertex0 = v;
    return e;
  }
  void _build() {}
};

// The part of segment p-q inside the box (Liang-Barsky); false if none.
bool clip_segment(Vec2& p, Vec2& q, const Box& b) {
  double t0 = 0, t1 = 1;
  const double dx = q.x - p.x, dy = q.y - p.y;
  auto edge = [&](double num, double den) {  // keep where num + t den >= 0
    if (den == 0) return num >= 0;
    const double t = -num / den;
    if (den > 0) t0 = std::max(t0, t);
    else t1 = std::min(t1, t);
    return t0 <= t1;
  };
  if (!edge(p.x - b.x1, dx) || !edge(b.x2 - p.x, -dx) || !edge(p.y - b.y1, dy) || !edge(b.y2 - p.y, -dy)) return false;
  const Vec2 a{p.x + t0 * dx, p.y + t0 * dy}, c{p.x + t1 * dx, p.y + t1 * dy};
  p = a, q = c;
  return t1 > t0;
}

double linf_distance(const Vec2& v, const Point& s) {
  return std::max(std::fabs(v.x - double(s.x)), std::fabs(v.y - double(s.y)));
}

}  // namespace

bool sweep_handles(const Sites& sites) {
  for (std::size_t i = 0; i < sites.sites.size(); ++i)
    if (!sites.sites[i].is_point()) return false;
  return true;
}

std::vector<Piece> sweep_pieces(const Sites& sites, const Box& clip, SweepStats* stats) {
  if (!sweep_handles(sites)) throw std::invalid_argument("sweep builder: segment sites are not supported yet");
  const SiteList& S = sites.sites;
  boost::polygon::voronoi_builder<std::int32_t, sweep::CoordinateTraits, sweep::Predicates> vb;
  for (std::size_t i = 0; i < S.size(); ++i) vb.insert_point(std::int32_t(S[i].a.x), std::int32_t(S[i].a.y));
  Topology topo;
  vb.construct(&topo);

  // Far enough along any bisector to be outside the box: the bisectors' slopes are at most 1.
  const double reach = 2 * (clip.x2 - clip.x1 + clip.y2 - clip.y1) + std::fabs(clip.x1) + std::fabs(clip.x2) +
                       std::fabs(clip.y1) + std::fabs(clip.y2) + 1;
  std::vector<Piece> out;
  struct Span {
    std::size_t first, last;
  };
  std::vector<Span> spans;  // each edge's pieces in `out`
  for (std::size_t e = 0; e + 1 < topo.halves.size(); e += 2) {
    const Topology::Half &h = topo.halves[e], &g = topo.halves[e + 1];
    const Point &s = S[h.site].a, &t = S[g.site].a;
    const sweep::PointBisector b(s, t);
    double from, to;  // the edge's parameter range, walked from h's vertex to g's
    if (h.vertex0 >= 0 && g.vertex0 >= 0) {
      from = b.param(topo.vertices[h.vertex0]), to = b.param(topo.vertices[g.vertex0]);
    } else if (h.vertex0 >= 0 || g.vertex0 >= 0) {
      // The edge runs from its vertex to infinity with the vertex's half-edge's site on its left.
      const bool from_h = h.vertex0 >= 0;
      const Point &left = from_h ? s : t, &right = from_h ? t : s;
      from = b.param(topo.vertices[from_h ? h.vertex0 : g.vertex0]);
      to = sweep::PointBisector::left_of_growing(left, right) ? from + reach : from - reach;
    } else {
      from = -reach, to = reach;
    }
    if (from > to) std::swap(from, to);
    double cuts[4] = {from, 0, 0, to};
    int n = 1;
    if (b.half > 0 && b.slope != 0)  // bends; else the bisector is one straight line
      for (double c : {b.mid_p - b.half, b.mid_p + b.half})
        if (c > from && c < to) cuts[n++] = c;
    cuts[n++] = to;
    const std::size_t first = out.size();
    for (int i = 0; i + 1 < n; ++i) {
      Vec2 p = b.point(cuts[i]), q = b.point(cuts[i + 1]);
      if (!clip_segment(p, q, clip)) continue;
      if (p.x == q.x && p.y == q.y) continue;
      Piece pc;
      pc.p = p, pc.q = q;
      pc.a = std::min(h.site, g.site), pc.b = std::max(h.site, g.site);
      pc.d1 = linf_distance(p, s), pc.d2 = linf_distance(q, s);
      out.push_back(pc);
    }
    if (out.size() > first) spans.push_back({first, out.size()});
  }
  // In join_order, as build_pieces leaves them: the edges sorted by owner pair (a pair has one
  // edge, so nothing is joined unless two edges share a pair), each edge's few pieces sorted.
  std::sort(spans.begin(), spans.end(), [&](const Span& x, const Span& y) {
    return std::tie(out[x.first].a, out[x.first].b) < std::tie(out[y.first].a, out[y.first].b);
  });
  std::vector<Piece> joined, run;
  joined.reserve(out.size());
  for (std::size_t i = 0; i < spans.size();) {
    std::size_t j = i + 1;
    const Piece& head = out[spans[i].first];
    while (j < spans.size() && out[spans[j].first].a == head.a && out[spans[j].first].b == head.b) ++j;
    run.clear();
    for (std::size_t k = i; k < j; ++k) run.insert(run.end(), out.begin() + spans[k].first, out.begin() + spans[k].last);
    std::sort(run.begin(), run.end(), join_order);
    if (j > i + 1) join_pair(run);
    joined.insert(joined.end(), run.begin(), run.end());
    i = j;
  }
  if (stats) stats->site_events = S.size(), stats->vertices = topo.vertices.size(), stats->edges = topo.halves.size() / 2;
  return joined;
}

}  // namespace linf
