# Runs the batch macro's gauges command on one layout and checks its outputs:
#   klayout -b -r tests/klayout/check_gauges_batch.py -rd input=FILE -rd layer=L/D [-rd cell=NAME] -rd work=DIR
# - gauges.csv: exact header; ranks 1..n in order; scores never decrease with rank; norm_score
#   = score / the highest; an axis-parallel line's ends lie on either side of the gauge point
#   along its axis, the farther cd/2 from it, the nearer at most that (cd apart unless the
#   features touch the gauge's square on two adjacent sides); every line is horizontal or
#   vertical but between two slanted edges (none of them within the gauge's reach); counts per
#   type as in summary.json; every type present on the sample;
# - gauges.lyrdb: loads in KLayout, one category per type, one item per row, each with an edge
#   and the named values;
# - gauges.oas: a line and a rank text per gauge on L/210;
# - per-pattern mode (-rd window=...): at most one gauge per type, each the best-ranked of its
#   type inside the window in the full list.
import csv
import json
import os
import subprocess
import sys

import pya

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from harness import BATCH, arg, expect, finish, repo  # noqa: E402

work = arg("work", "/tmp/linf_gauges_check")
TYPES = ["internal", "external", "sandwich", "comb", "T"]


def run(out, extra=()):
    args = ["-rd", "cmd=gauges", "-rd", "input=" + arg("input"), "-rd", "layer=" + arg("layer"), "-rd", "out=" + out]
    if arg("cell", None):
        args += ["-rd", "cell=" + arg("cell")]
    r = subprocess.run(BATCH + args + list(extra),
                       capture_output=True, text=True)
    print(r.stdout.strip())
    if r.returncode != 0:
        print(r.stderr)
        sys.exit(1)
    with open(os.path.join(out, "gauges.csv")) as f:
        rows = list(csv.reader(f))
    return rows, json.load(open(os.path.join(out, "summary.json")))


def slanted_edges():
    """The slanted edges of the layer (merged), in micrometres."""
    ly = pya.Layout()
    ly.read(arg("input"))
    top = ly.cell(arg("cell")) if arg("cell", None) else ly.top_cells()[0]
    L, D = (int(v) for v in arg("layer").split("/"))
    region = pya.Region(top.begin_shapes_rec(ly.layer(L, D))).merged()
    return [(e.p1.x * ly.dbu, e.p1.y * ly.dbu, e.p2.x * ly.dbu, e.p2.y * ly.dbu)
            for e in region.edges().each() if e.p1.x != e.p2.x and e.p1.y != e.p2.y], ly.dbu


def euclid_to_segment(x, y, e):
    dx, dy = e[2] - e[0], e[3] - e[1]
    t = max(0.0, min(1.0, ((x - e[0]) * dx + (y - e[1]) * dy) / (dx * dx + dy * dy)))
    return ((x - e[0] - t * dx) ** 2 + (y - e[1] - t * dy) ** 2) ** 0.5


slanted, dbu = slanted_edges()
rows, summary = run(work)
expect(rows[0] == "id,type,x1,y1,x2,y2,cx,cy,cd,score,norm_score,tiebreak,rank".split(","), "csv header")
rows = rows[1:]
expect(len(rows) == summary["gauges"] > 0, "rows %d vs summary %d" % (len(rows), summary["gauges"]))
counts = dict.fromkeys(TYPES, 0)
top = max(float(r[9]) for r in rows)
last = -1.0
shorter, tilted = 0, []
for i, r in enumerate(rows):
    t = r[1]
    x1, y1, x2, y2, cx, cy, cd, score, norm, tie = (float(v) for v in r[2:12])
    counts[t] = counts.get(t, 0) + 1
    expect(int(r[12]) == i + 1, "rank %s at row %d" % (r[12], i + 1))
    expect(score >= last - 1e-9, "score decreases at rank %d" % (i + 1))
    last = score
    expect(abs(norm - score / top) < 1e-5, "norm_score at rank %d" % (i + 1))
    if x1 == x2 or y1 == y2:
        d1, d2 = (x1 - cx, x2 - cx) if y1 == y2 else (y1 - cy, y2 - cy)
        far, near = max(abs(d1), abs(d2)), min(abs(d1), abs(d2))
        expect(d1 * d2 <= 0 and abs(far - cd / 2) < 2e-6 and near <= cd / 2 + 2e-6,
               "rank %d: line ends %g and %g from the gauge point along its axis, cd %g" % (i + 1, d1, d2, cd))
        shorter += abs(d2 - d1) < cd - 2e-6
    elif not any(euclid_to_segment(cx, cy, e) <= (cd / 2 + dbu) * 2 ** 0.5 for e in slanted):
        tilted.append(i + 1)
