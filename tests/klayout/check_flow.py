# Runs the batch macro's flow command on one layout with every file on request (all_gauges=1,
# diagram=1, halves=1, rdb_max=0) and checks every file it writes, each against the others and
# against KLayout's reading of it; then the default flow (quiet=1) into DIR_default:
#   klayout -b -r tests/klayout/check_flow.py -rd input=FILE -rd layer=L/D -rd markers=SPEC
#           [-rd cell=NAME] -rd work=DIR
# - exit status 0, the summary line, exactly the expected files (no staging leftovers), a
#   progress line on stderr for each stage;
# - summary.json: the four stages, each agreeing with the stage's own file;
# - voronoi.csv: exact header, one row per piece of summary.json, kinds as counted there;
#   voronoi.oas: one layer per kind holding the pieces drawn;
# - gauges.csv: exact header, ranks 1..n, one row per gauge, types as counted in summary.json;
#   every axis-parallel line (ends on the half-DBU grid) ends on the layer's boundary (KLayout's
#   merge), or (a corner offset both ways from the other feature) in line with the boundary
#   across the line at most cd/2 away; gauges.lyrdb: one category per gauge type, each item's line and values those of its
#   gauges.csv row; gauges.oas: a label per gauge, the lines of gauges.csv on the grid;
# - windows.csv: exact header, the chosen run's windows, each centred on the gauge it names with
#   that gauge's type and score, size x pitch wide, markers_covered adding up to M_c;
# - stats.json: its keys, twelve size x mode runs with their identities, the chosen run;
# - report.html: a whole page whose coverage tables say what stats.json says, with a picture of
#   the layout (the markers and the windows) and its figures;
# - split.json: the sets add up to the patterns, the classes to the sets;
#   calibration.oas and verification.oas: one top cell a pattern (SET_rRANK_TYPE_SCORE), each
#   with its window; calibration_gauges.csv and verification_gauges.csv: one row a pattern,
#   each the gauges.csv row of the cell's gauge;
# - flow.lyrdb: the gauge types, "patterns" (one sub-category a run, G_u items each),
#   "markers" (one item a marker) and "split" (one item a pattern, tagged with its set);
# - the default flow: the same summary line, nothing on stderr (quiet=1), exactly the default
#   files (no voronoi.* or gauges.*), the plan's and the windows' files byte for byte those of the
#   full run, summary.json's counts as the full run's, flow.lyrdb with the 100 most critical
#   gauges of each type (the full run's first ranks) and the same plan items.
import csv
import itertools
import json
import math
import os
import re
import shutil
import subprocess
import sys
from collections import Counter

import pya

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from harness import BATCH, arg, expect, finish, repo  # noqa: E402

work = arg("work", "/tmp/linf_flow_check")
TYPES = ["internal", "external", "sandwich", "comb", "T"]
KINDS = ["internal", "external", "notch", "adjacent"]
SETS = {"calibration": "CAL", "verification": "VER"}
GAUGE_HEADER = "id,type,x1,y1,x2,y2,cx,cy,cd,score,norm_score,tiebreak,rank".split(",")
DEFAULT_FILES = ["windows.csv", "pattern_classes.csv", "windows.oas", "stats.json", "report.html", "calibration.oas",
                 "verification.oas", "calibration_gauges.csv", "verification_gauges.csv", "split.json", "flow.lyrdb",
                 "summary.json"]
ON_REQUEST = {"all_gauges": ["gauges.csv", "gauges.lyrdb", "gauges.oas"], "diagram": ["voronoi.csv", "voronoi.oas"]}
FILES = DEFAULT_FILES + ON_REQUEST["all_gauges"] + ON_REQUEST["diagram"]
STAGES = ["read", "diagram and gauges", "writing the diagram", "writing the gauges", "selection", "pattern classes",
          "halves", "split", "writing the plan"]
L = int(arg("layer").split("/")[0])

work_default = work.rstrip("/") + "_default"
shutil.rmtree(work, ignore_errors=True)
shutil.rmtree(work_default, ignore_errors=True)


