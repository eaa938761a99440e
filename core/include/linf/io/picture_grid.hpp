// What a picture of a whole layer can show, computed without a second copy of the layer: the
// report's picture of a layer of millions of shapes is a few hundred pixels across, so a
// shape smaller than a couple of pixels is a dot there.
//
//   in:  the layer's polygons (flat arrays) and how many grid cells across its box's longer side;
//   out: the grid (square cells from the layer box's lower left corner), the cells touched by
//        the box of each polygon narrower than `large` cells in width or in height (row by row
//        from the bottom, 1 = touched), and the other polygons, to be drawn as they are.
#pragma once
#include <cstdint>
#include <vector>

#include "linf/geometry/polygons.hpp"

namespace linf {

struct PictureGrid {
  double x0 = 0, y0 = 0, cell = 1;
  int nx = 0, ny = 0;
  std::vector<std::uint8_t> cells;
  PolygonArrays large;
};

PictureGrid picture_grid(const FlatPolygons& layer, int cells_across, double large = 2);

}  // namespace linf
