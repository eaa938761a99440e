# The selection report's layout picture for a layer too large for SVG: the batch's select
# command run in this process with the SVG limit at zero (report.SVG_PICTURE_MAX), on the sample.
#   klayout -b -r tests/klayout/check_report_picture.py -rd work=DIR
# - report.html holds the picture as an embedded PNG (a data: URI, nothing else referenced) and
#   no SVG layout picture;
# - the PNG is 700 x 700, and not blank: its rows hold the layer's grey, a marker's red and a
#   window's blue (decoded here with zlib: PNG filters undone for 8-bit RGB(A));
# - the layer drawn at a picture's scale (picture.draw_layer) on coarse and fine grids covers
#   every shape, draws nothing further than three cells from one, and draws the large shapes
#   as they are.
import base64
import os
import re
import struct
import sys
import zlib

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from harness import arg, expect, finish, repo  # noqa: E402

import pya  # noqa: E402

from linf_opc import commands, layout, picture, report  # noqa: E402

work = arg("work", "/tmp/linf_report_picture")


def pixels(png):
    """(width, height, set of (r, g, b)) of an 8-bit RGB or RGBA, non-interlaced PNG."""
    assert png[:8] == b"\x89PNG\r\n\x1a\n", "not a PNG"
    pos, idat, w = 8, b"", None
    while pos < len(png):
        n, kind = struct.unpack(">I4s", png[pos:pos + 8])
        data = png[pos + 8:pos + 8 + n]
        if kind == b"IHDR":
            w, h, depth, colour, _, _, interlace = struct.unpack(">IIBBBBB", data)
            assert depth == 8 and colour in (2, 6) and interlace == 0, "unexpected PNG format"
            bpp = 3 if colour == 2 else 4
        elif kind == b"IDAT":
            idat += data
        pos += 12 + n
    raw, stride, prev, seen = zlib.decompress(idat), w * bpp, bytearray(w * bpp), set()
    for y in range(h):
        f, line = raw[y * (stride + 1)], bytearray(raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)])
        for i in range(stride):
            a = line[i - bpp] if i >= bpp else 0
            b, c = prev[i], prev[i - bpp] if i >= bpp else 0
            if f == 1:
                line[i] = (line[i] + a) & 255
            elif f == 2:
                line[i] = (line[i] + b) & 255
            elif f == 3:
                line[i] = (line[i] + (a + b) // 2) & 255
            elif f == 4:
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                line[i] = (line[i] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
        seen.update(tuple(line[i:i + 3]) for i in range(0, stride, bpp))
        prev = line
    return w, h, seen


report.SVG_PICTURE_MAX = 0
rc = commands.main(dict(cmd="select", input=os.path.join(repo, "samples", "metal.oas"), layer="1/0", markers="100/0",
                        halves="0", out=work))
expect(rc == 0, "select exit code %s" % rc)
page = open(os.path.join(work, "report.html")).read()
uris = re.findall(r'src="([^"]*)"', page)
expect(len(uris) == 1 and uris[0].startswith("data:image/png;base64,"), "one embedded PNG, found %d src" % len(uris))
expect('class="layout"' in page and '<svg xmlns="http://www.w3.org/2000/svg" width' in page and
       page.count('class="layout"') == 1 and "<img" in page, "the layout picture is the image, not an SVG")
expect("href=" not in page, "nothing linked")
if uris:
    w, h, colours = pixels(base64.b64decode(uris[0].split(",", 1)[1]))
    expect((w, h) == (700, 700), "picture %dx%d" % (w, h))
    rgb = lambda v: ((v >> 16) & 255, (v >> 8) & 255, v & 255)  # noqa: E731
    for name, colour in (("layer", picture.LAYER_FILL), ("marker", picture.MARKER_FRAME),
                         ("window", picture.WINDOW_FRAME)):
        expect(rgb(colour) in colours, "the %s colour %s is in the picture" % (name, rgb(colour)))

sample = pya.Layout()
sample.read(os.path.join(repo, "samples", "metal.oas"))
region = pya.Region(sample.top_cells()[0].begin_shapes_rec(sample.find_layer(1, 0))).merged()
for across in (12, 60, 4000):
    ly = pya.Layout()
    shapes = ly.create_cell("T").shapes(ly.layer(1, 0))
    picture.draw_layer(shapes, layout.polygons_of(region), across)
    drawn = pya.Region(shapes)
    side = max(region.bbox().width(), region.bbox().height()) / across
    large = [p for p in region.each() if min(p.bbox().width(), p.bbox().height()) >= 2 * side]
    polygons = [s.polygon for s in shapes.each()]
    expect((region - drawn).is_empty(), "%d cells across: every shape is drawn" % across)
    expect((drawn - region.sized(int(3 * side) + 1)).is_empty(),
           "%d cells across: nothing drawn further than three cells from a shape" % across)
    expect(all(p in polygons for p in large), "%d cells across: the large shapes as they are" % across)
    print("%d cells across: %d shapes drawn for %d (%d large)" % (across, drawn.count(), region.count(), len(large)))

finish()
