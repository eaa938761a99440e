# The GLP reader (plugin/python/linf_opc/glp.py): exact shapes, layers and units of a file
# written here; every malformed statement an error naming its line, through the batch as a
# usage error; and the ten ICCAD 2013 clips of ../shared/data read with one shape per RECT or
# PGON line: without them the check reports SKIPPED (exit 77) once the rest has passed.
#   klayout -b -r tests/klayout/check_glp.py -rd work=DIR [-rd data=../shared/data]
import glob
import os
import sys

import pya

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from harness import arg, expect, finish  # noqa: E402

from linf_opc import glp, inputs  # noqa: E402

work = arg("work", "/tmp/linf_glp")
os.makedirs(work, exist_ok=True)


def write(name, text):
    path = os.path.join(work, name)
    with open(path, "w") as f:
        f.write(text)
    return path


good = write("clip.glp", """BEGIN     /* a comment */
EQUIV  1  2000  MICRON  +X,+Y
CNAME Top
LEVEL M1
LEVEL V1

CELL Top PRIME
   RECT N M1  80  492  452  88
   PGON N M1  216  80  304  80  304  140  324  140  324  220  216 220
   RECT N V1  0  0  10  20   /* on the second level */
ENDMSG
""")
ly = glp.read(good)
top = ly.top_cells()[0]
expect(abs(ly.dbu - 0.0005) < 1e-15, "EQUIV 1 2000 MICRON: dbu 0.0005 um, got %g" % ly.dbu)
expect(top.name == "Top", "the cell's name")
infos = {(ly.get_info(i).layer, ly.get_info(i).datatype, ly.get_info(i).name) for i in ly.layer_indexes()}
expect(infos == {(1, 0, "M1"), (2, 0, "V1")}, "levels are layers 1/0, 2/0 in order, named: %s" % infos)
m1 = sorted(str(s.polygon) for s in top.shapes(ly.find_layer(1, 0)).each())
want = sorted([str(pya.Polygon(pya.Box(80, 492, 532, 580))),
               str(pya.Polygon([pya.Point(216, 80), pya.Point(304, 80), pya.Point(304, 140), pya.Point(324, 140),
                                 pya.Point(324, 220), pya.Point(216, 220)]))])
expect(m1 == want, "M1 shapes %s, want %s" % (m1, want))
v1 = [s.bbox() for s in top.shapes(ly.find_layer(2, 0)).each()]
expect(v1 == [pya.Box(0, 0, 10, 20)], "RECT x y width height: %s" % v1)

# The batch takes it as any layout.
got, cell, index, ld = inputs.load({"input": good, "layer": "1/0"})
expect(cell.name == "Top" and ld == (1, 0) and pya.Region(cell.begin_shapes_rec(index)).count() == 2, "inputs.load")

for text, line, what in [
        ("CELL A PRIME\n RECT N M1 0 0 10\n", 2, "RECT takes"),
        ("CELL A PRIME\n RECT N M1 0 0 10 -5\n", 2, "RECT takes"),
        ("CELL A PRIME\n PGON N M1 0 0 10 0\n", 2, "three"),
        ("CELL A PRIME\n PGON N M1 0 0 10 0 5 x\n", 2, "invalid literal"),
        (" RECT N M1 0 0 10 10\nCELL A PRIME\n", 1, "before CELL"),
        ("CELL A PRIME\nCELL B PRIME\n", 2, "second CELL"),
        ("EQUIV 1 1000 MICRON\nCELL A PRIME\n CIRCLE N M1 0 0 5\n", 3, "unknown statement CIRCLE"),
        ("EQUIV 1 1000 INCH\nCELL A PRIME\n", 1, "not MICRON")]:
    path = write("bad.glp", text)
    try:
        glp.read(path)
        expect(False, "%r: an error" % text)
    except glp.GlpError as e:
        expect(("line %d:" % line) in str(e) and what in str(e), "%r: %s" % (text, e))
    try:
        inputs.load({"input": path, "layer": "1/0"})
        expect(False, "%r: the batch stops" % text)
    except inputs.UsageError as e:
        expect(str(e).startswith("cannot read %s line %d" % (path, line)), "batch: %s" % e)
try:
    glp.read(write("empty.glp", "BEGIN\nENDMSG\n"))
    expect(False, "no CELL: an error")
except glp.GlpError as e:
    expect("no CELL" in str(e), str(e))

clips = sorted(glob.glob(os.path.join(arg("data", ""), "openilt", "M1_test*.glp")))
for path in clips:
    shapes = sum(1 for line in open(path) if line.split()[:1] in (["RECT"], ["PGON"]))
    ly = glp.read(path)
    n = pya.Region(ly.top_cells()[0].begin_shapes_rec(ly.find_layer(1, 0))).count()
    expect(shapes > 0 and n == shapes and abs(ly.dbu - 0.001) < 1e-15,
           "%s: %d shapes on M1 (1/0), %d in the file, dbu %g" % (os.path.basename(path), n, shapes, ly.dbu))

finish("%d contest clips" % len(clips),
       missing=None if clips else os.path.join(arg("data", "<-rd data>"), "openilt", "M1_test*.glp"))
