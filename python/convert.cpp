#include "convert.hpp"

namespace linf::bind {

namespace {
Ring ring_of(const std::vector<XY>& pts) {
  Ring r;
  r.reserve(pts.size());
  for (auto& p : pts) r.push_back({p.first, p.second});
  return r;
}

py::dict counts_dict(const DrawCounts& n) {
  py::dict out;
  for (PieceKind k : {PieceKind::Internal, PieceKind::External, PieceKind::Notch, PieceKind::Adjacent})
    out[kind_name(k)] = n[std::size_t(k)];
  return out;
}
}  // namespace

const std::int64_t* int64s_of(const py::buffer_info& info, const char* name) {
  if (info.ndim != 1 || info.itemsize != 8 || (info.format != "q" && info.format != "l"))
    throw py::value_error(std::string(name) + " must be a flat array of 64-bit integers, array('q')");
  return static_cast<const std::int64_t*>(info.ptr);
}

LayerInput::LayerInput(const py::object& obj) {
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

Doubles doubles_of(const py::buffer& b, std::size_t group, const char* name) {
  Doubles d{b.request()};
  if (d.info.format != py::format_descriptor<double>::format() || d.info.ndim != 1)
    throw py::value_error(std::string(name) + " must be a flat array of doubles, array('d')");
  d.data = static_cast<const double*>(d.info.ptr);
  d.n = std::size_t(d.info.shape[0]);
  if (d.n % group) throw py::value_error(std::string(name) + ": length must be a multiple of " + std::to_string(group));
  return d;
}

py::bytes blank_bytes(std::size_t n, char*& data) {
  PyObject* o = PyBytes_FromStringAndSize(nullptr, Py_ssize_t(n));
  if (!o) throw py::error_already_set();
  data = PyBytes_AsString(o);
  return py::reinterpret_steal<py::bytes>(o);
}

std::string_view bytes_view(const py::bytes& b) {
  char* data = nullptr;
  Py_ssize_t n = 0;
  if (PyBytes_AsStringAndSize(b.ptr(), &data, &n) != 0) throw py::error_already_set();
  return {data, std::size_t(n)};
}

ProgressFn progress_of(const py::object& fn) {
  if (fn.is_none()) return {};
  PyObject* f = fn.ptr();  // borrowed: a copy of the ProgressFn must not touch reference counts
  return [f](const char* stage, std::size_t done, std::size_t total) {
    py::gil_scoped_acquire held;
    try {
      const py::handle watcher(f);
      watcher(stage, done, total);
    } catch (py::error_already_set& e) {
      e.discard_as_unraisable("the progress callback");
    }
  };
}

DiagramOptions options(const py::object& check, int pairs, int threads, double tile, const py::object& progress,
                       const std::string& builder) {
  if (builder != "subdivision" && builder != "sweep")
    throw py::value_error("builder must be 'subdivision' or 'sweep', not '" + builder + "'");
  DiagramOptions o;
  o.sweep = builder == "sweep";
  o.progress = progress_of(progress);
  // True and "sample": the sampled check (the default); "full"; False and "off": none.
  const std::string mode = py::isinstance<py::str>(check) ? check.cast<std::string>()
                           : check.cast<bool>()            ? "sample"
                                                           : "off";
  if (mode != "sample" && mode != "full" && mode != "off")
    throw py::value_error("check must be True, False, 'sample', 'full' or 'off', not '" + mode + "'");
  o.check = mode != "off";
  o.checker.search_every = mode == "full" ? 1 : kSampledSearchEvery;
  o.checker.crossing_pairs = pairs;
  o.build.threads = threads;
  o.build.tile_size = tile;
  return o;
}

StreamOutputs outputs_of(const std::string& csv, double dbu, const std::string& gds, int gds_layer,
                         const std::string& gds_cell) {
  StreamOutputs so;
  so.csv = csv, so.dbu = dbu, so.gds = gds;
  so.layers.layer = gds_layer;
  so.layers.dbu = dbu;
  so.layers.cell = gds_cell;
  return so;
}

py::dict summary_dict(const Diagram& d, const CheckReport& c) {
  py::dict check;
  check["ok"] = c.ok();
  check["sampled_points"] = c.sampled_points;
  check["searched_pieces"] = c.searched_pieces;
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
  out["builder"] = d.swept ? "sweep" : "subdivision";
  py::dict t;
  t["merge"] = d.seconds_merge;
  t["build"] = d.seconds_build;
  t["check"] = d.seconds_check;
  t["csv"] = d.seconds_csv;
  out["seconds"] = t;
  return out;
}

py::dict result_dict(const Result& r) {
  const auto& S = r.diagram.sites.sites;
  py::list pieces;
  for (const Piece& p : r.diagram.pieces) {
    const Site& a = S[p.a];
    const Site& b = S[p.b];
    pieces.append(py::make_tuple(kind_name(p.kind), p.p.x, p.p.y, p.q.x, p.q.y, p.d1, p.d2, a.a.x, a.a.y, a.b.x,
                                 a.b.y, b.a.x, b.a.y, b.b.x, b.b.y, p.a, p.b));
  }
  py::dict out = summary_dict(r.diagram, r.check);
  out["pieces"] = pieces;
  return out;
}

namespace {
void put_counts(py::dict& d, const DrawCounts& counts, const DrawCounts& drawn, bool with_drawn) {
  d["counts"] = counts_dict(counts);
  if (with_drawn) d["drawn"] = counts_dict(drawn);
}
}  // namespace

py::dict stage_dict(const WholeResult& w, bool with_drawn) {
  py::dict d = result_dict(w.result);
  put_counts(d, w.counts, w.drawn, with_drawn);
  return d;
}

py::dict stage_dict(const StreamResult& r, bool with_drawn) {
  py::dict d = summary_dict(r.diagram, r.check);
  d["pieces"] = r.pieces;
  put_counts(d, r.counts, r.drawn, with_drawn);
  return d;
}

TileRunner runner_of(const py::object& runner) {
  if (runner.is_none()) return {};
  const py::handle f = runner;  // no reference counting where the GIL is not held
  return [f](const std::function<bool(std::string&)>& next, const std::function<void(std::string_view)>& done) {
    py::gil_scoped_acquire held;
    py::cpp_function py_next([&next]() -> py::object {
      std::string job;
      bool more;
      {
        py::gil_scoped_release free;
        more = next(job);
      }
      if (!more) return py::none();
      return py::bytes(job);
    });
    py::cpp_function py_done([&done](const py::bytes& result) {
      const std::string_view bytes = bytes_view(result);  // a tile's result is megabytes: no copy
      py::gil_scoped_release free;
      done(bytes);
    });
    f(py_next, py_done);
  };
}

}  // namespace linf::bind
