// Convex cells clipped by half-planes. The builder's only geometric construction: every
// Voronoi piece is (part of) an edge of such a cell.
#pragma once
#include <boost/container/small_vector.hpp>

#include "affine.hpp"
#include "linf/geometry/piece.hpp"

namespace linf::detail {

// Vertices counter-clockwise; edge i runs from v[i] to v[(i+1) % n].
// Cells are small (a box cut by a few half-planes) and made by the million: their vertices live
// inline, not on the heap.
struct Cell {
  boost::container::small_vector<Vec2, 10> v;
  bool empty() const { return v.size() < 3; }
};

inline Cell box_cell(const Box& b) {
  Cell c;
  c.v = {{b.x1, b.y1}, {b.x2, b.y1}, {b.x2, b.y2}, {b.x1, b.y2}};
  return c;
}

// Keeps the part of c where h >= 0, in place. Returns false once the cell is empty.
bool clip_in_place(Cell& c, const Affine& h);

double area(const Cell& c);

}  // namespace linf::detail
