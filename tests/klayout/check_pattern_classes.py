# Pattern classes of the selection's windows (cmd=select), checked against KLayout's own
# booleans: each window's clip matches its class's representative under one of the square's 8
# symmetries (XOR area at most class_area of the window), no two representatives match, the
# tables agree with each other; the switches' errors and off.
#   klayout -b -r tests/klayout/check_pattern_classes.py -rd input=FILE -rd layer=L/D -rd markers=SPEC
#           -rd work=DIR [-rd class_area=0.05]
import csv
import os
import shutil
import subprocess
import sys

import pya

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from harness import BATCH, arg, expect, finish, repo  # noqa: E402

inp, layer, markers, work = arg("input"), arg("layer"), arg("markers"), arg("work")
fraction = float(arg("class_area", "0.05"))
shutil.rmtree(work, ignore_errors=True)


def run(out, *extra):
    cmd = BATCH + ["-rd", "cmd=select", "-rd", "input=" + inp,
           "-rd", "layer=" + layer, "-rd", "markers=" + markers, "-rd", "out=" + out, "-rd", "quiet=1"]
    for e in extra:
        cmd += ["-rd", e]
    return subprocess.run(cmd, capture_output=True, text=True)


r = run(os.path.join(work, "area"), "class_area=%r" % fraction)
expect(r.returncode == 0, "select runs (%s)" % r.stderr.strip()[-300:])
if r.returncode != 0:
    finish()


def table(name):
    with open(os.path.join(work, "area", name), newline="") as f:
        rows = list(csv.reader(f))
    return rows[0], rows[1:]


wh, windows = table("windows.csv")
ch, classes = table("pattern_classes.csv")
expect(wh[-1] == "pattern_class", "windows.csv ends with pattern_class")
expect(ch == "class,windows,markers_covered,representative,x1,y1,x2,y2,gauge_id,type,score".split(","),
       "pattern_classes.csv header")
of = [int(w[-1]) for w in windows]
expect(sorted(set(of)) == list(range(1, len(classes) + 1)), "classes are numbered 1..%d and each is used" % len(classes))
for c in classes:
    k = int(c[0])
    mine = [w for w in windows if int(w[-1]) == k]
    expect(int(c[1]) == len(mine), "class %d: %s windows, counted %d" % (k, c[1], len(mine)))
    expect(int(c[2]) == sum(int(w[8]) for w in mine), "class %d: markers covered add up" % k)
    expect(mine and int(c[3]) == int(mine[0][0]) and c[4:8] == mine[0][1:5],
           "class %d: its representative is its first window, with that window's box" % k)
expect(0 < len(classes) <= len(windows), "%d windows form %d classes" % (len(windows), len(classes)))

# The oracle: KLayout's booleans, clips in doubled coordinates about the window's centre.
ly = pya.Layout()
ly.read(inp)
dbu = ly.dbu
top = ly.top_cell()
L, D = (int(v) for v in layer.split("/"))
region = pya.Region(top.begin_shapes_rec(ly.layer(L, D)))
region.merge()
doubled = region.transformed(pya.ICplxTrans(2.0))


def square(w):
    """A window of windows.csv as the core compares it: the side rounded to the DBU, about the
    centre rounded to the DBU grid; (x1, y1, side) in DBU."""
    x1, y1, x2, y2 = (float(v) / dbu for v in w[1:5])
    side = max(1, int(round(x2 - x1)))
    return int(round((x1 + x2) / 2 - side / 2)), int(round((y1 + y2) / 2 - side / 2)), side


clips = {}


def clip(i):
    if i not in clips:
        x, y, s = square(windows[i])
        c = doubled & pya.Region(pya.Box(2 * x, 2 * y, 2 * (x + s), 2 * (y + s)))
        clips[i] = (c.moved(-(2 * x + s), -(2 * y + s)), s)
    return clips[i]


SYMMETRIES = [pya.Trans(r, m, 0, 0) for m in (False, True) for r in range(4)]


def match(i, j):
    (a, s), (b, t) = clip(i), clip(j)
    if s != t:
        return False
    limit = fraction * (2 * s) ** 2 * (1 + 1e-12)
    return any((a ^ b.transformed(tr)).area() <= limit for tr in SYMMETRIES)


reps = [int(c[3]) - 1 for c in classes]
bad = [i for i in range(len(windows)) if not match(i, reps[of[i] - 1])]
expect(not bad, "every window matches its class's representative (%d do not: %s)" % (len(bad), bad[:5]))
pairs = [(a, b) for x, a in enumerate(reps) for b in reps[x + 1:] if match(b, a)]
expect(not pairs, "no two representatives match (%d pairs do: %s)" % (len(pairs), pairs[:5]))

# The switches.
for extra, message in (("pattern_classes=bogus", "pattern_classes must be area, edge or off"),
                       ("class_area=1.5", "class_area must be a fraction"),
                       ("class_edge=-1", "class_edge must not be negative")):
    e = run(os.path.join(work, "bad"), extra)
    expect(e.returncode == 2 and ("linf_opc: error: " + message) in e.stderr and "Traceback" not in e.stderr,
           "%s: exit 2 and one line (%d, %s)" % (extra, e.returncode, e.stderr.strip()[-200:]))
    bad_dir = os.path.join(work, "bad")
    expect(not os.path.isdir(bad_dir) or not [f for f in os.listdir(bad_dir) if not f.startswith(".")],
           "%s: nothing written" % extra)
o = run(os.path.join(work, "off"), "pattern_classes=off")
expect(o.returncode == 0 and not os.path.exists(os.path.join(work, "off", "pattern_classes.csv")),
       "pattern_classes=off: no pattern_classes.csv")
if o.returncode == 0:
    with open(os.path.join(work, "off", "windows.csv")) as f:
        expect(next(csv.reader(f))[-1] == "markers_covered", "pattern_classes=off: windows.csv without the column")
finish("%d windows in %d classes, class_area %g" % (len(windows), len(classes), fraction))
