"""A picture of a layer with boxes over it (markers, windows), rendered by KLayout's own
layout view into a PNG: for layers too large to draw as SVG in the HTML report, where the
renderer's C++ does in a second what an SVG path of every polygon cannot do at all."""
import os
import tempfile

import pya

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


def picture(region, dbu, markers, windows, width=700, height=700):
    """PNG bytes: the layer's merged region in grey, marker boxes in red, windows (tuples whose
    first four values are a box in DBU) in blue, fitted into width x height pixels. The view
    gets a layout of its own (it takes ownership of what it shows)."""
    ly = pya.Layout()
    ly.dbu = dbu
    top = ly.create_cell("PICTURE")
    top.shapes(ly.layer(1, 0)).insert(region)
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
