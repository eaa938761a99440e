#include "linf/geometry/sites.hpp"

#include <boost/polygon/polygon.hpp>
#include <algorithm>
#include <map>
#include <stdexcept>

#include "linf/util/box_tree.hpp"
#include "outline.hpp"
#include "util/parallel.hpp"

namespace linf {
namespace bp = boost::polygon;
using detail::cross;
using detail::oriented;
using detail::Outlines;

namespace {

using BPoint = bp::point_data<int>;
using BPolygon = bp::polygon_with_holes_data<int>;
using BSimple = bp::polygon_data<int>;

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

BSimple to_boost(const Ring& r) {
  std::vector<BPoint> pts;
  pts.reserve(r.size());
  for (const Point& p : r) pts.emplace_back(int(p.x), int(p.y));  // checked by PolygonIndex
  BSimple s;
  s.set(pts.begin(), pts.end());
  return s;
}

Ring from_boost(const BSimple& s) {
  Ring r;
  for (auto it = s.begin(); it != s.end(); ++it) r.push_back({Coord(bp::x(*it)), Coord(bp::y(*it))});
  return r;
}

// One Boost.Polygon scan over the polygons ids[0, n) of `ix` (those `alone` as they are),
// appended to `out` with the least vertex of each (the sort key) in `keys`.
void merge_group(const PolygonIndex& ix, const std::int32_t* ids, std::size_t n, const Outlines& outlines,
                 const Paged<char>& alone, PolygonArrays& out, Paged<Point>& keys) {
  // Everything goes into one set and is merged by a single scan at get(): a union per shape
  // would rescan the growing set each time (minutes on a layer of 100K shapes).
  bp::polygon_set_data<int> set;
  Polygon own;
  for (std::size_t k = 0; k < n; ++k) {
    if (alone[std::size_t(ids[k])]) {
      own.outer = outlines.as_merged(std::size_t(ids[k]));
      keys.push_back(*std::min_element(own.outer.begin(), own.outer.end()));
      out.add(own);
      continue;
    }
    const Polygon p = ix.polygon(std::size_t(ids[k]));
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
    keys.push_back(*std::min_element(p.outer.begin(), p.outer.end()));
    out.add(p);
  }
}

// Groups of whole clusters of polygons whose boxes overlap or touch (only those can merge),
// but for two plain polygons that do not meet; each group about `size` polygons: merged group
// by group, a layer of millions of shapes needs the scan's memory for one group at a time (one
// scan over five million wires held about 7 GB). `ids` gets the polygons cluster by cluster,
// clusters in the order of their first polygon; the result is where each group ends in it.
// `alone`: the plain polygons that are a cluster alone (outline.hpp).
std::vector<std::size_t> merge_groups(const PolygonIndex& ix, const Outlines& outlines, std::size_t size,
                                      Paged<std::int32_t>& ids, Paged<char>& alone) {
  const std::size_t n = ix.size();
  // Union-find; a root is the least polygon of its cluster, whatever the order of the joins.
  Paged<std::int32_t> parent;
  parent.resize(n);
  for (std::size_t i = 0; i < n; ++i) parent[i] = std::int32_t(i);
  auto root = [&](std::int32_t x) {
    while (parent[std::size_t(x)] != x) x = parent[std::size_t(x)] = parent[std::size_t(parent[std::size_t(x)])];
    return x;
  };
  {
    const BoxTree tree(n, [&](std::size_t i) { return ix.box(i); });
    for (std::size_t i = 0; i < n; ++i)
      tree.query(ix.box(i), [&](std::int32_t h) {  // closed boxes: touching counts
        const std::size_t j = std::size_t(h);
        if (j < i) return;  // the pair was met from j
        if (j != i && outlines.plain(i) && outlines.plain(j) && !outlines.meet(i, j)) return;
        const std::int32_t a = root(std::int32_t(i)), b = root(h);
        if (a != b) parent[std::size_t(std::max(a, b))] = std::min(a, b);
      });
  }
  // Counting sort by root, stable: clusters in the order of their least polygon.
  for (std::size_t i = 0; i < n; ++i) parent[i] = root(std::int32_t(i));  // each points at its root
  Paged<std::int32_t> place;  // a cluster's size, at its root; then where its next polygon goes
  place.resize(n);
  for (std::size_t i = 0; i < n; ++i) ++place[std::size_t(parent[i])];
  alone.resize(n);
  std::vector<std::size_t> ends;
  std::size_t at = 0, group = 0;
  for (std::size_t r = 0; r < n; ++r) {
    if (place[r] == 0) continue;
    const std::size_t c = std::size_t(place[r]);
    alone[r] = c == 1 && outlines.plain(r);  // then r is its root
    if (group > 0 && group + c > size) ends.push_back(at), group = 0;
    place[r] = std::int32_t(at);
    at += c, group += c;
  }
  if (group > 0) ends.push_back(at);
  ids.resize(n);
  for (std::size_t i = 0; i < n; ++i) ids[std::size_t(place[std::size_t(parent[i])]++)] = std::int32_t(i);
  return ends;
}

}  // namespace

PolygonArrays merge_polygons(const FlatPolygons& in, std::size_t group, int threads) {
  const PolygonIndex ix(in);
  // A layer of one group is cut into a group per worker, merged side by side; a larger one
  // group by group, each scan holding its group's memory alone.
  const unsigned workers = detail::worker_count(ix.size(), threads);
  const bool side_by_side = workers > 1 && ix.size() <= group;
  if (side_by_side) group = (ix.size() + workers - 1) / workers;
  Paged<std::int32_t> ids;
  Paged<char> alone;
  const Outlines outlines(ix, threads);
  const std::vector<std::size_t> ends = merge_groups(ix, outlines, group, ids, alone);
  std::vector<PolygonArrays> merged(side_by_side ? ends.size() : 1);
  std::vector<Paged<Point>> keys(merged.size());
  auto run = [&](std::size_t g, PolygonArrays& out, Paged<Point>& k) {
    const std::size_t from = g ? ends[g - 1] : 0;
    merge_group(ix, ids.data() + from, ends[g] - from, outlines, alone, out, k);
  };
  if (side_by_side)
    detail::parallel_for(ends.size(), threads, [&](unsigned, std::size_t g) { run(g, merged[g], keys[g]); });
  else
    for (std::size_t g = 0; g < ends.size(); ++g) run(g, merged[0], keys[0]);
  // Boost's output order depends on its scanline and on the groups; sorted by least vertex,
  // then by the whole outer ring (two polygons may share their least vertex, touching there),
  // for site numbering independent of both.
  std::vector<PolygonIndex> mx;
  struct Ref {
    std::uint32_t first;   // part
    std::int32_t second;   // polygon in it
  };
  Paged<Ref> order;
  for (std::size_t g = 0; g < merged.size(); ++g) {
    mx.emplace_back(merged[g].view());
    for (std::size_t i = 0; i < merged[g].count; ++i) order.push_back({std::uint32_t(g), std::int32_t(i)});
  }
  auto outer = [&](const Ref& o) {
    std::pair<const std::int64_t*, std::size_t> r{nullptr, 0};
    mx[o.first].rings(std::size_t(o.second), [&](const std::int64_t* xy, std::size_t n, bool is_outer) {
      if (is_outer) r = {xy, n};
    });
    return r;
  };
  std::sort(order.begin(), order.end(), [&](const Ref& a, const Ref& b) {
    const Point ka = keys[a.first][std::size_t(a.second)], kb = keys[b.first][std::size_t(b.second)];
    if (ka != kb) return ka < kb;
    const auto ra = outer(a), rb = outer(b);
    return std::lexicographical_compare(ra.first, ra.first + 2 * ra.second, rb.first, rb.first + 2 * rb.second);
  });
  PolygonArrays out;
  for (const auto& o : order) {
    mx[o.first].rings(std::size_t(o.second), [&](const std::int64_t* xy, std::size_t n, bool is_outer) {
      for (std::size_t j = 0; j < 2 * n; ++j) out.points.push_back(xy[j]);
      out.rings.push_back(is_outer ? std::int64_t(n) : -std::int64_t(n));
    });
    ++out.count;
  }
  return out;
}

std::vector<Polygon> merge_polygons(const std::vector<Polygon>& in, std::size_t group, int threads) {
  const PolygonArrays flat = flat_of(in);
  return polygons_of(merge_polygons(flat.view(), group, threads).view());
}

Sites sites_of_polygons(const FlatPolygons& merged) {
  Sites s;
  s.sites.reserve(2 * merged.n_points);  // at once: growing by doubling copies and remaps them
  std::int32_t pi = -1, ri = 0;
  std::size_t at = 0;
  for (std::size_t k = 0; k < merged.n_rings; ++k, ++ri) {
    const std::int64_t c = merged.rings[k];
    const std::int32_t n = std::int32_t(c < 0 ? -c : c);
    if (c >= 0) ++pi;
    const std::int64_t* xy = merged.points + 2 * at;
    at += std::size_t(n);
    auto point = [&](std::int32_t i) { return Point{xy[2 * i], xy[2 * i + 1]}; };
    const std::int32_t base = std::int32_t(s.sites.size());
    // Layout: vertex i at base + 2i, edge i (vertex i -> i+1) at base + 2i + 1.
    for (std::int32_t i = 0; i < n; ++i) {
      Site v;
      v.a = v.b = point(i);
      v.shape = pi, v.ring = ri, v.index = i;
      v.end0 = base + 2 * ((i + n - 1) % n) + 1;
      v.end1 = base + 2 * i + 1;
      s.sites.push_back(v);
      Site e;
      e.a = point(i), e.b = point((i + 1) % n);
      e.shape = pi, e.ring = ri, e.index = i;
      e.end0 = base + 2 * i;
      e.end1 = base + 2 * ((i + 1) % n);
      s.sites.push_back(e);
    }
  }
  s.shapes = std::size_t(pi + 1);
  return s;
}

Sites sites_of_polygons(const std::vector<Polygon>& merged) {
  const PolygonArrays flat = flat_of(merged);
  return sites_of_polygons(flat.view());
}

Sites sites_of_plain(const std::vector<Point>& points, const std::vector<Segment>& segments) {
  Sites s;
  std::map<Point, std::int32_t> at;
  auto point_site = [&](const Point& p, std::int32_t shape) {
    check_range(p.x, p.y);
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
