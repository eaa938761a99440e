#include "linf/sites.hpp"

#include <boost/geometry.hpp>
#include <boost/geometry/index/rtree.hpp>
#include <boost/polygon/polygon.hpp>
#include <algorithm>
#include <map>
#include <stdexcept>

namespace linf {
namespace bp = boost::polygon;

namespace {

using BPoint = bp::point_data<int>;
using BPolygon = bp::polygon_with_holes_data<int>;
using BSimple = bp::polygon_data<int>;

constexpr Coord kLimit = Coord(1) << 30;

// Every input point passes here once: intersections must stay representable, and the merge's
// and the checker's boxes are 32-bit.
void check_range(const Point& p) {
  if (p.x <= -kLimit || p.x >= kLimit || p.y <= -kLimit || p.y >= kLimit)
    throw std::invalid_argument("coordinate outside +-2^30 database units");
}

__int128 cross(const Point& o, const Point& a, const Point& b) {
  return __int128(a.x - o.x) * (b.y - o.y) - __int128(a.y - o.y) * (b.x - o.x);
}

// Drops repeated points and vertices in the middle of a straight run.
Ring clean_ring(const Ring& r) {
  Ring out;
  for (const Point& p : r)
    if (out.empty() || out.back() != p) out.push_back(p);
  while (out.size() > 1 && out.front() == out.back()) out.pop_back();
  bool changed = true;
  while (changed && out.size() >= 3) {
    changed = false;
    for (std::size_t i = 0; i < out.size() && out.size() >= 3; ++i) {
      const Point& a = out[(i + out.size() - 1) % out.size()];
      const Point& c = out[(i + 1) % out.size()];
      if (cross(a, out[i], c) == 0) {
        out.erase(out.begin() + long(i));
        changed = true;
        --i;
      }
    }
  }
  return out.size() >= 3 ? out : Ring{};
}

__int128 twice_area(const Ring& r) {
  __int128 s = 0;
  for (std::size_t i = 0; i < r.size(); ++i) {
    const Point& p = r[i];
    const Point& q = r[(i + 1) % r.size()];
    s += __int128(p.x) * q.y - __int128(q.x) * p.y;
  }
  return s;
}

Ring oriented(Ring r, bool ccw) {
  if ((twice_area(r) > 0) != ccw) std::reverse(r.begin(), r.end());
  return r;
}

BSimple to_boost(const Ring& r) {
  std::vector<BPoint> pts;
  pts.reserve(r.size());
  for (const Point& p : r) pts.emplace_back(int(p.x), int(p.y));  // checked in merge_groups
  BSimple s;
  s.set(pts.begin(), pts.end());
  return s;
}

Ring from_boost(const BSimple& s) {
  Ring r;
  for (auto it = s.begin(); it != s.end(); ++it) r.push_back({Coord(bp::x(*it)), Coord(bp::y(*it))});
  return r;
}

// One Boost.Polygon scan over the polygons `ids` of `in`, appended to `out`.
void merge_group(const std::vector<Polygon>& in, const std::vector<std::int32_t>& ids, std::vector<Polygon>& out) {
  // Everything goes into one set and is merged by a single scan at get(): a union per shape
  // would rescan the growing set each time (minutes on a layer of 100K shapes).
  bp::polygon_set_data<int> set;
  for (const std::int32_t i : ids) {
    const Polygon& p = in[std::size_t(i)];
    BPolygon b;
    const BSimple outer = to_boost(p.outer);
    b.set(outer.begin(), outer.end());
    std::vector<BSimple> holes;
    for (const Ring& h : p.holes) holes.push_back(to_boost(h));
    b.set_holes(holes.begin(), holes.end());
    set.insert(b);
  }
  std::vector<BPolygon> merged;
  set.get(merged);
  for (const BPolygon& m : merged) {
    Polygon p;
    p.outer = clean_ring(from_boost(BSimple(m.begin(), m.end())));
    if (p.outer.empty()) continue;
    p.outer = oriented(p.outer, true);
    for (auto h = m.begin_holes(); h != m.end_holes(); ++h) {
      Ring r = clean_ring(from_boost(*h));
      if (!r.empty()) p.holes.push_back(oriented(r, false));
    }
    out.push_back(std::move(p));
  }
}

// Groups of whole clusters of polygons whose boxes overlap or touch (only those can merge),
// each group about `size` polygons: merged group by group, a layer of millions of shapes needs
// the scan's memory for one group at a time (one scan over five million wires held about 7 GB).
std::vector<std::vector<std::int32_t>> merge_groups(const std::vector<Polygon>& in, std::size_t size) {
  namespace bg = boost::geometry;
  namespace bgi = boost::geometry::index;
  using IPt = bg::model::point<std::int32_t, 2, bg::cs::cartesian>;
  using IBox = bg::model::box<IPt>;
  using Entry = std::pair<IBox, std::int32_t>;
  const std::size_t n = in.size();
  std::vector<Entry> boxes;
  boxes.reserve(n);
  for (std::size_t i = 0; i < n; ++i) {
    Coord x1 = kLimit, y1 = kLimit, x2 = -kLimit, y2 = -kLimit;
    for (const Point& p : in[i].outer) {
      check_range(p);
      x1 = std::min(x1, p.x), y1 = std::min(y1, p.y), x2 = std::max(x2, p.x), y2 = std::max(y2, p.y);
    }
    for (const Ring& h : in[i].holes)
      for (const Point& p : h) check_range(p);
    if (in[i].outer.empty()) x1 = y1 = x2 = y2 = 0;
    boxes.push_back({IBox(IPt(std::int32_t(x1), std::int32_t(y1)), IPt(std::int32_t(x2), std::int32_t(y2))),
                     std::int32_t(i)});
  }
  std::vector<std::int32_t> parent(n);
  for (std::size_t i = 0; i < n; ++i) parent[i] = std::int32_t(i);
  auto root = [&](std::int32_t x) {
    while (parent[std::size_t(x)] != x) x = parent[std::size_t(x)] = parent[std::size_t(parent[std::size_t(x)])];
    return x;
  };
  {
    const bgi::rtree<Entry, bgi::rstar<16>> tree(boxes.begin(), boxes.end());
    std::vector<Entry> hit;
    for (const Entry& e : boxes) {
      hit.clear();
      tree.query(bgi::intersects(e.first), std::back_inserter(hit));  // closed boxes: touching counts
      for (const Entry& h : hit) {
        const std::int32_t a = root(e.second), b = root(h.second);
        if (a != b) parent[std::size_t(std::max(a, b))] = std::min(a, b);
      }
    }
  }
  // Clusters in the order of their first polygon, packed into groups.
  std::vector<std::vector<std::int32_t>> cluster_of(n);
  std::vector<std::int32_t> order;
  for (std::size_t i = 0; i < n; ++i) {
    const std::int32_t r = root(std::int32_t(i));
    if (cluster_of[std::size_t(r)].empty()) order.push_back(r);
    cluster_of[std::size_t(r)].push_back(std::int32_t(i));
  }
  std::vector<std::vector<std::int32_t>> groups(1);
  for (const std::int32_t r : order) {
    if (!groups.back().empty() && groups.back().size() + cluster_of[std::size_t(r)].size() > size) groups.emplace_back();
    auto& g = groups.back();
    g.insert(g.end(), cluster_of[std::size_t(r)].begin(), cluster_of[std::size_t(r)].end());
    std::vector<std::int32_t>().swap(cluster_of[std::size_t(r)]);
  }
  return groups;
}

}  // namespace

std::vector<Polygon> merge_polygons(const std::vector<Polygon>& in, std::size_t group) {
  std::vector<Polygon> out;
  for (const std::vector<std::int32_t>& g : merge_groups(in, group)) merge_group(in, g, out);
  // Boost's output order depends on its scanline; sort for reproducible site numbering.
  std::sort(out.begin(), out.end(), [](const Polygon& a, const Polygon& b) {
    return std::min_element(a.outer.begin(), a.outer.end())[0] < std::min_element(b.outer.begin(), b.outer.end())[0];
  });
  return out;
}

Sites sites_of_polygons(const std::vector<Polygon>& merged) {
  Sites s;
  std::int32_t ri = 0;
  for (std::size_t pi = 0; pi < merged.size(); ++pi) {
    std::vector<const Ring*> rings{&merged[pi].outer};
    for (const Ring& h : merged[pi].holes) rings.push_back(&h);
    for (const Ring* r : rings) {
      const std::int32_t n = std::int32_t(r->size());
      const std::int32_t base = std::int32_t(s.sites.size());
      // Layout: vertex i at base + 2i, edge i (vertex i -> i+1) at base + 2i + 1.
      for (std::int32_t i = 0; i < n; ++i) {
        Site v;
        v.a = v.b = (*r)[i];
        v.shape = std::int32_t(pi), v.ring = ri, v.index = i;
        v.end0 = base + 2 * ((i + n - 1) % n) + 1;
        v.end1 = base + 2 * i + 1;
        s.sites.push_back(v);
        Site e;
        e.a = (*r)[i], e.b = (*r)[(i + 1) % n];
        e.shape = std::int32_t(pi), e.ring = ri, e.index = i;
        e.end0 = base + 2 * i;
        e.end1 = base + 2 * ((i + 1) % n);
        s.sites.push_back(e);
      }
      ++ri;
    }
  }
  s.shapes = merged.size();
  return s;
}

Sites sites_of_plain(const std::vector<Point>& points, const std::vector<Segment>& segments) {
  Sites s;
  std::map<Point, std::int32_t> at;
  auto point_site = [&](const Point& p, std::int32_t shape) {
    check_range(p);
    auto it = at.find(p);
    if (it != at.end()) return it->second;
    Site v;
    v.a = v.b = p;
    v.shape = shape;
    s.sites.push_back(v);
    return at[p] = std::int32_t(s.sites.size() - 1);
  };
  std::int32_t shape = 0;
  for (const Segment& g : segments) {
    if (g.a == g.b) {
      point_site(g.a, shape++);
      continue;
    }
    Site e;
    e.a = g.a, e.b = g.b, e.shape = shape++;
    e.end0 = point_site(g.a, e.shape);
    e.end1 = point_site(g.b, e.shape);
    s.sites.push_back(e);
  }
  for (const Point& p : points) point_site(p, shape++);
  s.shapes = std::size_t(shape);
  return s;
}

}  // namespace linf
