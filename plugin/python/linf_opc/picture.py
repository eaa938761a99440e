"""A picture of a layer with boxes over it (markers, windows), rendered by KLayout's own
layout view into a PNG: for layers too large to draw as SVG in the HTML report, where the
renderer's C++ does in a second what an SVG path of every polygon cannot do at all.

The layer is drawn at the picture's scale (core.picture_coverage): a shape narrower than two
cells of a grid of GRID cells across is drawn as the cells its box touches, larger shapes as
they are. A copy of a layer of millions of shapes in the picture's layout would hold about
130 bytes a shape, where a cell is all a picture shows of such a shape."""
import math
import os
import tempfile

import pya

from . import core
from .polygons import Polygons, core_input

GRID = 1400  # cells across the layer's longer side: twice the picture's pixels

LAYER_FILL = 0xbbbbbb
MARKER_FRAME = 0xd62728  # as the SVG picture: markers red, windows blue
WINDOW_FRAME = 0x1f77b4


def _style(view, styles):
    """styles: {source: (fill or None for hollow, frame)} applied to the view's layer entries
    (entries replaced by new ones keep KLayout's default colours when rendered)."""
    it = view.begin_layers()
    while not it.at_end():
        lp = it.current().dup()
        if lp.source in styles:
            fill, frame = styles[lp.source]
            lp.frame_color = frame
            lp.fill_color = fill if fill is not None else frame
            lp.dither_pattern = 0 if fill is not None else 1  # solid, or hollow
            lp.width = 1
            view.set_layer_properties(it, lp)
        it.next()
    view.update_content()


def draw_layer(shapes, polygons, cells_across=GRID):
    """The layer's polygons (a polygons.Polygons or [(outer, [holes])], DBU) into `shapes` at
    the scale of cells_across cells along the longer side of their box: each row's runs of
    touched cells as one box, the large polygons as they are."""
    c = core.picture_coverage(core_input(polygons), cells_across)
    cells, nx, cell, x0, y0 = c["cells"], c["nx"], c["cell"], c["x0"], c["y0"]
    for j in range(c["ny"]):
        row, i = j * nx, 0
        while True:
            a = cells.find(1, row + i, row + nx)
            if a < 0:
                break
            b = cells.find(0, a, row + nx)
            b = row + nx if b < 0 else b
            shapes.insert(pya.Box(math.floor(x0 + (a - row) * cell), math.floor(y0 + j * cell),
                                  math.ceil(x0 + (b - row) * cell), math.ceil(y0 + (j + 1) * cell)))
            i = b - row
    for outer, holes in Polygons.from_flat(*c["large"]):
        p = pya.Polygon([pya.Point(x, y) for x, y in outer])
        for h in holes:
            p.insert_hole([pya.Point(x, y) for x, y in h])
        shapes.insert(p)


def picture(polygons, dbu, markers, windows, width=700, height=700):
    """PNG bytes: the layer's polygons (draw_layer) in grey, marker boxes in red, windows (tuples
    whose first four values are a box in DBU) in blue, fitted into width x height pixels. The
    view gets a layout of its own (it takes ownership of what it shows)."""
    ly = pya.Layout()
    ly.dbu = dbu
    top = ly.create_cell("PICTURE")
    draw_layer(top.shapes(ly.layer(1, 0)), polygons)
    for shapes, items in ((top.shapes(ly.layer(2, 0)), markers), (top.shapes(ly.layer(3, 0)), windows)):
        for b in items:
            shapes.insert(pya.Box(int(b[0]), int(b[1]), int(b[2]), int(b[3])))
    view = pya.LayoutView()
    view.set_config("background-color", "#ffffff")
    view.set_config("grid-visible", "false")
    cv = view.show_layout(ly, False)
    _style(view, {"1/0@%d" % (cv + 1): (LAYER_FILL, LAYER_FILL), "2/0@%d" % (cv + 1): (None, MARKER_FRAME),
                  "3/0@%d" % (cv + 1): (None, WINDOW_FRAME)})
    view.max_hier()
    view.zoom_fit()
    fd, path = tempfile.mkstemp(prefix="linf_opc-picture-", suffix=".png")
    os.close(fd)
    try:
        view.save_image(path, width, height)
        with open(path, "rb") as f:
            return f.read()
    finally:
        os.remove(path)
