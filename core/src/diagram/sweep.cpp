// The sweep-line builder (sweep.hpp): Boost.Polygon's voronoi_builder with our predicates
// (sweep/predicates.hpp) records the diagram's topology as half-edges; each edge is then the
// part of its two sites' bisector (sweep/bisector.hpp) between its vertices, cut where the
// bisector bends and clipped to the box.
#include "linf/diagram/sweep.hpp"

#include <algorithm>
#include <boost/polygon/voronoi_builder.hpp>
#include <array>
#include <cmath>
#include <cstdlib>
#include <deque>
#include <stdexcept>
#include <string>
#include <tuple>

#include "linf/diagram/builder.hpp"
#include "linf/geometry/distance.hpp"
#include "diagram/sweep/bisector.hpp"
#include "diagram/sweep/predicates.hpp"
#include "diagram/zero_width.hpp"
#include "util/huge_pages.hpp"

namespace linf {
namespace {

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
  // Our site of a site event, by its insertion index (Boost's initial_index): a segment's or a
  // lone point's own; a segment end's the point site there (the segment's end0 or end1, or
  // where a segment was cut, the point it was cut at; Boost keeps one event of a place where
  // several segments end, any of them). Point sites at one place are one site, the first
  // (same_place), whichever event stands for them.
  std::vector<std::int32_t> inserted, start, end, same_place;
  template <typename Site>
  std::int32_t site_of(const Site& e) const {
    const std::size_t k = e.initial_index();
    if (e.is_segment()) return inserted[k];
    switch (e.source_category()) {
      case boost::polygon::SOURCE_CATEGORY_SEGMENT_START_POINT: return same_place[start[k]];
      case boost::polygon::SOURCE_CATEGORY_SEGMENT_END_POINT: return same_place[end[k]];
      default: return same_place[inserted[k]];
    }
  }

