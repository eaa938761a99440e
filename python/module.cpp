// Thin binding: plain Python data in, plain Python data out. No logic lives here.
#include <pybind11/pybind11.h>

#include <fcntl.h>
#include <unistd.h>

#include <array>
#include <climits>
#include <cstdio>
#include <cerrno>
#include <cstring>
#include <stdexcept>
#include <chrono>
#include <string>
#include <tuple>
#include <pybind11/stl.h>

#include "linf/clips.hpp"
#include "linf/coverage.hpp"
#include "linf/csv.hpp"
#include "linf/diagram.hpp"
#include "linf/engine.hpp"
#include "linf/gds.hpp"
#include "linf/oasis.hpp"
#include "linf/pages.hpp"
#include "linf/farthest.hpp"
#include "linf/gauge.hpp"
#include "linf/selection.hpp"
#include "linf/sites.hpp"
#include "linf/stream.hpp"

namespace py = pybind11;
using namespace linf;

namespace {
using XY = std::pair<Coord, Coord>;

Ring ring_of(const std::vector<XY>& pts) {
  Ring r;
  r.reserve(pts.size());
  for (auto& p : pts) r.push_back({p.first, p.second});
  return r;
}

using PyPolygons = std::vector<std::pair<std::vector<XY>, std::vector<std::vector<XY>>>>;

// A contiguous buffer of signed 64-bit integers (array('q')).
const std::int64_t* int64s_of(const py::buffer_info& info, const char* name) {
  if (info.ndim != 1 || info.itemsize != 8 || (info.format != "q" && info.format != "l"))
    throw py::value_error(std::string(name) + " must be a flat array of 64-bit integers, array('q')");
  return static_cast<const std::int64_t*>(info.ptr);
}

// The core's input polygons: flat (points, rings) arrays, points = array('q') of x0, y0, x1,
// y1, ...; rings = array('q') of point counts, each outer ring followed by its holes with
// negative counts, read in place (a full layer's copy would be hundreds of MB); or
// [(outer, [holes])] lists, flattened here. Malformed arrays raise ValueError when the core
// reads them (std::invalid_argument).
class LayerInput {
 public:
  explicit LayerInput(const py::object& obj) {
    if (py::isinstance<py::tuple>(obj) && py::len(obj) == 2 && PyObject_CheckBuffer(obj[py::int_(0)].ptr())) {
      points_ = py::buffer(obj[py::int_(0)]).request(), rings_ = py::buffer(obj[py::int_(1)]).request();
      view_ = {int64s_of(points_, "points"), std::size_t(points_.shape[0]) / 2, int64s_of(rings_, "rings"),
               std::size_t(rings_.shape[0])};
      return;
    }
    for (auto& p : obj.cast<PyPolygons>()) {
      Polygon q;
      q.outer = ring_of(p.first);
      for (auto& h : p.second) q.holes.push_back(ring_of(h));
      owned_.add(q);
    }
    view_ = owned_.view();
  }
  const FlatPolygons& flat() const { return view_; }

 private:
  py::buffer_info points_, rings_;  // held while the core reads them
  PolygonArrays owned_;
  FlatPolygons view_;
};

py::dict to_python_summary(const Diagram& d, const CheckReport& c) {
  py::dict check;
  check["ok"] = c.ok();
  check["sampled_points"] = c.sampled_points;
  check["pairs_tested"] = c.pairs_tested;
  check["pairs_separated"] = c.pairs_separated;
  check["worst_error"] = c.worst_error;
  check["messages"] = c.messages;
  py::dict out;
  out["check"] = check;
  out["sites"] = d.sites.sites.size();
  out["polygons"] = d.sites.shapes;  // after merging
  out["clip"] = py::make_tuple(d.clip.x1, d.clip.y1, d.clip.x2, d.clip.y2);
  py::dict tiles;
  tiles["tiles"] = d.tiles;
  tiles["tasks"] = d.tile_tasks;
  tiles["largest_tile_sites"] = d.largest_tile_sites;
  out["tiles"] = tiles;
  py::dict t;
  t["merge"] = d.seconds_merge;
  t["build"] = d.seconds_build;
  t["check"] = d.seconds_check;
  t["csv"] = d.seconds_csv;
  out["seconds"] = t;
  return out;
}

py::dict to_python(const Result& r) {
  const auto& S = r.diagram.sites.sites;
  py::list pieces;
  for (const Piece& p : r.diagram.pieces) {
    const Site& a = S[p.a];
    const Site& b = S[p.b];
    pieces.append(py::make_tuple(kind_name(p.kind), p.p.x, p.p.y, p.q.x, p.q.y, p.d1, p.d2, a.a.x, a.a.y, a.b.x,
                                 a.b.y, b.a.x, b.a.y, b.b.x, b.b.y, p.a, p.b));
  }
  py::dict out = to_python_summary(r.diagram, r.check);
  out["pieces"] = pieces;
  return out;
}

py::tuple site_tuple(const Site& s) { return py::make_tuple(s.a.x, s.a.y, s.b.x, s.b.y); }

template <class T>
py::bytes bytes_of(const std::vector<T>& v) {
  return py::bytes(reinterpret_cast<const char*>(v.data()), v.size() * sizeof(T));
}

// A Python bytes object of n bytes, filled in place: a large layer's columns are hundreds of MB,
// and a C++ buffer copied into bytes would hold them twice.
py::bytes blank_bytes(std::size_t n, char*& data) {
  PyObject* o = PyBytes_FromStringAndSize(nullptr, Py_ssize_t(n));
  if (!o) throw py::error_already_set();
  data = PyBytes_AsString(o);
  return py::reinterpret_steal<py::bytes>(o);
}

// Where the gauge columns go: into two Python bytes objects, or into one file (the reals block,
// then the ints block) that Python maps instead of holding: on a full layer the columns are the
// largest thing the flow keeps (132 bytes a gauge), and a mapped file's pages are the kernel's to
// drop and read again. Written through buffers with pwrite, not a writable mapping, so that a
// full disk is an exception and not a SIGBUS.
class ColumnSink {
 public:
  ColumnSink(std::size_t n, const std::string& file) : n_(n), file_(file) {
    if (file_.empty()) {
      reals_ = blank_bytes(kReal * n, rd_);
      ints_ = blank_bytes(kInt * n, id_);
      return;
    }
    fd_ = ::open(file_.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0600);
    if (fd_ < 0) throw std::runtime_error("cannot write the gauge columns to " + file_ + ": " + std::strerror(errno));
    buf_r_.resize(kReal * kBatch);
    buf_i_.resize(kInt * kBatch);
    rd_ = buf_r_.data(), id_ = buf_i_.data();
  }
  ~ColumnSink() {
    if (fd_ >= 0) ::close(fd_);
  }
  ColumnSink(const ColumnSink&) = delete;
  ColumnSink& operator=(const ColumnSink&) = delete;