def flow(out, *more):
    args = ["-rd", "cmd=flow", "-rd", "input=" + arg("input"), "-rd", "layer=" + arg("layer"),
            "-rd", "markers=" + arg("markers"), "-rd", "out=" + out]
    if arg("cell", None):
        args += ["-rd", "cell=" + arg("cell")]
    return subprocess.run(BATCH + args +
                          [x for m in more for x in ("-rd", m)], capture_output=True, text=True)


def files_are(out, files):
    present = sorted(os.listdir(out)) if os.path.isdir(out) else []
    expect(present == sorted(files), "files in %s: missing %s, unexpected %s"
           % (os.path.basename(out), sorted(set(files) - set(present)), sorted(set(present) - set(files))))


r = flow(work, "all_gauges=1", "diagram=1", "halves=1", "rdb_max=0")
print(r.stdout.strip())
expect(r.returncode == 0, "flow exits 0 (exit %d): %s" % (r.returncode, r.stderr.strip()[-2000:]))
expect(re.search(r"patterns: calibration \d+, verification \d+; outputs in ", r.stdout), "flow's summary line")
expect(len(r.stdout.strip().splitlines()) == 1, "one line on stdout")
files_are(work, FILES)
# One line a stage on stderr as it ends: "linf_opc: STAGE 1.2 s: counts" (a core call's also as it starts).
ended = [m.group(1) for m in re.finditer(r"^linf_opc: (.+?) \d+\.\d s(?:: .*)?$", r.stderr, re.M)]
expect(ended == STAGES, "progress: a line as each stage ends, %s (got %s)" % (STAGES, ended))
expect(re.search(r"^linf_opc: diagram and gauges: [\d,]+ polygons \.\.\.$", r.stderr, re.M)
       and re.search(r"^linf_opc: diagram and gauges [\d.]+ s: [\d,]+ polygons, [\d,]+ pieces, [\d,]+ gauges$",
                     r.stderr, re.M), "progress: the diagram's start and end with its counts")
expect(all(line.startswith("linf_opc: ") and "error" not in line for line in r.stderr.splitlines()),
       "stderr holds progress lines only: %s" % r.stderr.strip()[-400:])
if r.returncode != 0 or not os.path.isdir(work):
    finish()


def path(name):
    return os.path.join(work, name)


def load_json(name):
    try:
        with open(path(name)) as f:
            return json.load(f)
    except (OSError, ValueError) as e:
        expect(False, "%s: %s" % (name, e))
        return {}


def load_csv(name):
    try:
        with open(path(name)) as f:
            rows = list(csv.reader(f))
    except OSError as e:
        expect(False, "%s: %s" % (name, e))
        return [], []
    expect(len(rows) > 0, "%s has a header" % name)
    return (rows[0], rows[1:]) if rows else ([], [])


def load_rdb(name):
    rdb = pya.ReportDatabase("check")
    try:
        rdb.load(path(name))
    except Exception as e:  # KLayout raises RuntimeError for a missing or broken file
        expect(False, "%s loads: %s" % (name, e))
        return None, {}
    items = {}
    for item in rdb.each_item():
        items.setdefault(rdb.category_by_id(item.category_id()).path(), []).append(item)
    return rdb, items


def load_layout(name):
    ly = pya.Layout()
    try:
        ly.read(path(name))
    except Exception as e:
        expect(False, "%s loads: %s" % (name, e))
        return None
    return ly


# summary.json: the four stages.
summary = load_json("summary.json")
expect(sorted(summary) == ["gauges", "select", "split", "voronoi"], "summary.json stages %s" % sorted(summary))
sv, sg = summary.get("voronoi", {}), summary.get("gauges", {})
ssel, ssplit = summary.get("select", {}), summary.get("split", {})
expect(sv.get("check", {}).get("ok") is True and sg.get("check", {}).get("ok") is True, "summary: diagram checked")

