"""Writing a Diagram: CSV in micrometres, layout layers, summary JSON."""
import csv
import json

import pya

from . import core
from .diagram import KINDS
from .polygons import core_input

CSV_HEADER = ["kind", "x1", "y1", "x2", "y2", "d1", "d2",
              "a_x1", "a_y1", "a_x2", "a_y2", "b_x1", "b_y1", "b_x2", "b_y2"]

# Diagram layers sit on the input's layer number, datatypes 200 + kind index, so that they
# sort next to the input in the layer list and never collide with drawn datatypes.
DATATYPE_BASE = 200


def diagram_layer_info(layer, datatype, kind):
    return pya.LayerInfo(layer, DATATYPE_BASE + KINDS.index(kind), "voronoi_%s (%d/%d)" % (kind, layer, datatype))


# KLayout's OASIS shape compaction (regular arrays found among repeated shapes) keeps a table
# of every shape while it writes: about 100 bytes a shape, 1 GB more at the peak on a layer of
# a million wires. Larger layouts are written without it (files about 5% larger there).
COMPACT_MAX_SHAPES = 1000000


def shape_count(layout):
    return sum(cell.shapes(li).size() for cell in layout.each_cell() for li in layout.layer_indexes())


def save(layout, path):
    """Writes a result layout (format from the file name), without shape compaction above
    COMPACT_MAX_SHAPES shapes."""
    opts = pya.SaveLayoutOptions()
    opts.set_format_from_filename(path)
    if shape_count(layout) > COMPACT_MAX_SHAPES:
        opts.oasis_compression_level = 0
    layout.write(path, opts)


def needs_core_writer(shapes):
    """Whether a result layout of this many shapes is written by the core (write_by_core)
    instead of being built in a KLayout Layout and saved."""
    return shapes > COMPACT_MAX_SHAPES


def write_by_core(path, drawing, polygons, layer, datatype, names, dbu, cell, boxes=()):
    """A result layout as OASIS straight from the core's GDSII drawing (paths and texts; None for
    none), boxes [(layer, datatype, array('q') x1, y1, x2, y2 a box)] and the input polygons,
    for layouts of millions of shapes, which KLayout would hold in memory while it saved them.
    names: [(layer, datatype, pya.LayerInfo name)]. Returns the shape count."""
    return core.oasis_from_drawing(drawing or "", core_input(polygons), layer, datatype, names, dbu, cell, path,
                                   list(boxes))


def write_csv(diagram, path, dbu):
    """The pieces as CSV (the core's write_pieces_csv writes the same bytes, faster: batch runs
    ask the core to write it while it holds the diagram)."""
    if diagram.csv_path == path:
        return
    if diagram.pieces is None:
        raise ValueError("the diagram was computed without its pieces: pass csv_path to diagram.compute")
    with open(path, "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(CSV_HEADER)
        for p in diagram.pieces:
            w.writerow([p.kind] + ["%.6f" % (v * dbu) for v in p[1:15]])


def copy_drawing(cell, path, targets, direct=False):
    """Puts the shapes of a GDSII file the core wrote (see drawing.py) on layer/datatype (l, d)
    into `cell`'s layer targets[(l, d)] (an index of cell's layout): read into a layout of its
    own and copied, an undoable insertion; or, `direct`, read straight into cell's layout,
    which holds them once instead of twice on the way (the batch's fresh result layouts: a
    full layer's diagram is tens of millions of shapes; the file's cell must be named as
    `cell`, and layers are matched by layer and datatype)."""
    layout = cell.layout()
    if direct:
        cells = sum(1 for _ in layout.each_cell())
        layout.read(path)
        if sum(1 for _ in layout.each_cell()) != cells:
            raise ValueError("the drawing %s is not for cell %s" % (path, cell.name))
        return
    drawn = pya.Layout()
    drawn.read(path)
    if not drawn.top_cells():
        return
    source = drawn.top_cell()
    for (layer, datatype), index in targets.items():
        found = drawn.find_layer(layer, datatype)
        if found is not None:
            cell.shapes(index).insert(source.shapes(found))


def add_layers(layout, cell, diagram, layer, datatype, direct=False):
    """Draws every piece as a zero-width path on its kind's layer (cleared first, so the
    action can be repeated), from the GDSII file the core wrote (diagram.compute with
    draw_layer=layer; `direct`: see copy_drawing, draw_cell=cell.name). A piece shorter than the database grid rounds
    to a point and is not drawn (the CSV keeps it). Returns {kind: number of pieces drawn}."""
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
    copy_drawing(cell, diagram.gds_path, targets, direct)
    return {k: diagram.drawn[k] for k in KINDS}


def summary(diagram, dbu, **extra):
    s = {
        "dbu": round(dbu, 12),
        "sites": diagram.sites,
        "pieces": diagram.n_pieces,
        "counts": diagram.counts(),
        "check": {k: v for k, v in diagram.check.items() if k != "messages"},
        "seconds": diagram.seconds,
        "tiles": diagram.tiles,
    }
    s.update(extra)
    return s


def write_json(data, path):
    with open(path, "w") as f:
        json.dump(data, f, indent=2, sort_keys=True)
        f.write("\n")
