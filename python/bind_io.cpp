// The writers the editor and the batch read results from: the gauges drawn as GDSII, some
// gauges as gauges.csv, a result layout as OASIS, and the report picture's grid of a layer.
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <cstdint>
#include <optional>
#include <string>
#include <tuple>
#include <vector>

#include "bind.hpp"
#include "convert.hpp"
#include "linf/io/csv.hpp"
#include "linf/io/gauge_table.hpp"
#include "linf/io/gds.hpp"
#include "linf/io/oasis.hpp"
#include "linf/io/picture_grid.hpp"

namespace linf::bind {

namespace {
// The gauge table's columns as gauges_polygons returns them, read in place: a full layer's are
// hundreds of MB.
struct GaugeColumns {
  py::buffer_info reals, ints;  // held while the core reads them
  GaugeTableView table;
};

GaugeColumns gauge_columns(const py::buffer& reals, const py::buffer& ints) {
  GaugeColumns c{reals.request(), ints.request(), {}};
  const py::buffer_info &ri = c.reals, &ii = c.ints;
  if (ri.itemsize != 8 || ri.format != "d" || ii.itemsize != 4 || (ii.format != "i" && ii.format != "l"))
    throw py::value_error("reals must be float64 and ints int32 columns, as gauges_polygons returns them");
  const std::size_t n = std::size_t(ri.size) / kGaugeReals;
  if (std::size_t(ri.size) != kGaugeReals * n || std::size_t(ii.size) != kGaugeInts * n)
    throw py::value_error("reals must hold 10 values a gauge and ints 13");
  c.table = {static_cast<const double*>(ri.ptr), static_cast<const std::int32_t*>(ii.ptr), n};
  return c;
}
}  // namespace

void bind_io(py::module_& m) {
  m.def(
      "cut_to_drawable",
      [](double x1, double y1, double x2, double y2) -> py::object {
        if (!cut_to_drawable(x1, y1, x2, y2)) return py::none();
        return py::make_tuple(x1, y1, x2, y2);
      },
      py::arg("x1"), py::arg("y1"), py::arg("x2"), py::arg("y2"),
      "The segment cut to the square +-(2^31 - 1) DBU, where layouts can hold it: (x1, y1, x2, y2), unchanged\n"
      "if it lies inside, or None if no point of it does. Every drawing of the diagrams goes through it (the\n"
      "core's GDSII drawings and the farthest diagram's layers); the CSV files keep the whole pieces.");

  m.def(
      "picture_coverage",
      [](const py::object& polys, int cells_across, double large) {
        const LayerInput in(polys);
        PictureGrid c;
        {
          py::gil_scoped_release unlocked;
          c = picture_grid(in.flat(), cells_across, large);
        }
        py::dict d;
        d["x0"] = c.x0, d["y0"] = c.y0, d["cell"] = c.cell, d["nx"] = c.nx, d["ny"] = c.ny;
        d["cells"] = py::bytes(reinterpret_cast<const char*>(c.cells.data()), c.cells.size());
        d["large"] = py::make_tuple(
            py::bytes(reinterpret_cast<const char*>(c.large.points.data()), c.large.points.size() * 8),
            py::bytes(reinterpret_cast<const char*>(c.large.rings.data()), c.large.rings.size() * 8));
        return d;
      },
      py::arg("polygons"), py::arg("cells_across"), py::arg("large") = 2.0,
      "A layer at a picture's scale, without a copy of it: {'x0', 'y0', 'cell', 'nx', 'ny': the grid, square\n"
      "cells from the layer box's lower left corner, cells_across along its longer side; 'cells': bytes, nx a\n"
      "row from the bottom, 1 where the box of a polygon narrower than `large` cells (in width or height)\n"
      "touches; 'large': the other polygons as flat (points, rings) bytes of int64}.");

  m.def(
      "oasis_from_drawing",
      [](const std::string& drawing, const py::object& polys, int layer, int datatype,
         const std::vector<std::tuple<int, int, std::string>>& names, double dbu, const std::string& cell,
         const std::string& path, const std::vector<std::tuple<int, int, py::buffer>>& boxes) {
        const LayerInput in(polys);
        std::vector<LayerName> ln;
        for (const auto& [l, d, n] : names) ln.push_back({l, d, n});
        std::vector<LayerBoxes> lb;
        for (const auto& [l, d, b] : boxes) {
          const py::buffer_info bi = b.request();
          const std::int64_t* v = int64s_of(bi, "boxes");
          if (bi.shape[0] % 4) throw py::value_error("boxes: four values a box, x1, y1, x2, y2");
          lb.push_back({l, d, {}});
          for (py::ssize_t i = 0; i < bi.shape[0]; i += 4) lb.back().boxes.push_back({v[i], v[i + 1], v[i + 2], v[i + 3]});
        }
        py::gil_scoped_release unlocked;
        return oasis_from_drawing(drawing, in.flat(), layer, datatype, ln, dbu, cell, path, lb);
      },
      py::arg("drawing"), py::arg("polygons"), py::arg("layer"), py::arg("datatype"), py::arg("names"),
      py::arg("dbu"), py::arg("cell"), py::arg("path"), py::arg("boxes") = std::vector<std::tuple<int, int, py::buffer>>{},
      "Writes a result layout as OASIS without KLayout holding it: the polygons (the input layer) on\n"
      "layer/datatype, then boxes: [(layer, datatype, array('q') x1, y1, x2, y2 a box)], then every path and\n"
      "text of a GDSII drawing the core wrote (write_gauges_gds, the diagram's draw_layer; '' for none), in one\n"
      "cell; names: (layer, datatype, name) for the result layers. Returns the number of shapes written.");

  m.def(
      "write_gauges_gds",
      [](const std::string& path, double dbu, int layer, int datatype, py::buffer reals, py::buffer ints,
         const std::string& cell) {
        const GaugeColumns c = gauge_columns(reals, ints);
        py::gil_scoped_release unlocked;
        write_gauges_gds(c.table, path, dbu, layer, datatype, cell);
      },
      py::arg("path"), py::arg("dbu"), py::arg("layer"), py::arg("datatype"), py::arg("reals"), py::arg("ints"),
      py::arg("cell") = "GAUGES",
      "Writes gauges as GDSII for the editor to read in one call, from the columns gauges_polygons returns (reals\n"
      "float64 x10, ints int32 x13 a gauge): each measurement line a zero-width path on layer/datatype and its label\n"
      "'#rank type cd' (cd in micrometres) as a text at the gauge point, in one cell of that name. Coordinates\n"
      "rounded to the grid, ties to even; dbu: micrometres per DBU.");

  m.def(
      "write_gauges_csv_rows",
      [](const std::string& path, double dbu, py::buffer reals, py::buffer ints, py::buffer rows,
         const py::object& contexts, const py::object& counts) {
        const GaugeColumns c = gauge_columns(reals, ints);
        const Column<std::int32_t> picked = column_of<std::int32_t>(rows, "rows");
        std::vector<std::size_t> at(picked.size());
        for (std::size_t i = 0; i < at.size(); ++i) {
          if (picked[i] < 0) throw py::index_error("rows: a negative row");
          at[i] = std::size_t(picked[i]);
        }
        if (contexts.is_none() != counts.is_none())
          throw py::value_error("contexts and counts come together");
        std::optional<GaugeContexts> extra;
        if (!contexts.is_none()) {
          extra.emplace();
          for (auto [from, name, to] : {std::tuple{&contexts, "contexts", &extra->ids},
                                        std::tuple{&counts, "counts", &extra->counts}}) {
            const py::buffer b = from->cast<py::buffer>();
            const py::buffer_info info = b.request();
            if (info.ndim != 1 || info.itemsize != 8 || (info.format != "Q" && info.format != "L"))
              throw py::value_error(std::string(name) + " must be a one-dimensional array('Q')");
            const auto* v = static_cast<const std::uint64_t*>(info.ptr);
            to->assign(v, v + info.shape[0]);
          }
        }
        py::gil_scoped_release unlocked;
        write_gauges_csv_rows(c.table, at, dbu, path, extra ? &*extra : nullptr);
      },
      py::arg("path"), py::arg("dbu"), py::arg("reals"), py::arg("ints"), py::arg("rows"),
      py::arg("contexts") = py::none(), py::arg("counts") = py::none(),
      "Writes some gauges as gauges.csv (header, then one line a gauge, in micrometres; dbu: micrometres per\n"
      "DBU) from the columns gauges_polygons returns (reals float64 x10, ints int32 x13 a gauge): rows, array('i'),\n"
      "the gauges' indices in the columns in the order written. Each line is the one the whole table's gauges.csv\n"
      "holds for that gauge (id and rank its rank in the table). A row beyond the columns raises IndexError.\n"
      "contexts, counts: array('Q'), one value a row: adds the columns context (16 hex digits) and count.");
}

}  // namespace linf::bind