  void _reserve(std::size_t site_events) { vertices.reserve(2 * site_events); }  // as Boost's diagram: at most 2n
  template <typename Site>
  void _process_single_site(const Site&) {}
  // Boost calls these as it processes an event, before it asks for the balls of the arcs that
  // event has made neighbours: they tell the predicates where the sweep is (ball.hpp).
  template <typename Site>
  std::pair<void*, void*> _insert_new_edge(const Site& s1, const Site& s2) {  // s2: the site event
    sweep::sweep_at() = {true, s2.x0()};
    return edge(s1, s2);
  }
  template <typename Site>
  std::pair<void*, void*> edge(const Site& s1, const Site& s2) {
    halves.push_back({site_of(s1)});
    Half* h1 = &halves.back();
    halves.push_back({site_of(s2)});
    return {h1, &halves.back()};
  }
  template <typename Site, typename Circle>
  std::pair<void*, void*> _insert_new_edge(const Site& s1, const Site& s3, const Circle& c, void* e12, void* e23) {
    const std::int32_t v = std::int32_t(vertices.size());
    vertices.push_back({c.x_limit(), c.y_limit()});
    static_cast<Half*>(e12)->vertex0 = v;
    static_cast<Half*>(e23)->vertex0 = v;
    sweep::sweep_at() = {false, 0};
    sweep::sweep_at_circle<typename std::decay_t<decltype(c.lower_x())>::Int>() = c.lower_x();
    auto e = edge(s1, s3);
    static_cast<Half*>(e.second)->vertex0 = v;
    return e;
  }
  void _build() {}
};

// The part of segment p-q inside the box (Liang-Barsky); false if none. An end cut at a side
// lies exactly on it, and on an axis-parallel or diagonal segment (every L-inf bisector piece
// of Manhattan sites) the other coordinate follows exactly: the same cut of the same line from
// another of its points (a tile's, the far field's) gives the same bits. A piece of a slanted
// site's bisector comes with its line's equation (exact in integers), which gives the other
// coordinate from the side alone, equally independent of p and q: one of another slope (with
// 45-degree sites: 1/3, 3), and a diagonal one whose p is rounded from a rational (a ray from a
// bend of a point's U with a steep edge, or the diagonal through a slanted segment's own end
// from a vertex of the diagram).
bool clip_segment(Vec2& p, Vec2& q, const Box& b, const sweep::Line* eq = nullptr) {
  double t0 = 0, t1 = 1;
  int s0 = -1, s1 = -1;  // the sides that cut: 0 x = x1, 1 x = x2, 2 y = y1, 3 y = y2
  const double dx = q.x - p.x, dy = q.y - p.y;
  auto edge = [&](double num, double den, int side) {  // keep where num + t den >= 0
    if (den == 0) return num >= 0;
    const double t = -num / den;
    if (den > 0 && t > t0) t0 = t, s0 = side;
    if (den < 0 && t < t1) t1 = t, s1 = side;
    return t0 <= t1;
  };
  if (!edge(p.x - b.x1, dx, 0) || !edge(b.x2 - p.x, -dx, 1) || !edge(p.y - b.y1, dy, 2) || !edge(b.y2 - p.y, -dy, 3))
    return false;
  const bool exact = dx == 0 || dy == 0 || std::fabs(dx) == std::fabs(dy);
  auto at = [&](double t, int side) -> Vec2 {
    if (side < 0) return {p.x + t * dx, p.y + t * dy};
    const double line = side == 0 ? b.x1 : side == 1 ? b.x2 : side == 2 ? b.y1 : b.y2;
    if (eq) return side < 2 ? Vec2{line, eq->y_at(line)} : Vec2{eq->x_at(line), line};
    if (!exact) return side < 2 ? Vec2{line, p.y + t * dy} : Vec2{p.x + t * dx, line};
    if (side < 2) return {line, dy == 0 ? p.y : p.y + (line - p.x) * (dy / dx)};  // dy / dx is +-1
    return {dx == 0 ? p.x : p.x + (line - p.y) * (dx / dy), line};
  };
  const Vec2 a = s0 < 0 ? p : at(t0, s0), c = s1 < 0 ? q : at(t1, s1);
  p = a, q = c;
  return t1 > t0;
}

// The parts of segment p-q outside the box `hole` (none, one or two), each handed to f.
template <typename F>
void outside(const Vec2& p, const Vec2& q, const Box& hole, F&& f, const sweep::Line* line) {
  Vec2 a = p, b = q;
  if (!clip_segment(a, b, hole, line)) return f(p, q);
  if (!(a.x == p.x && a.y == p.y)) f(p, a);
  if (!(b.x == q.x && b.y == q.y)) f(b, q);
}

// L-inf distance from v to a site: a point, or a segment (closed).
double linf_distance(const Vec2& v, const Site& s) {
  if (sweep::is_diagonal(s)) return dist_segment(v.x, v.y, s.a, s.b);
  const double dx = std::max({double(std::min(s.a.x, s.b.x)) - v.x, 0.0, v.x - double(std::max(s.a.x, s.b.x))});
  const double dy = std::max({double(std::min(s.a.y, s.b.y)) - v.y, 0.0, v.y - double(std::max(s.a.y, s.b.y))});
  return std::max(dx, dy);
}

// A segment neither axis-parallel nor at 45 degrees: its balls' coefficients outgrow int64.
bool steep(const Site& s) {
  return sweep::is_diagonal(s) && std::llabs(std::int64_t(s.b.x) - s.a.x) != std::llabs(std::int64_t(s.b.y) - s.a.y);
}

}  // namespace

bool sweep_handles(const Sites&) { return true; }

