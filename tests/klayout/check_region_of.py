# layout.region_of merges in the layout's hierarchy: its polygons must be exactly those of KLayout's
# flat merge of the flattened layer, vertex for vertex.
#   klayout -b -r tests/klayout/check_region_of.py [-rd input=FILE -rd layer=L/D [-rd cell=NAME]]
# Always on a layout drawn here whose shapes meet across cells: overlapping and touching array
# members, rotated and mirrored placements, a magnified placement at 30 degrees, a ring closed
# only by shapes of two cells (a hole), a 45-degree comb, bow-ties; with input=, also on that layer.
import os
import sys

import pya

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from harness import arg, expect, finish  # noqa: E402

from linf_opc import layout  # noqa: E402


def rings(region):
    """Each polygon as its rings' vertex lists, each list from its least vertex: independent of
    where KLayout starts a ring and of the polygons' order."""
    def ring(points):
        pts = [(p.x, p.y) for p in points]
        k = pts.index(min(pts))
        return tuple(pts[k:] + pts[:k])
    out = []
    for p in region.each():
        out.append((ring(p.each_point_hull()), tuple(sorted(ring(p.each_point_hole(h)) for h in range(p.holes())))))
    return sorted(out)


def compare(name, cell, li):
    got = layout.region_of(cell, li)
    flat = pya.Region(cell.begin_shapes_rec(li))
    flat.merged_semantics = True
    want = flat.merged()
    expect(not got.is_deep(), "%s: region_of gives a flat region" % name)
    expect(got.count() == want.count(), "%s: %d polygons, flat merge %d" % (name, got.count(), want.count()))
    expect(rings(got) == rings(want), "%s: the polygons differ from the flat merge's" % name)
    print("%s: %d shapes -> %d merged polygons, %d holes" % (name, flat.count(), got.count(),
                                                           sum(p.holes() for p in got.each())))
    return got


ly = pya.Layout()
ly.dbu = 0.001
li = ly.layer(1, 0)
top = ly.create_cell("TOP")
wire = ly.create_cell("WIRE")
wire.shapes(li).insert(pya.Box(0, 0, 1000, 100))
wire.shapes(li).insert(pya.Box(900, 0, 1000, 600))  # an L made of two overlapping boxes
corner = ly.create_cell("CORNER")  # half of a ring; the other half is drawn in TOP
corner.shapes(li).insert(pya.Box(0, 0, 2000, 200))
corner.shapes(li).insert(pya.Box(0, 0, 200, 2000))
comb = ly.create_cell("COMB")
teeth = [pya.Point(0, 0), pya.Point(3000, 0), pya.Point(3000, 300)]
for k in range(10):
    x = 3000 - 300 * k
    teeth += [pya.Point(x - 100, 300), pya.Point(x - 100, 1000 + 100 * k), pya.Point(x - 200, 1100 + 100 * k),
              pya.Point(x - 200, 300)]
teeth += [pya.Point(0, 300)]
comb.shapes(li).insert(pya.Polygon(teeth))
# Array members overlapping (pitch 950 < width 1000) and touching (row pitch 600 = L height).
top.insert(pya.CellInstArray(wire.cell_index(), pya.Trans(0, 0), pya.Vector(950, 0), pya.Vector(0, 600), 8, 5))
top.insert(pya.CellInstArray(wire.cell_index(), pya.Trans(pya.Trans.R90, 500, 100)))
top.insert(pya.CellInstArray(wire.cell_index(), pya.Trans(pya.Trans.M45, 4000, 2500)))
top.insert(pya.CellInstArray(corner.cell_index(), pya.Trans(20000, 0)))
top.shapes(li).insert(pya.Box(21800, 0, 22000, 2000))
top.shapes(li).insert(pya.Box(20000, 1800, 22000, 2000))  # the ring's other half: a hole
top.insert(pya.CellInstArray(comb.cell_index(), pya.ICplxTrans(1.5, 30, False, 10000, 5000)))
top.insert(pya.CellInstArray(comb.cell_index(), pya.Trans(pya.Trans.R180, 14000, 9000)))
top.insert(pya.CellInstArray(comb.cell_index(), pya.Trans(11500, 8200)))  # overlaps the rotated one
merged = compare("drawn", top, li)
expect(sum(p.holes() for p in merged.each()) >= 1, "drawn: the ring across two cells has its hole")

# A bow-tie (lobes wound opposite ways, signed area 0) placed in a cell twice, one placement
# overlapping a box: KLayout's hierarchical merge drops such a polygon, the flat merge keeps it.
bow = ly.create_cell("BOWTIE")
bow.shapes(li).insert(pya.Polygon([pya.Point(0, 0), pya.Point(1000, 1000), pya.Point(1000, 0), pya.Point(0, 1000)], True))
top.insert(pya.CellInstArray(bow.cell_index(), pya.Trans(30000, 0), pya.Vector(3000, 0), pya.Vector(0, 0), 2, 1))
top.shapes(li).insert(pya.Box(33900, 400, 35000, 600))
with_bow = compare("drawn with bow-ties", top, li)
expect(with_bow.area() > merged.area() + 2 * 500000 - 1, "drawn with bow-ties: both lobes of each bow-tie kept (%d -> %d)"
       % (merged.area(), with_bow.area()))

if arg("input", None):
    src = pya.Layout()
    src.read(arg("input"))
    L, D = layout.parse_layer(arg("layer", "1/0"))
    cell = src.cell(arg("cell")) if arg("cell", None) else src.top_cells()[0]
    compare(os.path.basename(arg("input")), cell, src.find_layer(L, D))

finish()
