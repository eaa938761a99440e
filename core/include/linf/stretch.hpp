// Stretches: the diagram regrouped by what it separates.
//
//   in:  a Diagram (pieces with owner sites)
//   out: Stretches = maximal chains of pieces owned by the same two sites, as ordered paths
//        with the clearance at every path point; plus, at diagram vertices where three or
//        more sites meet, a point stretch for each meeting pair that has no chain of its own
//        (the centre of a square via, where the four corner bisectors meet, is the only place
//        its top and bottom edges are equally near).
#pragma once
#include <cstdint>
#include <vector>

#include "linf/piece.hpp"

namespace linf {

struct Stretch {
  std::int32_t a = -1, b = -1;   // owner sites, a < b
  PieceKind kind = PieceKind::External;
  std::vector<Vec2> path;        // at least one point; consecutive points are piece ends
  std::vector<double> clearance; // L-inf clearance to the owners at each path point
  double length = 0;             // Euclidean length of the path
};

std::vector<Stretch> stretches_of(const Diagram& d);

// Two sites are adjacent when they share a vertex (an edge and its endpoint, two edges of one
// corner, the two ends of one edge): the distance between them is not a width or a space.
bool adjacent(const Sites& s, std::int32_t a, std::int32_t b);

}  // namespace linf
