// The Python module linf_opc_core: plain Python data in, plain Python data out. The bindings
// convert; what computes is in core/.
#include <pybind11/pybind11.h>

#include "bind.hpp"

PYBIND11_MODULE(linf_opc_core, m) {
  m.doc() = "L-infinity segment Voronoi diagram (core of the L-inf OPC KLayout plugin)";
  linf::bind::bind_diagram(m);
  linf::bind::bind_gauges(m);
  linf::bind::bind_io(m);
  linf::bind::bind_split(m);
  linf::bind::bind_selection(m);
  linf::bind::bind_farthest(m);
  linf::bind::bind_litho(m);
}
