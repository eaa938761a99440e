// The lithography model: kernels (a preset's optics or a folder of ICCAD 2013 files), the
// threshold rule, and the printability of gauges read from the gauge table's columns in place.
#include <complex>
#include <cstring>
#include <stdexcept>

#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <chrono>
#include <string>

#include "bind.hpp"
#include "convert.hpp"
#include "linf/litho/calibration.hpp"
#include "linf/litho/chunks.hpp"
#include "linf/litho/contour.hpp"
#include "linf/litho/opc.hpp"
#include "linf/litho/optics.hpp"
#include "linf/litho/printability.hpp"
#include "linf/litho/ranking.hpp"

namespace linf::bind {

namespace {

template <class T>
Strided<T> strided(const Column<T>& c) {
  return c.values;
}

// The optional context ids (array('Q')), read in place; `held` keeps the buffer while the core reads.
Strided<std::uint64_t> context_ids(const py::object& contexts, py::buffer_info& held) {
  Strided<std::uint64_t> ids;
  if (contexts.is_none()) return ids;
  held = py::buffer(contexts).request();
  if (held.ndim != 1 || held.itemsize != 8 || (held.format != "Q" && held.format != "L" && held.format != "B"))
    throw py::value_error("contexts must be a one-dimensional buffer of unsigned 64-bit ids, array('Q')");
  ids.data = static_cast<const char*>(held.ptr);
  ids.stride = held.strides[0];
  ids.n = std::size_t(held.shape[0]);
  return ids;
}

template <class T>
py::bytes int64_bytes(const std::vector<T>& v) {
  const std::vector<std::int64_t> out(v.begin(), v.end());
  return bytes_of(out);
}

}  // namespace

void bind_litho(py::module_& m) {
  py::class_<litho::Kernels>(m, "LithoKernels", "SOCS kernels of an imaging model (docs/design.md, 'Lithography model').")
      .def_property_readonly("period", [](const litho::Kernels& k) { return k.period; })
      .def_property_readonly("count", [](const litho::Kernels& k) { return k.count(); })
      .def_property_readonly("size", [](const litho::Kernels& k) { return k.size; })
      .def_property_readonly("clear_field", &litho::Kernels::clear_field)
      // Pickled with the editor's calls into its worker process (plugin worker.py).
      .def(py::pickle(
          [](const litho::Kernels& k) {
            py::list values;
            for (const auto& v : k.values)
              values.append(py::bytes(reinterpret_cast<const char*>(v.data()), v.size() * sizeof(v[0])));
            return py::make_tuple(k.size, k.period, k.weights, values);
          },
          [](const py::tuple& t) {
            if (t.size() != 4) throw std::invalid_argument("not a pickled LithoKernels");
            litho::Kernels k;
            k.size = t[0].cast<int>();
            k.period = t[1].cast<double>();
            k.weights = t[2].cast<std::vector<double>>();
            for (const auto& b : t[3].cast<py::list>()) {
              const std::string bytes = b.cast<std::string>();
              std::vector<std::complex<double>> v(bytes.size() / sizeof(std::complex<double>));
              std::memcpy(v.data(), bytes.data(), v.size() * sizeof(v[0]));
              k.values.push_back(std::move(v));
            }
            return k;
          }));

  m.def(
      "litho_kernels",
      [](const std::string& preset, const std::string& folder, double period, double defocus) {
        py::gil_scoped_release unlocked;
        if (!folder.empty()) return litho::read_kernels(folder, period);
        litho::Optics o = litho::optics_preset(preset);
        o.defocus = defocus;
        return litho::kernels_from_optics(o);
      },
      py::arg("preset") = "", py::arg("folder") = "", py::arg("period") = 2048.0, py::arg("defocus") = 0.0,
      "The kernels of an optics preset (`duv193`, `euv`: computed, at `defocus` nm from best focus) or, with\n"
      "`folder`, read from ICCAD 2013 files (scales.txt, fh*.bin) for a period of `period` nm. Bad input raises\n"
      "ValueError.");

  m.def(
      "litho_window_images",
      [](const py::object& polys, double dbu_nm, const std::vector<double>& cx, const std::vector<double>& cy,
         const litho::Kernels& kernels, int m, int threads, double blur) {
        const LayerInput in(polys);
        std::vector<std::vector<double>> images;
        {
          py::gil_scoped_release unlocked;
          images = litho::window_images(in.flat(), dbu_nm, cx, cy, kernels, m, threads, blur);
        }
        py::list out;
        for (const auto& v : images) out.append(bytes_of(v));
        return out;
      },
      py::arg("polygons"), py::arg("dbu"), py::arg("cx"), py::arg("cy"), py::arg("kernels"), py::arg("m") = 128,
      py::arg("threads") = 0, py::arg("blur") = 0.0,
      "Pictures' aerial images: for each centre (cx[k], cy[k]) in DBU the window of the kernels' period centred\n"
      "there, as gauge_printability clips it, imaged on an m x m grid: bytes of float64, value [j * m + i] at the\n"
      "window's corner (the centre minus half the period) + (i, j) * period / m, in nm; blurred by the resist's\n"
      "Gaussian `blur` (standard deviation, nm) in both directions.");

  m.def(
      "litho_contours",
      [](const py::buffer& values, int m, int lo, int hi, double level) {
        const py::buffer_info b = values.request();
        if (b.itemsize != sizeof(double) || b.ndim != 1 || b.strides[0] != b.itemsize)
          throw std::invalid_argument("contour: the image must be contiguous float64");
        const double* v = static_cast<const double*>(b.ptr);
        const std::vector<double> image(v, v + b.size);
        std::vector<double> segments;
        {
          py::gil_scoped_release unlocked;
          segments = litho::contour_segments(image, m, lo, hi, level);
        }
        return bytes_of(segments);
      },
      py::arg("values"), py::arg("m"), py::arg("lo"), py::arg("hi"), py::arg("level"),
      "Marching squares on an m x m image (float64, value [j * m + i], as litho_window_images gives it) over\n"
      "the cells [lo, hi - 1)^2: bytes of float64, four a segment (x1, y1, x2, y2) in grid units where the\n"
      "image crosses `level` (docs/design.md, 'The report's pictures').");

  m.def(
      "litho_layer_parts",
      [](const py::object& polys, double dbu_nm, double period, const py::buffer& cx, const py::buffer& cy,
         const py::buffer& starts) {
        const LayerInput in(polys);
        const auto ccx = column_of<double>(cx, "cx"), ccy = column_of<double>(cy, "cy");
        const auto cs = column_of<std::int64_t>(starts, "starts");
        std::vector<std::size_t> at;
        for (std::size_t k = 0; k < cs.size(); ++k) {
          if (cs[k] < 0) throw std::invalid_argument("the chunks' starts must ascend within the points");
          at.push_back(std::size_t(cs[k]));
        }
        std::vector<litho::LayerPart> parts;
        {
          py::gil_scoped_release unlocked;
          parts = litho::window_shapes(in.flat(), dbu_nm, period, strided(ccx), strided(ccy), at);
        }
        py::list out;
        for (const litho::LayerPart& p : parts) out.append(py::make_tuple(bytes_of(p.points), bytes_of(p.rings)));
        return out;
      },
      py::arg("polygons"), py::arg("dbu"), py::arg("period"), py::arg("cx"), py::arg("cy"), py::arg("starts"),
      "The parts of the merged layer that gauge_printability clips for chunks of gauge points: for each chunk\n"
      "(cx, cy)[starts[c]:starts[c + 1]] (float64 DBU; starts: int64, ascending) with kernels of `period` nm, dbu\n"
      "in nm, (points, rings) as bytes of int64: the polygons (with their holes) meeting some point's window, in\n"
      "the layer's order. gauge_printability reads a chunk's gauges on its part exactly as on the layer.");

  m.def(
      "litho_chunks",
      [](const py::buffer& cx, const py::buffer& cy, const py::buffer& types, const py::object& contexts, double band,
         std::size_t wanted) {
        const auto ccx = column_of<double>(cx, "cx"), ccy = column_of<double>(cy, "cy");
        const auto ct = column_of<std::int32_t>(types, "types");
        py::buffer_info held;
        const Strided<std::uint64_t> ids = context_ids(contexts, held);
        litho::Chunks c;
        {
          py::gil_scoped_release unlocked;
          c = litho::plan_chunks(strided(ccx), strided(ccy), strided(ct), ids, band, wanted);
        }
        return py::make_tuple(int64_bytes(c.gauges), int64_bytes(c.starts), int64_bytes(c.at));
      },
      py::arg("cx"), py::arg("cy"), py::arg("types"), py::arg("contexts"), py::arg("band"), py::arg("wanted"),
      "The chunks of gauge_printability's simulating gauges for tasks elsewhere (docs/design.md, 'The\n"
      "printability elsewhere'): cx, cy (float64, DBU), types (int32) and contexts (array('Q') or None) as\n"
      "gauge_printability takes them; band: the height (DBU) of the bands points are sorted in; wanted: about\n"
      "how many chunks. (gauges, starts, at) as bytes of int64: the simulating gauges chunk after chunk, chunk c\n"
      "being gauges[starts[c]:starts[c + 1]]; at[i]: where gauge i's reading is in that order.");

  m.def(
      "litho_rank",
      [](const py::buffer& score, const py::buffer& printed_cd, const py::buffer& fails) {
        const auto cs = column_of<double>(score, "score"), cp = column_of<double>(printed_cd, "printed_cd");
        const auto cf = column_of<std::uint8_t>(fails, "fails");
        litho::Ranking r;
        {
          py::gil_scoped_release unlocked;
          r = litho::rank_by_printability(strided(cs), strided(cp), strided(cf));
        }
        return py::make_tuple(bytes_of(r.order), bytes_of(r.score), r.read, r.highest);
      },
      py::arg("score"), py::arg("printed_cd"), py::arg("fails"),
      "The gauges ranked by printability (docs/design.md, 'Re-ranking'): score, printed_cd (float64) and\n"
      "fails (uint8) per gauge in the table's order, as gauge_printability gives them (NaN, NaN, 0 for a\n"
      "gauge not simulated). (order, score, read, highest): order as bytes of int32 (the read gauges by\n"
      "score, ties and the unread ones in the table's order), the scores in that order (bytes of float64,\n"
      "an unread gauge given the highest read one, 1 if none), how many were read, the highest score.");

  m.def(
      "calibrate_threshold",
      [](const litho::Kernels& k, double width, double pitch, double blur) {
        const litho::Calibration c = litho::calibrate_threshold(k, width, pitch, blur);
        py::dict d;
        d["threshold"] = c.threshold;
        d["pitch"] = c.pitch;
        d["contrast"] = c.contrast;
        return d;
      },
      py::arg("kernels"), py::arg("width"), py::arg("pitch"), py::arg("blur") = 0.0,
      "The resist threshold at which endless lines of `width` nm at `pitch` nm print at their drawn width, the\n"
      "image blurred across them by the resist's Gaussian `blur` (standard deviation, nm):\n"
      "{'threshold', 'pitch' (as used), 'contrast'}. ValueError when the model does not resolve them.");

  m.def(
      "opc_correct",
      [](const py::object& polys, double dbu_nm, const litho::Kernels& kernels, double threshold, double blur,
         double width, int iterations, int threads) {
        const LayerInput in(polys);
        litho::OpcResult r;
        {
          py::gil_scoped_release unlocked;
          litho::OpcRules rules;
          rules.width = width;
          rules.iterations = iterations;
          r = litho::correct_mask(in.flat(), dbu_nm, litho::OpcModel{&kernels, threshold, blur}, rules, threads);
        }
        py::dict d;
        d["points"] = bytes_of(r.points);
        d["rings"] = bytes_of(r.rings);
        d["scale"] = r.scale;
        d["fragments"] = r.fragments;
        d["kept"] = r.kept;
        d["rms_epe"] = r.rms_epe;
        d["max_epe"] = r.max_epe;
        return d;
      },
      py::arg("polygons"), py::arg("dbu_nm"), py::arg("kernels"), py::arg("threshold"), py::arg("blur"),
      py::arg("width"), py::arg("iterations") = 6, py::arg("threads") = 0,
      "The layer after an emulated model-based OPC (docs/design.md, 'OPC before the reading'): its edges cut\n"
      "into fragments and moved until the model (kernels, threshold, resist blur in nm) prints each at its drawn\n"
      "edge; `width` (nm, the layer's typical width) bounds the moves. {'points', 'rings' (bytes of int64, the\n"
      "core's flat arrays, the points in DBU / scale), 'scale', 'fragments', 'kept' (polygons with an edge off the axes, left as drawn),\n"
      "'rms_epe', 'max_epe' (nm, before each iteration and after the last)}. ValueError for bad input.");

  m.def(
      "gauge_printability",
      [](const py::object& polys, double dbu_nm, const py::buffer& cx, const py::buffer& cy, const py::buffer& x1,
         const py::buffer& y1, const py::buffer& x2, const py::buffer& y2, const py::buffer& types, const py::buffer& cd,
         const litho::Kernels& kernels, double threshold, const py::object& contexts, int threads,
         const litho::Kernels* defocus, double dose, double blur) {
        const LayerInput in(polys);
        const auto ccx = column_of<double>(cx, "cx"), ccy = column_of<double>(cy, "cy");
        const auto cx1 = column_of<double>(x1, "x1"), cy1 = column_of<double>(y1, "y1");
        const auto cx2 = column_of<double>(x2, "x2"), cy2 = column_of<double>(y2, "y2");
        const auto ct = column_of<std::int32_t>(types, "types");
        const auto ccd = column_of<double>(cd, "cd");
        litho::GaugeColumns g{strided(ccx), strided(ccy), strided(cx1), strided(cy1), strided(cx2),
                              strided(cy2), strided(ct),  strided(ccd), {}};
        py::buffer_info ids;
        g.context = context_ids(contexts, ids);
        litho::Printability p;
        const auto t0 = std::chrono::steady_clock::now();
        {
          py::gil_scoped_release unlocked;
          p = litho::printability(in.flat(), dbu_nm, g, litho::PrintModel{&kernels, threshold, defocus, dose, blur}, threads);
        }
        py::dict d;
        d["printed_cd"] = bytes_of(p.printed_cd);
        std::vector<std::uint8_t> fails(p.fails.size());
        for (std::size_t i = 0; i < fails.size(); ++i) fails[i] = std::uint8_t(p.fails[i]);
        d["fails"] = bytes_of(fails);
        for (std::size_t i = 0; i < fails.size(); ++i) fails[i] = std::uint8_t(p.fails_nominal[i]);
        d["fails_nominal"] = bytes_of(fails);
        d["pv_band"] = bytes_of(p.pv_band);
        d["score"] = bytes_of(p.score);
        d["simulations"] = p.simulations;
        d["shared"] = p.shared;
        d["images"] = p.images;
        d["seconds"] = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        return d;
      },
      py::arg("polygons"), py::arg("dbu"), py::arg("cx"), py::arg("cy"), py::arg("x1"), py::arg("y1"), py::arg("x2"),
      py::arg("y2"), py::arg("types"), py::arg("cd"), py::arg("kernels"), py::arg("threshold"),
      py::arg("contexts") = py::none(), py::arg("threads") = 0, py::arg("defocus") = py::none(),
      py::arg("dose") = 0.0, py::arg("blur") = 0.0,
      "Printability of gauges (docs/design.md, 'Printability of gauges'). polygons: the merged layer as\n"
      "gauges_polygons takes it (DBU); dbu in nm; cx..cd: float64 columns in DBU (strided views of the gauge\n"
      "table work), types: int32 (1 external = a space, the others a width); kernels from litho_kernels and\n"
      "the resist threshold; contexts: optional array('Q') of ids (gauges of one type and id share one\n"
      "simulation); dose > 0: the process window, corners at dose 1 - dose with the `defocus` kernels (None: in\n"
      "focus) and 1 + dose in focus; blur: the resist's Gaussian (standard deviation, nm), each reading's image\n"
      "blurred along its line. Returns bytes columns 'printed_cd' (float64 nm, NaN when not measured),\n"
      "'fails' (uint8: 0 none, 1 pinch, 2 bridge; the worst over nominal and the corners), 'fails_nominal',\n"
      "'pv_band' (float64 nm, NaN without a window), 'score' (float64, lower = worse) and 'simulations',\n"
      "'shared', 'images' (line profiles computed: simulated gauges on one line share one), 'seconds'.");
}

}  // namespace linf::bind
