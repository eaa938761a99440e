// The split's clip libraries: the plugin's columns handed to the core's OASIS writer.
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include "bind.hpp"
#include "convert.hpp"
#include "linf/split/clips.hpp"

namespace linf::bind {

void bind_split(py::module_& m) {
  m.def(
      "write_clip_library",
      [](const std::string& path, double dbu, const py::tuple& polygons, int layer, int datatype, int gauges,
         int windows, int markers, const std::string& prefix, const std::vector<std::string>& type_names,
         py::buffer window_box, py::buffer lines, py::buffer at, py::buffer ranks, const py::bytes& types,
         py::buffer values, py::buffer marker_counts, py::buffer marker_boxes) {
        if (py::len(polygons) != 2) throw py::value_error("polygons must be (points, rings) flat arrays");
        const LayerInput layer_input(polygons);
        const py::buffer_info wi = window_box.request(), li = lines.request(), ai = at.request(),
                              ri = ranks.request(), ci = marker_counts.request();
        ClipLibrarySpec spec;
        ClipColumns& c = spec.clips;
        c.windows = int64s_of(wi, "windows");
        c.lines = int64s_of(li, "lines");
        c.at = int64s_of(ai, "at");
        c.ranks = int64s_of(ri, "ranks");
        c.marker_counts = int64s_of(ci, "marker_counts");
        const Doubles v = doubles_of(values, 4, "values");
        const Doubles mb = doubles_of(marker_boxes, 4, "markers");
        c.values = v.data;
        c.marker_boxes = mb.data, c.marker_values = mb.size();
        c.types = reinterpret_cast<const unsigned char*>(PyBytes_AS_STRING(types.ptr()));
        const std::size_t n = c.count = std::size_t(PyBytes_GET_SIZE(types.ptr()));
        if (std::size_t(wi.shape[0]) != 4 * n || std::size_t(li.shape[0]) != 4 * n || std::size_t(ai.shape[0]) != 2 * n ||
            std::size_t(ri.shape[0]) != n || v.size() != 4 * n || std::size_t(ci.shape[0]) != n)
          throw py::value_error("one window, line, label position, rank, type, 4 values and marker count a clip");
        spec.path = path, spec.dbu = dbu, spec.layer = layer_input.flat();
        spec.layers.layer = layer, spec.layers.datatype = datatype;
        spec.layers.gauges = gauges, spec.layers.windows = windows, spec.layers.markers = markers;
        spec.prefix = prefix, spec.type_names = type_names;
        py::gil_scoped_release unlocked;
        return write_clip_library(spec);
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
}

}  // namespace linf::bind
