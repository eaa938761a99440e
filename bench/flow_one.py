# One input of bench/bench_flow.py, in its own KLayout process (so that its peak memory is its
# own): prints one JSON line with the stage times, counts and peak memory.
#   klayout -b -r bench/flow_one.py -rd input=FILE|generated:N -rd layer=L/D [-rd cell=NAME]
#           [-rd markers=SPEC] [-rd threads=N] [-rd tile=DBU] [-rd drc=1] [-rd reach=1]
#           [-rd polygons_json=FILE]
# tile: the builder's tile side in DBU (default -1, automatic; 0 one tile). polygons_json: also
# write the merged polygons there, for CGAL's construction in another process. drc=1 times
# KLayout's width + space checks at t = 2 x the narrowest width; reach=1 also at the gauges' own
# reach (width above the widest width, space above the widest space the gauges report: what the
# checks need to find every width and space the gauges measure).
import json
import os
import random
import resource
import sys
import threading
import time

repo = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(repo, "build"))
sys.path.insert(0, os.path.join(repo, "plugin", "python"))

import pya  # noqa: E402

from linf_opc import core, layout, markers as marker_io, selection, split  # noqa: E402
from linf_opc import gauges as gauge_stage  # noqa: E402
from linf_opc.polygons import SPILL_SHAPES, core_input  # noqa: E402

g = globals()
t = {}
peak = {}  # the process's peak memory (MB) after each stage: which stage sets it
anon = {"now": 0.0, "stage": 0.0}  # the peak of anonymous memory (MB) so far, and in the current stage
anon_peak = {}  # ... in each stage


def rss_anon_mb():
    with open("/proc/self/status") as f:
        for line in f:
            if line.startswith("RssAnon:"):
                return int(line.split()[1]) / 1024
    return 0.0


def sample_anon():
    # The core releases the GIL while it works, so this thread sees its memory too. Anonymous
    # memory is what the process must hold; the maximum RSS also counts the pages of the
    # mapped temporary files (linf/paged.hpp), which the kernel may drop.
    while True:
        a = rss_anon_mb()
        anon["now"] = max(anon["now"], a)
        anon["stage"] = max(anon["stage"], a)
        time.sleep(0.1)


threading.Thread(target=sample_anon, daemon=True).start()


def mark(stage):
    peak[stage] = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024
    anon_peak[stage] = max(anon["stage"], rss_anon_mb())
    anon["stage"] = 0.0


def generated(n, seed=1):
    """A routed-metal-like square block of n rectangles: horizontal tracks on a 100 DBU pitch,
    wires 50 DBU wide of random length (150-1500) with random gaps (50-600)."""
    rng = random.Random(seed)
    ly = pya.Layout()
    ly.dbu = 0.001
    top = ly.create_cell("GEN")
    shapes = top.shapes(ly.layer(1, 0))
    tracks = max(1, int((11.5 * n) ** 0.5))  # about 1150 DBU of track per wire: a square block
    length, count = 100 * tracks, 0
    for k in range(tracks):
        x = rng.randrange(0, 400)
        while x < length and count < n:
            w = rng.randrange(150, 1500)
            shapes.insert(pya.Box(x, k * 100, x + w, k * 100 + 50))
            count += 1
            x += w + rng.randrange(50, 600)
    return ly, top


t0 = time.perf_counter()
if g["input"].startswith("generated:"):
    ly, cell = generated(int(g["input"].split(":")[1]))
    L, D = 1, 0
else:
    ly = layout.read_layout(g["input"])  # GLP contest clips too
    cell = ly.cell(g["cell"]) if g.get("cell") else ly.top_cells()[0]
    L, D = layout.parse_layer(g["layer"])
li = ly.find_layer(L, D)
region = layout.region_of(cell, li)
polygons = layout.polygons_of(region, SPILL_SHAPES)  # as the batch reads it
t["load"] = time.perf_counter() - t0
mark("load")
threads = int(g.get("threads") or 0)
tile = float(g.get("tile") or -1)
if g.get("polygons_json"):
    with open(g["polygons_json"], "w") as f:  # one polygon at a time: no list of them all in memory
        f.write("[")
        for i, (outer, holes) in enumerate(polygons):
            f.write("," if i else "")
            json.dump([outer, holes], f)
        f.write("]")
t0 = time.perf_counter()
# As gauges.compute calls it: the columns written to a file that the gauge table maps.
raw = core.gauges_polygons(core_input(polygons), True, 2000, threads, tile=tile, columns=gauge_stage.columns_file())
t["diagram_and_gauges"] = time.perf_counter() - t0
t["diagram"] = raw["diagram"]["seconds"]["merge"] + raw["diagram"]["seconds"]["build"] + raw["diagram"]["seconds"]["check"]
t["gauges"] = raw["diagram"]["seconds"]["gauges"]
res = gauge_stage.Gauges(raw, t["diagram_and_gauges"])
mark("diagram_and_gauges")
gs = res.gauges
if g.get("markers"):
    ms = marker_io.load(g["markers"], ly, cell).boxes
else:  # no markers: 1% of the gauge points, seeded
    rng = random.Random(7)
    pts = rng.sample(gs, max(1, len(gs) // 100))
    ms = [(p.cx - 8, p.cy - 8, p.cx + 8, p.cy + 8) for p in pts]
t0 = time.perf_counter()
pitch = selection.pitch_of(gs)
st = selection.study(gs, ms, pitch, sizes=(7,), modes=("A",))
t["selection"] = time.perf_counter() - t0
mark("selection")
t0 = time.perf_counter()
sp = split.stratified(split.patterns_of(st.runs[("A", 7)], gs, ms))
t["split"] = time.perf_counter() - t0
mark("split")
out = {"input": os.path.basename(g["input"]), "polygons": raw["diagram"]["polygons"], "shapes": len(polygons),
       "sites": raw["diagram"]["sites"],
       "segments": raw["diagram"]["sites"] // 2, "gauges": len(gs),  # a segment site and a point site a vertex
       "markers": len(ms), "patterns": len(sp.patterns), "seconds": t, "threads": threads,
       "tiles": raw["diagram"]["tiles"]}
if g.get("drc") == "1":
    w0 = min(x.cd for x in gs if x.type == "internal")
    t0 = time.perf_counter()
    fresh = pya.Region(cell.begin_shapes_rec(li))
    fresh.width_check(int(2 * w0), False, pya.Region.Square).size()
    fresh.space_check(int(2 * w0), False, pya.Region.Square).size()
    t["klayout_width_space"] = time.perf_counter() - t0
if g.get("reach") == "1":
    w_max = max(x.cd for x in gs if x.type == "internal")
    s_max = max(x.cd for x in gs if x.type == "external")
    t0 = time.perf_counter()
    fresh = pya.Region(cell.begin_shapes_rec(li))
    fresh.width_check(int(w_max) + 1, False, pya.Region.Square).size()
    fresh.space_check(int(s_max) + 1, False, pya.Region.Square).size()
    t["klayout_width_space_reach"] = time.perf_counter() - t0
    out["reach_dbu"] = [int(w_max) + 1, int(s_max) + 1]
out["peak_rss_mb"] = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024
out["peak_mb_after"] = peak
out["peak_anon_mb"] = max(anon["now"], rss_anon_mb())
out["peak_anon_mb_in"] = anon_peak
print("RESULT " + json.dumps(out))
