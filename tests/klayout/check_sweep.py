# The sweep-line builder against the subdivision on a real layer: the sweep did build it, the
# same pieces (owners, kinds, ends within 10^-6 DBU), and the independent checker passes both
# diagrams; the sweep tile by tile is the whole layer's, bit for bit.
#   klayout -b -r tests/klayout/check_sweep.py -rd input=FILE -rd layer=L/D [-rd cell=NAME]
# input=drawn-slanted: a layer of slanted edges drawn here (a bus, a 45-degree bend, a wire bent
# at 42 degrees, round pads and a ring drawn with many vertices), layer 1/0.
import math
import os
import sys
import time

import pya

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from harness import arg, expect, finish, repo  # noqa: E402

sys.path.insert(0, os.path.join(repo, "build"))
sys.path.insert(0, os.path.join(repo, "plugin", "python"))
import linf_opc_core as core  # noqa: E402

from linf_opc import layout  # noqa: E402
from linf_opc.polygons import core_input  # noqa: E402

if arg("input") == "drawn-slanted":
    ly = pya.Layout()
    ly.dbu = 0.001
    shapes = ly.create_cell("SLANTED").shapes(ly.layer(1, 0))
    for k in range(4):
        shapes.insert(pya.Box(0, 120 * k, 2000, 120 * k + 60))
    shapes.insert(pya.Polygon([pya.Point(x, y) for x, y in
                               [(2400, 0), (2480, 0), (2480, 300), (2880, 700), (2880, 1000), (2800, 1000), (2800, 733), (2400, 333)]]))
    shapes.insert(pya.Polygon([pya.Point(x, y) for x, y in
                               [(3000, 0), (3300, 0), (3633, 300), (3633, 380), (3300, 80), (3000, 80)]]))
    for k, (cx, cy, r, n) in enumerate([(4200, 300, 250, 64), (4800, 300, 250, 200), (5600, 500, 400, 512)]):
        shapes.insert(pya.Polygon([pya.Point(round(cx + r * math.cos(2 * math.pi * i / n)),
                                             round(cy + r * math.sin(2 * math.pi * i / n))) for i in range(n)]))
    ring = pya.Polygon([pya.Point(round(4500 + 600 * math.cos(2 * math.pi * i / 300)),
                                  round(1400 + 600 * math.sin(2 * math.pi * i / 300))) for i in range(300)])
    ring.insert_hole([pya.Point(round(4500 + 450 * math.cos(2 * math.pi * i / 200)),
                                round(1400 + 450 * math.sin(2 * math.pi * i / 200))) for i in range(200)])
    shapes.insert(ring)
elif arg("input").lower().endswith(".glp"):  # a contest clip: KLayout does not read GLP
    from linf_opc import glp
    ly = glp.read(arg("input"))
else:
    ly = pya.Layout()
    ly.read(arg("input"))
top = ly.cell(arg("cell")) if arg("cell", None) else ly.top_cells()[0]
L, D = layout.parse_layer(arg("layer"))
region = layout.region_of(top, ly.find_layer(L, D))
polygons = core_input(layout.polygons_of(region))


def key(p):
    ends = sorted([(round(p[1], 6), round(p[2], 6)), (round(p[3], 6), round(p[4], 6))])
    return (p[0], p[15], p[16], ends[0], ends[1])


pieces = {}
for builder in ("subdivision", "sweep"):
    t0 = time.perf_counter()
    r = core.voronoi_polygons(polygons, check="full", threads=1, tile=0, builder=builder)
    print("%s: %d pieces, build %.2f s, whole %.2f s, check %s" % (
        builder, len(r["pieces"]), r["seconds"]["build"], time.perf_counter() - t0, r["check"]["ok"]))
    expect(r["check"]["ok"], "the checker passes the %s's diagram" % builder)
    expect(r["builder"] == builder, "asked for the %s, the %s built it" % (builder, r["builder"]))
    pieces[builder] = [key(p) for p in r["pieces"]]
    if builder == "sweep":
        whole = r["pieces"]

# The sweep tile by tile (tiles.hpp): every tile size and thread count gives the whole layer's
# sweep, bit for bit (pieces cut at the tiles' frames are joined again).
side = max(region.bbox().width(), region.bbox().height())
for tile, threads in ((-1, 2), (side / 5.0, 2), (side / 11.0, 1)):
    t0 = time.perf_counter()
    r = core.voronoi_polygons(polygons, check="full", threads=threads, tile=tile, builder="sweep")
    print("sweep, tile %s, %d threads: %d tiles (largest %d sites), %d pieces, build %.2f s, whole %.2f s" % (
        "auto" if tile < 0 else "%.0f DBU" % tile, threads, r["tiles"]["tiles"], r["tiles"]["largest_tile_sites"],
        len(r["pieces"]), r["seconds"]["build"], time.perf_counter() - t0))
    expect(r["check"]["ok"] and r["builder"] == "sweep", "tile %s: the sweep built it and the checker passes it" % tile)
    if tile > 0:
        expect(r["tiles"]["tiles"] > 1, "tile %.0f DBU: more than one tile (%d)" % (tile, r["tiles"]["tiles"]))
    diff = next((i for i, (u, v) in enumerate(zip(whole, r["pieces"])) if u != v), None)
    expect(len(r["pieces"]) == len(whole) and diff is None,
           "tile %s, %d threads: the whole layer's sweep bit for bit (%d pieces against %d; first difference %s)" % (
               tile, threads, len(r["pieces"]), len(whole), None if diff is None else (whole[diff], r["pieces"][diff])))

a, b = set(pieces["subdivision"]), set(pieces["sweep"])
expect(len(a) > 0, "the layer has a diagram")
expect(len(pieces["sweep"]) == len(b), "the sweep gives no piece twice")
expect(a == b, "the same pieces (only the subdivision's: %d, e.g. %s; only the sweep's: %d, e.g. %s)" % (
    len(a - b), sorted(a - b)[:2], len(b - a), sorted(b - a)[:2]))
finish()
