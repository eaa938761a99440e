# Result layouts written by the core (output.write_by_core, the batch's only writer of them)
# against the same layouts built in KLayout and saved by it (the test oracle, oracles.py): the
# batch's voronoi and gauges commands (and select, with markers: windows.oas) run in this
# process with polygons.SPILL_SHAPES at zero (the layer read from its spilled arrays).
#   klayout -b -r tests/klayout/check_core_oasis.py -rd input=FILE -rd layer=L/D [-rd cell=NAME]
#           [-rd markers=SPEC] -rd work=DIR
# input=rings draws its own layout first: boxes with one and two holes, and a triangle.
# Both files must hold, layer by layer (layer, datatype, name), the same paths (ends and width;
# KLayout's compacting writer keeps one of identical paths, as where a sandwich and a width gauge
# measure the same line, so they are compared as sets), the same texts (string and position) and
# the same area (the input polygons: OASIS has no holes, so the core joins them to their outline
# by cut lines; the merged regions must agree).
import os
import sys
from collections import Counter

import pya

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from harness import arg, expect, finish  # noqa: E402

from linf_opc import commands, polygons  # noqa: E402
import oracles  # noqa: E402

work = arg("work", "/tmp/linf_core_oasis")


def draw_rings(path):
    ly = pya.Layout()
    ly.dbu = 0.001
    top = ly.create_cell("RINGS")
    li = ly.layer(1, 0)
    for i in range(4):
        outer = pya.Region(pya.Box(i * 3000, 0, i * 3000 + 2000, 2000))
        hole = pya.Region(pya.Box(i * 3000 + 500, 500, i * 3000 + 1500, 1500 - 200 * i))
        slot = pya.Region(pya.Box(i * 3000 + 1700, 200, i * 3000 + 1800, 1800))
        top.shapes(li).insert(outer - hole - (slot if i % 2 else pya.Region()))
    top.shapes(li).insert(pya.Polygon([pya.Point(0, 3000), pya.Point(4000, 3000), pya.Point(2000, 6000)]))
    ly.write(path)


source = arg("input")
if source == "rings":
    os.makedirs(work, exist_ok=True)
    source, layer = os.path.join(work, "rings.oas"), "1/0"
    draw_rings(source)
else:
    layer = arg("layer")


def run(out):
    for cmd in ("voronoi", "gauges") + (("select",) if arg("markers", None) else ()):
        args = dict(cmd=cmd, input=source, layer=layer, cell=arg("cell", None), out=out, markers=arg("markers", None))
        expect(commands.main(args) == 0, "%s in %s" % (cmd, out))


def content(path):
    ly = pya.Layout()
    ly.read(path)
    tops = ly.top_cells()
    expect(len(tops) == 1, "%s: one top cell" % path)
    top = tops[0]
    layers = {}
    for li in ly.layer_indexes():
        info = ly.get_info(li)
        paths, texts, region = Counter(), Counter(), pya.Region()
        for s in top.shapes(li).each():
            if s.is_path():
                p = s.path
                pts = tuple((q.x, q.y) for q in p.each_point())
                paths[(min(pts, pts[::-1]), p.width, p.bgn_ext, p.end_ext)] += 1
            elif s.is_text():
                texts[(s.text_string, s.text_pos.x, s.text_pos.y)] += 1
            elif s.is_polygon() or s.is_box():
                region.insert(s.polygon)
        layers[(info.layer, info.datatype)] = (info.name, paths, texts, region)
    return ly.dbu, top.name, layers


default = os.path.join(work, "klayout")
core = os.path.join(work, "core")
oracles.result_layouts(dict(input=source, layer=layer, cell=arg("cell", None), markers=arg("markers", None)), default)
polygons.SPILL_SHAPES = 0  # and the layer read from its spilled arrays, as on a large layer
run(core)
for name in ("voronoi.oas", "gauges.oas") + (("windows.oas",) if arg("markers", None) else ()):
    dbu_k, cell_k, a = content(os.path.join(default, name))
    dbu_c, cell_c, b = content(os.path.join(core, name))
    expect(abs(dbu_k - dbu_c) < 1e-12 and cell_k == cell_c, "%s: dbu %r/%r, cell %s/%s" % (name, dbu_k, dbu_c, cell_k, cell_c))
    expect(set(a) == set(b), "%s: layers %s vs %s" % (name, sorted(a), sorted(b)))
    for key in sorted(set(a) & set(b)):
        na, pa, ta, ra = a[key]
        nb, pb, tb, rb = b[key]
        expect(na == nb, "%s %s: layer name %r vs %r" % (name, key, na, nb))
        expect(set(pa) == set(pb), "%s %s: %d vs %d distinct paths, %d differ"
               % (name, key, len(pa), len(pb), len(set(pa) ^ set(pb))))
        expect(ta == tb, "%s %s: %d vs %d texts" % (name, key, sum(ta.values()), sum(tb.values())))
        expect((ra ^ rb).is_empty(), "%s %s: the polygons differ in area" % (name, key))
    shapes = sum(sum(p.values()) + sum(t.values()) + r.count() for _, p, t, r in b.values())
    expect(shapes > 0, "%s: shapes written" % name)
    print("%s: %d layers, %d shapes, the same from KLayout and from the core" % (name, len(b), shapes))

finish()
