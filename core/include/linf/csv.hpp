// The diagram as CSV: one row per piece, in micrometres (the batch's voronoi.csv).
//
//   header: kind,x1,y1,x2,y2,d1,d2,a_x1,a_y1,a_x2,a_y2,b_x1,b_y1,b_x2,b_y2
//   values: DBU times `dbu`, six decimals; a point site repeats its coordinates.
// Written here rather than row by row in Python: a large layer has millions of pieces.
#pragma once
#include <string>

#include "linf/piece.hpp"

namespace linf {

// Writes the file and its time into d.seconds_csv; throws std::runtime_error if it cannot.
void write_pieces_csv(Diagram& d, double dbu, const std::string& path);

}  // namespace linf