  static constexpr std::size_t kReal = 10 * sizeof(double), kInt = 13 * sizeof(std::int32_t);

  // Where the next gauge's values go; next() after each gauge.
  char*& reals() { return rd_; }
  char*& ints() { return id_; }
  void next() {
    if (fd_ >= 0 && ++in_batch_ == kBatch) flush();
  }

  py::dict finish() {
    py::dict out;
    out["count"] = n_;
    if (fd_ < 0) {
      out["reals"] = reals_;
      out["ints"] = ints_;
      out["file"] = py::none();
      return out;
    }
    flush();
    if (::close(fd_) != 0) {
      fd_ = -1;
      throw std::runtime_error("cannot write the gauge columns to " + file_ + ": " + std::strerror(errno));
    }
    fd_ = -1;
    out["reals"] = py::none();
    out["ints"] = py::none();
    out["file"] = file_;
    return out;
  }

 private:
  static constexpr std::size_t kBatch = std::size_t(1) << 14;

  void put(const char* p, std::size_t left, std::uint64_t at) {
    while (left > 0) {
      const ssize_t k = pwrite(fd_, p, left, off_t(at));
      if (k < 0 && errno == EINTR) continue;
      if (k <= 0)
        throw std::runtime_error("cannot write the gauge columns to " + file_ + " (disk full?): " + std::strerror(errno));
      p += k, left -= std::size_t(k), at += std::uint64_t(k);
    }
  }
  void flush() {
    put(buf_r_.data(), kReal * in_batch_, kReal * done_);
    put(buf_i_.data(), kInt * in_batch_, kReal * n_ + kInt * done_);
    done_ += in_batch_, in_batch_ = 0;
    rd_ = buf_r_.data(), id_ = buf_i_.data();
  }

