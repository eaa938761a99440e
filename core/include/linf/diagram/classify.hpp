// Piece kinds from the owners and the side of the boundary the piece lies on.
#pragma once
#include "linf/geometry/piece.hpp"
#include "linf/geometry/site.hpp"

namespace linf {

// A point whose nearest site is s is reached from s without crossing the boundary, so the side
// of s (left of an edge, or inside the interior wedge at a vertex) tells inside from outside.
bool inside_near(const Sites& s, std::int32_t site, const Vec2& p);

PieceKind classify(const Sites& s, const Piece& piece);

}  // namespace linf
