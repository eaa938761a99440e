// Sites: the input of the diagram. Integer database units, as in a layout.
#pragma once
#include <cstdint>
#include <stdexcept>
#include <vector>

#include "linf/util/paged.hpp"

namespace linf {

using Coord = std::int64_t;

// Input coordinates lie within +-2^30 database units: intersections stay representable, and
// the merge's and the checker's boxes are 32-bit. Every input point passes here once.
constexpr Coord kCoordLimit = Coord(1) << 30;
inline void check_range(Coord x, Coord y) {
  if (x <= -kCoordLimit || x >= kCoordLimit || y <= -kCoordLimit || y >= kCoordLimit)
    throw std::invalid_argument("coordinate outside +-2^30 database units");
}

struct Point {
  Coord x = 0, y = 0;
  friend bool operator==(const Point& a, const Point& b) { return a.x == b.x && a.y == b.y; }
  friend bool operator!=(const Point& a, const Point& b) { return !(a == b); }
  friend bool operator<(const Point& a, const Point& b) { return a.x < b.x || (a.x == b.x && a.y < b.y); }
};

struct Segment {
  Point a, b;
};

// A closed ring; the first point is not repeated at the end.
using Ring = std::vector<Point>;

struct Polygon {
  Ring outer;
  std::vector<Ring> holes;
};

// A site of the segment Voronoi diagram: a point (a == b) or an open segment.
// `shape` says which merged polygon (or which plain input) the site belongs to; with `ring`
// and the neighbours (end0, end1) it lets the classifier tell inside from outside.
struct Site {
  Point a, b;
  std::int32_t shape = -1;  // polygon index after merging, or plain-input index
  std::int32_t ring = -1;   // which ring of the layer (outer rings and holes numbered in turn), -1 for plain input
  std::int32_t index = -1;  // vertex index (point) or edge index (segment: edge a->b) in its ring
  // A segment's endpoint sites, or for a ring vertex its incoming/outgoing edge sites; -1 if none.
  std::int32_t end0 = -1, end1 = -1;
  bool is_point() const { return a == b; }
};

// The sites of a layer: eight a wire, millions on a full layer, so Paged (a mapped file the
// kernel may write out and drop; see linf/paged.hpp).
using SiteList = Paged<Site>;

// All sites of one diagram. Their rings are oriented so that the interior of their polygon is
// on the left of every edge; a ring vertex's neighbours are the far ends of its edges (end0,
// end1), so the rings themselves are not kept.
struct Sites {
  SiteList sites;
  std::size_t shapes = 0;  // merged polygons, or plain input items (Site::shape < shapes)
};

}  // namespace linf
