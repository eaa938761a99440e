// Convex cells with labelled edges, clipped by half-planes. The builder's only geometric
// construction: every Voronoi piece is an edge of such a cell.
#pragma once
#include <vector>

#include "affine.hpp"
#include "linf/piece.hpp"

namespace linf::detail {

// Edge i runs from v[i] to v[(i+1) % n]; counter-clockwise. label[i] >= 0: the site whose
// comparison created the edge; kBoundary: a box side or a split between affine pieces.
struct Cell {
  static constexpr int kBoundary = -1;
  std::vector<Vec2> v;
  std::vector<int> label;
  bool empty() const { return v.size() < 3; }
};

inline Cell box_cell(const Box& b) {
  Cell c;
  c.v = {{b.x1, b.y1}, {b.x2, b.y1}, {b.x2, b.y2}, {b.x1, b.y2}};
  c.label.assign(4, Cell::kBoundary);
  return c;
}

// Keeps the part where h >= 0; the new edge gets `label`. Values within rounding of zero
// count as on the line, so a line through a vertex never produces a sliver.
Cell clip(const Cell& in, const Affine& h, int label);

// The same in place, without copying when the half-plane holds the whole cell (the common
// case). Returns false once the cell is empty.
bool clip_in_place(Cell& c, const Affine& h, int label);

double area(const Cell& c);

}  // namespace linf::detail
