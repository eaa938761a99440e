# Runs the batch macro's gauges and select commands on one layout and checks the selection
# independently of the core:
#   klayout -b -r tests/klayout/check_select_batch.py -rd input=FILE -rd layer=L/D -rd markers=SPEC
#           [-rd cell=NAME] -rd work=DIR
# - windows.csv: exact header; the chosen run's windows of windows.lyrdb;
# - every size x mode run (windows.lyrdb, "patterns" sub-categories, in the order chosen): each
#   window size x pitch wide and centred on the point of the gauge whose rank it names
#   (gauges.csv), with that gauge's type and score, in rank order;
# - coverage recounted for every run in Python from the marker source and gauges.csv alone:
#   each marker is covered first by the best-ranked gauge whose window covers it, so the run's
#   windows are exactly those gauges, each with the number of markers it covers first
#   (markers_covered), adding up to M_c; G_u = windows (the gauge points bucketed by window
#   side, exact integer arithmetic);
# - stats.json: every size x mode, P_d = M_c / markers, u_g = G_u / (G_u + G_f);
# - windows.oas: the chosen windows on L/220; report.html: self-contained (no src/href).
import csv
import json
import os
import subprocess
import sys

import pya

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from harness import BATCH, arg, expect, finish, repo  # noqa: E402

work = arg("work", "/tmp/linf_select_check")


def run(cmd, extra=()):
    args = ["-rd", "cmd=" + cmd, "-rd", "input=" + arg("input"), "-rd", "layer=" + arg("layer"), "-rd", "out=" + work]
    if arg("cell", None):
        args += ["-rd", "cell=" + arg("cell")]
    r = subprocess.run(BATCH + args + list(extra),
                       capture_output=True, text=True)
    print(r.stdout.strip())
    if r.returncode != 0:
        print(r.stderr)
        sys.exit(1)


run("gauges")
run("select", ["-rd", "markers=" + arg("markers")])
stats = json.load(open(os.path.join(work, "stats.json")))
with open(os.path.join(work, "gauges.csv")) as f:
    gauges = {int(r["rank"]): r for r in csv.DictReader(f)}
with open(os.path.join(work, "windows.csv")) as f:
    rows = list(csv.reader(f))
expect(rows[0] == "id,x1,y1,x2,y2,gauge_id,type,score,markers_covered,pattern_class".split(","), "windows.csv header")
rows = rows[1:]
chosen = stats["chosen"]
mode, size = chosen["mode"], chosen["size"]
expect(len(rows) == chosen["windows"] > 0, "windows: %d rows vs %d" % (len(rows), chosen["windows"]))

# Markers, read here without the plugin's code.
ly = pya.Layout()
ly.read(arg("input"))
dbu = ly.dbu
spec = arg("markers")
markers = set()
if spec.lower().endswith(".csv"):
    with open(spec) as f:
        for r in csv.DictReader(f):
            try:
                x, y = float(r["x"]) * dbu, float(r["y"]) * dbu
            except (KeyError, ValueError):
                continue
            markers.add((x, y, x, y))
else:
    cell = ly.cell(arg("cell")) if arg("cell", None) else ly.top_cells()[0]
    l, d = (int(v) for v in spec.split("/"))
    it = cell.begin_shapes_rec(ly.find_layer(l, d))
    while not it.at_end():
        b = it.shape().bbox().transformed(it.trans())
        markers.add((b.left * dbu, b.bottom * dbu, b.right * dbu, b.top * dbu))
        it.next()
markers = sorted(markers)
expect(len(markers) == stats["markers"], "markers: %d here vs %d in stats" % (len(markers), stats["markers"]))

eps = 2e-6  # um: the CSV's 6 decimals, the report database's boxes
# The recount in exact integers, in half-units of the CSV's last decimal (0.5e-6 um): marker
# boxes, their centres, the gauge points and the window sides are all integers there. A gauge
# point on the half-DBU grid (as most are) is exact in the CSV, and the window's border with it:
# a marker on that border is decided as the core decides it. Any other point may be rounded by
# up to one unit, and a marker that close to its window's border is left out of the recount.
UNIT = 2e6
HALF_DBU = round(dbu * UNIT / 2)


