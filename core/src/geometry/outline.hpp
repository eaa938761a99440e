// Which polygons of a layer are their own merge, so that merge_polygons (sites.cpp) passes them
// by Boost.Polygon's scan: a plain polygon (no holes; an outline that is clean, with no
// repeated point and no vertex on a straight line or turning back, and simple, no two edges
// meeting but neighbours at their vertex) that meets no other polygon comes out of the scan as
// the same ring, counter-clockwise from its greatest vertex (so on every polygon of the SRAM's
// metal 1, testcase 3 and gcd; Merge.PlainPolygonsAloneAreTheirOwnMerge compares the two).
// A layer that KLayout has merged is all such polygons, yet their boxes overlap: the SRAM's
// metal 1 has 7,471 polygons, all plain and alone, 377 of them alone by their boxes, and the
// scan took 0.8e9 instructions on it. Only polygons that meet no other are passed by: where
// slanted edges (other than at 45 degrees) were scanned with a neighbour they did not meet, the
// scan cut them at its events and rounded the cuts to the grid, moving them by a fraction of a
// unit; alone, they stay as drawn. Internal to sites.cpp.
#pragma once
#include <algorithm>
#include <cstdint>
#include <vector>

#include "linf/util/box_tree.hpp"
#include "linf/util/paged.hpp"
#include "linf/geometry/polygons.hpp"

namespace linf::detail {

inline __int128 cross(const Point& o, const Point& a, const Point& b) {
  return __int128(a.x - o.x) * (b.y - o.y) - __int128(a.y - o.y) * (b.x - o.x);
}

inline __int128 twice_area(const Ring& r) {
  __int128 s = 0;
  for (std::size_t i = 0; i < r.size(); ++i) {
    const Point& p = r[i];
    const Point& q = r[(i + 1) % r.size()];
    s += __int128(p.x) * q.y - __int128(q.x) * p.y;
  }
  return s;
}

inline Ring oriented(Ring r, bool ccw) {
  if ((twice_area(r) > 0) != ccw) std::reverse(r.begin(), r.end());
  return r;
}

// A polygon's outer ring in the flat arrays.
struct Outline {
  const std::int64_t* xy = nullptr;
  std::size_t n = 0;
  bool holes = false;
  Point operator[](std::size_t k) const { return {xy[2 * k], xy[2 * k + 1]}; }
  Point edge_end(std::size_t k) const { return (*this)[k + 1 < n ? k + 1 : 0]; }
  IntBox edge_box(std::size_t k) const;
};

class Outlines {
 public:
  Outlines(const PolygonIndex& ix, int threads);
  bool plain(std::size_t i) const { return plain_[i] != 0; }
  // Do plain polygons i and j meet: an edge on an edge, or one inside the other?
  bool meet(std::size_t i, std::size_t j) const;
  // Plain polygon i, which meets no other, as the scan would give it.
  Ring as_merged(std::size_t i) const;

 private:
  Outline outline(std::size_t i) const;
  bool simple(const Outline& o, const BoxTree* edges) const;
  bool inside(const Point& p, std::size_t i) const;

  const PolygonIndex& ix_;
  Paged<char> plain_;
  // The edges of each plain polygon of more than kFew points, indexed: its simplicity, and
  // every other polygon's test against it, without testing all its edges.
  Paged<std::int32_t> tree_of_;  // -1: none
  std::vector<BoxTree> trees_;
};

}  // namespace linf::detail
