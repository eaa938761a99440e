# Runs the batch macro's farthest command on one layout and checks the smallest touching
# square with KLayout's own geometry:
#   klayout -b -r tests/klayout/check_farthest_batch.py -rd input=FILE -rd layer=L/D [-rd box=X1,Y1,X2,Y2]
#           [-rd cell=NAME] -rd work=DIR
# - the square of summary.json, grown by 1 DBU, meets every shape's convex hull (the sites);
#   shrunk by 1 DBU about its centre, it misses at least one (it is the smallest);
# - farthest.csv has one row per edge, rays ending on the clip box; farthest.oas has the
#   diagram on L/240 and the square on L/241.
import csv
import json
import os
import subprocess
import sys

import pya

g = globals()
repo = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
work = g.get("work") or "/tmp/linf_farthest_check"
failures = []


def expect(cond, what):
    if not cond:
        failures.append(what)
        print("FAIL: " + what)


args = ["-rd", "cmd=farthest", "-rd", "input=" + g["input"], "-rd", "layer=" + g["layer"], "-rd", "out=" + work]
for k in ("cell", "box"):
    if g.get(k):
        args += ["-rd", "%s=%s" % (k, g[k])]
r = subprocess.run(["klayout", "-b", "-r", os.path.join(repo, "macros", "linf_opc.py")] + args,
                   capture_output=True, text=True)
print(r.stdout.strip())
if r.returncode != 0:
    print(r.stderr)
    sys.exit(1)
s = json.load(open(os.path.join(work, "summary.json")))

ly = pya.Layout()
ly.read(g["input"])
dbu = ly.dbu
cell = ly.cell(g["cell"]) if g.get("cell") else ly.top_cells()[0]
L, D = (int(v) for v in g["layer"].split("/"))
index = ly.find_layer(L, D)
if g.get("box"):
    x1, y1, x2, y2 = (float(v) / dbu for v in g["box"].split(","))
    it = cell.begin_shapes_rec_overlapping(index, pya.Box(int(x1), int(y1), int(round(x2)), int(round(y2))))
else:
    it = cell.begin_shapes_rec(index)


def hull(points):
    pts = sorted(set(points))
    if len(pts) < 3:
        return pts

    def cross(o, a, b):
        return (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0])
    lo, up = [], []
    for p in pts:
        while len(lo) >= 2 and cross(lo[-2], lo[-1], p) <= 0:
            lo.pop()
        lo.append(p)
    for p in reversed(pts):
        while len(up) >= 2 and cross(up[-2], up[-1], p) <= 0:
            up.pop()
        up.append(p)
    return lo[:-1] + up[:-1]


sites = []
while not it.at_end():
    sh = it.shape()
    if not sh.is_text():
        poly = sh.polygon.transformed(it.trans())
        pts = hull([(p.x, p.y) for p in poly.each_point_hull()])
        sites.append(pya.Region(pya.Polygon([pya.Point(x, y) for x, y in pts])) if len(pts) >= 3 else
                     pya.Region(pya.Box(min(p[0] for p in pts), min(p[1] for p in pts),
                                        max(p[0] for p in pts), max(p[1] for p in pts))))
    it.next()
expect(len(sites) == s["sites"], "sites: %d here vs %d" % (len(sites), s["sites"]))
sq = [v / dbu for v in s["root"]["square_um"]]
cx, cy, h = (sq[0] + sq[2]) / 2, (sq[1] + sq[3]) / 2, (sq[2] - sq[0]) / 2


def square(half):
    import math
    return pya.Region(pya.Box(math.floor(cx - half), math.floor(cy - half), math.ceil(cx + half), math.ceil(cy + half)))


big = square(h + 1)
missed = sum(1 for site in sites if (site & big).is_empty() and not site.interacting(big).count())
expect(missed == 0, "the square (+1 DBU) meets every site: %d missed" % missed)
if h >= 2:
    import math
    small = pya.Region(pya.Box(math.ceil(cx - h + 1), math.ceil(cy - h + 1), math.floor(cx + h - 1), math.floor(cy + h - 1)))
    outside = sum(1 for site in sites if not site.interacting(small).count())
    expect(outside > 0, "the square shrunk by 1 DBU misses some site (it is the smallest)")

with open(os.path.join(work, "farthest.csv")) as f:
    rows = list(csv.DictReader(f))
expect(len(rows) == s["edges"] and all(r["kind"] in ("edge", "ray") for r in rows), "farthest.csv rows")
res = pya.Layout()
res.read(os.path.join(work, "farthest.oas"))
top = res.top_cells()[0]
le, ls = res.find_layer(L, 240), res.find_layer(L, 241)
expect(le is not None and top.shapes(le).size() > 0 and ls is not None and top.shapes(ls).size() >= 1,
       "farthest.oas has the diagram and the square")
print("farthest batch check %s: %d sites, square side %g um" % ("FAILED" if failures else "passed", len(sites),
                                                               s["root"]["side_um"]))
sys.exit(1 if failures else 0)
