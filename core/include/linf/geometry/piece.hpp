// Pieces: the output of the diagram, straight parts of Voronoi edges.
#pragma once
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "linf/geometry/site.hpp"

namespace linf {

struct Vec2 {
  double x = 0, y = 0;
};

enum class PieceKind : std::uint8_t {
  Internal,  // inside a polygon, between two of its features (the L-inf medial axis)
  External,  // between two different polygons
  Notch,     // outside a polygon, between two non-adjacent features of that polygon
  Adjacent,  // between an edge and its own endpoint
};

const char* kind_name(PieceKind k);

// One straight piece of a Voronoi edge, owned by sites `a` and `b` (indices into Sites::sites);
// d1/d2: L-inf clearance to the owners at p/q. A builder's pieces run one way (orient()), so
// that every builder writes the same files.
struct Piece {
  Vec2 p, q;
  double d1 = 0, d2 = 0;
  std::int32_t a = -1, b = -1;
  PieceKind kind = PieceKind::External;
};

// The piece turned, d1 and d2 with its ends, to run along (1, g), g the golden ratio's
// fraction: no bisector of axis-parallel or 45-degree sites is perpendicular to that, so the
// rounding of two builders, or of the same input moved far away, never turns a piece (by x,
// then y, an upright piece would turn with its ends' last bits). Perpendicular: by x, then y.
inline void orient(Piece& c) {
  const double along = (c.q.x - c.p.x) + 0.6180339887498949 * (c.q.y - c.p.y);
  if (along < 0 || (along == 0 && (c.q.x < c.p.x || (c.q.x == c.p.x && c.q.y < c.p.y))))
    std::swap(c.p, c.q), std::swap(c.d1, c.d2);
}

struct Box {
  double x1 = 0, y1 = 0, x2 = 0, y2 = 0;
};

struct Diagram {
  Sites sites;
  std::vector<Piece> pieces;
  Box clip;                 // rays are clipped to this box
  int attempts = 0;         // constructions tried until one passed the checker
  std::size_t tiles = 0, tile_tasks = 0, largest_tile_sites = 0;  // how the builder cut the work
  bool swept = false;       // built by the sweep-line builder (sweep.hpp), not the subdivision
  double seconds_merge = 0, seconds_build = 0, seconds_extract = 0, seconds_check = 0, seconds_csv = 0;
};

}  // namespace linf
