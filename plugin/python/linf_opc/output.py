"""What the stages' writers share: result layouts written by the core, layouts saved by
KLayout, the core's GDSII drawings copied into a layout, summary JSON."""
import json

import pya

from . import core
from .polygons import core_input

# KLayout's OASIS shape compaction (regular arrays found among repeated shapes) keeps a table
# of every shape while it writes: about 100 bytes a shape, 1 GB more at the peak on a layer of
# a million wires. Larger layouts are written without it (files about 5% larger there).
COMPACT_MAX_SHAPES = 1000000


def shape_count(layout):
    return sum(cell.shapes(li).size() for cell in layout.each_cell() for li in layout.layer_indexes())


def save(layout, path):
    """Writes a layout built in KLayout (format from the file name), without shape compaction
    above COMPACT_MAX_SHAPES shapes."""
    opts = pya.SaveLayoutOptions()
    opts.set_format_from_filename(path)
    if shape_count(layout) > COMPACT_MAX_SHAPES:
        opts.oasis_compression_level = 0
    layout.write(path, opts)


def write_by_core(path, drawing, polygons, layer, datatype, names, dbu, cell, boxes=()):
    """A result layout (voronoi.oas, gauges.oas, windows.oas) as OASIS, written by the core: the
    input polygons, the core's GDSII drawing (paths and texts; None for none) and boxes
    [(layer, datatype, array('q') x1, y1, x2, y2 a box)], in one top cell named `cell`. Built in
    a KLayout layout, a layer of millions of shapes would be held in memory while it was saved.
    names: [(layer, datatype, pya.LayerInfo name)]. Returns the shape count."""
    if drawing and not 0 <= layer <= GDS_LAYER_MAX:
        return _write_wide_layer(path, drawing, polygons, layer, datatype, names, dbu, cell, boxes)
    return core.oasis_from_drawing(drawing or "", core_input(polygons), layer, datatype, names, dbu, cell, path,
                                   list(boxes))


# The core's GDSII drawings hold a layer number in 16 bits, and it reads them back signed: a
# layer above this (OASIS and KLayout have no such limit) comes back as another number.
GDS_LAYER_MAX = 32767


def in_drawing(layer):
    """The number a layer has in a GDSII drawing as KLayout reads it (16 bits, unsigned)."""
    return layer & 0xFFFF


def _write_wide_layer(path, drawing, polygons, layer, datatype, names, dbu, cell, boxes):
    """write_by_core for a layer number GDSII cannot hold: the core writes the layer and the boxes,
    KLayout adds the drawing's shapes on their real layer and writes the file again. KLayout holds
    the result layout for this (as it would for any layout it writes)."""
    shapes = core.oasis_from_drawing("", core_input(polygons), layer, datatype, names, dbu, cell, path, list(boxes))
    ly = pya.Layout()
    ly.read(path)
    top = ly.cell(cell) or ly.create_cell(cell)
    drawn = pya.Layout()
    drawn.read(drawing)
    if drawn.top_cells():
        source = drawn.top_cell()
        named = {(l, d): n for l, d, n in names}
        for index in drawn.layer_indexes():
            info = drawn.get_info(index)
            if info.layer != in_drawing(layer) or source.shapes(index).is_empty():
                continue
            target = ly.find_layer(layer, info.datatype)
            if target is None:
                target = ly.insert_layer(pya.LayerInfo(layer, info.datatype, named.get((layer, info.datatype), "")))
            top.shapes(target).insert(source.shapes(index))
            shapes += source.shapes(index).size()
    opts = pya.SaveLayoutOptions()
    opts.format = "OASIS"
    opts.oasis_compression_level = 0  # compaction would drop repeated shapes (gauges measuring one line)
    ly.write(path, opts)
    return shapes


def read_drawing(path):
    """A GDSII file the core wrote (see drawing.py) read into a layout of its own (editable)."""
    drawn = pya.Layout()
    drawn.read(path)
    return drawn


def copy_drawing(cell, path, targets, drawn=None):
    """Puts the shapes of a GDSII file the core wrote on layer/datatype (l, d) into `cell`'s
    layer targets[(l, d)] (an index of cell's layout): read into a layout of its own (or `drawn`,
    that file read already by read_drawing) and copied, an undoable insertion."""
    if drawn is None:
        drawn = read_drawing(path)
    if not drawn.top_cells():
        return
    source = drawn.top_cell()
    for (layer, datatype), index in targets.items():
        found = drawn.find_layer(in_drawing(layer), datatype)  # a layer above 65535 is its low 16 bits there
        if found is not None:
            cell.shapes(index).insert(source.shapes(found))


def write_json(data, path):
    with open(path, "w") as f:
        json.dump(data, f, indent=2, sort_keys=True)
        f.write("\n")
