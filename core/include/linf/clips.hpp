// Clip libraries: the split's calibration and verification patterns as one OASIS file each,
// written by the core (KLayout kept about 2 KB a cell of a library of hundreds of thousands of
// clips, even after deleting it).
//
//   in:  the layer's polygons as drawn (flat arrays, as the flow holds them) and the clips;
//   out: one cell a clip, in layout coordinates: the layer's merged shapes inside the window
//        (on the layer), the gauge's measurement line and label, the window outline and the
//        markers that meet it (on their datatypes); returns the number of shapes written.
#pragma once
#include <array>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "linf/oasis.hpp"
#include "linf/polygons.hpp"

namespace linf {

// The name and the label are views into the caller's text: a full layer's split has hundreds
// of thousands of clips, and a string of each, held twice, was most of the writer's memory.
struct Clip {
  std::string_view name;
  std::array<std::int64_t, 4> window{};  // x1, y1, x2, y2 (DBU): the clip boundary
  std::array<std::int64_t, 4> line{};    // the measurement line's ends
  std::array<std::int64_t, 2> at{};      // where its label goes
  std::string_view label;
  std::vector<std::array<std::int64_t, 4>> markers;
};

struct ClipLayers {
  int layer = 0, datatype = 0;          // the clipped shapes
  int gauges = 210, windows = 220, markers = 230;  // datatypes on `layer`
};

std::size_t write_clip_library(const std::string& path, double dbu, const FlatPolygons& layer,
                               const ClipLayers& layers, const std::vector<Clip>& clips);

}  // namespace linf