# voronoi.csv and voronoi.oas.
header, rows = load_csv("voronoi.csv")
expect(header == "kind,x1,y1,x2,y2,d1,d2,a_x1,a_y1,a_x2,a_y2,b_x1,b_y1,b_x2,b_y2".split(","), "voronoi.csv header")
kinds = {k: 0 for k in KINDS}
for row in rows:
    kinds[row[0]] = kinds.get(row[0], 0) + 1
expect(len(rows) == sv.get("pieces", -1) > 0, "voronoi.csv: %d rows, summary %s pieces" % (len(rows), sv.get("pieces")))
expect(kinds == sv.get("counts"), "voronoi.csv kinds %s, summary %s" % (kinds, sv.get("counts")))
ly = load_layout("voronoi.oas")
if ly is not None:
    for i, kind in enumerate(KINDS):
        li = ly.find_layer(L, 200 + i)
        n = ly.top_cells()[0].shapes(li).size() if li is not None else 0
        expect(n == sv.get("drawn", {}).get(kind) and n <= kinds[kind],
               "voronoi.oas %d/%d: %d %s pieces, summary drawn %s" % (L, 200 + i, n, kind, sv.get("drawn", {}).get(kind)))

# gauges.csv, gauges.lyrdb, gauges.oas.
header, grows = load_csv("gauges.csv")
expect(header == GAUGE_HEADER, "gauges.csv header")
gauges = {}
counts = {t: 0 for t in TYPES}
for i, row in enumerate(grows):
    expect(row[0] == row[12] == str(i + 1), "gauges.csv row %d: id and rank %s, %s" % (i + 1, row[0], row[12]))
    gauges[row[0]] = row
    counts[row[1]] = counts.get(row[1], 0) + 1
expect(len(grows) == sg.get("gauges", -1) > 0, "gauges.csv: %d rows, summary %s" % (len(grows), sg.get("gauges")))
expect(counts == sg.get("counts"), "gauges.csv types %s, summary %s" % (counts, sg.get("counts")))
cap = sg.get("report_max_per_type", -1)
expect(cap == 0, "summary.json: rdb_max=0 puts every gauge into the report databases (%s)" % cap)
cap = len(grows)  # every gauge
grdb, gitems = load_rdb("gauges.lyrdb")
for t in TYPES:
    expect(len(gitems.get(t, ())) == min(counts[t], cap), "gauges.lyrdb %s: %d items for %d gauges"
           % (t, len(gitems.get(t, ())), counts[t]))
# Each report item says what its gauges.csv row says: the line and the values (other writers).
unlike = []
for t in TYPES:
    for item in gitems.get(t, ()):
        line, values = None, {}
        for v in item.each_value():
            if v.is_edge():
                e = v.edge()
                line = (e.p1.x, e.p1.y, e.p2.x, e.p2.y)
            elif v.tag_id and v.is_float():
                values[grdb.tag_name(v.tag_id)] = v.float()
        row = gauges.get(str(int(values.get("rank", 0))))
        if (row is None or row[1] != t or line is None
                or any(abs(a - float(b)) > 2e-6 for a, b in zip(line, row[2:6]))
                or any(abs(values.get(k, -1) - float(row[i])) > 2e-6 for k, i in
                       (("cd", 8), ("score", 9), ("norm_score", 10), ("tiebreak", 11)))):
            unlike.append(int(values.get("rank", 0)))
expect(not unlike, "gauges.lyrdb: every item's line and values as in gauges.csv (ranks %s differ)" % unlike[:5])
ly = load_layout("gauges.oas")
li = ly.find_layer(L, 210) if ly is not None else None
shapes = list(ly.top_cells()[0].shapes(li).each()) if li is not None else []
texts = sorted(sh.text_string.rsplit(" ", 1)[0] for sh in shapes if sh.is_text())
expect(texts == sorted("#%s %s" % (row[0], row[1]) for row in grows),
       "gauges.oas: a label '#rank type cd' for each of %d gauges (%d labels)" % (len(grows), len(texts)))
