// The farthest-site diagram and the smallest square touching every site.
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include "bind.hpp"
#include "convert.hpp"
#include "linf/farthest/farthest.hpp"

namespace linf::bind {

void bind_farthest(py::module_& m) {
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
          d = l1 ? farthest_voronoi_l1(in) : farthest_voronoi(in);
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
}

}  // namespace linf::bind
