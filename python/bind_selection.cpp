// The selection stage: pattern windows around the ranked gauges, the split's extra windows,
// the window-reduction heuristic and the layer's pitch. The gauge table's columns are read in
// place (strided views): a full layer has millions of gauges.
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <array>
#include <chrono>
#include <tuple>

#include "bind.hpp"
#include "convert.hpp"
#include "linf/selection/pattern_classes.hpp"
#include "linf/selection/selection.hpp"

namespace linf::bind {

namespace {

py::list tally_list(const Tally& t) {
  py::list out;
  for (int k = 0; k < kTypes; ++k) out.append(py::make_tuple(t.n[k], t.lo[k], t.hi[k]));
  return out;
}

// One run's result. Windows as columns, not a tuple a window: a full layer's study has twelve
// runs of tens of thousands of windows each.
py::dict selection_dict(const std::string& mode, double side, const Selection& s, double seconds, bool with_failed) {
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
  // int32 each, and only when asked: on a large layer most gauges fail, and a study's twelve
  // runs would hold them twelve times.
  r["failed_spots"] = with_failed ? py::object(bytes_of(s.failed)) : py::object(py::none());
  r["used_by_type"] = tally_list(s.used_by_type);
  r["failed_by_type"] = tally_list(s.failed_by_type);
  r["redundant"] = s.redundant;
  r["traversed"] = s.traversed;
  r["covered"] = s.covered;
  r["seconds"] = seconds;
  return r;
}

}  // namespace

void bind_selection(py::module_& m) {
  m.def(
      "select_windows",
      [](py::buffer x, py::buffer y, py::buffer types, py::buffer norms, py::buffer markers,
         const std::vector<double>& sides, const std::vector<std::string>& modes, bool brute, bool with_failed) {
        const Column<double> xs = column_of<double>(x, "x"), ys = column_of<double>(y, "y");
        const Column<double> ns = column_of<double>(norms, "norms");
        const Column<std::int32_t> ts = column_of<std::int32_t>(types, "types");
        if (ys.size() != xs.size() || ts.size() != xs.size() || ns.size() != xs.size())
          throw py::value_error("x, y, types and norms must have one value per gauge");
        const Doubles mv = doubles_of(markers, 4, "markers");
        Paged<Spot> sp;  // 32 bytes a gauge: a mapped file on a full layer
        sp.reserve(xs.size());
        for (std::size_t i = 0; i < xs.size(); ++i) sp.push_back({{xs[i], ys[i]}, std::int32_t(i), ts[i], ns[i]});
        std::vector<Box> mk;
        mk.reserve(mv.size() / 4);
        for (std::size_t i = 0; i < mv.size() / 4; ++i) mk.push_back({mv[4 * i], mv[4 * i + 1], mv[4 * i + 2], mv[4 * i + 3]});
        py::list out;
        for (const std::string& mode : modes) {
          const Cover c = cover_of(mode);
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
            out.append(selection_dict(mode, side, s, seconds, with_failed));
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
        // The points picked by `ids` (the failed gauges): on a full layer tens of millions.
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
      "classify_patterns",
      [](const py::object& polygons, const py::buffer& windows, const std::string& by, double area_fraction,
         std::int64_t edge) {
        if (py::len(polygons) != 2) throw py::value_error("polygons must be (points, rings) flat arrays");
        const LayerInput layer_input(polygons);
        const py::buffer_info wi = windows.request();
        const std::int64_t* w = int64s_of(wi, "windows");
        if (wi.shape[0] % 4) throw py::value_error("windows: x1, y1, x2, y2 a window");
        std::vector<std::array<std::int64_t, 4>> boxes(std::size_t(wi.shape[0] / 4));
        for (std::size_t i = 0; i < boxes.size(); ++i) boxes[i] = {w[4 * i], w[4 * i + 1], w[4 * i + 2], w[4 * i + 3]};
        ClassRule rule;
        if (by == "area") rule.by = ClassRule::Area;
        else if (by == "edge") rule.by = ClassRule::Edge;
        else throw py::value_error("the pattern rule is 'area' or 'edge'");
        rule.area_fraction = area_fraction, rule.edge = edge;
        const auto t0 = std::chrono::steady_clock::now();
        PatternClasses p;
        {
          py::gil_scoped_release release;
          p = classify_patterns(layer_input.flat(), boxes, rule);
        }
        py::dict r;
        r["of_window"] = bytes_of(p.of_window);
        r["representative"] = bytes_of(p.representative);
        r["count"] = bytes_of(p.count);
        r["compared"] = p.compared;
        r["seconds"] = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        return r;
      },
      py::arg("polygons"), py::arg("windows"), py::arg("by"), py::arg("area_fraction"), py::arg("edge"),
      "Pattern classes of square windows (array('q') x1, y1, x2, y2 each, DBU) over the layer's flat\n"
      "polygons: windows whose clips match under a symmetry of the square, by 'area' (XOR area at most\n"
      "area_fraction of the window) or 'edge' (nothing wider than edge DBU in the XOR), leader clustering\n"
      "in the given order. Returns {of_window, representative, count: bytes of int32, compared, seconds}.");

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
        const Column<double> c = column_of<double>(cd, "cd"), e = column_of<double>(extension, "extension");
        const Column<std::int32_t> t = column_of<std::int32_t>(types, "types");
        return estimate_pitch_of_gauges(c.values, e.values, t.values);
      },
      py::arg("cd"), py::arg("extension"), py::arg("types"),
      "The same from the gauges' columns (one-dimensional buffers, strided views too): cd, extension\n"
      "(doubles) and type (int32: 0 internal, the widths; 1 external, the spaces; others ignored).");
}

}  // namespace linf::bind