  std::size_t n_;
  std::string file_;
  int fd_ = -1;
  py::bytes reals_, ints_;
  std::vector<char> buf_r_, buf_i_;
  char *rd_ = nullptr, *id_ = nullptr;
  std::size_t in_batch_ = 0, done_ = 0;
};

// Gauges as columns in rank order, row-major blocks of plain numbers (a Python tuple a gauge
// would be most of the flow's memory on a large layer; plugin/python/linf_opc/gauges.py wraps
// them): "reals" float64 x10 (x1, y1, x2, y2, cx, cy, cd, score, norm_score, tiebreak), "ints"
// int32 x13 (rank, teeth, site_a, site_b, a_x1, a_y1, a_x2, a_y2, b_x1, b_y1, b_x2, b_y2, type
// index in internal, external, sandwich, comb, T); with `file`, both blocks in that file instead
// (ColumnSink). The stretches are let go first unless their paths are asked for, and the gauges
// as their columns are written (g.gauges is empty after).
py::dict gauge_columns(const Sites& sites, Gauges& g, bool with_paths, const std::string& file) {
  const auto& S = sites.sites;
  if (!with_paths) g.stretches = Stretches();
  const std::size_t n = g.gauges.size();
  ColumnSink sink(n, file);
  char*& rd = sink.reals();
  char*& id = sink.ints();
  py::list paths;
  // The gauges are consumed as the columns are written and their pages given back: on a full
  // layer both are gigabytes, and nothing reads the records afterwards.
  std::size_t done = 0, released = 0;
  for (const Gauge& x : g.gauges) {
    const MeasurementLine m = measurement_line(sites, x);
    for (double v : {m.p.x, m.p.y, m.q.x, m.q.y, x.at.x, x.at.y, x.cd, x.score, g.norm_score(x), x.tiebreak}) {
      std::memcpy(rd, &v, sizeof v);
      rd += sizeof v;
    }
    const Site& a = S[x.a];
    const Site& b = S[x.b];
    for (Coord v : {Coord(done + 1), Coord(x.teeth), Coord(x.a), Coord(x.b), a.a.x, a.a.y, a.b.x, a.b.y, b.a.x, b.a.y,
                    b.b.x, b.b.y, Coord(x.type)}) {
      if (v < INT32_MIN || v > INT32_MAX) throw py::value_error("coordinates beyond 32 bits (layouts have 32)");
      const std::int32_t w = std::int32_t(v);
      std::memcpy(id, &w, sizeof w);
      id += sizeof w;
    }
    sink.next();
    if (with_paths) {
      py::list pts;
      for (const Vec2& v : g.stretches[x.stretch].path) pts.append(py::make_tuple(v.x, v.y));
      paths.append(pts);
    }
    if (++done - released >= (std::size_t(1) << 16)) {
      detail::release_pages(g.gauges.data() + released, g.gauges.data() + done);
      released = done;
    }
  }
  g.gauges = Paged<Gauge>();
  py::dict out = sink.finish();
  out["paths"] = with_paths ? py::object(paths) : py::object(py::none());
  return out;
}

// A contiguous buffer of doubles (array('d'), memoryview), its length a multiple of `group`,
// read in place: a full layer's gauge points are hundreds of MB.
struct Doubles {
  py::buffer_info info;
  const double* data = nullptr;
  std::size_t n = 0;
  std::size_t size() const { return n; }
  double operator[](std::size_t i) const { return data[i]; }
};

Doubles doubles_of(const py::buffer& b, std::size_t group, const char* name) {
  Doubles d{b.request()};
  if (d.info.format != py::format_descriptor<double>::format() || d.info.ndim != 1)
    throw py::value_error(std::string(name) + " must be a flat array of doubles, array('d')");
  d.data = static_cast<const double*>(d.info.ptr);
  d.n = std::size_t(d.info.shape[0]);
  if (d.n % group) throw py::value_error(std::string(name) + ": length must be a multiple of " + std::to_string(group));
  return d;
}

// One column of values read in place, possibly strided (a memoryview slice such as
// reals[4::10] of the gauge table): the selection reads millions of gauges without a copy.
template <class T>
struct Column {
  py::buffer_info info;
  const char* data = nullptr;
  py::ssize_t stride = 0;
  std::size_t n = 0;
  std::size_t size() const { return n; }
  T operator[](std::size_t i) const {
    T v;
    std::memcpy(&v, data + py::ssize_t(i) * stride, sizeof v);
    return v;
  }
};

template <class T>
Column<T> column_of(const py::buffer& b, const char* name) {
  Column<T> c{b.request()};
  if (c.info.format != py::format_descriptor<T>::format() || c.info.ndim != 1)
    throw py::value_error(std::string(name) + " must be a one-dimensional buffer of " +
                          (std::is_same_v<T, double> ? "doubles, array('d')" : "int32, array('i')"));
  c.data = static_cast<const char*>(c.info.ptr);
  c.stride = c.info.strides[0];
  c.n = std::size_t(c.info.shape[0]);
  return c;
}

DiagramOptions options(bool check, int pairs, int threads, double tile = 0) {
  DiagramOptions o;
  o.check = check;
  o.checker.crossing_pairs = pairs;
  o.build.threads = threads;
  o.build.tile_size = tile;
  return o;
}

// What is taken from the diagram while the core holds it: the pieces per kind, voronoi.csv, and
// the pieces as GDSII for the editor to read (`gds_layer`: the input's layer number, datatypes
// 200 + kind).
struct Files {
  std::string csv, gds;
  int gds_layer = 0;
  double dbu = 1.0;
  std::string gds_cell;
  DrawCounts drawn{};
  DrawCounts counts{};  // pieces per kind, counted in C++: tens of millions on a layer

  GdsLayers layers() const {
    GdsLayers L;
    L.layer = gds_layer;
    L.dbu = dbu;
    L.cell = gds_cell;
    return L;
  }
  void write(Diagram& d) {
    for (const Piece& p : d.pieces) ++counts[std::size_t(p.kind)];
    if (!csv.empty()) write_pieces_csv(d, dbu, csv);
    if (!gds.empty()) drawn = write_pieces_gds(d, layers(), gds);
  }
  // The diagram held whole, its files written; the GIL released meanwhile.
  Result whole(const FlatPolygons& in, const DiagramOptions& o) {
    py::gil_scoped_release unlocked;
    Result r = voronoi_of_polygons(in, o);
    write(r.diagram);
    return r;
  }
  // The same files with the pieces streamed past (stream.hpp), never all in memory; with the
  // gauges' stretches if asked.
  StreamResult stream(const FlatPolygons& in, const DiagramOptions& o, bool stretches) {
    StreamOutputs so;
    so.csv = csv, so.dbu = dbu, so.gds = gds, so.layers = layers();
    if (stretches) so.keep = measurable_pair;
    StreamResult r = stream_voronoi(in, o, so);
    counts = r.counts, drawn = r.drawn;
    return r;
  }
  void report(py::dict& d) const {
    d["counts"] = counts_dict(counts);
    if (!gds.empty()) d["drawn"] = counts_dict(drawn);
  }
  static py::dict counts_dict(const DrawCounts& n) {
    py::dict out;
    for (PieceKind k : {PieceKind::Internal, PieceKind::External, PieceKind::Notch, PieceKind::Adjacent})
      out[kind_name(k)] = n[std::size_t(k)];
    return out;
  }
};

// DiagramError becomes ValueError with the checker's first message; nothing is returned.
template <class F>
py::dict guarded(F&& f) {
  Result r;
  {
    py::gil_scoped_release unlocked;
    r = f();
  }
  return to_python(r);
}
}  // namespace

