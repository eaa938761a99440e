"""Reading a layer of a KLayout layout as plain polygons (the flow's input contract)."""
import pya

from .polygons import Polygons


def parse_layer(text):
    """'L/D' -> (L, D). Raises ValueError with a readable message."""
    try:
        l, d = text.split("/")
        return int(l), int(d)
    except (ValueError, AttributeError):
        raise ValueError("layer must be given as L/D, e.g. 11/0, not %r" % (text,))


def region_of(cell, layer_index):
    """The layer's shapes in `cell` and below, flattened, as drawn: not merged. Merged semantics
    (booleans and checks see overlaps and touches joined); the core merges the polygons itself,
    so a merged copy here would only cost memory (on a layer of millions of shapes KLayout's
    merge holds about twice the layer while it runs)."""
    region = pya.Region(cell.begin_shapes_rec(layer_index))
    region.merged_semantics = True
    return region


def polygons_of(region):
    """The core's input, a polygons.Polygons (flat arrays; iterating gives (outer, [holes]) with
    rings as [(x, y)] in integer DBU): the region's polygons as they are (each(), not merged)."""
    out = Polygons()
    for poly in region.each():
        out.add(((p.x, p.y) for p in poly.each_point_hull()),
                [[(p.x, p.y) for p in poly.each_point_hole(h)] for h in range(poly.holes())])
    return out