# The lines of gauges.oas: those of gauges.csv rounded to the grid, where the CSV's six decimals
# leave a tie either way.
lines = Counter(tuple(v for q in sh.path.each_point() for v in (q.x, q.y)) for sh in shapes if sh.is_path())
dbu = ly.dbu if ly is not None else 0.001
unmatched = 0
rounded = []
for row in grows:
    exact = [float(v) / dbu for v in row[2:6]]
    # Python's round (ties to even) first: the core's rule
    rounded.append([sorted({math.floor(v + 0.5 - 1e-3), math.floor(v + 0.5 + 1e-3)}, key=lambda c: c != round(v))
                    for v in exact])
for options in sorted(rounded, key=lambda o: max(len(c) for c in o)):  # the lines without a tie first
    hit = next((c for c in itertools.product(*options) if lines[c] > 0), None)
    if hit is None:
        unmatched += 1
    else:
        lines[hit] -= 1
expect(unmatched == 0 and not +lines, "gauges.oas: the lines of gauges.csv on the grid (%d unmatched, %d extra)"
       % (unmatched, sum((+lines).values())))
# An axis-parallel gauge measures across its shape or gap: where its line's ends lie on the
# half-DBU grid, both lie on the boundary of the layer (KLayout's merge of it), or, where a
# corner is offset both ways from the other feature, in line with the boundary across the line
# at most cd/2 from it (the line ends at the corner's coordinate on its axis): a probe that long
# across the line at that end meets the boundary.
source = pya.Layout()
source.read(arg("input"))
top = source.cell(arg("cell")) if arg("cell", None) else source.top_cells()[0]
merged = pya.Region(top.begin_shapes_rec(source.layer(L, int(arg("layer").split("/")[1])))).merged()
across, along = {}, {}  # twice the coordinates: horizontal edges by y, vertical by x
for e in merged.edges().each():
    if e.p1.y == e.p2.y:
        across.setdefault(2 * e.p1.y, []).append((2 * min(e.p1.x, e.p2.x), 2 * max(e.p1.x, e.p2.x)))
    elif e.p1.x == e.p2.x:
        along.setdefault(2 * e.p1.x, []).append((2 * min(e.p1.y, e.p2.y), 2 * max(e.p1.y, e.p2.y)))


def on_boundary(x, y):
    return any(a <= x <= b for a, b in across.get(y, ())) or any(a <= y <= b for a, b in along.get(x, ()))


ends, probes, probed = 0, pya.Edges(), []
probes.merged_semantics = False  # one probe an end, kept as drawn
for row in grows:
    twice = [2 * float(v) / source.dbu for v in row[2:6]]
    grid = [round(v) for v in twice]
    if (grid[0] == grid[2] or grid[1] == grid[3]) and all(abs(a - b) < 1e-3 for a, b in zip(grid, twice)):
        ends += 1
        reach = math.floor(float(row[8]) / source.dbu + 1e-3)  # cd/2, twice
        for x, y in ((grid[0], grid[1]), (grid[2], grid[3])):
            if not on_boundary(x, y):
                probe = pya.Edge(x, y - reach, x, y + reach) if grid[1] == grid[3] else pya.Edge(x - reach, y, x + reach, y)
                probes.insert(probe)
                probed.append((int(row[0]), probe))
met = set(str(e) for e in probes.interacting(merged.edges().transformed(pya.ICplxTrans(2.0))).each())
off = [rank for rank, probe in probed if str(probe) not in met]
expect(ends > 0 and not off and len(probed) <= ends // 2,  # at most a quarter of the ends
       "gauges.csv: %d axis-parallel lines end on the layer's boundary, %d ends beside a corner (not ranks %s)"
       % (ends, len(probed), off[:5]))

# stats.json and windows.csv.
stats = load_json("stats.json")
keys = ["cell", "chosen", "coverage", "distribution", "gauges", "heuristic", "input", "layer", "marker_source",
        "markers", "max_norm", "pitch_source", "pitch_um", "representatives", "seconds", "similarity"]
