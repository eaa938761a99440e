# The fault matrix's geometry rows (docs/testing.md, "Fault matrix"), through the batch macro:
# each input gives a correct result (exit 0, the outputs there and sane) or exit 2 with one
# line `linf_opc: error: ...` and nothing written; never a traceback, never another exit code.
#   klayout -b -r tests/klayout/check_faults_geometry.py -rd group=range|shapes|hierarchy|huge_polygon -rd work=DIR
# check_bad_input.py has the awkward shapes of one layer together (bow-tie, zero-area box,
# repeated points, a path, a text), a layer near 2^31 and the empty and unknown layers; the rows
# here take each input alone, across the documented range.
import csv
import json
import math
import os
import shutil
import subprocess
import sys
import time

import pya

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import harness  # noqa: E402
from harness import BATCH, arg, expect, finish, repo  # noqa: E402

harness.report_ok = True  # the rows and what each gives, read as a whole
group = arg("group")
work = os.path.join(arg("work", "/tmp/linf_faults_geometry"), group)
shutil.rmtree(work, ignore_errors=True)
os.makedirs(work)

LIMIT = 2 ** 30            # coordinates must lie strictly within +-LIMIT
DRAW = 2 ** 31 - 1         # drawings are cut to +-DRAW (and to the diagram's clip box)
KINDS = ("internal", "external", "notch", "adjacent")


# ---- running the macro --------------------------------------------------------------------

def run(cmd, path, layer, out, *extra):
    """exit code, stdout + stderr of one batch command (quiet: a refusal is exactly one line)."""
    args = ["cmd=" + cmd, "input=" + path, "layer=" + layer, "out=" + out, "quiet=1"] + list(extra)
    t0 = time.time()
    r = subprocess.run(BATCH +
                       [x for a in args for x in ("-rd", a)], capture_output=True, text=True)
    print("      (%s %s %s: exit %d, %.1f s)" % (cmd, os.path.basename(path), layer, r.returncode, time.time() - t0))
    return r.returncode, (r.stdout + r.stderr).strip()


def visible(d):
    return sorted(f for f in os.listdir(d) if not f.startswith(".")) if os.path.isdir(d) else []


def succeeded(row, code, out, outdir, files):
    """exit 0, no traceback, every file in `files` written and not empty."""
    missing = [f for f in files if not (os.path.isfile(os.path.join(outdir, f)) and
                                        os.path.getsize(os.path.join(outdir, f)) > 0)]
    return expect(code == 0 and "Traceback" not in out and not missing,
                  "%s: exit 0 with %s (exit %d, missing %s: %s)" % (row, ", ".join(files), code, missing,
                                                                   out.splitlines()[-1][:160] if out else ""))


def refused(row, code, out, outdir, words):
    """exit 2, exactly one line `linf_opc: error: ...` holding every one of `words` (besides
    warnings), nothing written in the output folder."""
    lines = out.splitlines()
    # Warnings about the run's options (e.g. markers on the working layer) may come first.
    errors = [l for l in lines if not l.startswith("linf_opc: warning: ")]
    expect(code == 2 and len(errors) == 1 and errors[0].startswith("linf_opc: error: ") and
           all(w in errors[0] for w in words),
           "%s: exit 2 and one line naming %s (exit %d: %s)" % (row, words, code, out[-300:]))
    expect(not visible(outdir), "%s: nothing written (%s)" % (row, visible(outdir)))


def summary(outdir):
    return json.load(open(os.path.join(outdir, "summary.json")))


def checked(row, s):
    c = s.get("check", {})
    return expect(c.get("ok") is True and c.get("sampled_points", 0) > 0,
                  "%s: the diagram passed its independent check (%s)" % (row, c))


def layout_of(path, cell=None):
    ly = pya.Layout()
    ly.read(path)
    return ly, (ly.cell(cell) if cell else ly.top_cell())


def region(ly, cell, layer, datatype):
    i = ly.find_layer(layer, datatype)
    return pya.Region() if i is None else pya.Region(cell.begin_shapes_rec(i))


def paths_on(ly, cell, layer, datatype):
    """The two-point paths of a layer as (x1, y1, x2, y2)."""
    i = ly.find_layer(layer, datatype)
    out = []
    if i is not None:
        for s in cell.shapes(i).each():
            if s.is_path():
                pts = list(s.path.each_point())
                out.append((pts[0].x, pts[0].y, pts[-1].x, pts[-1].y))
    return out


