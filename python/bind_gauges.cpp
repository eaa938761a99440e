// The gauges stage: the diagram, then its gauges ranked, handed over as the gauge table.
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <chrono>
#include <cmath>
#include <cstring>
#include <functional>
#include <optional>
#include <string>

#include "bind.hpp"
#include "convert.hpp"
#include "linf/gauges/context.hpp"
#include "linf/gauges/neighbours.hpp"
#include "linf/gauges/gauge.hpp"
#include "linf/io/csv.hpp"
#include "linf/io/gauge_table.hpp"
#include "linf/pipeline/stream.hpp"
#include "linf/pipeline/whole.hpp"

namespace linf::bind {

namespace {

double since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// The gauge table (gauge_table.hpp) as two bytes objects, or in `file` for the caller to map;
// with the stretches' paths if asked for, else the stretches are let go first and the rows are
// made on `threads` threads. The gauges are consumed (g.gauges is empty after).
py::dict gauge_table(const Sites& sites, Gauges& g, bool with_paths, const std::string& file, int threads) {
  if (!with_paths) g.stretches = Stretches();
  const std::size_t n = g.gauges.size();
  py::object reals = py::none(), ints = py::none();
  std::optional<GaugeTableWriter> table;
  if (file.empty()) {
    char *rd = nullptr, *id = nullptr;
    reals = blank_bytes(kGaugeRealBytes * n, rd);
    ints = blank_bytes(kGaugeIntBytes * n, id);
    table.emplace(n, rd, id);
  } else {
    table.emplace(n, file);
  }
  py::list paths;
  std::function<void(const Gauge&)> each;
  if (with_paths)
    each = [&](const Gauge& x) {
      py::list pts;
      for (const Vec2& v : g.stretches[x.stretch].path) pts.append(py::make_tuple(v.x, v.y));
      paths.append(pts);
    };
  write_gauge_table(sites, g, *table, each, threads);
  py::dict out;
  out["count"] = n;
  out["reals"] = reals;
  out["ints"] = ints;
  out["file"] = file.empty() ? py::object(py::none()) : py::object(py::str(file));
  out["paths"] = with_paths ? py::object(paths) : py::object(py::none());
  return out;
}

// The gauge table's records of `size` bytes read in place, for permute_records and
// take_records: contiguous, or (`column`) also a strided view of single values.
struct Records {
  py::buffer_info info;  // held while they are read
  const char* data = nullptr;
  std::ptrdiff_t step = 0;
  std::size_t n = 0;
  const char* operator[](std::size_t i) const { return data + std::ptrdiff_t(i) * step; }
};

Records records_of(const py::buffer& b, std::size_t size, bool column, const std::string& who) {
  Records r{b.request()};
  const py::buffer_info& d = r.info;
  const bool strided = d.ndim == 1 && d.strides[0] != d.itemsize && column && std::size_t(d.itemsize) == size;
  if (d.ndim != 1 || (d.strides[0] != d.itemsize && !strided))
    throw py::value_error(who + (column ? ": the data must be contiguous, or a column of single values"
                                        : ": the data must be contiguous"));
  const std::size_t bytes = std::size_t(d.size) * std::size_t(d.itemsize);
  if (size == 0 || bytes % size != 0) throw py::value_error(who + ": the data is not whole records");
  r.data = static_cast<const char*>(d.ptr);
  r.step = strided ? d.strides[0] : std::ptrdiff_t(size);
  r.n = bytes / size;
  return r;
}

}  // namespace

void bind_gauges(py::module_& m) {
  m.def(
      "gauges_polygons",
      [](const py::object& polys, const py::object& check, int pairs, int threads, double tooth_fraction, double space_limit,
         bool with_pieces, bool with_paths, double tile, const std::string& csv, double dbu, const std::string& gds,
         int gds_layer, const std::string& gds_cell, const std::string& gauges_csv, const std::string& columns,
         const py::object& tiles, const py::object& progress, const std::string& builder) {
        const LayerInput in(polys);
        const TileRunner runner = runner_of(tiles);
        StreamOutputs files = outputs_of(csv, dbu, gds, gds_layer, gds_cell);
        GaugeOptions o;
        o.tooth_fraction = tooth_fraction;
        o.space_limit_widths = space_limit;
        o.threads = threads;
        const ProgressFn told = progress_of(progress);
        auto stage = [&](const char* name) {
          if (told) told(name, 0, 0);
        };
        Diagram diagram;  // sites and statistics
        Gauges g;
        double seconds = 0;
        py::dict d;
        if (with_pieces) {
          WholeResult w;
          {
            py::gil_scoped_release unlocked;
            w = voronoi_whole(in.flat(), options(check, pairs, threads, tile, progress, builder), files);
          }
          d = stage_dict(w, !gds.empty());
          py::gil_scoped_release unlocked;
          stage("placing the gauges");
          const auto t0 = std::chrono::steady_clock::now();
          Stretches st = take_gauge_stretches(w.result.diagram);
          g = gauges_of(w.result.diagram.sites, std::move(st), o);
          seconds = since(t0);
          diagram = std::move(w.result.diagram);
        } else {
          // The pieces stream past the writers and into the stretches: never all in memory.
          files.keep = measurable_pair;
          files.keep_measurable = true;
          StreamResult r;
          {
            py::gil_scoped_release unlocked;
            r = stream_voronoi(in.flat(), options(check, pairs, threads, tile, progress, builder), files, runner);
            stage("placing the gauges");
            const auto t0 = std::chrono::steady_clock::now();
            g = gauges_of(r.diagram.sites, std::move(r.stretches), o);
            seconds = r.seconds_stretches + since(t0);
          }
          d = stage_dict(r, !gds.empty());
          diagram = std::move(r.diagram);
        }
        if (!gauges_csv.empty()) {
          py::gil_scoped_release unlocked;
          stage("writing gauges.csv");
          write_gauges_csv(diagram.sites, g, dbu, gauges_csv);
        }
        d["seconds"].cast<py::dict>()["gauges"] = seconds;
        py::dict res;
        res["stretches"] = g.measurable;
        res["gauges"] = gauge_table(diagram.sites, g, with_paths, columns, threads);
        res["typical_width"] = g.typical_width;
        res["space_limit"] = g.space_limit;
        res["diagram"] = d;
        return res;
      },
      py::arg("polygons"), py::arg("check") = true, py::arg("check_pairs") = 2000, py::arg("threads") = 0,
      py::arg("tooth_fraction") = 0.5, py::arg("space_limit_widths") = 10.0, py::arg("pieces") = false, py::arg("paths") = false,
      py::arg("tile") = -1.0, py::arg("csv") = "", py::arg("dbu") = 1.0, py::arg("gds") = "", py::arg("gds_layer") = 0,
      py::arg("gds_cell") = "VORONOI", py::arg("gauges_csv") = "", py::arg("columns") = "",
      py::arg("tiles") = py::none(), py::arg("progress") = py::none(), py::arg("builder") = "sweep",
      "Ranked gauges of polygons (same input as voronoi_polygons); the diagram is built and checked first.\n"
      "Returns {'gauges': {'count': n, 'reals': bytes, 'ints': bytes, 'paths': [[(x, y)]] if paths=True else None},\n"
      "'stretches': n, ...}: the gauges in rank order as columns, float64 x10 per gauge (x1, y1, x2, y2, cx, cy, cd,\n"
      "score, norm_score, tiebreak) and int32 x13 (rank, teeth, site_a, site_b, a_x1, a_y1, a_x2, a_y2, b_x1, b_y1,\n"
      "b_x2, b_y2, type: 0 internal, 1 external, 2 sandwich, 3 comb, 4 T); 'stretches': the measurable stretches,\n"
      "'typical_width', 'space_limit', 'diagram': {'counts', 'pieces', 'sites', 'check', 'clip', 'seconds'}}.\n"
      "DBU throughout. space_limit_widths: spaces wider than this many typical widths are not pattern (0: keep all).\n"
      "pieces=True: 'diagram' also holds the pieces as voronoi_polygons returns them (else they stream past, see\n"
      "voronoi_polygons). csv, gds, gds_layer, dbu:\n"
      "as in voronoi_polygons, and gds_cell. gauges_csv: also write the gauges there (gauges.csv, micrometres).\n"
      "columns: write the two column blocks into this file (reals for every gauge, then ints) instead of bytes:\n"
      "'gauges' is then {'count', 'file', 'reals': None, 'ints': None, 'paths'}, for the caller to map.\n"
      "tiles: as in voronoi_polygons (with pieces=False). progress: as in voronoi_polygons, then 'placing the\n"
      "gauges' and 'writing gauges.csv'. builder: as in voronoi_polygons.");

  m.def(
      "gauge_contexts",
      [](const py::object& polys, const py::buffer& points, double radius, int threads) {
        const LayerInput in(polys);
        const Doubles at = doubles_of(points, 2, "points");
        const std::int64_t r = std::llround(radius);
        std::vector<std::uint64_t> ids;
        {
          py::gil_scoped_release unlocked;
          const PolygonIndex ix(in.flat());
          const BoxTree boxes(ix.size(), [&](std::size_t i) { return ix.box(i); });
          ids = context_ids(ix, boxes, at.data, at.size() / 2, r, threads);
        }
        char* out = nullptr;
        py::bytes b = blank_bytes(8 * ids.size(), out);
        for (std::size_t i = 0; i < ids.size(); ++i)
          for (int k = 0; k < 8; ++k) out[8 * i + std::size_t(k)] = char((ids[i] >> (8 * k)) & 0xffu);
        return b;
      },
      py::arg("polygons"), py::arg("points"), py::arg("radius"), py::arg("threads") = 0,
      "Context ids of points on a merged layer (docs/design.md, 'Gauge contexts'): for each point, the layer\n"
      "clipped exactly to the square of half-side `radius` around it, taken up to translation and the eight\n"
      "symmetries of the square, hashed. polygons: as gauges_polygons takes them; points: array('d') x0, y0,\n"
      "x1, y1, ... in DBU (rounded to the nearest half DBU); radius in DBU (rounded to an integer, >= 1).\n"
      "Returns bytes: one unsigned 64-bit id per point, little-endian (array('Q', ...) on this platform).");

  m.def(
      "neighbour_spaces",
      [](const py::buffer& x, const py::buffer& y, const py::buffer& cd, const py::buffer& types, const py::buffer& asked,
         double radius, int threads) {
        const Column<double> cx = column_of<double>(x, "x"), cy = column_of<double>(y, "y"), c = column_of<double>(cd, "cd");
        const Column<std::int32_t> t = column_of<std::int32_t>(types, "types"), a = column_of<std::int32_t>(asked, "asked");
        if (cy.size() != cx.size() || c.size() != cx.size() || t.size() != cx.size())
          throw py::value_error("x, y, cd and types must be columns of the same gauges");
        std::vector<SpacePoint> g(cx.size());
        for (std::size_t i = 0; i < g.size(); ++i) {
          if (t[i] < 0 || t[i] > int(GaugeType::T)) throw py::value_error("a gauge type index out of range");
          g[i] = {cx[i], cy[i], c[i], GaugeType(t[i])};
        }
        std::vector<std::int32_t> which(a.size());
        for (std::size_t i = 0; i < which.size(); ++i) which[i] = a[i];
        std::vector<double> spaces;
        {
          py::gil_scoped_release unlocked;
          spaces = neighbouring_spaces(g, which, radius, threads);
        }
        return bytes_of(spaces);
      },
      py::arg("x"), py::arg("y"), py::arg("cd"), py::arg("types"), py::arg("asked"), py::arg("radius"),
      py::arg("threads") = 0,
      "Neighbouring spaces of gauges (docs/design.md, 'Split rules'): for each index of `asked` (array('i')),\n"
      "the least cd among the other kind's gauges (external for a width gauge, internal for an external\n"
      "one) whose points lie within `radius` DBU (L-infinity) of its point; NaN where there is none. x, y, cd:\n"
      "double columns, types: int32 indices (internal, external, sandwich, comb, T), one entry a gauge\n"
      "(the gauge table's column views). Returns bytes: one double per asked gauge (array('d')).");

  m.def(
      "permute_records",
      [](const py::buffer& data, std::size_t size, const py::buffer& order) {
        const Records r = records_of(data, size, false, "permute_records");
        const Column<std::int32_t> o = column_of<std::int32_t>(order, "order");
        const std::size_t n = r.n;
        if (o.size() != n) throw py::value_error("permute_records: the order must name every record once");
        char* to = nullptr;
        py::bytes out = blank_bytes(n * size, to);
        std::vector<bool> seen(n, false);
        for (std::size_t k = 0; k < n; ++k) {
          const std::int32_t i = o[k];
          if (i < 0 || std::size_t(i) >= n || seen[std::size_t(i)])
            throw py::value_error("permute_records: the order must name every record once");
          seen[std::size_t(i)] = true;
          std::memcpy(to + k * size, r[std::size_t(i)], size);
        }
        return out;
      },
      py::arg("data"), py::arg("size"), py::arg("order"),
      "The gauge table's records in a new order: `data` holds records of `size` bytes (the table's reals\n"
      "or ints), `order` (array('i')) names each record once; record k of the result is record order[k].\n"
      "ValueError when the data is not whole records or the order is not a permutation.");

  m.def(
      "take_records",
      [](const py::buffer& data, std::size_t size, const py::buffer& index) {
        const Records r = records_of(data, size, true, "take_records");
        const py::buffer_info x = index.request();
        if (x.ndim != 1 || x.itemsize != 8 || (x.format != "q" && x.format != "l"))
          throw py::value_error("take_records: the index must be a one-dimensional buffer of int64, array('q')");
        const std::size_t m = std::size_t(x.shape[0]);
        const char* at = static_cast<const char*>(x.ptr);
        char* to = nullptr;
        py::bytes out = blank_bytes(m * size, to);
        for (std::size_t k = 0; k < m; ++k) {
          std::int64_t i;
          std::memcpy(&i, at + std::ptrdiff_t(k) * x.strides[0], sizeof i);
          if (i < 0 || std::size_t(i) >= r.n) throw py::value_error("take_records: an index names no record");
          std::memcpy(to + k * size, r[std::size_t(i)], size);
        }
        return out;
      },
      py::arg("data"), py::arg("size"), py::arg("index"),
      "Records picked by number: `data` holds records of `size` bytes (or is a strided column of values of\n"
      "that size), `index` (array('q')) numbers them;\n"
      "record k of the result is record index[k] (any number of times, or none). A loop of C over columns\n"
      "of millions of gauges. ValueError for data that is not whole records or an index that names none.");
}

}  // namespace linf::bind