expect(all(k in stats for k in keys), "stats.json keys: missing %s" % [k for k in keys if k not in stats])
coverage = stats.get("coverage", [])
runs = {(x["mode"], x["W_s"]): x for x in coverage}
expect(len(coverage) == len(runs) == 12, "stats.json: %d size x mode runs" % len(coverage))
for x in coverage:
    expect(x["markers"] == stats.get("markers") and 0 < x["M_c"] <= x["markers"] and x["G_u"] <= x["M_c"],
           "stats.json %s %s: M_c %d of %d markers with %d windows" % (x["mode"], x["W_s"], x["M_c"], x["markers"], x["G_u"]))
    expect(abs(x["P_d"] - 100.0 * x["M_c"] / x["markers"]) < 1e-3, "stats.json P_d of %s %s" % (x["mode"], x["W_s"]))
    expect(abs(x["u_g"] - 100.0 * x["G_u"] / max(1, x["G_u"] + x["G_f"])) < 1e-3,
           "stats.json u_g of %s %s" % (x["mode"], x["W_s"]))
expect(stats.get("gauges") == len(grows), "stats.json: %s gauges, gauges.csv %d" % (stats.get("gauges"), len(grows)))
chosen = stats.get("chosen", {})
expect(chosen == ssel.get("chosen") and stats.get("pitch_um") == ssel.get("pitch_um")
       and stats.get("markers") == ssel.get("markers"), "summary.json select is stats.json's")
run = runs.get((chosen.get("mode"), "%dx%d" % (chosen.get("size", 0), chosen.get("size", 0))), {})
header, wrows = load_csv("windows.csv")
expect(header == "id,x1,y1,x2,y2,gauge_id,type,score,markers_covered,pattern_class".split(","), "windows.csv header")
expect(len(wrows) == chosen.get("windows", -1) == run.get("G_u") > 0,
       "windows.csv: %d rows, chosen %s, G_u %s" % (len(wrows), chosen.get("windows"), run.get("G_u")))
side = chosen.get("size", 0) * stats.get("pitch_um", 0)
windows = []
for w in wrows:
    box = [float(v) for v in w[1:5]]
    windows.append(box)
    g = gauges.get(w[5])
    expect(g is not None and g[1] == w[6] and g[9] == w[7], "window %s names gauge %s with its type and score" % (w[0], w[5]))
    if g is not None:
        expect(abs((box[0] + box[2]) / 2 - float(g[6])) < 2e-6 and abs((box[1] + box[3]) / 2 - float(g[7])) < 2e-6,
               "window %s is centred on its gauge" % w[0])
    expect(abs(box[2] - box[0] - side) < 2e-6 and abs(box[3] - box[1] - side) < 2e-6, "window %s is %g wide" % (w[0], side))
expect(sum(int(w[8]) for w in wrows) == run.get("M_c"), "windows.csv markers_covered add up to M_c %s" % run.get("M_c"))
ly = load_layout("windows.oas")
li = ly.find_layer(L, 220) if ly is not None else None
n = ly.top_cells()[0].shapes(li).size() if li is not None else 0
expect(n == len(wrows), "windows.oas: %d boxes for %d windows" % (n, len(wrows)))

# report.html: the page, its coverage tables as in stats.json, its pictures.
try:
    with open(path("report.html")) as f:
        page = f.read()
except OSError as e:
    expect(False, "report.html: %s" % e)
    page = ""
expect(page.startswith("<!DOCTYPE html>") and page.rstrip().endswith("</html>"), "report.html is a whole page")
for mode in "ABC":
    at = page.find("<h2>Coverage, mode %s</h2>" % mode)
    table = page[at:page.find("</table>", at)] if at >= 0 else ""
    cells = [re.findall(r"<td>(.*?)</td>", tr) for tr in re.findall(r"<tr>(.*?)</tr>", table, re.S)]
    cells = [c for c in cells if c]
    expect(len(cells) == 4, "report.html: coverage table of mode %s with %d rows" % (mode, len(cells)))
    for c in cells:
        x = runs.get((c[0], c[1]))
        expect(x is not None and c[0] == mode and (int(c[3]), int(c[4]), int(c[6])) == (x["M_c"], x["G_u"], x["G_f"]),
               "report.html: %s %s says M_c, G_u, G_f = %s, %s, %s as stats.json" % (c[0], c[1], c[3], c[4], c[6]))
