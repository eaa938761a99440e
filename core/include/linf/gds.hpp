// The diagram as a GDSII stream: one cell, each piece a two-point path of width zero on its
// kind's layer. The editor reads it into the layout in one C++ call; drawing the pieces one by
// one through KLayout's Python API costs 11-14 us a piece, minutes on a full layer.
#pragma once
#include <array>
#include <cstddef>
#include <string>

#include "linf/piece.hpp"

namespace linf {

struct GdsLayers {
  int layer = 0;                                 // every kind on this layer number...
  std::array<int, 4> datatype{200, 201, 202, 203};  // ...with these datatypes (PieceKind order)
  double dbu = 0.001;                            // micrometres per DBU, as the layout's
  std::string cell = "VORONOI";
};

// Pieces drawn per kind (PieceKind order). A piece whose ends round to the same DBU grid point
// is not drawn: a path needs two distinct points.
using DrawCounts = std::array<std::size_t, 4>;

// Writes the file; throws std::runtime_error if it cannot, or std::out_of_range if a coordinate
// does not fit GDSII's 32 bits.
DrawCounts write_pieces_gds(const Diagram& d, const GdsLayers& layers, const std::string& path);

}  // namespace linf
