"""Reading a layer of a KLayout layout as plain polygons (the flow's input contract)."""
import pya


def parse_layer(text):
    """'L/D' -> (L, D). Raises ValueError with a readable message."""
    try:
        l, d = text.split("/")
        return int(l), int(d)
    except (ValueError, AttributeError):
        raise ValueError("layer must be given as L/D, e.g. 11/0, not %r" % (text,))


def region_of(cell, layer_index):
    """The layer's shapes in `cell` and below, flattened and merged (overlaps and touches joined)."""
    region = pya.Region(cell.begin_shapes_rec(layer_index))
    region.merged_semantics = True
    return region.merged()


def polygons_of(region):
    """[(outer, [holes])], rings as [(x, y)] in integer DBU: the core's input."""
    out = []
    for poly in region.each():
        outer = [(p.x, p.y) for p in poly.each_point_hull()]
        holes = [[(p.x, p.y) for p in poly.each_point_hole(h)] for h in range(poly.holes())]
        out.append((outer, holes))
    return out
