// The diagram stage with the diagram held whole: the outputs of the streamed stage
// (stream.hpp), the same voronoi.csv and drawing and the pieces counted per kind, while the
// caller keeps the pieces. For a layer small enough to hold them, or a caller that wants them.
#pragma once
#include "linf/diagram/diagram.hpp"
#include "linf/io/gds.hpp"
#include "linf/pipeline/stream.hpp"

namespace linf {

struct WholeResult {
  Result result;
  DrawCounts counts{};  // pieces per kind
  DrawCounts drawn{};   // drawn per kind, if out.gds
};

// out.keep is not used: the caller holds the pieces to make stretches of. Throws DiagramError
// if the checker rejects the diagram, before any file is written.
WholeResult voronoi_whole(const FlatPolygons& polygons, const DiagramOptions& opt, const StreamOutputs& out);

}  // namespace linf
