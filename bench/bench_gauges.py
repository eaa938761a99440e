# Speed of the gauge stage (diagram included) against KLayout's own width plus space checks
# (metrics Square) on the same layer, measured in the same run:
#   klayout -b -r bench/bench_gauges.py [-rd input=FILE -rd layer=L/D [-rd cell=NAME] -rd t=DBU] [-rd reach=0]
#                                       [-rd builder=sweep]
# Default input: ../shared/data/iccad16/testcase3.oas, 1000/0.
# The goal's comparison (docs/benchmarks.md, "Comparing with KLayout's checks"): the checks at the gauges' own reach,
# width_check above the widest width and space_check above the widest space the gauges report,
# what KLayout needs to find every width and space the gauges measure. For reference also at
# t (default 2 x the narrowest width), where the checks report only the narrowest places.
# reach=0 leaves the reach out (on a layer with a wide space it takes KLayout minutes).
# Threads: KLayout's flat Region checks run on one thread, so the ratios are given with our
# builder on one thread (equal threads) and on one a core beside them.
import os
import sys
import time

repo = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(repo, "build"))
sys.path.insert(0, os.path.join(repo, "plugin", "python"))

import pya  # noqa: E402

from linf_opc import gauges, layout  # noqa: E402

g = globals()
path = g.get("input") or os.path.join(repo, "..", "shared", "data", "iccad16", "testcase3.oas")
L, D = layout.parse_layer(g.get("layer") or "1000/0")
ly = pya.Layout()
ly.read(path)
cell = ly.cell(g["cell"]) if g.get("cell") else ly.top_cells()[0]
li = ly.find_layer(L, D)

t0 = time.perf_counter()
region = layout.region_of(cell, li)
polygons = layout.polygons_of(region)
t_read = time.perf_counter() - t0
cores = os.cpu_count() or 1
builder = g.get("builder") or "subdivision"
r_all = gauges.compute(polygons, threads=0, builder=builder)
t_all = t_read + r_all.seconds["total"]
del r_all
r = gauges.compute(polygons, threads=1, builder=builder)
t_gauges = t_read + r.seconds["total"]
w0 = min(x.cd for x in r.gauges if x.type == "internal")
t = int(g.get("t") or 2 * w0)

# KLayout's checks on a fresh region from the layout, as a DRC deck would start.
t0 = time.perf_counter()
fresh = pya.Region(cell.begin_shapes_rec(li))
width = fresh.width_check(t, False, pya.Region.Square)
space = fresh.space_check(t, False, pya.Region.Square)
n_drc = width.size() + space.size()
t_drc = time.perf_counter() - t0

s = r.seconds
print("input: %s %d/%d cell %s: %d polygons, %d sites, %d gauges; builder %s"
      % (os.path.basename(path), L, D, cell.name, len(polygons), r.diagram["sites"], len(r.gauges), builder))
print("gauges (diagram included), 1 builder thread: %.2f s (read %.2f, merge %.2f, build %.2f, check %.2f, gauges %.2f);"
      " %d threads: %.2f s" % (t_gauges, t_read, s["merge"], s["build"], s["check"], s["gauges"], cores, t_all))
print("KLayout width + space checks, t = %d DBU, Square: %.2f s (%d edge pairs: the narrowest places only)"
      % (t, t_drc, n_drc))
print("ratio gauges / (width + space at t = %d DBU, KLayout 1 thread): %.2f with 1 builder thread, %.2f with %d"
      % (t, t_gauges / t_drc, t_all / t_drc, cores))

if g.get("reach") != "0":
    w_max = max(x.cd for x in r.gauges if x.type == "internal")
    s_max = max(x.cd for x in r.gauges if x.type == "external")
    t0 = time.perf_counter()
    fresh = pya.Region(cell.begin_shapes_rec(li))
    n_reach = (fresh.width_check(int(w_max) + 1, False, pya.Region.Square).size()
               + fresh.space_check(int(s_max) + 1, False, pya.Region.Square).size())
    t_reach = time.perf_counter() - t0
    print("KLayout width + space checks at the gauges' reach (width t = %d, space t = %d DBU): %.2f s (%d edge pairs)"
          % (int(w_max) + 1, int(s_max) + 1, t_reach, n_reach))
    print("ratio gauges / (width + space at the gauges' reach, KLayout 1 thread): %.2f with 1 builder thread, %.2f with "
          "%d (goal: under 1)" % (t_gauges / t_reach, t_all / t_reach, cores))