def csv_rows(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def same_layer(row, path, ly_in, cell_in, layer, datatype, cell_name=None):
    """The result layout's input layer equals the input layer flattened (KLayout XOR)."""
    ly, top = layout_of(path, cell_name)
    a = region(ly, top, layer, datatype)
    b = region(ly_in, cell_in, layer, datatype)
    x = a ^ b
    return expect(x.is_empty(), "%s: the input layer in %s equals the input (%d polygons differ)"
                  % (row, os.path.basename(path), x.count()))


# ---- the drawing bounds, computed here on their own ----------------------------------------

def clip_box_of(boxes):
    """The diagram's clip box: the layer's box enlarged by its larger side on every side."""
    x1 = min(b[0] for b in boxes)
    y1 = min(b[1] for b in boxes)
    x2 = max(b[2] for b in boxes)
    y2 = max(b[3] for b in boxes)
    m = max(x2 - x1, y2 - y1, 1)
    return (x1 - m, y1 - m, x2 + m, y2 + m)


def drawn_box(clip):
    return (max(clip[0], -DRAW), max(clip[1], -DRAW), min(clip[2], DRAW), min(clip[3], DRAW))


def cut(seg, box):
    """The segment cut to the box (Liang-Barsky), or None."""
    x1, y1, x2, y2 = seg
    dx, dy = x2 - x1, y2 - y1
    t0, t1 = 0.0, 1.0
    for p, q in ((-dx, x1 - box[0]), (dx, box[2] - x1), (-dy, y1 - box[1]), (dy, box[3] - y1)):
        if p == 0:
            if q < 0:
                return None
            continue
        r = q / p
        if p < 0:
            if r > t1:
                return None
            t0 = max(t0, r)
        else:
            if r < t0:
                return None
            t1 = min(t1, r)
    c = lambda v, lo, hi: min(max(v, lo), hi)  # noqa: E731
    return (c(x1 + t0 * dx, box[0], box[2]), c(y1 + t0 * dy, box[1], box[3]),
            c(x1 + t1 * dx, box[0], box[2]), c(y1 + t1 * dy, box[1], box[3]))


def matched(expected, drawn, tol=2):
    """Drawn segments (x1, y1, x2, y2) against expected ones, each end within `tol` DBU, either
    direction: (unmatched expected, unmatched drawn)."""
    def key(s):
        a, b = (s[0], s[1]), (s[2], s[3])
        return a + b if a <= b else b + a
    left = {}
    for s in drawn:
        left.setdefault(tuple(round(v / 64) for v in key(s)), []).append(key(s))
    todo = []
    for e in expected:
        k = key(e)
        bucket = left.get(tuple(round(v / 64) for v in k), [])
        hit = next((i for i, d in enumerate(bucket) if max(abs(u - v) for u, v in zip(k, d)) <= tol), None)
        if hit is None:
            todo.append(k)
        else:
            bucket.pop(hit)
    rest = [d for b in left.values() for d in b]
    near = lambda k, d: max(abs(u - v) for u, v in zip(k, d)) <= tol  # noqa: E731
    for k in list(todo):  # near a bucket border, or ends within tol ordered the other way
        hit = next((i for i, d in enumerate(rest) if near(k, d) or near(k, d[2:] + d[:2])), None)
        if hit is not None:
            rest.pop(hit)
            todo.remove(k)
    return todo, rest


def diagram_drawn_as_csv(row, outdir, path_oas, layer, boxes, dbu=0.001, cell=None):
    """voronoi.oas's diagram layers against voronoi.csv: each piece cut to the drawn box (the
    clip box within +-(2^31 - 1)), rounded to the grid, is drawn on its kind's layer, and nothing
    else; voronoi.csv keeps the whole pieces (to the clip box). Returns the number of cut pieces."""
    rows = csv_rows(os.path.join(outdir, "voronoi.csv"))
    s = summary(outdir)
    s = s.get("voronoi", s)
    expect(len(rows) == s["pieces"], "%s: voronoi.csv has a row a piece (%d, summary %d)" % (row, len(rows), s["pieces"]))
    clip = clip_box_of(boxes)
    box = drawn_box(clip)
    far = max((abs(float(r[c])) / dbu for r in rows for c in ("x1", "y1", "x2", "y2")), default=0)
    within = all(clip[0] - 2 <= float(r[c]) / dbu <= clip[2] + 2 for r in rows for c in ("x1", "x2")) and \
        all(clip[1] - 2 <= float(r[c]) / dbu <= clip[3] + 2 for r in rows for c in ("y1", "y2"))
    expect(within, "%s: voronoi.csv's pieces lie in the clip box %s" % (row, clip))
    ly, top = layout_of(path_oas, cell)
    n_cut = 0
    for k, kind in enumerate(KINDS):
        want = []
        for r in rows:
            if r["kind"] != kind:
                continue
            seg = tuple(float(r[c]) / dbu for c in ("x1", "y1", "x2", "y2"))
            c = cut(seg, box)
            if c != seg:
                n_cut += 1
            if c is None:
                continue
            g = tuple(int(round(v)) for v in c)
            if g[:2] != g[2:]:
                want.append(g)
        got = paths_on(ly, top, layer, 200 + k)
        outside = [p for p in got if not (box[0] <= min(p[0], p[2]) and max(p[0], p[2]) <= box[2] and
                                         box[1] <= min(p[1], p[3]) and max(p[1], p[3]) <= box[3])]
        expect(not outside, "%s: every %s path lies in the drawn box %s (%d outside, e.g. %s)"
               % (row, kind, box, len(outside), outside[:1]))
        lost, extra = matched(want, got)
        expect(not lost and not extra and s["drawn"][kind] == len(got),
               "%s: %s pieces drawn as voronoi.csv's cut to the drawn box (%d drawn, %d expected, %d missing, "
               "%d extra, summary %d; e.g. %s %s)" % (row, kind, len(got), len(want), len(lost), len(extra),
                                                     s["drawn"][kind], lost[:2], extra[:2]))
    return n_cut, far


def write(ly, name):
    path = os.path.join(work, name)
    ly.write(path)
    return path


def new_layout():
    ly = pya.Layout()
    ly.dbu = 0.001
    return ly, ly.create_cell("TOP")


# ---- rows -----------------------------------------------------------------------------------

def range_rows():
    # Near +-1.0737e9, inside the range: the rays reach 3 x 2^31 and are cut where drawn.
    ly, top = new_layout()
    l1 = ly.layer(1, 0)
    boxes = [(1073741000, 1073741000, 1073741800, 1073741800), (-1073741800, -1073741800, -1073741000, -1073741000),
             (0, 0, 1000, 300)]
    for b in boxes:
        top.shapes(l1).insert(pya.Box(*b))
    top.shapes(ly.layer(100, 0)).insert(pya.Box(0, 0, 1000, 300))
    path = write(ly, "near_limit.oas")
    row = "two boxes near +-1.0737e9 and an ordinary one, voronoi"
    out = os.path.join(work, "near_v")
    code, text = run("voronoi", path, "1/0", out)
    if succeeded(row, code, text, out, ["voronoi.csv", "voronoi.oas", "summary.json"]):
        checked(row, summary(out))
        n_cut, far = diagram_drawn_as_csv(row, out, os.path.join(out, "voronoi.oas"), 1, boxes)
        expect(n_cut > 0 and far > DRAW, "%s: voronoi.csv keeps pieces beyond 32 bits (%d cut where drawn, "
               "farthest coordinate %.4g DBU)" % (row, n_cut, far))
        same_layer(row, os.path.join(out, "voronoi.oas"), ly, top, 1, 0)
    row = "two boxes near +-1.0737e9 and an ordinary one, flow with every file"
    out = os.path.join(work, "near_f")
    code, text = run("flow", path, "1/0", out, "markers=100/0", "diagram=1", "all_gauges=1", "pitch=1")
    if succeeded(row, code, text, out, ["voronoi.csv", "voronoi.oas", "gauges.csv", "gauges.oas", "windows.csv",
                                       "calibration.oas", "summary.json"]):
        s = summary(out)
        checked(row, s["voronoi"])
        diagram_drawn_as_csv(row, out, os.path.join(out, "voronoi.oas"), 1, boxes)
        g = csv_rows(os.path.join(out, "gauges.csv"))
        widths = sorted(float(r["cd"]) for r in g if r["type"] == "internal")
        expect(len(g) == s["gauges"]["gauges"] and widths[:1] == [0.3] and 0.8 in widths,
               "%s: gauges.csv: the ordinary box's width 0.3 um and the far boxes' 0.8 um (%s)" % (row, widths))
        glines = paths_on(*layout_of(os.path.join(out, "gauges.oas")), 1, 210)
        expect(len(glines) == len(g), "%s: gauges.oas has a line a gauge (%d, %d)" % (row, len(glines), len(g)))
    row = "two boxes near +-1.0737e9 and an ordinary one, default flow"
    out = os.path.join(work, "near_fd")
    code, text = run("flow", path, "1/0", out, "markers=100/0", "pitch=1")  # spaces too wide to make a pitch
    succeeded(row, code, text, out, ["windows.csv", "calibration.oas", "flow.lyrdb", "summary.json"])
    row = "two boxes near +-1.0737e9 and an ordinary one, farthest"
    out = os.path.join(work, "near_far")
    code, text = run("farthest", path, "1/0", out)
    if succeeded(row, code, text, out, ["farthest.csv", "farthest.oas", "summary.json"]):
        farthest_drawn_as_csv(row, out, boxes)

    # At +-(2^30 - 1), the largest coordinates allowed.
    ly, top = new_layout()
    l1 = ly.layer(1, 0)
    m = LIMIT - 1
    boxes = [(m - 500, m - 500, m, m), (-m, -m, -m + 500, -m + 500), (-m, m - 400, -m + 400, m),
             (m - 300, -m, m, -m + 300), (-200, -100, 200, 100)]
    for b in boxes:
        top.shapes(l1).insert(pya.Box(*b))
    path = write(ly, "at_limit.oas")
    for cmd in ("voronoi", "flow"):
        row = "coordinates at +-(2^30 - 1), " + cmd
        out = os.path.join(work, "at_" + cmd)
        code, text = run(cmd, path, "1/0", out, *(["markers=1/0", "diagram=1", "pitch=1"] if cmd == "flow" else []))
        if succeeded(row, code, text, out, ["voronoi.csv", "voronoi.oas", "summary.json"]):
            s = summary(out)
            checked(row, s.get("voronoi", s))
            expect(s.get("voronoi", s)["polygons"] == 5, "%s: 5 polygons (%s)" % (row, s.get("voronoi", s)["polygons"]))
            n_cut, far = diagram_drawn_as_csv(row, out, os.path.join(out, "voronoi.oas"), 1, boxes)
            expect(n_cut > 0, "%s: pieces beyond 32 bits cut where drawn (%d)" % (row, n_cut))
            same_layer(row, os.path.join(out, "voronoi.oas"), ly, top, 1, 0)

    # At +-2^30 exactly: outside the range, refused.
    for name, b in (("+2^30", (LIMIT - 1000, 0, LIMIT, 1000)), ("-2^30", (0, -LIMIT, 1000, -LIMIT + 1000))):
        ly, top = new_layout()
        top.shapes(ly.layer(1, 0)).insert(pya.Box(*b))
        top.shapes(ly.layer(1, 0)).insert(pya.Box(0, 0, 100, 100))
        path = write(ly, "beyond_%s.oas" % name[0].replace("+", "p").replace("-", "m"))
        for cmd in ("voronoi", "flow", "farthest"):
            out = os.path.join(work, "beyond_%s_%s" % (name[0], cmd))
            code, text = run(cmd, path, "1/0", out, *(["markers=1/0"] if cmd == "flow" else []))
            refused("a coordinate at %s, %s" % (name, cmd), code, text, out, ["2^30"])

    # The whole range: shapes near the four corners and spread in between, with a few
    # ordinary wires in the middle. (A row of aligned wires seen from the corners of the range
    # is the builder's slow case, README Limits: minutes; not part of this row.)
    import random
    rnd = random.Random(35)
    ly, top = new_layout()
    l1 = ly.layer(1, 0)
    m = LIMIT - 1
    boxes = [(-m, -m, -m + 700, -m + 300), (m - 700, m - 300, m, m), (-m, m - 500, -m + 500, m), (m - 500, -m, m, -m + 500)]
    for _ in range(60):
        x, y = rnd.randrange(-m, m - 5000), rnd.randrange(-m, m - 5000)
        boxes.append((x, y, x + rnd.randrange(50, 5000), y + rnd.randrange(50, 5000)))
    boxes += [(0, 0, 100, 4000), (300, 500, 3300, 700), (200, 1000, 260, 1600)]
    for b in boxes:
        top.shapes(l1).insert(pya.Box(*b))
    top.shapes(ly.layer(100, 0)).insert(pya.Box(500, 1000, 1500, 2000))
    path = write(ly, "whole_range.oas")
    merged = pya.Region(top.begin_shapes_rec(l1)).merged().count()
    row = "a layer spanning the whole range, voronoi"
    out = os.path.join(work, "whole_v")
    code, text = run("voronoi", path, "1/0", out)
    if succeeded(row, code, text, out, ["voronoi.csv", "voronoi.oas", "summary.json"]):
        s = summary(out)
        checked(row, s)
        expect(s["polygons"] == merged, "%s: %d polygons, as KLayout merges them (%d)" % (row, s["polygons"], merged))
        n_cut, far = diagram_drawn_as_csv(row, out, os.path.join(out, "voronoi.oas"), 1, boxes)
        expect(n_cut > 0 and far > DRAW, "%s: pieces beyond 32 bits kept in voronoi.csv, cut where drawn (%d)"
               % (row, n_cut))
    row = "a layer spanning the whole range, flow"
    out = os.path.join(work, "whole_f")
    code, text = run("flow", path, "1/0", out, "markers=100/0", "all_gauges=1")
    if succeeded(row, code, text, out, ["gauges.csv", "gauges.oas", "windows.csv", "calibration.oas", "summary.json"]):
        s = summary(out)
        checked(row, s["voronoi"])
        w = csv_rows(os.path.join(out, "windows.csv"))
        covered = sum(int(r["markers_covered"]) for r in w)
        expect(s["select"]["markers"] == 1 and covered == 1, "%s: the marker is covered (%s)" % (row, s["select"]))
    row = "a layer spanning the whole range, farthest"
    out = os.path.join(work, "whole_far")
    code, text = run("farthest", path, "1/0", out)
    if succeeded(row, code, text, out, ["farthest.csv", "farthest.oas", "summary.json"]):
        farthest_drawn_as_csv(row, out, boxes)


def farthest_drawn_as_csv(row, outdir, boxes, dbu=0.001):
    """farthest.oas's L/240 against farthest.csv: each edge and ray cut to the drawn box,
    rounded to the grid, and nothing else (no coordinate wrapped around 32 bits)."""
    rows = csv_rows(os.path.join(outdir, "farthest.csv"))
    box = drawn_box(clip_box_of(boxes))
    want = []
    for r in rows:
        c = cut(tuple(float(r[k]) / dbu for k in ("x1", "y1", "x2", "y2")), box)
        if c is not None:
            g = tuple(int(round(v)) for v in c)
            if g[:2] != g[2:]:
                want.append(g)
    ly, top = layout_of(os.path.join(outdir, "farthest.oas"))
    got = paths_on(ly, top, 1, 240)
    lost, extra = matched(want, got)
    expect(not lost and not extra, "%s: farthest.oas draws farthest.csv's edges cut to the drawn box %s "
           "(%d drawn, %d expected, %d missing, %d extra)" % (row, box, len(got), len(want), len(lost), len(extra)))


def gauges_of(outdir):
    return csv_rows(os.path.join(outdir, "gauges.csv"))


def same_file(a, b):
    with open(a, "rb") as f, open(b, "rb") as g:
        return f.read() == g.read()


def shape_rows():
    ly, top = new_layout()
    L = {n: ly.layer(n, 0) for n in range(1, 10)}
    P = lambda pts: pya.Polygon([pya.Point(*p) for p in pts], True)  # noqa: E731  raw: as drawn

    # 1/0 any-angle edges that nearly meet: a vertex 1 DBU below a 1:100 edge, and two parallel
    # 1:100 edges 1 DBU apart.
    for pts in ([(0, 0), (100000, 1000), (100000, 5000), (0, 5000)], [(40000, -5000), (60000, -5000), (50000, 499)],
                [(200000, 0), (300000, 1000), (300000, 3000), (200000, 3000)],
                [(200000, -1), (300000, 999), (300000, -3000), (200000, -3000)]):
        top.shapes(L[1]).insert(P(pts))
    # 2/0 self-intersections: a figure-8 touching itself at a vertex, a ring that crosses itself
    # and overlaps its own loop; 10/0 a bow-tie (its lobes wound opposite ways) beside a box.
    top.shapes(ly.layer(10, 0)).insert(P([(0, 0), (1000, 1000), (1000, 0), (0, 1000)]))
    top.shapes(ly.layer(10, 0)).insert(pya.Box(2000, 0, 3000, 400))
    for pts in ([(2000, 0), (3000, 0), (3000, 1000), (4000, 1000), (4000, 2000), (3000, 2000), (3000, 1000), (2000, 1000)],
                [(5000, 0), (8000, 0), (8000, 1000), (6000, 1000), (6000, -1000), (7000, -1000), (7000, 500), (5000, 500)]):
        top.shapes(L[2]).insert(P(pts))
    # 3/0 holes touching their ring (at a vertex, along an edge) and each other (an edge, a vertex).
    frame = P([(0, 0), (10000, 0), (10000, 10000), (0, 10000)])
    for h in ([(3000, 0), (5000, 2000), (3000, 4000), (1000, 2000)],
              [(6000, 1000), (10000, 1000), (10000, 2000), (6000, 2000)],
              [(6000, 6000), (7000, 6000), (7000, 7000), (6000, 7000)], [(7000, 6000), (8000, 6000), (8000, 7000), (7000, 7000)],
              [(2000, 6000), (3000, 6000), (3000, 7000), (2000, 7000)], [(3000, 7000), (4000, 7000), (4000, 8000), (3000, 8000)]):
        frame.insert_hole([pya.Point(*p) for p in h], True)
    top.shapes(L[3]).insert(frame)
    # 4/0 duplicates and nested shapes; 5/0 the same layer drawn once.
    for b in ((0, 0, 1000, 300), (0, 0, 1000, 300), (0, 600, 3000, 2000), (500, 800, 1500, 1200), (0, 600, 3000, 2000)):
        top.shapes(L[4]).insert(pya.Box(*b))
    for b in ((0, 0, 1000, 300), (0, 600, 3000, 2000)):
        top.shapes(L[5]).insert(pya.Box(*b))
    # 6/0 a 1-DBU sliver, a 1-DBU gap, with zero-area shapes and zero-width paths among them;
    # 7/0 the same without those.
    for layer in (6, 7):
        for b in ((0, 0, 10000, 1), (0, 10, 5000, 1000), (5001, 10, 9000, 1000)):
            top.shapes(L[layer]).insert(pya.Box(*b))
    top.shapes(L[6]).insert(pya.Box(2000, 3000, 2000, 3500))
    top.shapes(L[6]).insert(P([(3000, 3000), (3500, 3500), (4000, 4000)]))
    top.shapes(L[6]).insert(pya.Path([pya.Point(0, 5000), pya.Point(9000, 5000), pya.Point(9000, 9000)], 0))
    # 8/0 only zero-area shapes and zero-width paths; 9/0 texts only.
    top.shapes(L[8]).insert(pya.Box(0, 0, 0, 500))
    top.shapes(L[8]).insert(pya.Path([pya.Point(0, 0), pya.Point(900, 0)], 0))
    top.shapes(L[9]).insert(pya.Text("ONLY", pya.Trans(pya.Point(0, 0))))
    top.shapes(L[9]).insert(pya.Text("TEXTS", pya.Trans(pya.Point(100, 100))))
    path = write(ly, "shapes.oas")

    def both(row, layer, tag):
        """voronoi and gauges on the layer: both exit 0, checked; returns (voronoi out, gauges out)."""
        outs = []
        for cmd in ("voronoi", "gauges"):
            out = os.path.join(work, "%s_%s" % (tag, cmd))
            code, text = run(cmd, path, layer, out)
            files = ["voronoi.csv", "voronoi.oas"] if cmd == "voronoi" else ["gauges.csv", "gauges.oas"]
            if succeeded("%s, %s" % (row, cmd), code, text, out, files + ["summary.json"]):
                checked("%s, %s" % (row, cmd), summary(out))
                outs.append(out)
            else:
                outs.append(None)
        return outs

    row = "any-angle edges 1 DBU apart at a 1:100 slope"
    v, g = both(row, "1/0", "near")
    if v:
        expect(summary(v)["polygons"] == 4, "%s: 4 polygons, none merged (%s)" % (row, summary(v)["polygons"]))
        same_layer(row, os.path.join(v, "voronoi.oas"), ly, top, 1, 0)
    if g:
        spaces = sorted(float(r["cd"]) for r in gauges_of(g) if r["type"] == "external")
        expect(spaces and 0 < spaces[0] <= 0.001, "%s: the narrowest space gauged is at most 1 DBU (%s)" % (row, spaces[:3]))

    row = "self-intersections (figure-8, a ring over its own loop)"
    v, g = both(row, "2/0", "self")
    if v:
        expect(summary(v)["counts"]["internal"] > 0, "%s: widths found (%s)" % (row, summary(v)["counts"]))
        same_layer(row, os.path.join(v, "voronoi.oas"), ly, top, 2, 0)
    # The bow-tie: both lobes reach the core (KLayout's hierarchical merge would drop them).
    row = "a bow-tie beside a box"
    v, g = both(row, "10/0", "bowtie")
    if v:
        # KLayout's flat merge gives the bow-tie as one polygon touching itself where its edges
        # cross; the core's merge parts it there: two lobes and the box (the box alone before).
        expect(summary(v)["polygons"] == 3, "%s: the bow-tie's two lobes and the box (%d polygons)"
               % (row, summary(v)["polygons"]))
        same_layer(row, os.path.join(v, "voronoi.oas"), ly, top, 10, 0)

    row = "holes touching their ring and each other"
    v, g = both(row, "3/0", "holes")
    if v:
        s = summary(v)
        merged = pya.Region(top.begin_shapes_rec(L[3])).merged(True, 0)
        expect(s["polygons"] == merged.count(), "%s: %d polygons, as KLayout merges the layer (%d)"
               % (row, s["polygons"], merged.count()))
        same_layer(row, os.path.join(v, "voronoi.oas"), ly, top, 3, 0)

    row = "duplicate and nested shapes"
    v4, g4 = both(row, "4/0", "dup")
    v5, g5 = both(row + " (drawn once)", "5/0", "once")
    if v4 and v5:
        expect(summary(v4)["polygons"] == 2, "%s: 2 polygons after merging (%s)" % (row, summary(v4)["polygons"]))
        expect(same_file(os.path.join(v4, "voronoi.csv"), os.path.join(v5, "voronoi.csv")),
               "%s: voronoi.csv identical to the layer drawn once" % row)
    if g4 and g5:
        expect(same_file(os.path.join(g4, "gauges.csv"), os.path.join(g5, "gauges.csv")),
               "%s: gauges.csv identical to the layer drawn once" % row)

    row = "1-DBU sliver and gap, with zero-area shapes and zero-width paths"
    v6, g6 = both(row, "6/0", "sliver")
    v7, g7 = both(row + " (without the zero-area shapes)", "7/0", "plain")
    if v6 and v7:
        expect(same_file(os.path.join(v6, "voronoi.csv"), os.path.join(v7, "voronoi.csv")),
               "%s: zero-area shapes and zero-width paths are ignored (voronoi.csv identical)" % row)
    if g6:
        cds = {(r["type"], r["cd"]) for r in gauges_of(g6)}
        expect(("internal", "0.001000") in cds and ("external", "0.001000") in cds,
               "%s: the sliver's width and the gap gauged at 0.001 um (%s)" % (row, sorted(cds)[:6]))

    for layer, what in (("8/0", "only zero-area shapes and zero-width paths"), ("9/0", "texts only")):
        for cmd in ("voronoi", "flow"):
            out = os.path.join(work, "empty_%s_%s" % (layer[0], cmd))
            code, text = run(cmd, path, layer, out, *(["markers=1/0"] if cmd == "flow" else []))
            refused("a layer of %s, %s" % (what, cmd), code, text, out, ["layer %s" % layer, "empty"])


def hierarchy_rows():
    # Eight levels, each an array of the one below (2 x 1, along x then y, alternately), a
    # rotated and a mirrored instance among them; the leaf holds a box and a 45-degree shape.
    ly = pya.Layout()
    ly.dbu = 0.001
    l1 = ly.layer(1, 0)
    leaf = ly.create_cell("L0")
    leaf.shapes(l1).insert(pya.Box(0, 0, 100, 300))
    leaf.shapes(l1).insert(pya.Polygon([pya.Point(200, 0), pya.Point(300, 0), pya.Point(400, 100), pya.Point(300, 100)]))
    child, w, h = leaf, 500, 400
    for k in range(1, 9):
        c = ly.create_cell("L%d" % k)
        a, b = (pya.Vector(w, 0), pya.Vector(0, 0)) if k % 2 else (pya.Vector(0, 0), pya.Vector(0, h))
        na, nb = (2, 1) if k % 2 else (1, 2)
        c.insert(pya.CellInstArray(child.cell_index(), pya.Trans(), a, b, na, nb))
        if k == 3:  # a rotated copy beside the array
            c.insert(pya.CellInstArray(child.cell_index(), pya.Trans(pya.Trans.R90, 4 * w + 1000, 0)))
        if k == 6:  # and a mirrored one
            c.insert(pya.CellInstArray(child.cell_index(), pya.Trans(pya.Trans.M0, 0, -1000)))
        w, h = (w * 2 + 2000, h) if k % 2 else (w, h * 2 + 2000)
        child = c
    top = child
    path = write(ly, "deep.oas")
    for cell in ("L8", "L4"):
        row = "8 levels of arrays, cell %s" % cell
        out = os.path.join(work, "deep_" + cell)
        code, text = run("voronoi", path, "1/0", out, *(["cell=" + cell] if cell != "L8" else []))
        if succeeded(row, code, text, out, ["voronoi.csv", "voronoi.oas", "summary.json"]):
            s = summary(out)
            checked(row, s)
            c = ly.cell(cell)
            # Shapes touching only at a corner stay apart (KLayout's min_coherence)
            flat = pya.Region(c.begin_shapes_rec(l1)).merged(True, 0)
            expect(s["polygons"] == flat.count() and s["cell"] == cell,
                   "%s: %d polygons, KLayout's flattened and merged layer has %d" % (row, s["polygons"], flat.count()))
            same_layer(row, os.path.join(out, "voronoi.oas"), ly, c, 1, 0, cell)
    row = "8 levels of arrays, flow"
    out = os.path.join(work, "deep_flow")
    code, text = run("flow", path, "1/0", out, "markers=1/0")
    if succeeded(row, code, text, out, ["windows.csv", "calibration.oas", "summary.json"]):
        checked(row, summary(out)["voronoi"])
    del top

    # An empty top cell, alone; several top cells.
    ly = pya.Layout()
    ly.dbu = 0.001
    ly.create_cell("EMPTY")
    ly.layer(1, 0)
    alone = write(ly, "empty_top.oas")
    full = ly.create_cell("FULL")
    full.shapes(ly.layer(1, 0)).insert(pya.Box(0, 0, 1000, 300))
    full.shapes(ly.layer(1, 0)).insert(pya.Box(0, 500, 1000, 800))
    several = write(ly, "two_tops.oas")
    for cmd in ("voronoi", "flow"):
        extra = ["markers=1/0"] if cmd == "flow" else []
        out = os.path.join(work, "empty_top_" + cmd)
        code, text = run(cmd, alone, "1/0", out, *extra)
        refused("an empty top cell, %s" % cmd, code, text, out, ["1/0"])
        out = os.path.join(work, "two_tops_" + cmd)
        code, text = run(cmd, several, "1/0", out, *extra)
        refused("two top cells without cell=, %s" % cmd, code, text, out, ["2 top cells", "cell=NAME"])
        out = os.path.join(work, "two_tops_empty_" + cmd)
        code, text = run(cmd, several, "1/0", out, "cell=EMPTY", *extra)
        refused("two top cells, cell=EMPTY, %s" % cmd, code, text, out, ["empty", "EMPTY"])
        out = os.path.join(work, "two_tops_nope_" + cmd)
        code, text = run(cmd, several, "1/0", out, "cell=NOPE", *extra)
        refused("two top cells, cell=NOPE, %s" % cmd, code, text, out, ["no cell named", "NOPE"])
        out = os.path.join(work, "two_tops_full_" + cmd)
        code, text = run(cmd, several, "1/0", out, "cell=FULL", *extra)
        if succeeded("two top cells, cell=FULL, %s" % cmd, code, text, out, ["summary.json"]):
            s = summary(out)
            s = s.get("voronoi", s)
            expect(s["polygons"] == 2 and s["cell"] == "FULL", "two top cells, cell=FULL, %s: the 2 polygons of FULL (%s, %s)"
                   % (cmd, s["polygons"], s["cell"]))


def tree(branches, teeth):
    """A Manhattan polygon of about branches x (4 teeth + 4) vertices: a spine with branches to
    its right, each with a row of teeth (10 DBU wide, 10 apart, 40 tall)."""
    out = [(0, 0), (20, 0)]
    for b in range(branches):
        y = 200 * b + 50
        out += [(20, y), (30 + 20 * teeth, y), (30 + 20 * teeth, y + 20)]
        for t in range(teeth - 1, -1, -1):
            tx = 30 + 20 * t
            out += [(tx + 10, y + 20), (tx + 10, y + 60), (tx, y + 60), (tx, y + 20)]
        out.append((20, y + 20))
    return out + [(20, 200 * branches + 50), (0, 200 * branches + 50)]


def huge_polygon_rows():
    # One polygon of many vertices (-rd vertices=N, about; ctest gives 10^5: 10^6 takes minutes,
    # docs/testing.md). Spread in two dimensions: a long row of steps is the builder's slow case.
    want = int(arg("vertices", "1000000"))
    teeth = max(1, int(math.sqrt(want / 4.0)))
    branches = max(1, want // (4 * teeth + 4))
    ring = tree(branches, teeth)
    ly, top = new_layout()
    top.shapes(ly.layer(1, 0)).insert(pya.Polygon([pya.Point(*p) for p in ring], True))
    path = write(ly, "huge.oas")
    row = "a polygon of %d vertices" % len(ring)
    out = os.path.join(work, "huge")
    t0 = time.time()
    code, text = run("voronoi", path, "1/0", out)
    seconds = time.time() - t0
    if succeeded(row, code, text, out, ["voronoi.csv", "voronoi.oas", "summary.json"]):
        s = summary(out)
        checked(row, s)
        expect(s["polygons"] == 1 and s["sites"] == 2 * len(ring), "%s: 1 polygon, %d sites (%s, %s)"
               % (row, 2 * len(ring), s["polygons"], s["sites"]))
        rl, rt = layout_of(os.path.join(out, "voronoi.oas"))
        pts = [sh.polygon.num_points() for sh in rt.shapes(rl.find_layer(1, 0)).each()]
        expect(pts == [len(ring)], "%s: voronoi.oas holds it whole (%s points)" % (row, pts))
        internal = sum(1 for r in csv_rows(os.path.join(out, "voronoi.csv")) if r["kind"] == "internal")
        expect(internal >= branches * teeth, "%s: a medial axis in every tooth (%d internal pieces, %d teeth)"
               % (row, internal, branches * teeth))
    print("      the polygon of %d vertices: %.1f s" % (len(ring), seconds))


if group == "range":
    range_rows()
elif group == "shapes":
    shape_rows()
elif group == "hierarchy":
    hierarchy_rows()
elif group == "huge_polygon":
    huge_polygon_rows()
else:
    print("unknown -rd group=%s" % group)
    sys.exit(2)
finish(group)
