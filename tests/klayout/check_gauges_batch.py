# Runs the batch macro's gauges command on one layout and checks its outputs:
#   klayout -b -r tests/klayout/check_gauges_batch.py -rd input=FILE -rd layer=L/D [-rd cell=NAME] -rd work=DIR
# - gauges.csv: exact header; ranks 1..n in order; scores never decrease with rank; norm_score
#   = score / the highest; the line's ends are cd apart along the axis it measures (axis-parallel
#   lines); counts per type as in summary.json; every type present on the sample;
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

g = globals()
repo = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
work = g.get("work") or "/tmp/linf_gauges_check"
failures = []
TYPES = ["internal", "external", "sandwich", "comb", "T"]


def expect(cond, what):
    if not cond:
        failures.append(what)
        print("FAIL: " + what)


def run(out, extra=()):
    args = ["-rd", "cmd=gauges", "-rd", "input=" + g["input"], "-rd", "layer=" + g["layer"], "-rd", "out=" + out]
    if g.get("cell"):
        args += ["-rd", "cell=" + g["cell"]]
    r = subprocess.run(["klayout", "-b", "-r", os.path.join(repo, "macros", "linf_opc.py")] + args + list(extra),
                       capture_output=True, text=True)
    print(r.stdout.strip())
    if r.returncode != 0:
        print(r.stderr)
        sys.exit(1)
    with open(os.path.join(out, "gauges.csv")) as f:
        rows = list(csv.reader(f))
    return rows, json.load(open(os.path.join(out, "summary.json")))


rows, summary = run(work)
expect(rows[0] == "id,type,x1,y1,x2,y2,cx,cy,cd,score,norm_score,tiebreak,rank".split(","), "csv header")
rows = rows[1:]
expect(len(rows) == summary["gauges"] > 0, "rows %d vs summary %d" % (len(rows), summary["gauges"]))
counts = dict.fromkeys(TYPES, 0)
top = max(float(r[9]) for r in rows)
last = -1.0
for i, r in enumerate(rows):
    t = r[1]
    x1, y1, x2, y2, cx, cy, cd, score, norm, tie = (float(v) for v in r[2:12])
    counts[t] = counts.get(t, 0) + 1
    expect(int(r[12]) == i + 1, "rank %s at row %d" % (r[12], i + 1))
    expect(score >= last - 1e-9, "score decreases at rank %d" % (i + 1))
    last = score
    expect(abs(norm - score / top) < 1e-5, "norm_score at rank %d" % (i + 1))
    if x1 == x2 or y1 == y2:
        expect(abs(max(abs(x2 - x1), abs(y2 - y1)) - cd) < 2e-6,
               "rank %d: line length %g vs cd %g" % (i + 1, max(abs(x2 - x1), abs(y2 - y1)), cd))
expect(counts == summary["counts"], "counts %s vs summary %s" % (counts, summary["counts"]))
if os.path.basename(g["input"]) == "metal.oas":
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
L = int(g["layer"].split("/")[0])
li = ly.find_layer(L, 210)
shapes = list(ly.top_cells()[0].shapes(li).each()) if li is not None else []
texts = sorted(s.text_string for s in shapes if s.is_text())
lines = sum(1 for s in shapes if s.is_path())
expect(sorted(t.rsplit(" ", 1)[0] for t in texts) == sorted("#%s %s" % (r[12], r[1]) for r in rows),
       "gauge layer: %d rank texts '#rank type cd' for %d gauges" % (len(texts), len(rows)))
# Sandwich, comb and T gauges measure the same line as an internal gauge: the file keeps one.
distinct = len(set((r[2], r[3], r[4], r[5]) for r in rows))
expect(lines == distinct, "gauge layer: %d lines for %d distinct measurement lines" % (lines, distinct))

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

print("gauges batch check %s: %d gauges %s" % ("FAILED" if failures else "passed", len(rows), counts))
sys.exit(1 if failures else 0)
