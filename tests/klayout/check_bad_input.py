# Bad input through the batch macro: a clear error (exit 2, one line) or a documented handling,
# never a crash or a traceback, never a partial output.
#   klayout -b -r tests/klayout/check_bad_input.py -rd work=DIR
import csv
import json
import os
import subprocess
import sys

import pya

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import harness  # noqa: E402
from harness import BATCH, arg, expect, finish, repo  # noqa: E402

harness.report_ok = True  # the list of inputs and what each gives, read as a whole
work = arg("work", "/tmp/linf_bad_input")
os.makedirs(work, exist_ok=True)


def run(*args):
    args = list(args) + (["cell=TOP"] if any(a.endswith("awkward.oas") for a in args) else [])
    r = subprocess.run(BATCH +
                       [x for a in args for x in ("-rd", a)], capture_output=True, text=True)
    return r.returncode, (r.stdout + r.stderr).strip()


# A layout with every awkward shape on 1/0, a far-out box on 2/0, an empty layer 3/0.
ly = pya.Layout()
ly.dbu = 0.001
top = ly.create_cell("TOP")
l1, l2, l3 = (ly.layer(i, 0) for i in (1, 2, 3))
s = top.shapes(l1)
s.insert(pya.Polygon([pya.Point(0, 0), pya.Point(1000, 1000), pya.Point(1000, 0), pya.Point(0, 1000)], True))  # bow-tie
s.insert(pya.Box(2000, 0, 2000, 500))                                              # zero area
s.insert(pya.Polygon([pya.Point(3000, 0), pya.Point(3000, 0), pya.Point(3400, 0), pya.Point(3400, 300),
                      pya.Point(3400, 300), pya.Point(3000, 300)], True))          # repeated points
s.insert(pya.Path([pya.Point(0, 2000), pya.Point(3000, 2000), pya.Point(3000, 2600)], 120))  # a path
s.insert(pya.Box(4000, 0, 4300, 900))                                              # a box
s.insert(pya.Text("NOT A SHAPE", pya.Trans(pya.Point(500, 500))))                  # a text
top.shapes(l2).insert(pya.Box(2 ** 31 - 2000, 0, 2 ** 31 - 1000, 1000))
top.shapes(l2).insert(pya.Box(0, 0, 1000, 1000))
other = ly.create_cell("OTHER")  # 3/0 exists in the file, but not in TOP: empty there
other.shapes(l3).insert(pya.Box(0, 0, 100, 100))
layout_path = os.path.join(work, "awkward.oas")
ly.write(layout_path)

code, out = run("cmd=voronoi", "input=" + layout_path, "layer=1/0", "out=" + os.path.join(work, "v"))
expect(code == 0 and "checked" in out, "self-intersecting, zero-area, repeated points, path, box, text: "
       "merged by KLayout, the text ignored, diagram checked (%s)" % out.splitlines()[-1][:80])
code, out = run("cmd=flow", "input=" + layout_path, "layer=1/0", "markers=1/0", "out=" + os.path.join(work, "f"))
expect(code == 0, "the whole flow on the awkward layer")
code, out = run("cmd=voronoi", "input=" + layout_path, "layer=2/0", "out=" + os.path.join(work, "far"))
expect(code == 2 and "linf_opc: error:" in out and "2^30" in out and "Traceback" not in out,
       "coordinates near 2^31: a clear error (%s)" % out[-90:])
expect(not [f for f in os.listdir(os.path.join(work, "far")) if not f.startswith(".")] if os.path.isdir(
    os.path.join(work, "far")) else True, "... and no partial output")
code, out = run("cmd=gauges", "input=" + layout_path, "layer=3/0", "out=" + os.path.join(work, "e"))
expect(code == 2 and "is empty" in out, "an empty layer: a clear error")
code, out = run("cmd=gauges", "input=" + layout_path, "layer=9/9", "out=" + os.path.join(work, "u"))
expect(code == 2 and "is not in" in out, "an unknown layer: a clear error")
code, out = run("cmd=gauges", "input=" + layout_path, "layer=one", "out=" + os.path.join(work, "u"))
expect(code == 2 and "L/D" in out, "a layer that is not L/D: a clear error")

garbage = os.path.join(work, "garbage.oas")
with open(garbage, "wb") as f:
    f.write(b"this is not a layout\x00\x01\x02")
code, out = run("cmd=voronoi", "input=" + garbage, "layer=1/0", "out=" + os.path.join(work, "g"))
expect(code == 2 and "cannot read" in out and "Traceback" not in out, "unreadable input: a clear error")
code, out = run("cmd=voronoi", "input=" + os.path.join(work, "missing.oas"), "layer=1/0", "out=" + work)
expect(code == 2 and "not found" in out, "a missing input: a clear error")
code, out = run("cmd=voronoi", "input=" + layout_path, "layer=1/0", "out=" + os.path.join(layout_path, "sub"))
expect(code == 2 and "cannot create the output folder" in out, "an output folder that cannot be written")

markers = os.path.join(work, "markers.csv")
with open(markers, "w") as f:
    f.write("x,y\n500,500\nnot,a number\n1500\n4100,400\n")
code, out = run("cmd=select", "input=" + layout_path, "layer=1/0", "markers=" + markers, "halves=0",
                "out=" + os.path.join(work, "m"))
stats = json.load(open(os.path.join(work, "m", "stats.json"))) if code == 0 else {}
expect(code == 0 and stats.get("marker_source", {}).get("skipped_rows") == 2 and stats.get("markers") == 2,
       "malformed marker rows are skipped and counted")
with open(markers, "w") as f:
    f.write("x,y\nnot,numbers\n")
code, out = run("cmd=select", "input=" + layout_path, "layer=1/0", "markers=" + markers, "out=" + os.path.join(work, "m2"))
expect(code == 2 and "no usable row" in out, "a marker file without a usable row: a clear error")
with open(markers, "w") as f:
    f.write("a,b\n1,2\n")
code, out = run("cmd=select", "input=" + layout_path, "layer=1/0", "markers=" + markers, "out=" + os.path.join(work, "m3"))
expect(code == 2 and "columns x,y" in out, "a marker file without x,y columns: a clear error")

finish()
