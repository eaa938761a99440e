# Runs the batch macro's farthest command on one layout and checks the smallest touching
# square with KLayout's own geometry:
#   klayout -b -r tests/klayout/check_farthest_batch.py -rd input=FILE -rd layer=L/D [-rd box=X1,Y1,X2,Y2]
#           [-rd cell=NAME] -rd work=DIR
# - the square of summary.json (grown by at most 1/4 DBU for rounding), centred at either end of
#   the root, meets every shape's convex hull (the sites);
# - it is the smallest: with a side 3/4 DBU smaller (so also 1 DBU smaller) no centre at all
#   gives a square meeting every site (the sites grown by that square have no common point:
#   KLayout's AND of them is empty);
# - farthest.csv has one row per edge, rays ending on the clip box; farthest.oas has the
#   diagram on L/240 and the square on L/241.
import csv
import json
import math
import os
import subprocess
import sys

import pya

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from harness import BATCH, arg, expect, finish, repo  # noqa: E402

work = arg("work", "/tmp/linf_farthest_check")
args = ["-rd", "cmd=farthest", "-rd", "input=" + arg("input"), "-rd", "layer=" + arg("layer"), "-rd", "out=" + work]
for k in ("cell", "box"):
    if arg(k, None):
        args += ["-rd", "%s=%s" % (k, arg(k))]
r = subprocess.run(BATCH + args,
                   capture_output=True, text=True)
print(r.stdout.strip())
if r.returncode != 0:
    print(r.stderr)
    sys.exit(1)
s = json.load(open(os.path.join(work, "summary.json")))

ly = pya.Layout()
ly.read(arg("input"))
dbu = ly.dbu
cell = ly.cell(arg("cell")) if arg("cell", None) else ly.top_cells()[0]
L, D = (int(v) for v in arg("layer").split("/"))
index = ly.find_layer(L, D)
if arg("box", None):
    x1, y1, x2, y2 = (float(v) / dbu for v in arg("box").split(","))
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


hulls = []  # each site's convex hull (a point or a segment where the shape is that thin)
while not it.at_end():
    sh = it.shape()
    if not sh.is_text():
        poly = sh.polygon.transformed(it.trans())
        hulls.append(hull([(p.x, p.y) for p in poly.each_point_hull()]))
    it.next()
expect(len(hulls) == s["sites"], "sites: %d here vs %d" % (len(hulls), s["sites"]))
sq = [v / dbu for v in s["root"]["square_um"]]
cx, cy, h = (sq[0] + sq[2]) / 2, (sq[1] + sq[3]) / 2, (sq[2] - sq[0]) / 2
root = [tuple(v / dbu for v in s["root"][k]) for k in ("p_um", "q_um")]
expect(abs(h - s["root"]["half_side_um"] / dbu) < 1e-6 and max(abs(cx - root[0][0]), abs(cy - root[0][1])) < 1e-6,
       "the square is centred at the root's first point, half_side_um from its centre to its sides")

# A square of half side r centred at c meets a convex site S exactly where c lies in S grown by
# the square, the hull of S's vertices each moved by (+-r, +-r). KLayout decides that, on a grid
# of 1/8 DBU (coordinates times 8) so that half a DBU is well resolved.
GRID = 8


def grown(pts, r8):
    """S grown by the square of half side r8 / GRID, on the 1/GRID grid."""
    moved = [(GRID * x + a, GRID * y + b) for x, y in pts for a in (-r8, r8) for b in (-r8, r8)]
    return pya.Polygon([pya.Point(x, y) for x, y in hull(moved)])


# The square of summary.json meets every site (the root's both ends as centres): grown by 1/8 to
# 1/4 DBU for the rounding of its numbers, never by the half DBU a side 1 DBU smaller lacks.
r8 = math.floor(GRID * h) + 2
for c in root:
    at = pya.Point(round(GRID * c[0]), round(GRID * c[1]))
    missed = sum(1 for pts in hulls if not grown(pts, r8).inside(at))
    expect(missed == 0, "the square centred at (%g, %g) um meets every site: %d missed" % (c[0] * dbu, c[1] * dbu, missed))
# It is the smallest: the sites grown by the square of half side h - 3/8 to h - 1/4 (on the grid)
# have no point in common, so no square of a side 3/4 DBU smaller, wherever its centre, meets
# them all (KLayout's boolean AND of the grown sites is empty). Not 1/2 DBU: where the square is
# the smallest plus 1 DBU, the sites grown by the smallest meet in a point or a segment only,
# which the AND leaves out; a square 1/4 DBU larger than the smallest leaves an area.
r8 = math.ceil(GRID * h) - 3
common = None
if r8 >= 0:
    for pts in hulls:
        g = pya.Region(grown(pts, r8))
        common = g if common is None else common & g
        if common.is_empty():
            break
expect(common is not None and common.is_empty(),
       "no square of side %g um (3/4 DBU smaller), wherever its centre, meets every site" % ((2 * h - 0.75) * dbu))

with open(os.path.join(work, "farthest.csv")) as f:
    rows = list(csv.DictReader(f))
expect(len(rows) == s["edges"] and all(r["kind"] in ("edge", "ray") for r in rows), "farthest.csv rows")
res = pya.Layout()
res.read(os.path.join(work, "farthest.oas"))
top = res.top_cells()[0]
le, ls = res.find_layer(L, 240), res.find_layer(L, 241)
expect(le is not None and top.shapes(le).size() > 0 and ls is not None and top.shapes(ls).size() >= 1,
       "farthest.oas has the diagram and the square")
finish("%d sites, square side %g um" % (len(hulls), s["root"]["side_um"]))
