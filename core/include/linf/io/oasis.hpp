// A result layout written as OASIS by the core, for layers whose results are tens of millions
// of shapes: KLayout would hold them all in a Layout while it saves (gigabytes on a full layer).
//
//   in:  the core's own GDSII drawing (gds.hpp: two-point paths of width zero and texts), the
//        input layer's polygons, the names of the result layers;
//   out: one OASIS cell holding the input polygons (holes joined to their outline by cut
//        lines, as OASIS has no holes) and every path and text of the drawing, streamed.
// A plain subset of OASIS 1.0: no name tables, positions relative to the previous shape's,
// records deflated in CBLOCKs; KLayout reads it as the same shapes (tests/klayout/check_core_oasis.py).
#pragma once
#include <array>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "linf/geometry/polygons.hpp"
#include "linf/geometry/site.hpp"

namespace linf {

class OasisWriter {
 public:
  // Throws std::runtime_error if the file cannot be written. dbu: micrometres per DBU.
  OasisWriter(const std::string& path, double dbu, const std::string& cell);
  ~OasisWriter();
  // A name for a layer/datatype pair (for geometry and for texts); all before any shape.
  void layer_name(const std::string& name, int layer, int datatype);
  // An outline without holes, at least three points.
  void polygon(int layer, int datatype, const Ring& outline);
  // A two-point path of width zero with flush ends.
  void path(int layer, int datatype, std::int64_t x1, std::int64_t y1, std::int64_t x2, std::int64_t y2);
  void text(int layer, int datatype, std::int64_t x, std::int64_t y, const std::string& s);
  // The shapes from here on go into a new cell of this name (a library of clips); a cell that
  // got no shape is not written, but for the last.
  void cell(const std::string& name);
  void close();  // ends the file; throws on a write error

 private:
  struct Stream;
  std::unique_ptr<Stream> s_;
};

struct LayerName {
  int layer = 0, datatype = 0;
  std::string name;
};

// A box (x1, y1, x2, y2) as the outline of a polygon.
Ring box_ring(const std::array<std::int64_t, 4>& b);

// A polygon as outlines without holes (each hole joined to its outline by a cut line).
std::vector<Ring> outlines(const Polygon& p);

// Boxes (x1, y1, x2, y2) on one layer/datatype: the selection's windows.
struct LayerBoxes {
  int layer = 0, datatype = 0;
  std::vector<std::array<std::int64_t, 4>> boxes;
};

// The input polygons on (layer, datatype), then the boxes, then the drawing's paths and texts
// (none for an empty name), into `path`. Returns the number of shapes written. Throws
// std::runtime_error on an unreadable drawing.
std::size_t oasis_from_drawing(const std::string& drawing, const FlatPolygons& input, int layer,
                               int datatype, const std::vector<LayerName>& names, double dbu,
                               const std::string& cell, const std::string& path,
                               const std::vector<LayerBoxes>& boxes = {});

}  // namespace linf