namespace {

// For each segment of S, the point sites strictly inside it (one of each place, as same_place
// has them), ordered from its end0 to its end1; empty unless S has a slanted segment (a
// Manhattan layer's merged polygons meet only along shared stretches, so never so). Points by
// their line through each octilinear direction, then along it: one binary search a segment.
// A segment of another slope holds lattice points only every (dx, dy) / gcd: those, or the
// points within its x-span, whichever are fewer, are looked up.
std::vector<std::vector<std::int32_t>> touching_points(const SiteList& S, const std::vector<std::int32_t>& points,
                                                       const std::vector<std::int32_t>& same_place, bool diagonal) {
  if (!diagonal) return {};
  // Direction d: 0 horizontal (line y, along x), 1 vertical (x, y), 2 up-right (x - y, x),
  // 3 down-right (x + y, x).
  auto key = [](int d, const Point& p) -> std::pair<std::int64_t, std::int64_t> {
    switch (d) {
      case 0: return {p.y, p.x};
      case 1: return {p.x, p.y};
      case 2: return {std::int64_t(p.x) - p.y, p.x};
      default: return {std::int64_t(p.x) + p.y, p.x};
    }
  };
  std::vector<std::pair<std::pair<std::int64_t, std::int64_t>, std::int32_t>> by[4];
  for (std::int32_t p : points)
    if (same_place[p] == p)
      for (int d = 0; d < 4; ++d) by[d].push_back({key(d, S[p].a), p});
  for (auto& v : by) std::sort(v.begin(), v.end());
  const auto& by_x = by[1];  // (x, y)
  std::vector<std::vector<std::int32_t>> cuts(S.size());
  for (std::size_t i = 0; i < S.size(); ++i) {
    const Site& s = S[i];
    if (s.is_point()) continue;
    if (steep(s)) {
      const std::int64_t dx = std::int64_t(s.b.x) - s.a.x, dy = std::int64_t(s.b.y) - s.a.y;
      const std::int64_t g = sweep::gcd64(dx, dy);
      if (g < 2) continue;  // no lattice point strictly inside
      const std::int64_t lo = std::min(s.a.x, s.b.x), hi = std::max(s.a.x, s.b.x);
      const auto first = std::upper_bound(by_x.begin(), by_x.end(), std::make_pair(std::make_pair(lo, std::int64_t(INT64_MAX)), INT32_MAX));
      const auto last = std::lower_bound(by_x.begin(), by_x.end(), std::make_pair(std::make_pair(hi, std::int64_t(INT64_MIN)), INT32_MIN));
      if (first >= last) continue;
      if (std::int64_t(last - first) <= g - 1) {
        for (auto it = first; it != last; ++it) {
          const Point& q = S[it->second].a;
          if (__int128(q.x - std::int64_t(s.a.x)) * dy == __int128(q.y - std::int64_t(s.a.y)) * dx) cuts[i].push_back(it->second);
        }
        std::sort(cuts[i].begin(), cuts[i].end(), [&](std::int32_t u, std::int32_t w) {
          return (std::int64_t(S[u].a.x) - S[w].a.x) * (dx > 0 ? 1 : -1) < 0;
        });
      } else {
        for (std::int64_t k = 1; k < g; ++k) {
          const std::int64_t qx = s.a.x + dx / g * k, qy = s.a.y + dy / g * k;
          const auto it = std::lower_bound(by_x.begin(), by_x.end(), std::make_pair(std::make_pair(qx, qy), INT32_MIN));
          if (it != by_x.end() && it->first.first == qx && it->first.second == qy) cuts[i].push_back(it->second);
        }
      }
      continue;
    }
    const int d = s.a.y == s.b.y ? 0 : s.a.x == s.b.x ? 1 : (s.b.x > s.a.x) == (s.b.y > s.a.y) ? 2 : 3;
    const auto ka = key(d, s.a), kb = key(d, s.b);
    const std::int64_t lo = std::min(ka.second, kb.second), hi = std::max(ka.second, kb.second);
    const auto& v = by[d];
    for (auto it = std::upper_bound(v.begin(), v.end(), std::make_pair(std::make_pair(ka.first, lo), INT32_MAX));
         it != v.end() && it->first.first == ka.first && it->first.second < hi; ++it)
      cuts[i].push_back(it->second);
    if (ka.second > kb.second) std::reverse(cuts[i].begin(), cuts[i].end());
  }
  return cuts;
}

// Boost's builder with the predicates of coefficient type I (eps.hpp) on the inserted
// segments and points; the topology into topo.
template <typename I>
void construct(const SiteList& S, const std::vector<char>& at_an_end, const std::vector<std::vector<std::int32_t>>& cuts,
               Topology& topo) {
  boost::polygon::voronoi_builder<std::int32_t, sweep::CoordinateTraits<I>, sweep::Predicates<I>> vb;
  sweep::sweep_at() = {};  // before the first event
  auto insert = [&](std::int32_t site, std::int32_t from, std::int32_t to) {
    topo.inserted.push_back(site), topo.start.push_back(from), topo.end.push_back(to);
  };
  for (std::size_t i = 0; i < S.size(); ++i) {
    const Site& s = S[i];
    if (!s.is_point()) {
      std::int32_t from = s.end0;
      if (!cuts.empty())
        for (std::int32_t c : cuts[i]) {
          vb.insert_segment(std::int32_t(S[from].a.x), std::int32_t(S[from].a.y), std::int32_t(S[c].a.x), std::int32_t(S[c].a.y));
          insert(std::int32_t(i), from, c);
          from = c;
        }
      vb.insert_segment(std::int32_t(S[from].a.x), std::int32_t(S[from].a.y), std::int32_t(s.b.x), std::int32_t(s.b.y));
      insert(std::int32_t(i), from, s.end1);
    } else if (!at_an_end[i]) {
      vb.insert_point(std::int32_t(s.a.x), std::int32_t(s.a.y));
      insert(std::int32_t(i), -1, -1);
    }
  }
  vb.construct(&topo);
}

// The diagram of S (ends numbered within S) inside clip and outside *hole (if given): pieces
// with ids into S, joined, in join_order.
std::vector<Piece> sweep_run(const SiteList& S, const Box& clip, const Box* hole, SweepStats* stats) {
  Topology topo;
  // A point at a segment's end comes with the segment; points at one place are one site.
  std::vector<char> at_an_end(S.size(), 0);
  std::vector<std::int32_t> points;
  for (std::size_t i = 0; i < S.size(); ++i) {
    const Site& s = S[i];
    if (s.is_point()) {
      points.push_back(std::int32_t(i));
    } else {
      if (s.end0 < 0 || s.end1 < 0 || !(S[s.end0].a == s.a) || !(S[s.end1].a == s.b))
        throw std::logic_error("sweep builder: a segment without its end sites");
      at_an_end[s.end0] = at_an_end[s.end1] = 1;
    }
  }
  std::sort(points.begin(), points.end(), [&](std::int32_t u, std::int32_t w) {
    return std::tie(S[u].a.x, S[u].a.y, u) < std::tie(S[w].a.x, S[w].a.y, w);
  });
  topo.same_place.assign(S.size(), -1);
  for (std::size_t k = 0; k < points.size(); ++k)
    topo.same_place[points[k]] = k > 0 && S[points[k - 1]].a == S[points[k]].a ? topo.same_place[points[k - 1]] : points[k];
  // More than two segments ending at one place: a pinch, or plain segments from one point.
  bool crowded = false;
  {
    std::vector<std::uint8_t> ends(S.size(), 0);
    for (const Site& s : S)
      if (!s.is_point())
        for (std::int32_t e : {s.end0, s.end1}) crowded = crowded || ++ends[std::size_t(topo.same_place[e])] > 2;
  }
  // Boost's builder takes segments that meet at their ends only. Merged polygons meet where a
  // corner of one touches an edge of another; on a Manhattan layer the two then share a stretch
  // of boundary and are one polygon, but a corner touching a slanted edge, or a slanted corner
  // touching any edge, stays a point inside a segment. Such a segment is swept in parts cut at
  // those points; the parts keep the segment's id (edges between them are left out).
  bool diagonal = false, any_steep = false;
  std::int64_t normal = 0;  // the largest entry of a slanted segment's normal
  for (const Site& s : S) {
    diagonal = diagonal || sweep::is_diagonal(s);
    if (!steep(s)) continue;
    any_steep = true;
    const std::int64_t dx = std::int64_t(s.b.x) - s.a.x, dy = std::int64_t(s.b.y) - s.a.y, g = sweep::gcd64(dx, dy);
    normal = std::max<std::int64_t>(normal, std::max(std::llabs(dx), std::llabs(dy)) / g);
  }
  const std::vector<std::vector<std::int32_t>> cuts = touching_points(S, points, topo.same_place, diagonal);
  // A slanted segment of another slope than 45 degrees has rows as large as its normal: the
  // balls' coefficients grow as its cube (ball.hpp). Within 2^24 (every edge of a drawn curve,
  // any edge shorter than 16 million DBU) they stay within 2^112: 128 bits, products in 256;
  // beyond, 256 bits. Layers of points, axis-parallel and 45-degree edges keep int64.
  if (!any_steep) construct<std::int64_t>(S, at_an_end, cuts, topo);
  else if (normal <= (std::int64_t(1) << 24)) construct<__int128>(S, at_an_end, cuts, topo);
  else construct<sweep::Int256>(S, at_an_end, cuts, topo);
  // Two segments that end at one point with one separator, on opposite sides of it (a polygon
  // pinched at a slanted corner): the point's region there is a ray of that separator (or two),
  // of no width. The rule gives the ray to the point; the subdivision (and the files) have the
  // two segments beside the ray meet along it (zero_width.hpp). Its edges with either segment
  // are those of the two segments (their bisector: that separator).
  // (Only where a segment is slanted or more than two end at one place: elsewhere no two are.)
  const std::vector<detail::Partners> in_line =
      diagonal || crowded ? detail::zero_width_partners(S) : std::vector<detail::Partners>{};
  // The partner of seg at the place of point pt on the ray their edge lies on (seg's half-edge
  // of_seg, the point's twin of_pt), if pt's region there has no width, or -1. The ray: by the
  // vertex farther from the place along it, or, where the edge has a vertex only at the place,
  // by the way seg's half-edge runs from it.
  auto partner = [&](std::int32_t seg, std::int32_t pt, const Topology::Half& of_seg,
                     const Topology::Half& of_pt) -> std::int32_t {
    if (in_line.empty() || S[seg].is_point() || !S[pt].is_point()) return -1;
    const int end = detail::end_at(S, seg, pt);
    if (end < 0) return -1;
    const Vec2 none{double(S[pt].a.x), double(S[pt].a.y)};
    const Vec2 from = of_seg.vertex0 >= 0 ? topo.vertices[std::size_t(of_seg.vertex0)] : none;
    const Vec2 to = of_pt.vertex0 >= 0 ? topo.vertices[std::size_t(of_pt.vertex0)] : none;
    int ray = detail::ray_of(S[seg], end, from, to);
    if (ray < 0 && of_seg.vertex0 >= 0) ray = detail::outward_ray(S[seg], end);
    else if (ray < 0 && of_pt.vertex0 >= 0) ray = 1 - detail::outward_ray(S[seg], end);
    return detail::partner_at(in_line, seg, end, ray);
  };
  auto cut_between = [&](std::int32_t u, std::int32_t w) {
    if (S[u].is_point() == S[w].is_point()) return false;
    const std::int32_t seg = S[u].is_point() ? w : u, pt = S[u].is_point() ? u : w;
    return std::find(cuts[seg].begin(), cuts[seg].end(), pt) != cuts[seg].end();
  };

  // Far enough along any bisector to be outside the box: the bisectors' slopes are at most 1.
  const double reach = 2 * (clip.x2 - clip.x1 + clip.y2 - clip.y1) + std::fabs(clip.x1) + std::fabs(clip.x2) +
                       std::fabs(clip.y1) + std::fabs(clip.y2) + 1;
  // Edges in join order first (by owner pair; a pair has one edge, so nothing is joined unless
  // two edges share a pair), then each edge's pieces written straight where they belong and
  // sorted there: one array of pieces, touched once (fresh pages cost a fault each).
  struct Edge {  // what its pieces need, so that the sorted walk reads no half-edge
    std::uint64_t pair;  // (a, b) of its pieces, the sort key
    std::int32_t v0, v1; // the vertices of its half-edge from a and of its twin's, or -1
    std::int32_t ga, gb; // the sites whose bisector it lies on, standing for a and b (a point
                         // of no width is labelled as its partner segment)
  };
  std::vector<Edge> edges;
  edges.reserve(topo.halves.size() / 2);
  for (std::size_t e = 0; e + 1 < topo.halves.size(); e += 2) {
    const Topology::Half &h = topo.halves[e], &g = topo.halves[e + 1];
    if (h.site < 0 || g.site < 0) throw std::logic_error("sweep builder: a site event without its site");
    if (h.site == g.site) continue;  // two parts of one cut segment
    // A point inside a segment owns, by the rule (a point before a segment), only the line
    // through it along which both are nearest: no area, no piece.
    if (!cuts.empty() && cut_between(h.site, g.site)) continue;
    std::int32_t hs = h.site, gs = g.site;
    std::int32_t h_geo = hs, g_geo = gs;
    if (!in_line.empty() && !S[hs].is_point() && !S[gs].is_point()) {
      // Two segments whose common end has no width between them: their edge is that end's
      // separator (the point stands for gs there), not a branch of their lines' bisector.
      const detail::Partners& o = in_line[hs];
      if (o[0][0] == gs || o[0][1] == gs) g_geo = topo.same_place[S[hs].end0];
      else if (o[1][0] == gs || o[1][1] == gs) g_geo = topo.same_place[S[hs].end1];
    }
    if (!in_line.empty()) {
      // A point's region of no width between two segments: its edge with the lower one is the
      // two segments' edge, its edge with the other the same line again (left out).
      const std::int32_t ph = partner(gs, hs, g, h), pg = partner(hs, gs, h, g);
      if (ph >= 0) {
        if (ph < gs) continue;
        hs = ph;
      } else if (pg >= 0) {
        if (pg < hs) continue;
        gs = pg;
      }
    }
    const bool h_first = hs <= gs;
    edges.push_back({std::uint64_t(std::uint32_t(h_first ? hs : gs)) << 32 | std::uint32_t(h_first ? gs : hs),
                     h_first ? h.vertex0 : g.vertex0, h_first ? g.vertex0 : h.vertex0, h_first ? h_geo : g_geo,
                     h_first ? g_geo : h_geo});
  }
  std::sort(edges.begin(), edges.end(), [](const Edge& x, const Edge& y) { return x.pair < y.pair; });
  std::vector<Piece> joined, run;
  joined.reserve(3 * edges.size());  // at most three pieces an edge: reserved, untouched
  huge_pages(joined);
  std::vector<Piece>* out = &joined;
  auto keep = [&](Vec2 p, Vec2 q, std::int32_t u, std::int32_t w) {
    if (p.x == q.x && p.y == q.y) return;
    Piece pc;
    pc.p = p, pc.q = q;
    pc.a = std::min(u, w), pc.b = std::max(u, w);
    pc.d1 = linf_distance(p, S[u]), pc.d2 = linf_distance(q, S[u]);
    orient(pc);
    out->push_back(pc);
  };
  auto emit = [&](Vec2 p, Vec2 q, std::int32_t u, std::int32_t w, const sweep::Line* line = nullptr) {
    if (!clip_segment(p, q, clip, line)) return;
    if (!hole) return keep(p, q, u, w);
    outside(p, q, *hole, [&](const Vec2& a, const Vec2& b) { keep(a, b, u, w); }, line);
  };
  // With a slanted segment: the chain's parts between the edge's vertices (or towards
  // infinity with the vertex's half-edge's site on the left), each vertex where it lies on it.
  auto chain_pieces = [&](const Edge& e, std::int32_t u, std::int32_t w) {
    const Site &s = S[e.ga], &t = S[e.gb];
    const sweep::Chain c(s, t);
    if (c.straight) {
      if (e.v0 < 0 && e.v1 < 0)
        throw std::logic_error("sweep builder: a straight edge without a vertex between sites " + std::to_string(u) +
                               " and " + std::to_string(w));
      if (e.v0 >= 0 && e.v1 >= 0) {
        const sweep::Line l = sweep::Chain::between_lines(s, t, topo.vertices[e.v0], topo.vertices[e.v1]);
        return emit(topo.vertices[e.v0], topo.vertices[e.v1], u, w, &l);
      }
      // Unbounded: where both segments' strips of interior nearest points (bounded by the
      // diagonals through their ends) overlap without end, the edge runs along the overlap to
      // infinity, from its vertex with the vertex's half-edge's site on its left.
      const bool from_u = e.v0 >= 0;
      const Vec2 v = topo.vertices[from_u ? e.v0 : e.v1];
      const sweep::Line l = sweep::Chain::between_lines(s, t, v, v);
      Vec2 d{-double(l.b), double(l.a)};
      const double big = std::max(std::fabs(d.x), std::fabs(d.y));
      d = {d.x / big, d.y / big};
      // The site lies on one side of the line (touching it at most at the lines' crossing): its
      // end farther from the line tells which.
      const Site& left = from_u ? s : t;
      auto side = [&](const Point& e) { return d.x * (double(e.y) - v.y) - d.y * (double(e.x) - v.x); };
      const double sa = side(left.a), sb = side(left.b);
      if ((std::fabs(sa) > std::fabs(sb) ? sa : sb) < 0) d = {-d.x, -d.y};
      return emit(v, Vec2{v.x + reach * d.x, v.y + reach * d.y}, u, w, &l);
    }
    using At = std::pair<int, double>;
    const At far_in{-1, -reach}, far_out{c.n - 1, reach};
    auto point_at = [&](const At& a) {  // a on a ray: far_in or far_out
      const Vec2 o = a.first < 0 ? c.v[0] : c.v[c.n - 1], d = a.first < 0 ? c.in : c.out;
      return Vec2{o.x + a.second * d.x, o.y + a.second * d.y};
    };
    // The chain from a (at pa) to b (at pb), a <= b, cut at its bends.
    auto walk = [&](const At& a, Vec2 pa, const At& b, const Vec2& pb) {
      if (c.n > 1)  // a chain of one vertex is a straight line through it: no bend there
        for (int k = a.first + 1; k <= b.first; ++k) emit(pa, c.v[k], u, w, c.line_of(k - 1)), pa = c.v[k];
      emit(pa, pb, u, w, c.line_of(b.first));
    };
    At a, b;
    Vec2 pa, pb;
    if (e.v0 >= 0 && e.v1 >= 0) {
      pa = topo.vertices[e.v0], pb = topo.vertices[e.v1];
      a = c.locate(pa), b = c.locate(pb);
      // A U's two rays run the same way, where a point's arc and a slanted line's are parallel:
      // the breakpoint of an edge can leave for infinity along one ray and come back along the
      // other later, when the line's arc has caught up (a point below a slanted segment). Such
      // an edge is the U less the part between its vertices: its half-edge from v0 then has its
      // site on the right of that part, not on the left.
      if (c.n == 3 && a != b && (a < b) != c.left_of(s)) {
        if (b < a) std::swap(a, b), std::swap(pa, pb);
        walk(far_in, point_at(far_in), a, pa);
        return walk(b, pb, far_out, point_at(far_out));
      }
    } else if (e.v0 >= 0 || e.v1 >= 0) {
      const bool from_u = e.v0 >= 0;
      pa = topo.vertices[from_u ? e.v0 : e.v1];
      a = c.locate(pa);
      b = c.left_of(from_u ? s : t) ? far_out : far_in;
      pb = point_at(b);
    } else {
      a = far_in, b = far_out, pa = point_at(a), pb = point_at(b);
    }
    if (b < a) std::swap(a, b), std::swap(pa, pb);
    walk(a, pa, b, pb);
  };
  auto pieces_of = [&](const Edge& e) {
    const std::int32_t u = std::int32_t(e.pair >> 32), w = std::int32_t(e.pair & 0xffffffffu);
    const Site &s = S[e.ga], &t = S[e.gb];
    if (sweep::is_diagonal(s) || sweep::is_diagonal(t)) return chain_pieces(e, u, w);
    const sweep::Bisector b(s, t);
    if (b.straight) {
      if (e.v0 < 0 || e.v1 < 0)
        throw std::logic_error("sweep builder: an unbounded diagonal edge between sites " + std::to_string(u) +
                               " and " + std::to_string(w));
      const sweep::Line l = sweep::Bisector::diagonal(s, t, topo.vertices[e.v0], topo.vertices[e.v1]);
      return emit(topo.vertices[e.v0], topo.vertices[e.v1], u, w, &l);
    }
    double from, to;  // the edge's parameter range
    if (e.v0 >= 0 && e.v1 >= 0) {
      from = b.param(topo.vertices[e.v0]), to = b.param(topo.vertices[e.v1]);
    } else if (e.v0 >= 0 || e.v1 >= 0) {
      // From its vertex to infinity with the vertex's half-edge's site on its left.
      const bool from_u = e.v0 >= 0;
      from = b.param(topo.vertices[from_u ? e.v0 : e.v1]);
      to = b.left_of_growing(from_u ? s : t, from_u ? t : s) ? from + reach : from - reach;
    } else {
      from = -reach, to = reach;
    }
    if (from > to) std::swap(from, to);
    double cuts[4] = {from, 0, 0, to};
    int n = 1;
    if (b.bends())
      for (double c : {b.mid_p - b.half, b.mid_p + b.half})
        if (c > from && c < to) cuts[n++] = c;
    cuts[n++] = to;
    for (int i = 0; i + 1 < n; ++i) {
      const sweep::Line l = b.line_between(cuts[i], cuts[i + 1]);
      emit(b.point(cuts[i]), b.point(cuts[i + 1]), u, w, &l);
    }
  };
  // A point's arc between two arcs of one slanted segment vanishes where the segment's arc,
  // parallel to the point's lower (or upper) ray, overtakes it. In L2 that never happens, and
  // Boost's builder has no such event: the arc stays, and its two breakpoints run on past each
  // other to infinity, one edge each, one each way along the pair's U. Both edges are one: the
  // part of the U between their vertices (into e; f is marked gone, v0 = -2).
  auto missed_vanishing = [&](Edge& e, Edge& f) {
    const Site &s = S[e.ga], &t = S[e.gb];
    if (!(sweep::is_diagonal(s) || sweep::is_diagonal(t)) || e.ga != f.ga || e.gb != f.gb) return;
    if ((e.v0 >= 0) + (e.v1 >= 0) != 1 || (f.v0 >= 0) + (f.v1 >= 0) != 1 || (e.v0 >= 0) == (f.v0 >= 0)) return;
    const sweep::Chain c(s, t);
    if (c.n != 3) return;
    Edge& from_u = e.v0 >= 0 ? e : f;  // its vertex is a's; the other's is b's
    Edge& from_w = e.v0 >= 0 ? f : e;
    const auto a = c.locate(topo.vertices[from_u.v0]), b = c.locate(topo.vertices[from_w.v1]);
    // a's half-edge runs from its vertex with a on its left: along the walk if a is there.
    if (a == b || (a < b) != c.left_of(s)) return;
    from_u.v1 = from_w.v1;
    from_w.v0 = -2;
  };
  for (std::size_t i = 0; i < edges.size();) {
    std::size_t j = i + 1;
    while (j < edges.size() && edges[j].pair == edges[i].pair) ++j;
    if (j == i + 1) {  // the usual case
      const std::size_t first = joined.size();
      pieces_of(edges[i]);
      std::sort(joined.begin() + first, joined.end(), join_order);
      i = j;
      continue;
    }
    if (j == i + 2) missed_vanishing(edges[i], edges[i + 1]);
    run.clear();
    out = &run;
    int with_pieces = 0;  // two edges' pieces are joined; one edge's are left as they are
    for (std::size_t k = i; k < j; ++k) {
      if (edges[k].v0 == -2) continue;
      const std::size_t before = run.size();
      pieces_of(edges[k]);
      with_pieces += run.size() > before;
    }
    out = &joined;
    std::sort(run.begin(), run.end(), join_order);
    if (with_pieces > 1) join_pair(run);
    joined.insert(joined.end(), run.begin(), run.end());
    i = j;
  }
  if (stats) stats->site_events = S.size(), stats->vertices = topo.vertices.size(), stats->edges = topo.halves.size() / 2;
  return joined;
}

}  // namespace

