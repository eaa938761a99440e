"""Writing a Diagram: voronoi.oas, the diagram's layers in the editor's layout, the summary.
voronoi.csv is the core's, written while it holds the diagram (diagram.compute's csv_path)."""
import time

import pya

from . import output
from .diagram import KINDS
from .progress import breathe

# Diagram layers sit on the input's layer number, datatypes 200 + kind index, so that they
# sort next to the input in the layer list and never collide with drawn datatypes.
DATATYPE_BASE = 200


def diagram_layer_info(layer, datatype, kind):
    return pya.LayerInfo(layer, DATATYPE_BASE + KINDS.index(kind), "voronoi_%s (%d/%d)" % (kind, layer, datatype))


def drawing(diagram, layer, box):
    """The core's drawing of `diagram` (diagram.compute with draw_layer=layer) read into a layout
    of its own, each kind's pieces cut to `box` (cut_to_box); the event loop turns between the
    steps (progress.breathe). The editor does this before its undo step opens, and add_layers
    then only copies."""
    drawn = output.read_drawing(diagram.gds_path)
    if drawn.top_cells():
        top = drawn.top_cell()
        for i in range(len(KINDS)):
            breathe()
            found = drawn.find_layer(output.in_drawing(layer), DATATYPE_BASE + i)
            if found is not None:
                cut_to_box(top.shapes(found), box)
    breathe()
    return drawn


def add_layers(layout, cell, diagram, layer, datatype, drawn=None):
    """Draws every piece as a zero-width path on its kind's layer (cleared first, so the
    action can be repeated), from the GDSII file the core wrote (diagram.compute with
    draw_layer=layer), or from `drawn`, that drawing as drawing() read and cut it. A piece
    shorter than the database grid rounds to a point and is not drawn (the CSV keeps it).
    Returns {kind: number of pieces as the core drew them}."""
    if not diagram.gds_path:
        raise ValueError("the diagram was computed without draw_layer: nothing to draw")
    targets = {}
    for kind in KINDS:
        info = diagram_layer_info(layer, datatype, kind)
        index = layout.find_layer(info)
        if index is None:
            index = layout.insert_layer(info)
        cell.shapes(index).clear()
        targets[(layer, DATATYPE_BASE + KINDS.index(kind))] = index
    output.copy_drawing(cell, diagram.gds_path, targets, drawn)
    return {k: diagram.drawn[k] for k in KINDS}


def _cut(p, q, box):
    """The part of segment p-q (float pairs) inside `box` (Liang-Barsky), or None."""
    t0, t1 = 0.0, 1.0
    dx, dy = q[0] - p[0], q[1] - p[1]
    for d, room in ((-dx, p[0] - box.left), (dx, box.right - p[0]), (-dy, p[1] - box.bottom), (dy, box.top - p[1])):
        if d == 0:
            if room < 0:
                return None
            continue
        t = room / d
        if d < 0:
            t0 = max(t0, t)
        else:
            t1 = min(t1, t)
        if t0 > t1:
            return None
    return ((p[0] + t0 * dx, p[1] + t0 * dy), (p[0] + t1 * dx, p[1] + t1 * dy))


def cut_to_box(shapes, box):
    """Cuts the zero-width paths of `shapes` (an editable layout's) to `box`, removing those
    wholly outside: the core draws rays and far pieces out to the layer's box enlarged by its
    larger side on every side (3 times its size), so that in the editor "zoom fit" showed mostly
    rays. Only the pieces touching the four strips around the box are visited, found through
    the shapes' box tree: the far field's few, not the layer's millions. The files keep the
    whole pieces. Returns the number of pieces cut or removed."""
    far = 2 ** 31 - 1  # drawn pieces lie within +-(2^31 - 1) DBU
    whole = pya.Box(-far, -far, far, far)
    strips = [pya.Box(whole.left, whole.bottom, box.left - 1, whole.top),
              pya.Box(box.right + 1, whole.bottom, whole.right, whole.top),
              pya.Box(whole.left, whole.bottom, whole.right, box.bottom - 1),
              pya.Box(whole.left, box.top + 1, whole.right, whole.top)]
    strips = [b for b in strips if b.left <= b.right and b.bottom <= b.top]
    leaving = []
    for k, strip in enumerate(strips):
        for s in shapes.each_touching(pya.Shapes.SPaths, strip):
            if not any(s.bbox().touches(b) for b in strips[:k]):  # found once, in its first strip
                leaving.append(s)
    kept = []
    for s in leaving:
        pts = [(float(pt.x), float(pt.y)) for pt in s.path.each_point()]
        for a, b in zip(pts, pts[1:]):
            part = _cut(a, b, box)
            if part is not None:
                (x1, y1), (x2, y2) = part
                a2, b2 = pya.Point(round(x1), round(y1)), pya.Point(round(x2), round(y2))
                if a2 != b2:
                    kept.append(pya.Path([a2, b2], 0))
        shapes.erase(s)
    for path in kept:
        shapes.insert(path)
    return len(leaving)


def summary(diagram, dbu, **extra):
    s = {
        "dbu": round(dbu, 12),
        "sites": diagram.sites,
        "pieces": diagram.n_pieces,
        "counts": diagram.counts(),
        "check": {k: v for k, v in diagram.check.items() if k != "messages"},
        "seconds": diagram.seconds,
        "tiles": diagram.tiles,
        "builder": diagram.builder,
    }
    s.update(extra)
    return s


def write_voronoi(inp, diagram):
    """voronoi.oas of the Input `inp`: its layer and the diagram's layers as add_layers draws
    them, from the core's drawing (diagram.compute with draw_layer and draw_cell=inp.cell.name).
    The diagram must have been computed with csv_path=inp.file("voronoi.csv"). Returns the summary."""
    t0 = time.perf_counter()
    if diagram.csv_path != inp.file("voronoi.csv"):
        raise ValueError("the diagram was computed without csv_path: the core writes voronoi.csv")
    names = [(inp.layer, DATATYPE_BASE + i, diagram_layer_info(inp.layer, inp.datatype, k).name)
             for i, k in enumerate(KINDS)]
    output.write_by_core(inp.file("voronoi.oas"), diagram.gds_path, inp.polygons, inp.layer, inp.datatype, names,
                         inp.dbu, inp.cell.name)
    s = layer_summary(inp, diagram)
    s["seconds"]["write"] = time.perf_counter() - t0
    return s


def layer_summary(inp, diagram):
    """The summary of the Input `inp`'s diagram, drawn or not (a flow that writes no diagram
    file still reports its pieces): `drawn` only where it was drawn."""
    s = summary(diagram, inp.dbu, input=inp.path, cell=inp.cell.name, layer=inp.name, polygons=diagram.polygons)
    if diagram.drawn is not None:
        s["drawn"] = {k: diagram.drawn[k] for k in KINDS}
    s["seconds"].update(read=inp.t_read)
    return s