expect("<h2>Figures</h2>" in page and page.count("<svg") >= 2, "report.html has its figures")
at = page.find("<h2>Layout with the windows")
picture = page[at:page.find("</svg>", at)] if at >= 0 else ""
if "<img" in picture[:400]:
    expect("src=\"data:image/png;base64," in picture, "report.html: the layout as an embedded PNG")
else:
    expect(picture.count("<rect") == len(wrows) + stats.get("markers", 0) > 0,
           "report.html: the layout's SVG draws %d boxes for %d windows and %d markers"
           % (picture.count("<rect"), len(wrows), stats.get("markers", 0)))

# split.json, the clip libraries and the split's gauge lists.
split = load_json("split.json")
sc = split.get("counts", {})
expect(sc == ssplit.get("counts") and split.get("patterns") == ssplit.get("patterns")
       and split.get("mode") == ssplit.get("mode"), "summary.json split is split.json's")
# The plan (the default) takes a marker window's gauge once a context (check_plan.py checks it);
# the other modes take every window.
plan = split.get("mode") == "plan"
expect(sum(sc.values()) == split.get("patterns", -1)
       and (split.get("covering_markers", -1) <= len(wrows) if plan else
            split.get("patterns", -1) >= len(wrows) == split.get("covering_markers")),
       "split.json: sets %s of %s patterns, %s covering markers for %d windows"
       % (sc, split.get("patterns"), split.get("covering_markers"), len(wrows)))
for s in SETS:
    expect(sum(c[s] for c in split.get("classes", [])) == sc.get(s) if not plan else
           split.get("sets", {}).get(s, {}).get("gauges") == sc.get(s), "split.json classes add up to %s" % s)
clip_windows = []
for s, prefix in SETS.items():
    ly = load_layout(s + ".oas")
    header, rows = load_csv(s + "_gauges.csv")
    expect(header == GAUGE_HEADER + (["context", "count"] if plan else []), "%s_gauges.csv header" % s)
    expect(len(rows) == sc.get(s), "%s_gauges.csv: %d rows, split.json %s" % (s, len(rows), sc.get(s)))
    for row in rows:
        expect(gauges.get(row[0]) == row[:len(GAUGE_HEADER)], "%s_gauges.csv: gauge %s as in gauges.csv" % (s, row[0]))
    if ly is None:
        continue
    tops = ly.top_cells()
    expect(len(tops) == ly.cells() == sc.get(s), "%s.oas: %d top cells (%d cells), split.json %s"
           % (s, len(tops), ly.cells(), sc.get(s)))
    named = sorted((int(m.group(1)), m.group(2)) for m in
                   (re.match(r"%s_r(\d{6})_(\w+?)_\d+p\d{4}$" % prefix, c.name) for c in tops) if m)
    expect(named == sorted((int(row[0]), row[1]) for row in rows),
           "%s.oas: the cells name the gauges of %s_gauges.csv (rank and type)" % (s, s))
    li = ly.find_layer(L, 220)
    for c in tops:
        boxes = [sh.bbox() for sh in c.shapes(li).each()] if li is not None else []
        expect(len(boxes) == 1, "%s.oas %s: one window" % (s, c.name))
        clip_windows += [(b.left * ly.dbu, b.bottom * ly.dbu, b.right * ly.dbu, b.top * ly.dbu) for b in boxes]
for w in windows:  # a clip's window is on the DBU grid
    near = [c for c in clip_windows if all(abs(c[i] - w[i]) <= 0.0015 for i in range(4))]
    expect(plan or len(near) == 1, "the window %s is one clip" % w)

# flow.lyrdb: the gauges, the runs, the markers, the split.
rdb, items = load_rdb("flow.lyrdb")
for t in TYPES:
    expect(len(items.get(t, ())) == min(counts[t], cap), "flow.lyrdb %s: %d items for %d gauges"
           % (t, len(items.get(t, ())), counts[t]))