PYBIND11_MODULE(linf_opc_core, m) {
  m.doc() = "L-infinity segment Voronoi diagram (core of the L-inf OPC KLayout plugin)";
  py::register_exception<DiagramError>(m, "DiagramError", PyExc_RuntimeError);

  m.def(
      "voronoi_polygons",
      [](const py::object& polys, bool check, int pairs, int threads, double tile, const std::string& csv,
         double dbu, bool with_pieces, const std::string& gds, int gds_layer, const std::string& gds_cell) {
        const LayerInput in(polys);
        Files files{csv, gds, gds_layer, dbu, gds_cell};
        py::dict d;
        if (with_pieces) {
          Result r = files.whole(in.flat(), options(check, pairs, threads, tile));
          d = to_python(r);
        } else {
          StreamResult r;
          {
            py::gil_scoped_release unlocked;
            r = files.stream(in.flat(), options(check, pairs, threads, tile), false);
          }
          d = to_python_summary(r.diagram, r.check);
          d["pieces"] = r.pieces;
        }
        files.report(d);
        return d;
      },
      py::arg("polygons"), py::arg("check") = true, py::arg("check_pairs") = 2000, py::arg("threads") = 0,
      py::arg("tile") = -1.0, py::arg("csv") = "", py::arg("dbu") = 1.0, py::arg("pieces") = true,
      py::arg("gds") = "", py::arg("gds_layer") = 0, py::arg("gds_cell") = "VORONOI",
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
      "'counts': pieces per kind. Raises DiagramError if the independent checker rejects the diagram.");

  m.def(
      "gauges_polygons",
      [](const py::object& polys, bool check, int pairs, int threads, double tooth_fraction, double space_limit,
         bool with_pieces, bool with_paths, double tile, const std::string& csv, double dbu, const std::string& gds,
         int gds_layer, const std::string& gds_cell, const std::string& gauges_csv, const std::string& columns) {
        const LayerInput in(polys);
        Files files{csv, gds, gds_layer, dbu, gds_cell};
        GaugeOptions o;
        o.tooth_fraction = tooth_fraction;
        o.space_limit_widths = space_limit;
        Diagram diagram;  // sites and statistics
        Gauges g;
        double seconds = 0;
        py::dict d;
        if (with_pieces) {
          Result r = files.whole(in.flat(), options(check, pairs, threads, tile));
          d = to_python(r);
          py::gil_scoped_release unlocked;
          const auto t0 = std::chrono::steady_clock::now();
          Stretches st = take_gauge_stretches(r.diagram);
          g = gauges_of(r.diagram.sites, std::move(st), o);
          seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
          diagram = std::move(r.diagram);
        } else {
          // The pieces stream past the writers and into the stretches: never all in memory.
          StreamResult r;
          {
            py::gil_scoped_release unlocked;
            r = files.stream(in.flat(), options(check, pairs, threads, tile), true);
            const auto t0 = std::chrono::steady_clock::now();
            g = gauges_of(r.diagram.sites, std::move(r.stretches), o);
            seconds = r.seconds_stretches + std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
          }
          d = to_python_summary(r.diagram, r.check);
          d["pieces"] = r.pieces;
          diagram = std::move(r.diagram);
        }
        files.report(d);
        if (!gauges_csv.empty()) {
          py::gil_scoped_release unlocked;
          write_gauges_csv(diagram.sites, g, dbu, gauges_csv);
        }
        d["seconds"].cast<py::dict>()["gauges"] = seconds;
        py::dict res;
        res["stretches"] = g.measurable;
        res["gauges"] = gauge_columns(diagram.sites, g, with_paths, columns);
        res["typical_width"] = g.typical_width;
        res["space_limit"] = g.space_limit;
        res["diagram"] = d;
        return res;
      },
      py::arg("polygons"), py::arg("check") = true, py::arg("check_pairs") = 2000, py::arg("threads") = 0,
      py::arg("tooth_fraction") = 0.5, py::arg("space_limit_widths") = 10.0, py::arg("pieces") = false, py::arg("paths") = false,
      py::arg("tile") = -1.0, py::arg("csv") = "", py::arg("dbu") = 1.0, py::arg("gds") = "", py::arg("gds_layer") = 0,
      py::arg("gds_cell") = "VORONOI", py::arg("gauges_csv") = "", py::arg("columns") = "",
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
      "'gauges' is then {'count', 'file', 'reals': None, 'ints': None, 'paths'}, for the caller to map.");

  m.def(
      "picture_coverage",
      [](const py::object& polys, int cells_across, double large) {
        const LayerInput in(polys);
        Coverage c;
        {
          py::gil_scoped_release unlocked;
          c = coverage(in.flat(), cells_across, large);
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
      "write_clip_library",
      [](const std::string& path, double dbu, const py::tuple& polygons, int layer, int datatype, int gauges,
         int windows, int markers, const std::string& prefix, const std::vector<std::string>& type_names,
         py::buffer window_box, py::buffer lines, py::buffer at, py::buffer ranks, const py::bytes& types,
         py::buffer values, py::buffer marker_counts, py::buffer marker_boxes) {
        if (py::len(polygons) != 2) throw py::value_error("polygons must be (points, rings) flat arrays");
        const LayerInput layer_input(polygons);
        const FlatPolygons& flat = layer_input.flat();
        const py::buffer_info wi = window_box.request(), li = lines.request(), ai = at.request(),
                              ri = ranks.request(), ci = marker_counts.request();
        const std::int64_t* w = int64s_of(wi, "windows");
        const std::int64_t* ln = int64s_of(li, "lines");
        const std::int64_t* a = int64s_of(ai, "at");
        const std::int64_t* rk = int64s_of(ri, "ranks");
        const std::int64_t* mc = int64s_of(ci, "marker_counts");
        const Doubles v = doubles_of(values, 4, "values");
        const Doubles mb = doubles_of(marker_boxes, 4, "markers");
        const std::string_view ty(PyBytes_AS_STRING(types.ptr()), std::size_t(PyBytes_GET_SIZE(types.ptr())));
        const std::size_t n = ty.size();
        if (std::size_t(wi.shape[0]) != 4 * n || std::size_t(li.shape[0]) != 4 * n || std::size_t(ai.shape[0]) != 2 * n ||
            std::size_t(ri.shape[0]) != n || v.size() != 4 * n || std::size_t(ci.shape[0]) != n)
          throw py::value_error("one window, line, label position, rank, type, 4 values and marker count a clip");
        std::vector<std::size_t> first_marker(n + 1, 0);
        for (std::size_t i = 0; i < n; ++i) {
          if (static_cast<unsigned char>(ty[i]) >= type_names.size()) throw py::value_error("a type beyond type_names");
          if (mc[i] < 0) throw py::value_error("a negative marker count");
          first_marker[i + 1] = first_marker[i] + std::size_t(mc[i]);
        }
        if (4 * first_marker[n] != mb.size()) throw py::value_error("the marker boxes do not match the counts");
        ClipLayers l;
        l.layer = layer, l.datatype = datatype, l.gauges = gauges, l.windows = windows, l.markers = markers;
        auto clip_at = [&](std::size_t i, Clip& c) {
          // As the plugin computed them: g.score * dbu and so on, then "%.4f" / "%.4g".
          const ClipGauge g{rk[i], type_names[static_cast<unsigned char>(ty[i])], v[4 * i + 1] * dbu,
                            v[4 * i] * dbu, v[4 * i + 2], v[4 * i + 3] * dbu};
          c.name = clip_name(prefix, g);
          c.label = clip_label(g);
          for (int k = 0; k < 4; ++k) c.window[k] = w[4 * i + k], c.line[k] = ln[4 * i + k];
          c.at = {a[2 * i], a[2 * i + 1]};
          c.markers.clear();
          for (std::size_t m = first_marker[i]; m < first_marker[i + 1]; ++m) {
            // As KLayout rounds a box given in micrometres (half away from zero).
            std::array<std::int64_t, 4> box{};
            for (int k = 0; k < 4; ++k) box[k] = std::llround(mb[4 * m + k] * dbu / dbu);
            c.markers.push_back(box);
          }
        };
        py::gil_scoped_release unlocked;
        return write_clip_library(path, dbu, flat, l, n, clip_at);
      },
      py::arg("path"), py::arg("dbu"), py::arg("polygons"), py::arg("layer"), py::arg("datatype"), py::arg("gauges"),
      py::arg("windows"), py::arg("markers"), py::arg("prefix"), py::arg("type_names"), py::arg("window_boxes"),
      py::arg("lines"), py::arg("at"), py::arg("ranks"), py::arg("types"), py::arg("values"),
      py::arg("marker_counts"), py::arg("marker_boxes"),
      "Writes a clip library as OASIS, one cell a clip: the layer's polygons (flat (points, rings) arrays, as\n"
      "drawn) merged and cut to the clip's window on layer/datatype; its measurement line (a zero-width path) and\n"
      "label (a text) on datatype `gauges`, the window outline on `windows`, its markers on `markers`. Cells are\n"
      "named PREFIX_rRANK_TYPE_SCORE. A clip's gauge: ranks array('q'), types bytes (an index into type_names a\n"
      "clip), values array('d') score, cd, norm_score, tiebreak a clip (DBU but norm_score); window_boxes, lines:\n"
      "array('q') x1, y1, x2, y2 a clip (DBU); at: array('q') x, y a clip (the label); marker_counts: array('q') a\n"
      "clip; marker_boxes: array('d') x1, y1, x2, y2 (DBU), the clips' markers in turn. Returns the number of\n"
      "shapes written.");

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
        // Read in place: a full layer's columns are hundreds of MB.
        const py::buffer_info ri = reals.request(), ii = ints.request();
        if (ri.itemsize != 8 || ri.format != "d" || ii.itemsize != 4 || (ii.format != "i" && ii.format != "l"))
          throw py::value_error("reals must be float64 and ints int32 columns, as gauges_polygons returns them");
        const std::size_t n = std::size_t(ri.size) / 10;
        if (std::size_t(ri.size) != 10 * n || std::size_t(ii.size) != 13 * n)
          throw py::value_error("reals must hold 10 values a gauge and ints 13");
        const auto* r = static_cast<const double*>(ri.ptr);
        const auto* k = static_cast<const std::int32_t*>(ii.ptr);
        py::gil_scoped_release unlocked;
        GdsWriter w(path, dbu, cell);
        char label[96];
        for (std::size_t i = 0; i < n; ++i, r += 10, k += 13) {
          w.path(layer, datatype, r[0], r[1], r[2], r[3]);
          if (k[12] < 0 || k[12] > int(GaugeType::T)) throw std::out_of_range("gauge type index out of range");
          // As Python's "#%d %s %.4g" % (rank, type, cd * dbu) (gauge_output.label; tested).
          std::snprintf(label, sizeof label, "#%d %s %.4g", k[0], gauge_type_name(GaugeType(k[12])), r[6] * dbu);
          w.text(layer, datatype, r[4], r[5], label);
        }
        w.close();
      },
      py::arg("path"), py::arg("dbu"), py::arg("layer"), py::arg("datatype"), py::arg("reals"), py::arg("ints"),
      py::arg("cell") = "GAUGES",
      "Writes gauges as GDSII for the editor to read in one call, from the columns gauges_polygons returns (reals\n"
      "float64 x10, ints int32 x13 a gauge): each measurement line a zero-width path on layer/datatype and its label\n"
      "'#rank type cd' (cd in micrometres) as a text at the gauge point, in one cell of that name. Coordinates\n"
      "rounded to the grid, ties to even; dbu: micrometres per DBU.");

  m.def(
      "select_windows",
      [](py::buffer x, py::buffer y, py::buffer types, py::buffer norms, py::buffer markers,
         const std::vector<double>& sides, const std::vector<std::string>& modes, bool brute, bool with_failed) {
        // Columns read in place (the gauge table's strided views): a full layer has millions
        // of gauges, and neither a Python object nor a second flat copy per gauge.
        const Column<double> xs = column_of<double>(x, "x"), ys = column_of<double>(y, "y");
        const Column<double> ns = column_of<double>(norms, "norms");
        const Column<std::int32_t> ts = column_of<std::int32_t>(types, "types");
        if (ys.size() != xs.size() || ts.size() != xs.size() || ns.size() != xs.size())
          throw py::value_error("x, y, types and norms must have one value per gauge");
        const Doubles mv = doubles_of(markers, 4, "markers");
        Paged<Spot> sp;  // 32 bytes a gauge: a mapped file on a full layer
        sp.reserve(xs.size());
        for (std::size_t i = 0; i < xs.size(); ++i) sp.push_back({{xs[i], ys[i]}, std::int32_t(i), ts[i], ns[i]});
        auto tally = [](const Tally& t) {
          py::list out;
          for (int k = 0; k < kTypes; ++k) out.append(py::make_tuple(t.n[k], t.lo[k], t.hi[k]));
          return out;
        };
        std::vector<Box> mk;
        mk.reserve(mv.size() / 4);
        for (std::size_t i = 0; i < mv.size() / 4; ++i) mk.push_back({mv[4 * i], mv[4 * i + 1], mv[4 * i + 2], mv[4 * i + 3]});
        py::list out;
        for (const std::string& mode : modes) {
          if (mode != "A" && mode != "B" && mode != "C") throw py::value_error("mode must be A, B or C");
          const Cover c = mode == "A" ? Cover::Centre : mode == "B" ? Cover::Inside : Cover::Overlap;
          for (double side : sides) {
            Selection s;
            double seconds = 0;
            {
              py::gil_scoped_release unlocked;
              const auto t0 = std::chrono::steady_clock::now();
              s = brute ? select_windows_brute(sp.data(), sp.size(), mk, side, c)
                        : select_windows(sp.data(), sp.size(), mk, side, c);
              seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
            }
            // Columns, not a tuple a window: a full layer's study has twelve runs of tens of
            // thousands of windows each.
            std::vector<double> boxes;
            std::vector<std::int32_t> gauges, starts{0}, covered;
            boxes.reserve(4 * s.windows.size()), gauges.reserve(s.windows.size()), starts.reserve(s.windows.size() + 1);
            for (const Window& w : s.windows) {
              boxes.insert(boxes.end(), {w.box.x1, w.box.y1, w.box.x2, w.box.y2});
              gauges.push_back(w.gauge);
              covered.insert(covered.end(), w.markers.begin(), w.markers.end());
              starts.push_back(std::int32_t(covered.size()));
            }
            py::dict windows;
            windows["boxes"] = bytes_of(boxes);
            windows["gauges"] = bytes_of(gauges);
            windows["starts"] = bytes_of(starts);
            windows["markers"] = bytes_of(covered);
            py::dict r;
            r["mode"] = mode;
            r["side"] = side;
            r["windows"] = windows;
            r["used"] = bytes_of(s.used);
            r["failed"] = s.failed.size();
            // int32 each, and only when asked: on a large layer most gauges fail, and a study's
            // twelve runs would hold them twelve times.
            r["failed_spots"] = with_failed ? py::object(bytes_of(s.failed)) : py::object(py::none());
            r["used_by_type"] = tally(s.used_by_type);
            r["failed_by_type"] = tally(s.failed_by_type);
            r["redundant"] = s.redundant;
            r["traversed"] = s.traversed;
            r["covered"] = s.covered;
            r["seconds"] = seconds;
            out.append(r);
          }
        }
        return out;
      },
      py::arg("x"), py::arg("y"), py::arg("types"), py::arg("norms"), py::arg("markers"), py::arg("sides"),
      py::arg("modes"), py::arg("brute") = false, py::arg("failed") = true,
      "Pattern windows for every mode and side. Gauges in rank order as four columns (one-dimensional buffers,\n"
      "strided views allowed): x, y (doubles), types (int32 type index 0-4), norms (normalised score, doubles);\n"
      "markers = array('d') of x1, y1, x2, y2 per marker; sides the window sides, modes among A (centre strictly\n"
      "inside), B (marker inside), C (overlap). Returns, modes outer and sides inner, [{'mode', 'side', 'windows':\n"
      "{'boxes': float64 bytes x1, y1, x2, y2 a window, 'gauges': int32 bytes (its spot index), 'starts': int32\n"
      "bytes (window i's markers newly covered are markers[starts[i]:starts[i + 1]]), 'markers': int32 bytes},\n"
      "'used' (spot indices as int32 bytes), 'failed' (count),\n"
      "'failed_spots' (spot indices as int32 bytes; None unless failed=True), 'used_by_type', 'failed_by_type'\n"
      "([(count, lowest, highest normalised score)] per type index), 'redundant', 'traversed', 'covered',\n"
      "'seconds'}]. brute=True: the brute-force oracle.");

  m.def(
      "free_windows",
      [](py::buffer taken, py::buffer x, py::buffer y, double side, const py::object& ids) {
        const Doubles t = doubles_of(taken, 4, "taken");
        // Read in place (the gauge table's centre columns), picked by `ids` (the failed gauges):
        // on a full layer tens of millions of points.
        const Column<double> xs = column_of<double>(x, "x"), ys = column_of<double>(y, "y");
        if (ys.size() != xs.size()) throw py::value_error("x and y must have one value per point");
        std::vector<Box> tb;
        tb.reserve(t.size() / 4);
        for (std::size_t i = 0; i < t.size(); i += 4) tb.push_back({t[i], t[i + 1], t[i + 2], t[i + 3]});
        Paged<Vec2> pv;
        if (ids.is_none()) {
          pv.reserve(xs.size());
          for (std::size_t i = 0; i < xs.size(); ++i) pv.push_back({xs[i], ys[i]});
        } else {
          const Column<std::int32_t> is = column_of<std::int32_t>(py::buffer(ids), "ids");
          pv.reserve(is.size());
          for (std::size_t k = 0; k < is.size(); ++k) {
            const std::int32_t i = is[k];
            if (i < 0 || std::size_t(i) >= xs.size()) throw py::index_error("a point id out of range");
            pv.push_back({xs[std::size_t(i)], ys[std::size_t(i)]});
          }
        }
        std::vector<std::int32_t> kept;
        {
          py::gil_scoped_release unlocked;
          kept = free_windows(tb, pv.data(), pv.size(), side);
        }
        return bytes_of(kept);
      },
      py::arg("taken"), py::arg("x"), py::arg("y"), py::arg("side"), py::arg("ids") = py::none(),
      "The split's extra patterns: taken array('d') x1, y1, x2, y2 per window; the points' x and y as two\n"
      "one-dimensional buffers of doubles (strided views too), or with ids (int32) the points x[id], y[id]; in\n"
      "order, each point whose window (side, centred) overlaps no window before it (open boxes). Returns bytes\n"
      "of int32: the kept points' positions in that order.");

  m.def(
      "cover_points",
      [](const std::vector<std::pair<double, double>>& points, double side) {
        std::vector<Vec2> p;
        for (auto& q : points) p.push_back({q.first, q.second});
        std::vector<std::tuple<double, double, double, double>> out;
        for (const Box& b : cover_points(p, side)) out.emplace_back(b.x1, b.y1, b.x2, b.y2);
        return out;
      },
      py::arg("points"), py::arg("side"),
      "The thesis's window-reduction heuristic: windows [(x1, y1, x2, y2)] covering the points.");

  m.def(
      "estimate_pitch",
      [](const py::buffer& widths, const py::buffer& spaces) {
        auto pairs = [](const py::buffer& b, const char* name) {
          const Doubles v = doubles_of(b, 2, name);
          std::vector<std::pair<double, double>> out(v.size() / 2);
          for (std::size_t i = 0; i < out.size(); ++i) out[i] = {v[2 * i], v[2 * i + 1]};
          return out;
        };
        return estimate_pitch(pairs(widths, "widths"), pairs(spaces, "spaces"));
      },
      py::arg("widths"), py::arg("spaces"), "The same with flat array('d') of cd, extension pairs.");
  m.def("estimate_pitch", &estimate_pitch, py::arg("widths"), py::arg("spaces"),
        "Pitch from gauges: weighted median width + weighted median space; pairs are (cd, extension).");
  m.def(
      "estimate_pitch_of_gauges",
      [](const py::buffer& cd, const py::buffer& extension, const py::buffer& types) {
        // The gauge table's columns read in place: no Python copy of a full layer's pairs.
        const Column<double> c = column_of<double>(cd, "cd"), e = column_of<double>(extension, "extension");
        const Column<std::int32_t> t = column_of<std::int32_t>(types, "types");
        if (e.size() != c.size() || t.size() != c.size()) throw py::value_error("one value a gauge in every column");
        Paged<Weighted> widths, spaces;
        for (std::size_t i = 0; i < c.size(); ++i) {
          if (t[i] == 0) widths.push_back({c[i], e[i]});
          else if (t[i] == 1) spaces.push_back({c[i], e[i]});
        }
        return estimate_pitch_in_place(widths, spaces);
      },
      py::arg("cd"), py::arg("extension"), py::arg("types"),
      "The same from the gauges' columns (one-dimensional buffers, strided views too): cd, extension\n"
      "(doubles) and type (int32: 0 internal, the widths; 1 external, the spaces; others ignored).");

  m.def(
      "farthest_voronoi",
      [](const std::vector<std::vector<XY>>& sites, bool l1) {
        FarthestDiagram d;
        {
          std::vector<std::vector<Point>> in;
          for (auto& s : sites) {
            in.emplace_back();
            for (auto& p : s) in.back().push_back({p.first, p.second});
          }
          py::gil_scoped_release unlocked;
          if (l1) {
            std::vector<Segment> segs;
            for (auto& s : in) {
              if (s.size() > 2) throw std::invalid_argument("the L1 diagram takes points and segments only");
              segs.push_back({s.front(), s.back()});
            }
            d = farthest_voronoi_l1(segs);
          } else {
            d = farthest_voronoi(in);
          }
        }
        py::list faces, vertices, edges;
        for (const FarthestFace& f : d.faces) faces.append(py::make_tuple(f.owners, f.direction.x, f.direction.y));
        for (const FarthestVertex& v : d.vertices) vertices.append(py::make_tuple(v.at.x, v.at.y, v.weight, v.faces));
        for (const FarthestEdge& e : d.edges)
          edges.append(py::make_tuple(e.left, e.right, e.from, e.to, e.direction.x, e.direction.y));
        py::dict out;
        out["faces"] = faces;
        out["vertices"] = vertices;
        out["edges"] = edges;
        out["root"] = py::make_tuple(d.root.p.x, d.root.p.y, d.root.q.x, d.root.q.y, d.root.half_side);
        return out;
      },
      py::arg("sites"), py::arg("l1") = false,
      "Farthest-site Voronoi diagram in L-inf (l1=True: in L1) of sites [[(x, y), ...]]: a point, a segment\n"
      "(two points) or a convex polygon each, integer coordinates below 2^30; segments may cross.\n"
      "Returns {'faces': [([owner sites], dx, dy)], 'vertices': [(x, y, weight, [faces])], 'edges':\n"
      "[(left face, right face, from vertex, to vertex or -1 for a ray, dx, dy)], 'root': (x1, y1, x2, y2,\n"
      "half_side)}: the centres of the smallest axis-parallel squares touching every site, and their half-side.");

  m.def(
      "cgal_construction_seconds",
      [](const py::object& polys, std::uint64_t seed) {
        const LayerInput in(polys);
        py::gil_scoped_release unlocked;
        return cgal_linf_construction_seconds(sites_of_polygons(merge_polygons(in.flat()).view()), seed);
      },
      py::arg("polygons"), py::arg("seed") = 1,
      "Benchmark baseline: seconds CGAL's Segment_Delaunay_graph_Linf_2 takes to construct the diagram of the\n"
      "same sites (range insertion, segments in shuffled order). Its result is not used: it can be wrong.");

  m.def(
      "voronoi_sites",
      [](const std::vector<XY>& points, const std::vector<std::pair<XY, XY>>& segments, bool check, int pairs,
         int threads) {
        std::vector<Point> p;
        for (auto& q : points) p.push_back({q.first, q.second});
        std::vector<Segment> s;
        for (auto& g : segments) s.push_back({{g.first.first, g.first.second}, {g.second.first, g.second.second}});
        return guarded([&] { return voronoi_of_sites(p, s, options(check, pairs, threads)); });
      },
      py::arg("points"), py::arg("segments"), py::arg("check") = true, py::arg("check_pairs") = 2000,
      py::arg("threads") = 0,
      "Diagram of plain sites: points [(x, y)] and non-crossing segments [((x1, y1), (x2, y2))]. Same output.");
}
