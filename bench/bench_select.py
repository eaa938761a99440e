# Speed of pattern selection: all size x mode runs together against KLayout's width plus space
# checks (metrics Square) on the same layer, and mode C against mode A, in the same run:
#   klayout -b -r bench/bench_select.py [-rd input=FILE -rd layer=L/D -rd markers=SPEC]
# Default: ../shared/data/iccad16/testcase3.oas 1000/0 with test3.csv and with layer 10000/0.
# The gauges (diagram included) are computed once before and are not part of the selection time.
# Threads: the selection runs on one thread (the core's selection has none of its own), and so do
# KLayout's flat Region checks: equal threads, one each.
import os
import sys
import time

repo = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(repo, "build"))
sys.path.insert(0, os.path.join(repo, "plugin", "python"))

import pya  # noqa: E402

from linf_opc import gauges, layout, markers as marker_io, selection  # noqa: E402

g = globals()
data = os.path.join(repo, "..", "shared", "data", "iccad16")
path = g.get("input") or os.path.join(data, "testcase3.oas")
L, D = layout.parse_layer(g.get("layer") or "1000/0")
specs = [g["markers"]] if g.get("markers") else [os.path.join(data, "test3.csv"), "10000/0"]
ly = pya.Layout()
ly.read(path)
cell = ly.top_cells()[0]
li = ly.find_layer(L, D)
polygons = layout.polygons_of(layout.region_of(cell, li))
r = gauges.compute(polygons)
pitch = selection.pitch_of(r.gauges)
w0 = min(x.cd for x in r.gauges if x.type == "internal")
t = int(2 * w0)
t0 = time.perf_counter()
fresh = pya.Region(cell.begin_shapes_rec(li))
n = fresh.width_check(t, False, pya.Region.Square).size() + fresh.space_check(t, False, pya.Region.Square).size()
t_drc = time.perf_counter() - t0
print("input: %s %d/%d: %d polygons, %d gauges, pitch %.4g um" % (os.path.basename(path), L, D, len(polygons),
                                                                  len(r.gauges), pitch * ly.dbu))
print("KLayout width + space checks (t = %d DBU, Square, 1 thread): %.3f s" % (t, t_drc))
for spec in specs:
    m = marker_io.load(spec, ly, cell)
    st = selection.study(r.gauges, m.boxes, pitch)
    per = {k: v.seconds for k, v in st.runs.items()}
    a = sum(v for (mode, _), v in per.items() if mode == "A")
    c = sum(v for (mode, _), v in per.items() if mode == "C")
    print("markers %s: %d; 12 size x mode runs (1 thread) %.3f s (core %.3f s) -> ratio to width + space %.2f (goal: under 1); "
          "mode C / mode A %.2f (goal: at most 2)" % (os.path.basename(spec) if os.path.exists(spec) else "layer " + spec, len(m.boxes), st.seconds,
                                                     sum(per.values()), st.seconds / t_drc, c / a if a else 0))
