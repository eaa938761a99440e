// Results as a GDSII stream for the editor to read: KLayout reads a file and copies its shapes
// in C++, where drawing them one by one through its Python API costs 11-14 us a shape
// (minutes on a full layer). One cell; coordinates in DBU, rounded to the grid (ties to even,
// as Python's round()).
#pragma once
#include <array>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>

#include "linf/geometry/piece.hpp"

namespace linf {

// Drawing is never an error. Layouts hold 32-bit coordinates, but the diagram's rays and far
// pieces reach the clip box (the input's box enlarged by its larger side on every side: up to
// 3 x 2^31 from the origin for input within +-2^30). Where a piece is drawn (GDSII, OASIS, the
// editor) it is cut to the clip box within +-kDrawLimit; the CSV files keep it whole. Every
// piece lies in the clip box already, so cutting to the square +-kDrawLimit is the whole rule.
constexpr double kDrawLimit = 2147483647.0;  // 2^31 - 1: symmetric, and every KLayout coordinate

// Cuts the segment (x1, y1)-(x2, y2) to the square +-kDrawLimit, in place. False if no point of
// it lies in the square. A segment inside it is left exactly as it was (the drawing of a layer
// within the range does not change).
bool cut_to_drawable(double& x1, double& y1, double& x2, double& y2);

class GdsWriter {
 public:
  // Throws std::runtime_error if the file cannot be written. dbu: micrometres per DBU.
  GdsWriter(const std::string& path, double dbu, const std::string& cell);
  ~GdsWriter();
  // A two-point path of width zero, cut to the square +-kDrawLimit (cut_to_drawable). False,
  // and nothing written, where no point of it is in the square.
  bool path(int layer, int datatype, double x1, double y1, double x2, double y2);
  // Throws std::out_of_range beyond GDSII's 32 bits (a gauge's label lies on the layer).
  void text(int layer, int datatype, double x, double y, const std::string& s);
  void close();  // ends the cell and the library; throws on a write error

 private:
  struct Stream;
  std::unique_ptr<Stream> s_;
};

struct GdsLayers {
  int layer = 0;                                    // every kind on this layer number...
  std::array<int, 4> datatype{200, 201, 202, 203};  // ...with these datatypes (PieceKind order)
  double dbu = 0.001;
  std::string cell = "VORONOI";  // name the target cell's, and KLayout reads the file straight into it
};

// Pieces drawn per kind (PieceKind order). A piece whose ends round to the same grid point
// is not drawn: a path needs two distinct points; nor is a piece wholly beyond +-kDrawLimit.
using DrawCounts = std::array<std::size_t, 4>;

DrawCounts write_pieces_gds(const Diagram& d, const GdsLayers& layers, const std::string& path);

// The same drawing as the pieces come: each piece longer than the grid a path on its kind's
// datatype, counted in `drawn`.
void draw_pieces(GdsWriter& w, const GdsLayers& layers, const Piece* pieces, std::size_t n, DrawCounts& drawn);

}  // namespace linf
