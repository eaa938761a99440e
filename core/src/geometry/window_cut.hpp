// A layer cut to windows: the shapes that meet a window, merged and cut to it, as KLayout's
// `layer & window` gives them. The clip libraries (split/clips.cpp) write these polygons and
// the pattern classes (selection/pattern_classes.cpp) compare them. Internal to the core.
#pragma once
#include <boost/polygon/polygon.hpp>

#include <array>
#include <cstdint>
#include <vector>

#include "linf/geometry/polygons.hpp"
#include "linf/util/box_tree.hpp"

namespace linf {

class WindowCut {
 public:
  // Indexes the layer's polygons by their boxes; `layer` must outlive this.
  explicit WindowCut(const FlatPolygons& layer);
  // The layer inside the window (x1, y1, x2, y2), merged, holes joined to their outlines by
  // cut lines (Boost.Polygon's polygon_data): no polygon for an empty window.
  std::vector<boost::polygon::polygon_data<int>> cut(const std::array<std::int64_t, 4>& window) const;

 private:
  PolygonIndex index_;
  BoxTree tree_;
};

}  // namespace linf
