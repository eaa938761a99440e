// The Python module linf_opc_cgal: CGAL's L-inf segment Delaunay graph for the benchmarks
// (bench/cgal_baseline.py). Built with the tests and the benchmarks only, never installed:
// the shipped module linf_opc_core does not hold CGAL's construction.
#include <pybind11/pybind11.h>

#include <cstdint>

#include "convert.hpp"
#include "linf/baseline/cgal_baseline.hpp"
#include "linf/geometry/sites.hpp"

namespace py = pybind11;
using linf::bind::LayerInput;

PYBIND11_MODULE(linf_opc_cgal, m) {
  m.doc() = "CGAL's L-infinity segment Voronoi diagram: the benchmarks' baseline (not shipped)";
  m.def(
      "cgal_construction_seconds",
      [](const py::object& polys, std::uint64_t seed) {
        const LayerInput in(polys);
        py::gil_scoped_release unlocked;
        return linf::cgal_linf_construction_seconds(linf::sites_of_polygons(linf::merge_polygons(in.flat()).view()),
                                                    seed);
      },
      py::arg("polygons"), py::arg("seed") = 1,
      "Benchmark baseline: seconds CGAL's Segment_Delaunay_graph_Linf_2 takes to construct the diagram of the\n"
      "same sites (range insertion, segments in shuffled order). Its result is not used: it can be wrong.");
}