for (mode, ws), x in runs.items():
    got = len(items.get("patterns.'%s %s'" % (mode, ws), ()))
    expect(got == x["G_u"], "flow.lyrdb patterns %s %s: %d items, G_u %d" % (mode, ws, got, x["G_u"]))
expect(len([p for p in items if p.startswith("patterns.")]) == 12, "flow.lyrdb: 12 runs under patterns")
expect(len(items.get("markers", ())) == stats.get("markers"), "flow.lyrdb markers: %d items" % len(items.get("markers", ())))
expect(len(items.get("split", ())) == split.get("patterns"), "flow.lyrdb split: %d items" % len(items.get("split", ())))
if rdb is not None:
    tagged = {s: sum(1 for i in items.get("split", ()) if i.has_tag(rdb.tag_id(s))) for s in SETS}
    expect(tagged == sc, "flow.lyrdb split tags %s, split.json %s" % (tagged, sc))


# The default flow: the plan, the windows and the reports only, quietly.
d = flow(work_default, "quiet=1")
expect(d.returncode == 0, "default flow exits 0 (exit %d): %s" % (d.returncode, d.stderr.strip()[-2000:]))
expect(d.stderr == "", "quiet=1: nothing on stderr (%r)" % d.stderr[-400:])
expect(d.stdout.replace(work_default, work) == r.stdout, "default flow: the same summary line (%s)" % d.stdout.strip())
files_are(work_default, DEFAULT_FILES)
for name in DEFAULT_FILES:
    if name not in ("summary.json", "stats.json", "report.html", "flow.lyrdb"):  # timings; the gauges' cap
        with open(path(name), "rb") as a, open(os.path.join(work_default, name), "rb") as b:
            expect(a.read() == b.read(), "default flow: %s as the full run's" % name)
dsum = {}
try:
    with open(os.path.join(work_default, "summary.json")) as f:
        dsum = json.load(f)
except (OSError, ValueError) as e:
    expect(False, "default summary.json: %s" % e)
dv, dg = dsum.get("voronoi", {}), dsum.get("gauges", {})
expect(sorted(dsum) == sorted(summary) and dsum.get("select") == ssel and dsum.get("split") == ssplit,
       "default summary.json: the stages, selection and split of the full run's")
expect(all(dv.get(k) == sv.get(k) for k in ("polygons", "sites", "pieces", "counts", "tiles"))
       and "drawn" not in dv and dv.get("check", {}).get("ok") is True,
       "default summary.json voronoi: the full run's counts, checked, nothing drawn")
expect(all(dg.get(k) == sg.get(k) for k in ("gauges", "counts", "score_range_um", "stretches", "typical_width_um"))
       and dg.get("report_max_per_type") == 100 and dg.get("written") == 0,
       "default summary.json gauges: the full run's counts, 100 a type in flow.lyrdb, no gauge list written")
drdb, ditems = load_rdb(os.path.join(work_default, "flow.lyrdb"))
for t in TYPES:
    got = sorted(int(v.float()) for i in ditems.get(t, ()) for v in i.each_value()
                 if v.tag_id and drdb.tag_name(v.tag_id) == "rank")
    want = sorted(int(row[0]) for row in grows if row[1] == t)[:100]
    expect(got == want, "default flow.lyrdb %s: the %d most critical gauges (%d items)" % (t, len(want), len(got)))
expect(sum(len(v) for k, v in ditems.items() if k in TYPES) == dg.get("report_items"),
       "default summary.json: report_items %s" % dg.get("report_items"))
plan = sorted(k for k in ditems if k not in TYPES)
expect(plan == sorted(k for k in items if k not in TYPES)
       and all(len(ditems[k]) == len(items[k]) for k in plan), "default flow.lyrdb: the full run's plan categories")

finish("%d pieces, %d gauges, %d windows, patterns %s" % (sv.get("pieces", 0), len(grows), len(wrows), sc))
