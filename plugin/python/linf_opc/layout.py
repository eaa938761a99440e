"""Reading a layer of a KLayout layout as plain polygons (the flow's input contract)."""
import pya

from . import glp
from .polygons import Polygons
from .progress import breathe


def read_layout(path, options=None):
    """The layout in `path`: a GLP contest clip (glp.py; KLayout does not read GLP, and
    `options` do not apply), else as KLayout reads it with `options` (pya.LoadLayoutOptions).
    Raises glp.GlpError or KLayout's RuntimeError."""
    if glp.is_glp(path):
        return glp.read(path)
    ly = pya.Layout()
    if options is None:
        ly.read(path)
    else:
        ly.read(path, options)
    return ly


def parse_layer(text):
    """'L/D' -> (L, D). Raises ValueError with a readable message."""
    try:
        l, d = text.split("/")
        return int(l), int(d)
    except (ValueError, AttributeError):
        raise ValueError("layer must be given as L/D, e.g. 11/0, not %r" % (text,))


# Up to this many shapes KLayout merges the layer before the core sees it, else the layer reaches
# the core as drawn and the core merges it in groups (it merges what it gets either way; the
# polygons are the same). KLayout merges in the layout's hierarchy (a DeepShapeStore): a cell
# placed many times is merged once, and only what meets across cells is merged flat. On the
# SRAM's 113,019 shapes that takes 0.13 s where the flat merge takes 0.69 s, the core's 0.7 s.
# The merged layer is then made flat: the flat merge still holds about twice the layer while it
# runs, hence the limit.
MERGE_IN_KLAYOUT_MAX = 200000


def region_of(cell, layer_index):
    """The layer's shapes in `cell` and below, flattened, with merged semantics (booleans and
    checks see overlaps and touches joined); merged by KLayout up to MERGE_IN_KLAYOUT_MAX
    shapes (in the hierarchy, or flat where a polygon is a balanced bow-tie), else as drawn.
    A flat region either way."""
    region = pya.Region(cell.begin_shapes_rec(layer_index))
    region.merged_semantics = True
    if region.count() > MERGE_IN_KLAYOUT_MAX:
        return region
    if _balanced_self_intersection(cell, layer_index):
        return region.merged()
    store = pya.DeepShapeStore()
    merged = pya.Region()
    merged.insert(pya.Region(cell.begin_shapes_rec(layer_index), store).merged())
    merged.merged_semantics = True
    return merged


def _balanced_self_intersection(cell, layer_index):
    """Whether a polygon drawn in `cell` or below has lobes of opposite winding that cancel (a
    bow-tie: signed area 0, yet area where merged). KLayout's hierarchical merge drops such a
    polygon whole, the flat merge keeps its lobes. Each cell's polygons are looked at once,
    not each placement."""
    layout = cell.layout()
    for ci in [cell.cell_index()] + list(cell.called_cells()):
        for shape in layout.cell(ci).shapes(layer_index).each(pya.Shapes.SPolygons):
            poly = shape.polygon
            if poly.area() == 0 and pya.Region(poly).merged().count() > 0:
                return True
    return False


def _add(out, poly):
    out.add(((p.x, p.y) for p in poly.each_point_hull()),
            [[(p.x, p.y) for p in poly.each_point_hole(h)] for h in range(poly.holes())])


def halves_of(region, xm, spill_over=None):
    """The region cut at x = xm into the polygons left and right of it, two Polygons as
    polygons_of gives them, in one pass: a polygon on one side goes there as it is, one across
    the cut is clipped (a boolean of that polygon alone). The same area as `region & box` for
    each half, without KLayout merging the whole layer for it (the core merges anyway)."""
    left, right = Polygons(spill_over), Polygons(spill_over)
    for poly in region.each():
        b = poly.bbox()
        if b.right <= xm:
            _add(left, poly)
        elif b.left >= xm:
            _add(right, poly)
        else:
            whole = pya.Region(poly)
            for out, x1, x2 in ((left, b.left, xm), (right, xm, b.right)):
                for part in (whole & pya.Region(pya.Box(x1, b.bottom, x2, b.top))).each():
                    _add(out, part)
    return left.done(), right.done()


def polygons_of(region, spill_over=None):
    """The core's input, a polygons.Polygons (flat arrays; iterating gives (outer, [holes]) with
    rings as [(x, y)] in integer DBU): the region's polygons as they are (each(), not merged).
    A layer of more than `spill_over` shapes goes to a mapped file as it is read (Polygons.spill)."""
    out = Polygons(spill_over)
    n = region.count()
    for k, poly in enumerate(region.each()):
        breathe(k, n)
        _add(out, poly)
    return out.done()
