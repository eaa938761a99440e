#include "linf/pipeline/whole.hpp"

#include "linf/io/csv.hpp"

namespace linf {

WholeResult voronoi_whole(const FlatPolygons& polygons, const DiagramOptions& opt, const StreamOutputs& out) {
  WholeResult w;
  w.result = voronoi_of_polygons(polygons, opt);
  Diagram& d = w.result.diagram;
  for (const Piece& p : d.pieces) ++w.counts[std::size_t(p.kind)];
  if (!out.csv.empty()) write_pieces_csv(d, out.dbu, out.csv);
  if (!out.gds.empty()) w.drawn = write_pieces_gds(d, out.layers, out.gds);
  return w;
}

}  // namespace linf
