// The public entry point of the diagram stage.
//
//   in:  polygons with holes (integer DBU, any angle, may overlap or touch), or plain points
//        and non-crossing segments;
//   out: Diagram = the sites, and the straight Voronoi pieces with owners, clearances, kinds,
//        checked by the independent checker before they are returned.
#pragma once
#include <stdexcept>
#include <vector>

#include "linf/diagram/builder.hpp"
#include "linf/diagram/checker.hpp"
#include "linf/geometry/piece.hpp"
#include "linf/geometry/polygons.hpp"
#include "linf/geometry/site.hpp"
#include "linf/util/progress.hpp"

namespace linf {

struct DiagramOptions {
  BuildOptions build;
  bool check = true;          // run the checker on the result
  CheckOptions checker;
  ProgressFn progress;        // told of the stages and of the builder's tasks (util/progress.hpp)
  bool sweep = false;         // build with the sweep-line builder where it takes the layer
                              // (sweep_handles, linf/diagram/sweep.hpp), with build's tiles and
                              // threads; else, and by default, the subdivision
};

// Thrown when the checker rejects a diagram: a wrong diagram is never handed on silently.
struct DiagramError : std::runtime_error {
  CheckReport report;
  DiagramError(const std::string& what, CheckReport r) : std::runtime_error(what), report(std::move(r)) {}
};

struct Result {
  Diagram diagram;
  CheckReport check;  // empty if options.check is false
};

// The input's bounding box enlarged by its larger side on every side: where rays end.
Box clip_box(const Sites& s);

// Polygons as flat arrays (a view: nothing copied; polygons.hpp), or as a vector.
Result voronoi_of_polygons(const FlatPolygons& polygons, const DiagramOptions& opt = {});
Result voronoi_of_polygons(const std::vector<Polygon>& polygons, const DiagramOptions& opt = {});
Result voronoi_of_sites(const std::vector<Point>& points, const std::vector<Segment>& segments,
                        const DiagramOptions& opt = {});

}  // namespace linf
