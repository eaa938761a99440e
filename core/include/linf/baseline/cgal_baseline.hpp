// CGAL's L-inf segment Delaunay graph (the thesis's implementation), turned into plain
// polylines. Not used to build diagrams: it is wrong on some inputs (tests/cpp/
// test_reproducers.cpp). It serves as the speed baseline and to show the checker at work.
#pragma once
#include <cstdint>
#include <vector>

#include "linf/geometry/piece.hpp"
#include "linf/geometry/site.hpp"

namespace linf {

// One Voronoi edge as CGAL draws it: a polyline, possibly with rays at its ends
// (a ray starts at the first/last vertex and goes along dir_in/dir_out).
struct RawEdge {
  std::int32_t a = -1, b = -1;
  std::vector<Vec2> pts;
  bool ray_in = false, ray_out = false;
  Vec2 dir_in, dir_out;
};

// Builds the diagram of `sites` (segments must not cross; they may share endpoints).
// `order_seed` permutes the segment insertion order: CGAL's failures depend on it.
// Throws std::runtime_error if a CGAL site cannot be mapped back to an input site.
std::vector<RawEdge> cgal_linf_edges(const Sites& sites, std::uint64_t order_seed);

// Wall time of CGAL's construction alone (range insertion), the benchmark's baseline.
double cgal_linf_construction_seconds(const Sites& sites, std::uint64_t order_seed);

// The same edges as pieces clipped to `clip` (clearances from the first owner), for the
// checker and for comparisons. CGAL's assertion failures come through as exceptions.
std::vector<Piece> cgal_linf_pieces(const Sites& sites, const Box& clip, std::uint64_t order_seed);

}  // namespace linf
