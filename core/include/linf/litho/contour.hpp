// Contours of a sampled image at a level (marching squares): the printed contours of the
// report's and the editor's pictures.
#pragma once
#include <vector>

namespace linf::litho {

// The segments where `values` (an m x m grid, value [j * m + i]) crosses `level`, over the
// cells [lo, hi - 1) x [lo, hi - 1) (cell (i, j) has corners (i, j) .. (i + 1, j + 1)), four
// doubles a segment (x1, y1, x2, y2) in grid units, cells row by row. A corner is inside when
// its value is >= level; an edge's crossing is interpolated linearly; a saddle (corners inside
// and outside alternately) is split by the mean of its four corners. Throws
// std::invalid_argument when the grid is not m x m or [lo, hi) is not inside it.
std::vector<double> contour_segments(const std::vector<double>& values, int m, int lo, int hi, double level);

}  // namespace linf::litho