def units(v):
    return int(round(float(v) * UNIT))


def covers(mode, w, m, grow):
    """Does window w cover marker m in `mode` (A: its centre strictly inside, B: all of it inside,
    C: any of it), the window grown by `grow` units (shrunk where negative)? Integers."""
    x1, y1, x2, y2 = w[0] - grow, w[1] - grow, w[2] + grow, w[3] + grow
    if mode == "A":
        cx, cy = m[0] + m[2], m[1] + m[3]  # twice the centre
        return 2 * x1 < cx < 2 * x2 and 2 * y1 < cy < 2 * y2
    if mode == "B":
        return m[0] >= x1 and m[2] <= x2 and m[1] >= y1 and m[3] <= y2
    return m[0] <= x2 and m[2] >= x1 and m[1] <= y2 and m[3] >= y1


# Every run's windows, in the order chosen, from the report database.
rdb = pya.ReportDatabase("check")
rdb.load(os.path.join(work, "windows.lyrdb"))
runs = {}
for item in rdb.each_item():
    c = rdb.category_by_id(item.category_id())
    if not c.path().startswith("patterns."):
        continue
    box, values = None, {}
    for v in item.each_value():
        if v.is_box():
            box = v.box()
        elif v.tag_id:
            values[rdb.tag_name(v.tag_id)] = v.float() if v.is_float() else v.string()
    runs.setdefault(c.name(), []).append(((box.left, box.bottom, box.right, box.top) if box else None,
                                          int(values.get("gauge_rank", 0)), values.get("type"),
                                          values.get("score"), int(values.get("markers_covered", -1))))
expect(len(runs) == 12 == len(stats["coverage"]), "report database: %d runs, stats.json %d" % (len(runs), len(stats["coverage"])))
chosen_run = runs.get("%s %dx%d" % (mode, size, size), [])
expect([(r[1], r[4]) for r in chosen_run] == [(int(r[5]), int(r[8])) for r in rows]
       and all(abs(a - float(b)) < eps for r, w in zip(chosen_run, rows) for a, b in zip(r[0], w[1:5])),
       "windows.csv is the chosen run's windows in the report database")

# The gauge points bucketed by window side, to find the gauges whose window covers a marker.
ranked = sorted(gauges)
points = {k: (float(gauges[k]["cx"]), float(gauges[k]["cy"])) for k in ranked}
at = {k: (units(gauges[k]["cx"]), units(gauges[k]["cy"])) for k in ranked}
on_grid = {k: HALF_DBU > 0 and p[0] % HALF_DBU == 0 and p[1] % HALF_DBU == 0 for k, p in at.items()}
marker_units = [tuple(units(v) for v in m) for m in markers]
pitch = stats["pitch_um"]
pitch_on_grid = HALF_DBU > 0 and units(pitch) % HALF_DBU == 0


