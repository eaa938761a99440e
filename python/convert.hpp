// Plain data between Python and the core, shared by the bindings: buffers read in place as the
// core's arrays, lists as its structs, its results as dicts. Conversions only; what computes is
// in core/.
#pragma once
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <cstdint>
#include <cstring>
#include <string>
#include <string_view>
#include <type_traits>
#include <utility>
#include <vector>

#include "linf/diagram/diagram.hpp"
#include "linf/geometry/polygons.hpp"
#include "linf/io/gds.hpp"
#include "linf/pipeline/stream.hpp"
#include "linf/pipeline/whole.hpp"
#include "linf/util/strided.hpp"

namespace linf::bind {

namespace py = pybind11;

using XY = std::pair<Coord, Coord>;
using PyPolygons = std::vector<std::pair<std::vector<XY>, std::vector<std::vector<XY>>>>;

// A Python tile runner, callable(next, done) (see TileRunner in builder.hpp; the batch's is
// plugin/python/linf_opc/cluster.py): next() -> the next job's bytes or None, done(bytes).
// None: no runner. The core calls it with the GIL released; it takes the GIL to call Python
// and releases it again while next and done work. `runner` must outlive the TileRunner.
TileRunner runner_of(const py::object& runner);

// A Python callable(stage, done, total) as the core's ProgressFn (linf/util/progress.hpp); None:
// none. Called from the core's threads, it takes the GIL; an exception it raises is reported
// as unraisable and dropped (the core is never unwound from a watcher). `fn` must outlive it.
ProgressFn progress_of(const py::object& fn);

// A contiguous buffer of signed 64-bit integers (array('q')).
const std::int64_t* int64s_of(const py::buffer_info& info, const char* name);

// The core's input polygons: flat (points, rings) arrays, points = array('q') of x0, y0, x1,
// y1, ...; rings = array('q') of point counts, each outer ring followed by its holes with
// negative counts, read in place (a full layer's copy would be hundreds of MB); or
// [(outer, [holes])] lists, flattened here. Malformed arrays raise ValueError when the core
// reads them (std::invalid_argument).
class LayerInput {
 public:
  explicit LayerInput(const py::object& obj);
  const FlatPolygons& flat() const { return view_; }

 private:
  py::buffer_info points_, rings_;  // held while the core reads them
  PolygonArrays owned_;
  FlatPolygons view_;
};

// A contiguous buffer of doubles (array('d'), memoryview), its length a multiple of `group`,
// read in place: a full layer's gauge points are hundreds of MB.
struct Doubles {
  py::buffer_info info;
  const double* data = nullptr;
  std::size_t n = 0;
  std::size_t size() const { return n; }
  double operator[](std::size_t i) const { return data[i]; }
};

Doubles doubles_of(const py::buffer& b, std::size_t group, const char* name);

// One column of values read in place, possibly strided (a memoryview slice such as
// reals[4::10] of the gauge table): the selection reads millions of gauges without a copy.
template <class T>
struct Column {
  py::buffer_info info;  // held while the core reads it
  Strided<T> values;
  std::size_t size() const { return values.size(); }
  T operator[](std::size_t i) const { return values[i]; }
};

template <class T>
Column<T> column_of(const py::buffer& b, const char* name) {
  Column<T> c{b.request(), {}};
  if (c.info.format != py::format_descriptor<T>::format() || c.info.ndim != 1)
    throw py::value_error(std::string(name) + " must be a one-dimensional buffer of " +
                          (std::is_same_v<T, double> ? "doubles, array('d')" : "int32, array('i')"));
  c.values.data = static_cast<const char*>(c.info.ptr);
  c.values.stride = c.info.strides[0];
  c.values.n = std::size_t(c.info.shape[0]);
  return c;
}

template <class T>
py::bytes bytes_of(const std::vector<T>& v) {
  return py::bytes(reinterpret_cast<const char*>(v.data()), v.size() * sizeof(T));
}

// A Python bytes object of n bytes, filled in place: a large layer's columns are hundreds of MB,
// and a C++ buffer copied into bytes would hold them twice.
py::bytes blank_bytes(std::size_t n, char*& data);

// A bytes object's contents, read in place: valid while the object lives (its caller holds it).
std::string_view bytes_view(const py::bytes& b);

DiagramOptions options(const py::object& check, int pairs, int threads, double tile = 0, const py::object& progress = py::none(),
                       const std::string& builder = "sweep");

// What is taken from the diagram while the core holds it: voronoi.csv and the pieces as GDSII
// for the editor to read (`gds_layer`: the input's layer number, datatypes 200 + kind).
StreamOutputs outputs_of(const std::string& csv, double dbu, const std::string& gds, int gds_layer,
                         const std::string& gds_cell);

// The diagram's summary: 'check', 'sites', 'polygons', 'clip', 'tiles', 'seconds'.
py::dict summary_dict(const Diagram& d, const CheckReport& c);
// The same with 'pieces' as tuples.
py::dict result_dict(const Result& r);
// The diagram stage's dict, as voronoi_polygons and gauges_polygons return it, from either
// path: the summary, 'pieces' (tuples in memory, a count streamed), 'counts' and, if drawn, 'drawn'.
py::dict stage_dict(const WholeResult& w, bool with_drawn);
py::dict stage_dict(const StreamResult& r, bool with_drawn);

}  // namespace linf::bind
