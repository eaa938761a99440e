// The diagram stage for a layer too large to hold its pieces.
//
//   in:  polygons (as voronoi_of_polygons) and what to make of the pieces: voronoi.csv, the
//        drawing, the stretches between the pairs `keep` accepts;
//   out: the sites, the pieces' counts, the check, those files and stretches: the same bytes
//        and the same stretches as the in-memory stage (Diagram + write_pieces_csv,
//        write_pieces_gds, stretches_of), while only one tile's pieces are in memory.
//
// The builder hands over each tile's pieces (build_parts); they are classified, their vertices
// given to the stretches (StretchStream), and written to a temporary file as one sorted run.
// Then the runs are merged by owner pair, each pair's pieces joined as build_pieces joins
// them, and the checker, the writers and the stretches take them in that order, in batches.
// The temporary file (in $TMPDIR, else /tmp; deleted when closed) holds the pieces: 64 bytes
// each, about 1.8 GB a million wires.
#pragma once
#include <functional>
#include <string>
#include <vector>

#include "linf/diagram/builder.hpp"
#include "linf/diagram/diagram.hpp"
#include "linf/io/gds.hpp"
#include "linf/gauges/stretch.hpp"

namespace linf {

struct StreamOutputs {
  std::string csv;    // voronoi.csv here, if not empty
  double dbu = 1.0;   // micrometres per DBU, for the CSV
  std::string gds;    // the drawing here, if not empty
  GdsLayers layers;
  // Stretches between the pairs this accepts (with the sites); none if empty.
  std::function<bool(const Sites&, std::int32_t a, std::int32_t b, PieceKind kind)> keep;
  // keep is measurable_pair (the gauges'): then a runner's sweep tiles are classified and read
  // for the stretches by their own tasks (tile_task.hpp), not here.
  bool keep_measurable = false;
};

struct StreamResult {
  Diagram diagram;      // sites, clip, statistics and timings; no pieces
  std::size_t pieces = 0;
  DrawCounts counts{};  // pieces per kind
  DrawCounts drawn{};   // drawn per kind
  CheckReport check;    // empty if the check is off
  Stretches stretches;  // if outputs.keep
  double seconds_stretches = 0;
};

// Throws DiagramError if the checker rejects the diagram, after removing the files it wrote.
// `tiles`, if set, builds the tiles elsewhere (build_parts with a TileRunner, builder.hpp): the
// parts reach the same classification, runs, merge, check and writers, so the same bytes.
StreamResult stream_voronoi(const FlatPolygons& polygons, const DiagramOptions& opt, const StreamOutputs& out,
                            const TileRunner& tiles = {});
StreamResult stream_voronoi(const std::vector<Polygon>& polygons, const DiagramOptions& opt, const StreamOutputs& out,
                            const TileRunner& tiles = {});

}  // namespace linf
