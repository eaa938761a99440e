# Runs the batch macro's gauges and select commands on one layout and checks the selection
# independently of the core:
#   klayout -b -r tests/klayout/check_select_batch.py -rd input=FILE -rd layer=L/D -rd markers=SPEC
#           [-rd cell=NAME] -rd work=DIR
# - windows.csv: exact header; each window is size x pitch wide and centred on the point of the
#   gauge whose rank it names (gauges.csv), with that gauge's type and score;
# - coverage recounted by brute force in Python from the marker source and the windows: each
#   window covers (chosen mode) a marker no earlier window covers, markers_covered adds up to
#   M_c, and M_c is the number of markers covered by the union of the windows;
# - stats.json: every size x mode, P_d = M_c / markers, u_g = G_u / (G_u + G_f), G_u = windows;
# - windows.lyrdb: one sub-category of "patterns" per size x mode with G_u items;
# - windows.oas: the chosen windows on L/220; report.html: self-contained (no src/href).
import csv
import json
import os
import subprocess
import sys

import pya

g = globals()
repo = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
work = g.get("work") or "/tmp/linf_select_check"
failures = []


def expect(cond, what):
    if not cond:
        failures.append(what)
        print("FAIL: " + what)


def run(cmd, extra=()):
    args = ["-rd", "cmd=" + cmd, "-rd", "input=" + g["input"], "-rd", "layer=" + g["layer"], "-rd", "out=" + work]
    if g.get("cell"):
        args += ["-rd", "cell=" + g["cell"]]
    r = subprocess.run(["klayout", "-b", "-r", os.path.join(repo, "macros", "linf_opc.py")] + args + list(extra),
                       capture_output=True, text=True)
    print(r.stdout.strip())
    if r.returncode != 0:
        print(r.stderr)
        sys.exit(1)


run("gauges")
run("select", ["-rd", "markers=" + g["markers"]])
stats = json.load(open(os.path.join(work, "stats.json")))
with open(os.path.join(work, "gauges.csv")) as f:
    gauges = {int(r["rank"]): r for r in csv.DictReader(f)}
with open(os.path.join(work, "windows.csv")) as f:
    rows = list(csv.reader(f))
expect(rows[0] == "id,x1,y1,x2,y2,gauge_id,type,score,markers_covered".split(","), "windows.csv header")
rows = rows[1:]
chosen = stats["chosen"]
mode, size = chosen["mode"], chosen["size"]
side = size * stats["pitch_um"]
expect(len(rows) == chosen["windows"] > 0, "windows: %d rows vs %d" % (len(rows), chosen["windows"]))

# Markers, read here without the plugin's code.
ly = pya.Layout()
ly.read(g["input"])
dbu = ly.dbu
spec = g["markers"]
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
    cell = ly.cell(g["cell"]) if g.get("cell") else ly.top_cells()[0]
    l, d = (int(v) for v in spec.split("/"))
    it = cell.begin_shapes_rec(ly.find_layer(l, d))
    while not it.at_end():
        b = it.shape().bbox().transformed(it.trans())
        markers.add((b.left * dbu, b.bottom * dbu, b.right * dbu, b.top * dbu))
        it.next()
markers = sorted(markers)
expect(len(markers) == stats["markers"], "markers: %d here vs %d in stats" % (len(markers), stats["markers"]))

eps = 1e-6  # the CSV's micrometres carry 6 decimals


def covers(w, m):
    if mode == "A":
        cx, cy = (m[0] + m[2]) / 2, (m[1] + m[3]) / 2
        return w[0] + eps < cx < w[2] - eps and w[1] + eps < cy < w[3] - eps
    if mode == "B":
        return m[0] >= w[0] - eps and m[2] <= w[2] + eps and m[1] >= w[1] - eps and m[3] <= w[3] + eps
    return m[0] <= w[2] + eps and m[2] >= w[0] - eps and m[1] <= w[3] + eps and m[3] >= w[1] - eps


covered = set()
total_new = 0
for r in rows:
    w = [float(v) for v in r[1:5]]
    gid, new = int(r[5]), int(r[8])
    ga = gauges.get(gid)
    expect(ga is not None and ga["type"] == r[6] and abs(float(ga["score"]) - float(r[7])) < 1e-6,
           "window %s names gauge %d with its type and score" % (r[0], gid))
    if ga is not None:
        cx, cy = float(ga["cx"]), float(ga["cy"])
        expect(abs((w[0] + w[2]) / 2 - cx) < 2e-6 and abs((w[1] + w[3]) / 2 - cy) < 2e-6,
               "window %s centred on its gauge" % r[0])
    expect(abs(w[2] - w[0] - side) < 2e-6 and abs(w[3] - w[1] - side) < 2e-6, "window %s is %g wide" % (r[0], side))
    hit = set(i for i, m in enumerate(markers) if covers(w, m))
    fresh = hit - covered
    expect(len(fresh) > 0, "window %s covers a marker not covered before" % r[0])
    expect(len(fresh) == new, "window %s: %d markers covered first, csv says %d" % (r[0], len(fresh), new))
    covered |= hit
    total_new += new
row = next(x for x in stats["coverage"] if x["mode"] == mode and x["W_s"] == "%dx%d" % (size, size))
expect(len(covered) == row["M_c"] == total_new, "M_c %d, recount %d, csv sum %d" % (row["M_c"], len(covered), total_new))
for x in stats["coverage"]:
    expect(abs(x["P_d"] - 100.0 * x["M_c"] / x["markers"]) < 1e-3, "P_d of %s %s" % (x["mode"], x["W_s"]))
    expect(abs(x["u_g"] - 100.0 * x["G_u"] / max(1, x["G_u"] + x["G_f"])) < 1e-3, "u_g of %s %s" % (x["mode"], x["W_s"]))
expect(len(stats["coverage"]) == 12, "12 size x mode runs")

rdb = pya.ReportDatabase("check")
rdb.load(os.path.join(work, "windows.lyrdb"))
subs = {}
for item in rdb.each_item():
    c = rdb.category_by_id(item.category_id())
    if c.path().startswith("patterns."):
        subs[c.name()] = subs.get(c.name(), 0) + 1
expect(len(subs) == 12, "report database: %d pattern sub-categories" % len(subs))
for x in stats["coverage"]:
    key = "%s %s" % (x["mode"], x["W_s"])
    expect(subs.get(key) == x["G_u"], "report database %s: %s items vs G_u %d" % (key, subs.get(key), x["G_u"]))

res = pya.Layout()
res.read(os.path.join(work, "windows.oas"))
li = res.find_layer(int(g["layer"].split("/")[0]), 220)
n = res.top_cells()[0].shapes(li).size() if li is not None else 0
expect(n == len(rows), "windows layer: %d boxes for %d windows" % (n, len(rows)))
page = open(os.path.join(work, "report.html")).read()
expect("<svg" in page and "src=" not in page and "href=" not in page, "report.html is self-contained with SVG")

print("select batch check %s: mode %s %dx%d, %d windows, %d/%d markers"
      % ("FAILED" if failures else "passed", mode, size, size, len(rows), len(covered), len(markers)))
sys.exit(1 if failures else 0)