std::vector<Piece> sweep_pieces(const Sites& sites, const Box& clip, SweepStats* stats) {
  return sweep_run(sites.sites, clip, nullptr, stats);
}

namespace {

// The sites `ids` as their own list (subset[k] is site ids[k]), ends renumbered, swept, and the
// pieces told their global ids again (ascending ids: the order stays).
template <class SiteAt>
std::vector<Piece> sweep_own(const SiteAt& site_at, const std::vector<int>& ids, const Box& frame, const Box* hole) {
  auto local = [&](std::int32_t t) -> std::int32_t {
    const auto it = std::lower_bound(ids.begin(), ids.end(), t);
    return t >= 0 && it != ids.end() && *it == t ? std::int32_t(it - ids.begin()) : -1;
  };
  SiteList own;
  own.reserve(ids.size());
  for (std::size_t k = 0; k < ids.size(); ++k) {
    Site s = site_at(k);
    s.end0 = local(s.end0), s.end1 = local(s.end1);  // a point's ring neighbours may be absent
    own.push_back(s);
  }
  std::vector<Piece> part = sweep_run(own, frame, hole, nullptr);
  for (Piece& p : part) p.a = ids[p.a], p.b = ids[p.b];
  return part;
}

}  // namespace

std::vector<Piece> sweep_part(const SiteList& sites, const std::vector<int>& ids, const Box& frame, const Box* hole) {
  return sweep_own([&](std::size_t k) { return sites[ids[k]]; }, ids, frame, hole);
}

std::vector<Piece> sweep_subset(const std::vector<Site>& subset, const std::vector<int>& ids, const Box& frame) {
  if (subset.size() != ids.size()) throw std::invalid_argument("sweep_subset: one site an id");
  return sweep_own([&](std::size_t k) { return subset[k]; }, ids, frame, nullptr);
}

}  // namespace linf
