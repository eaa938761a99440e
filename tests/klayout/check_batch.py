# Runs the batch macro on one layout and checks its outputs independently of the core:
#   klayout -b -r tests/klayout/check_batch.py -rd input=FILE -rd layer=L/D [-rd cell=NAME] -rd work=DIR
# - voronoi.csv: exact header, one row per piece, kinds as in summary.json;
# - voronoi.oas: the merged input layer and one layer per kind, with as many shapes as drawn
#   (every row but pieces shorter than the grid);
# - clearances, with KLayout's own geometry: around a sampled piece end (x, y) with clearance d,
#   the square of half-side d - 2 DBU holds no boundary of the layer and the one of d + 2 DBU
#   meets it; the two owner sites written in the row are at L-inf distance d;
# - -rd check: the sampled default and check=full write the same voronoi.csv, full searches
#   every piece; check=some is a usage error (exit 2, nothing written).
# Exit code 0 when all hold; the first failures are printed.
import csv
import json
import math
import os
import random
import subprocess
import sys

import pya

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from harness import BATCH, arg, expect, finish, repo  # noqa: E402

work = arg("work", "/tmp/linf_check")
args = ["-rd", "cmd=voronoi", "-rd", "input=" + arg("input"), "-rd", "layer=" + arg("layer"), "-rd", "out=" + work]
if arg("cell", None):
    args += ["-rd", "cell=" + arg("cell")]

run = subprocess.run(BATCH + args,
                     capture_output=True, text=True)
print(run.stdout.strip())
if run.returncode != 0:
    print(run.stderr)
    sys.exit(1)

summary = json.load(open(os.path.join(work, "summary.json")))
with open(os.path.join(work, "voronoi.csv")) as f:
    rows = list(csv.reader(f))
expect(rows[0] == "kind,x1,y1,x2,y2,d1,d2,a_x1,a_y1,a_x2,a_y2,b_x1,b_y1,b_x2,b_y2".split(","), "csv header")
rows = rows[1:]
expect(len(rows) == summary["pieces"] and len(rows) > 0, "csv rows %d vs summary %d" % (len(rows), summary["pieces"]))
counts = {}
for r in rows:
    counts[r[0]] = counts.get(r[0], 0) + 1
expect(set(counts) <= {"internal", "external", "notch", "adjacent"}, "kinds %s" % sorted(counts))
expect(all(counts.get(k, 0) == n for k, n in summary["counts"].items()), "counts %s vs %s" % (counts, summary["counts"]))
expect(summary["check"]["ok"], "core checker")
expect(counts.get("adjacent", 0) > 0, "adjacent pieces exist")

# The input as KLayout sees it.
L, D = [int(v) for v in arg("layer").split("/")]
if arg("input").lower().endswith(".glp"):  # a contest clip: KLayout does not read GLP (check_glp.py tests the reader)
    sys.path.insert(0, os.path.join(repo, "plugin", "python"))
    from linf_opc import glp
    src = glp.read(arg("input"))
else:
    src = pya.Layout()
    src.read(arg("input"))
cell = src.cell(arg("cell")) if arg("cell", None) else src.top_cells()[0]
region = pya.Region(cell.begin_shapes_rec(src.find_layer(L, D))).merged()
dbu = src.dbu
expect(abs(summary["dbu"] - dbu) < 1e-12, "dbu")

res = pya.Layout()
res.read(os.path.join(work, "voronoi.oas"))
top = res.top_cells()[0]
inp = res.find_layer(L, D)
# The layer as drawn (the core merges it for the diagram): the same area as the merged layer.
expect(inp is not None and (pya.Region(top.shapes(inp)) ^ region).is_empty(), "input layer copied")
for i, kind in enumerate(["internal", "external", "notch", "adjacent"]):
    li = res.find_layer(L, 200 + i)
    n = top.shapes(li).size() if li is not None else 0
    # Pieces shorter than the grid are in the CSV only: summary "drawn" counts what is drawn,
    # and every piece spanning at least one grid step in x or y must be among them.
    drawn = summary["drawn"][kind]
    expect(n == drawn, "layer %d/%d holds %d %s pieces, summary drawn %d" % (L, 200 + i, n, kind, drawn))
    long_rows = sum(1 for r in rows if r[0] == kind and
                    max(abs(float(r[3]) - float(r[1])), abs(float(r[4]) - float(r[2]))) >= dbu * 1.001)
    expect(long_rows <= drawn <= counts.get(kind, 0),
           "%s: %d drawn, %d rows of which %d span a grid step" % (kind, drawn, counts.get(kind, 0), long_rows))

