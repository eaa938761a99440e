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
#include <functional>
#include <string>
#include <string_view>
#include <vector>

#include "linf/io/oasis.hpp"
#include "linf/geometry/polygons.hpp"

namespace linf {

struct Clip {
  std::string name;                      // the cell's (clip_name)
  std::array<std::int64_t, 4> window{};  // x1, y1, x2, y2 (DBU): the clip boundary
  std::array<std::int64_t, 4> line{};    // the measurement line's ends
  std::array<std::int64_t, 2> at{};      // where its label goes
  std::string label;                     // clip_label
  std::vector<std::array<std::int64_t, 4>> markers;
};

// What names and labels a clip: its gauge's rank, type and values (micrometres).
struct ClipGauge {
  std::int64_t rank = 0;
  std::string_view type;
  double cd_um = 0, score_um = 0, norm_score = 0, tiebreak_um = 0;
};
// SET_rRANK_TYPE_SCORE, e.g. CAL_r000042_sandwich_0p0245 (the score in um to 4 decimals,
// '.' -> 'p', '-' -> 'm'): a cell name KLayout and OPC tools take as it is.
std::string clip_name(std::string_view set_prefix, const ClipGauge& g);
// "#RANK TYPE cd=.. score=.. norm=.. tiebreak=.." (4 significant digits), beside the line.
std::string clip_label(const ClipGauge& g);

struct ClipLayers {
  int layer = 0, datatype = 0;          // the clipped shapes
  int gauges = 210, windows = 220, markers = 230;  // datatypes on `layer`
};

// Sets every field of clip i (the same Clip is passed again and again), asked for in order,
// i = 0 .. count - 1. A full layer's split has hundreds of thousands of clips: each is made,
// written and let go, so only the caller's plain columns are held (a name and a label of
// each, as text, were most of the writer's memory).
using ClipSource = std::function<void(std::size_t i, Clip& clip)>;

std::size_t write_clip_library(const std::string& path, double dbu, const FlatPolygons& layer,
                               const ClipLayers& layers, std::size_t count, const ClipSource& clip_at);

// The clips as the plugin's split holds them: plain columns, a row a clip, read in place.
struct ClipColumns {
  std::size_t count = 0;
  const std::int64_t* windows = nullptr;        // x1, y1, x2, y2 (DBU)
  const std::int64_t* lines = nullptr;          // the measurement line's ends, x1, y1, x2, y2
  const std::int64_t* at = nullptr;             // x, y: where the label goes
  const std::int64_t* ranks = nullptr;          // the gauge's rank
  const unsigned char* types = nullptr;         // the gauge's type, an index into type_names
  const double* values = nullptr;               // score, cd, norm_score, tiebreak (DBU but norm_score)
  const std::int64_t* marker_counts = nullptr;  // the clip's markers...
  const double* marker_boxes = nullptr;         // ...in turn, x1, y1, x2, y2 each (DBU)
  std::size_t marker_values = 0;                // doubles in marker_boxes
};

struct ClipLibrarySpec {
  std::string path;
  double dbu = 0.001;  // micrometres per DBU
  FlatPolygons layer;  // as drawn
  ClipLayers layers;
  std::string prefix;                   // the set's (clip_name)
  std::vector<std::string> type_names;  // by type index
  ClipColumns clips;
};

// The same from columns: each clip named and labelled from its gauge's values in micrometres,
// its markers rounded to the grid as KLayout rounds a box given in micrometres. Throws
// std::invalid_argument, before anything is written, for a type beyond type_names, a negative
// marker count, or marker boxes that do not add up to the counts.
std::size_t write_clip_library(const ClipLibrarySpec& spec);

}  // namespace linf
