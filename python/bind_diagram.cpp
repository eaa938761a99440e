// The diagram stage: the L-inf segment Voronoi diagram of polygons or of plain sites.
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include "bind.hpp"
#include "convert.hpp"
#include "linf/diagram/diagram.hpp"
#include "linf/pipeline/stream.hpp"
#include "linf/pipeline/tile_task.hpp"
#include "linf/pipeline/whole.hpp"

namespace linf::bind {

void bind_diagram(py::module_& m) {
  // A diagram the independent checker rejects: a RuntimeError with the checker's first message.
  py::register_exception<DiagramError>(m, "DiagramError", PyExc_RuntimeError);

  m.def(
      "voronoi_polygons",
      [](const py::object& polys, const py::object& check, int pairs, int threads, double tile, const std::string& csv,
         double dbu, bool with_pieces, const std::string& gds, int gds_layer, const std::string& gds_cell,
         const py::object& tiles, const py::object& progress, const std::string& builder) {
        const LayerInput in(polys);
        const TileRunner runner = runner_of(tiles);
        const StreamOutputs files = outputs_of(csv, dbu, gds, gds_layer, gds_cell);
        if (with_pieces) {
          WholeResult w;
          {
            py::gil_scoped_release unlocked;
            w = voronoi_whole(in.flat(), options(check, pairs, threads, tile, progress, builder), files);
          }
          return stage_dict(w, !gds.empty());
        }
        StreamResult r;
        {
          py::gil_scoped_release unlocked;
          r = stream_voronoi(in.flat(), options(check, pairs, threads, tile, progress, builder), files, runner);
        }
        return stage_dict(r, !gds.empty());
      },
      py::arg("polygons"), py::arg("check") = true, py::arg("check_pairs") = 2000, py::arg("threads") = 0,
      py::arg("tile") = -1.0, py::arg("csv") = "", py::arg("dbu") = 1.0, py::arg("pieces") = true,
      py::arg("gds") = "", py::arg("gds_layer") = 0, py::arg("gds_cell") = "VORONOI", py::arg("tiles") = py::none(),
      py::arg("progress") = py::none(), py::arg("builder") = "sweep",
      "Diagram of polygons [(outer, [holes])], rings as [(x, y)] in integer DBU, or the same flat:\n"
      "(points, rings), points array('q') x0, y0, x1, y1, ..., rings array('q') of point counts, each outer\n"
      "ring followed by its holes with negative counts. Shapes are merged first.\n"
      "Returns {'pieces': [(kind, x1, y1, x2, y2, d1, d2, a_x1, a_y1, a_x2, a_y2, b_x1, b_y1, b_x2, b_y2,\n"
      "site_a, site_b)], 'check': {...}, 'sites': n, 'clip': box, 'seconds': {...}}.\n"
      "threads: worker threads of the builder, 0 for one per core.\n"
      "tile: side of the builder's tiles in DBU (same diagram for every size); 0 one tile, < 0 automatic.\n"
      "csv: also write the pieces there (voronoi.csv, micrometres: DBU times dbu).\n"
      "gds: also write them there as GDSII, zero-width paths on gds_layer, datatype 200 + kind index, in one cell\n"
      "named gds_cell (dbu: its units); 'drawn' then counts them per kind (a piece rounding to one grid point is\n"
      "not drawn).\n"
      "pieces=False: 'pieces' is only their number (a large layer's pieces as tuples take gigabytes), and the\n"
      "pieces stream past the checker and the writers tile by tile, never all in memory (same files).\n"
      "'counts': pieces per kind. Raises DiagramError if the independent checker rejects the diagram.\n"
      "tiles: with pieces=False, a callable(next, done) that has the tiles built elsewhere: next() gives the next\n"
      "tile job's bytes (None when none is left), each job's result bytes (build_tile_job) go to done() in the\n"
      "order the jobs were taken. Same pieces, same files.\n"
      "progress: a callable(stage, done, total): the stages' names as they start (done 0), and inside the\n"
      "builder's and the merge's stages how many parts are done of how many, at most ten times a second, from\n"
      "the core's threads (it is given the GIL); what it raises is reported and dropped.\n"
      "builder: 'sweep' (default), the sweep-line builder (any layer; with `tile`, `threads` and `tiles`), or\n"
      "'subdivision', the subdivision builder (several times slower; the tests' oracle). Same pieces.");

  m.def(
      "build_tile_job",
      [](const py::bytes& job, int threads) {
        const std::string_view in = bytes_view(job);  // the caller holds the bytes: no copy
        std::string out;
        {
          py::gil_scoped_release unlocked;
          out = run_tile_job(in, threads);
        }
        return py::bytes(out);
      },
      py::arg("job"), py::arg("threads") = 1,
      "One tile job's result bytes from its bytes (see voronoi_polygons' tiles), with `threads` builder workers\n"
      "(0: one a core); the same bytes on every host. Where the job asks (gauges_polygons' sweep tiles), its pieces\n"
      "are also classified and read for the gauges' stretches here. ValueError for bytes that are not a job of this core.");

  m.def(
      "voronoi_sites",
      [](const std::vector<XY>& points, const std::vector<std::pair<XY, XY>>& segments, const py::object& check, int pairs,
         int threads, const std::string& builder) {
        std::vector<Point> p;
        for (auto& q : points) p.push_back({q.first, q.second});
        std::vector<Segment> s;
        for (auto& g : segments) s.push_back({{g.first.first, g.first.second}, {g.second.first, g.second.second}});
        Result r;
        {
          py::gil_scoped_release unlocked;
          r = voronoi_of_sites(p, s, options(check, pairs, threads, 0, py::none(), builder));
        }
        return result_dict(r);
      },
      py::arg("points"), py::arg("segments"), py::arg("check") = true, py::arg("check_pairs") = 2000,
      py::arg("threads") = 0, py::arg("builder") = "subdivision",
      "Diagram of plain sites: points [(x, y)] and non-crossing segments [((x1, y1), (x2, y2))]. Same output.\n"
      "builder: 'subdivision' (default; it also takes segments that cross) or 'sweep' (several times faster;\n"
      "segments that do not cross, points off the segments' insides, as a merged layer's sites are).");
}

}  // namespace linf::bind