edges = region.edges()


def linf_to(px, py, ax, ay, bx, by):
    dx, dy = bx - ax, by - ay
    best = float("inf")
    ts = [0.0, 1.0]
    if dx: ts.append((px - ax) / dx)
    if dy: ts.append((py - ay) / dy)
    if dx - dy: ts.append(((px - ax) - (py - ay)) / (dx - dy))
    if dx + dy: ts.append(((px - ax) + (py - ay)) / (dx + dy))
    for t in ts:
        t = min(1.0, max(0.0, t))
        best = min(best, max(abs(px - ax - t * dx), abs(py - ay - t * dy)))
    return best


random.seed(1)
sample = random.sample(rows, min(300, len(rows)))
bad = 0
for r in sample:
    v = [float(x) / dbu for x in r[1:]]  # to DBU
    for (x, y, d) in ((v[0], v[1], v[4]), (v[2], v[3], v[5])):
        da = linf_to(x, y, *v[6:10])
        db = linf_to(x, y, *v[10:14])
        if abs(da - d) > 0.01 or abs(db - d) > 0.01:
            bad += 1
            if bad < 5: print("owner distance", r, da, db)
        if d <= 1:  # on the boundary: nothing to test with integer boxes
            continue
        # Integer boxes, and edges that merely touch a box count as meeting it: 2 DBU of slack.
        inner = pya.Box(math.ceil(x - d + 2), math.ceil(y - d + 2), math.floor(x + d - 2), math.floor(y + d - 2))
        outer = pya.Box(math.floor(x - d - 2), math.floor(y - d - 2), math.ceil(x + d + 2), math.ceil(y + d + 2))
        if inner.width() > 0 and inner.height() > 0 and not edges.interacting(pya.Region(inner)).is_empty():
            bad += 1
            if bad < 5: print("boundary closer than the clearance", r)
        if edges.interacting(pya.Region(outer)).is_empty():
            bad += 1
            if bad < 5: print("no boundary at the clearance", r)
expect(bad == 0, "%d clearance failures in %d sampled pieces" % (bad, len(sample)))

# -rd check: the default searches about one piece in 16 for a closer site, check=full every
# piece; the diagram is the same bytes either way, and anything else is a usage error.
searched = summary["check"]["searched_pieces"]
if len(rows) >= 1000:
    expect(len(rows) / 64 < searched < len(rows) / 4, "sampled check searched %d of %d pieces" % (searched, len(rows)))
full = subprocess.run(BATCH +
                      [a.replace("out=" + work, "out=" + work + "_full") for a in args] + ["-rd", "check=full"],
                      capture_output=True, text=True)
expect(full.returncode == 0, "check=full exit %d: %s" % (full.returncode, full.stderr.strip()))
if full.returncode == 0:
    fs = json.load(open(os.path.join(work + "_full", "summary.json")))
    expect(fs["check"]["ok"] and fs["check"]["searched_pieces"] == fs["pieces"] == summary["pieces"],
           "check=full searched %d of %d pieces" % (fs["check"]["searched_pieces"], fs["pieces"]))
    expect(open(os.path.join(work + "_full", "voronoi.csv"), "rb").read() ==
           open(os.path.join(work, "voronoi.csv"), "rb").read(), "check=full: the same voronoi.csv")
bogus = subprocess.run(BATCH +
                       [a.replace("out=" + work, "out=" + work + "_bogus") for a in args] + ["-rd", "check=some"],
                       capture_output=True, text=True)
expect(bogus.returncode == 2 and "check must be sample or full" in bogus.stderr and
       not os.path.exists(os.path.join(work + "_bogus", "voronoi.csv")), "check=some: exit %d" % bogus.returncode)
finish("checked %d rows, %d sampled ends" % (len(rows), 2 * len(sample)))