expect(not tilted, "%d lines neither horizontal nor vertical away from slanted edges (ranks %s)" % (len(tilted), tilted[:5]))
expect(shorter <= len(rows) // 5, "%d of %d lines shorter than cd" % (shorter, len(rows)))
expect(counts == summary["counts"], "counts %s vs summary %s" % (counts, summary["counts"]))
if os.path.basename(arg("input")) == "metal.oas":
    expect(all(counts[t] > 0 for t in TYPES), "every gauge type on the sample: %s" % counts)

rdb = pya.ReportDatabase("check")
rdb.load(os.path.join(work, "gauges.lyrdb"))
cats = {c.name(): c.num_items() for c in rdb.each_category()}
expect(cats == counts, "report database categories %s vs csv %s" % (cats, counts))
first = next(rdb.each_item())
tags = sorted(rdb.tag_name(v.tag_id) for v in first.each_value() if v.tag_id)
expect(tags == ["cd", "norm_score", "rank", "score", "tiebreak"], "named values %s" % tags)
expect(any(v.is_edge() for v in first.each_value()), "an item holds its measurement line")

ly = pya.Layout()
ly.read(os.path.join(work, "gauges.oas"))
L = int(arg("layer").split("/")[0])
li = ly.find_layer(L, 210)
shapes = list(ly.top_cells()[0].shapes(li).each()) if li is not None else []
texts = sorted(s.text_string for s in shapes if s.is_text())
lines = [tuple((q.x, q.y) for q in s.path.each_point()) for s in shapes if s.is_path()]
expect(sorted(t.rsplit(" ", 1)[0] for t in texts) == sorted("#%s %s" % (r[12], r[1]) for r in rows),
       "gauge layer: %d rank texts '#rank type cd' for %d gauges" % (len(texts), len(rows)))
# Sandwich, comb and T gauges measure the same line as an internal gauge: the core's file keeps
# a line a gauge, KLayout's kept one of each.
distinct = len(set((r[2], r[3], r[4], r[5]) for r in rows))
expect(len(lines) == len(rows) and len(set(lines)) == distinct,
       "gauge layer: %d lines (%d distinct) for %d gauges (%d distinct measurement lines)"
       % (len(lines), len(set(lines)), len(rows), distinct))

# Per-pattern mode on the middle of the layer's extent.
xs = [float(r[6]) for r in rows]
ys = [float(r[7]) for r in rows]
# Off the DBU grid, so that no gauge point sits on the window's border.
w = (min(xs) - 0.00037, min(ys) - 0.00037, (min(xs) + max(xs)) / 2 + 0.00037, (min(ys) + max(ys)) / 2 + 0.00037)
prow, _ = run(work + "_window", ["-rd", "window=%g,%g,%g,%g" % w])
prow = prow[1:]
inside = [r for r in rows if w[0] <= float(r[6]) <= w[2] and w[1] <= float(r[7]) <= w[3]]
best = {}
for r in inside:
    best.setdefault(r[1], r)
expect(len(prow) == len(best) > 0, "per-pattern: %d gauges for %d types in the window" % (len(prow), len(best)))
for r in prow:
    expect(r[1] in best and r[2:10] == best[r[1]][2:10], "per-pattern %s is the best of its type" % r[1])

finish("%d gauges %s" % (len(rows), counts))
