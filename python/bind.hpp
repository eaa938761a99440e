// The module's functions, one group a stage; module.cpp puts them together.
#pragma once
#include <pybind11/pybind11.h>

namespace linf::bind {

void bind_diagram(pybind11::module_& m);    // voronoi_polygons, voronoi_sites, DiagramError
void bind_gauges(pybind11::module_& m);     // gauges_polygons
void bind_selection(pybind11::module_& m);  // select_windows, free_windows, cover_points, estimate_pitch*
void bind_split(pybind11::module_& m);      // write_clip_library
void bind_farthest(pybind11::module_& m);   // farthest_voronoi
void bind_io(pybind11::module_& m);         // write_gauges_gds, oasis_from_drawing, picture_coverage
void bind_litho(pybind11::module_& m);      // litho_kernels, calibrate_threshold, gauge_printability

}  // namespace linf::bind