def first_covering(mode, h, grid, m):
    """The best rank whose window (half side h units) covers m for certain, and the best whose
    window may cover it (rounding aside); None where there is none. The selection takes the
    gauges in rank order, each window covering a marker not covered before, so a marker is
    covered first by the window of the best-ranked gauge whose window covers it."""
    side = 2 * h
    grow = 0 if pitch_on_grid else 1 + 4 * h // max(1, units(pitch))
    sure = maybe = None
    for i in range((m[0] - h - grow - 2) // side, (m[2] + h + grow + 2) // side + 1):
        for j in range((m[1] - h - grow - 2) // side, (m[3] + h + grow + 2) // side + 1):
            for k in grid.get((i, j), ()):
                if sure is not None and k >= sure:
                    break
                x, y = at[k]
                w = (x - h, y - h, x + h, y + h)
                g = grow if on_grid[k] else grow + 2
                if covers(mode, w, m, g):
                    maybe = k if maybe is None else min(maybe, k)
                    if covers(mode, w, m, -g):
                        sure = k
                        break
    return sure, maybe


grids = {}
for x in stats["coverage"]:
    name = "%s %s" % (x["mode"], x["W_s"])
    k = int(x["W_s"].split("x")[0])
    side = k * pitch
    h = k * units(pitch) // 2  # units(pitch) is even: twice the CSV's last decimal
    if k not in grids:
        grids[k] = {}
        for r in ranked:  # rank order in every cell
            grids[k].setdefault((at[r][0] // (2 * h), at[r][1] // (2 * h)), []).append(r)
    windows = runs.get(name, [])
    # The windows: each centred on the gauge it names, with its type and score, side x side,
    # in rank order.
    ok = all(b is not None and abs(b[2] - b[0] - side) < eps and abs(b[3] - b[1] - side) < eps for b, *_ in windows)
    expect(ok, "%s: every window %g um wide" % (name, side))
    named = [(b, g, t, s) for b, g, t, s, n in windows if g in gauges]
    expect(len(named) == len(windows) and all(
        t == gauges[g]["type"] and abs(s - float(gauges[g]["score"])) < 1e-6
        and abs((b[0] + b[2]) / 2 - points[g][0]) < eps and abs((b[1] + b[3]) / 2 - points[g][1]) < eps
        for b, g, t, s in named), "%s: every window centred on the gauge it names, with its type and score" % name)
    expect(all(a[1] < b[1] for a, b in zip(windows, windows[1:])), "%s: windows in rank order" % name)
    # Coverage recounted: each marker goes to the best-ranked window covering it.
    want, unsure = {}, 0
    for m in marker_units:
        sure, maybe = first_covering(x["mode"], h, grids[k], m)
        if sure != maybe:
            unsure += 1
        elif sure is not None:
            want[sure] = want.get(sure, 0) + 1
    got = {g: n for b, g, t, s, n in windows}
    if unsure:  # a marker on a rounded window border: the counts near it may differ
        print("  %s: %d markers within rounding of a window's border, not recounted" % (name, unsure))
        wrong = sum(1 for g in set(got) | set(want) if got.get(g, 0) != want.get(g, 0))
        expect(wrong <= unsure, "%s: the windows and their first-covered markers, recounted (%d differ)" % (name, wrong))
    else:
        missing = sorted(set(want) - set(got))[:5]
        extra = sorted(set(got) - set(want))[:5]
        counts = sorted(g for g in set(got) & set(want) if got[g] != want[g])[:5]
        expect(got == want, "%s: the windows and their first-covered markers, recounted "
               "(missing ranks %s, extra ranks %s, other counts at ranks %s)" % (name, missing, extra, counts))
    expect(sum(got.values()) == x["M_c"] and len(windows) == x["G_u"],
           "%s: M_c %d, windows cover %d first; G_u %d, %d windows"
           % (name, x["M_c"], sum(got.values()), x["G_u"], len(windows)))
    expect(abs(sum(want.values()) - x["M_c"]) <= unsure, "%s: M_c %d, recount %d" % (name, x["M_c"], sum(want.values())))
    expect(abs(x["P_d"] - 100.0 * x["M_c"] / x["markers"]) < 1e-3, "P_d of %s" % name)
    expect(abs(x["u_g"] - 100.0 * x["G_u"] / max(1, x["G_u"] + x["G_f"])) < 1e-3, "u_g of %s" % name)
row = next(x for x in stats["coverage"] if x["mode"] == mode and x["W_s"] == "%dx%d" % (size, size))

res = pya.Layout()
res.read(os.path.join(work, "windows.oas"))
li = res.find_layer(int(arg("layer").split("/")[0]), 220)
n = res.top_cells()[0].shapes(li).size() if li is not None else 0
expect(n == len(rows), "windows layer: %d boxes for %d windows" % (n, len(rows)))
page = open(os.path.join(work, "report.html")).read()
expect("<svg" in page and "src=" not in page and "href=" not in page, "report.html is self-contained with SVG")

finish("mode %s %dx%d, %d windows, %d/%d markers" % (mode, size, size, len(rows), row["M_c"], len(markers)))
