"""Clip libraries: one cell per pattern, for OPC model calibration or verification.

Each clip cell holds, in layout coordinates (so that it overlays the source):
  L/D     the layer's merged shapes clipped to the window (hierarchy flattened);
  L/210   the gauge's measurement line and a text with the gauge's values;
  L/220   the window outline;
  L/230   the markers that meet the window.
Cells are named SET_rRANK_TYPE_SCORE, e.g. CAL_r000042_sandwich_0p0245 (score in µm, '.' -> 'p').
"""
import pya

from . import output
from .gauge_output import DATATYPE as GAUGE_DATATYPE
from .selection_output import DATATYPE as WINDOW_DATATYPE

MARKER_DATATYPE = 230
PREFIX = {"calibration": "CAL", "verification": "VER"}


def window_box(b):
    """A pattern window on the integer DBU grid (the clip boundary)."""
    return pya.Box(int(round(b[0])), int(round(b[1])), int(round(b[2])), int(round(b[3])))


def cell_name(which, g, dbu):
    score = ("%.4f" % (g.score * dbu)).replace(".", "p").replace("-", "m")
    return "%s_r%06d_%s_%s" % (PREFIX[which], g.rank, g.type, score)


def write_library(path, which, patterns, source, index, layer, datatype, dbu):
    """Writes the clips of one set, cut from the shapes of layer `index` in the cell `source` and below;
    returns the cell names in order."""
    lib = pya.Layout()
    lib.dbu = dbu
    li = lib.layer(pya.LayerInfo(layer, datatype))
    lg = lib.layer(pya.LayerInfo(layer, GAUGE_DATATYPE, "gauges"))
    lw = lib.layer(pya.LayerInfo(layer, WINDOW_DATATYPE, "windows"))
    lm = lib.layer(pya.LayerInfo(layer, MARKER_DATATYPE, "markers"))
    # Only the shapes that overlap the window, found through the layout's own box trees (a
    # merged region of the whole layer `& box` scans all of it: minutes for the patterns of a
    # large layer; a copy of it to query would hold the layer once more). Merged semantics: the
    # shapes are merged as they are clipped, so the clip is the merged layer's.
    names = []
    # Inserting a Region updates the whole layout unless it is marked under construction:
    # without this every clip costs time in proportion to the clips before it.
    lib.start_changes()
    for p in patterns:
        g = p.gauge
        cell = lib.create_cell(cell_name(which, g, dbu))
        names.append(cell.name)
        box = window_box(p.box)
        near = pya.Region(source.begin_shapes_rec_overlapping(index, box))
        cell.shapes(li).insert(near & pya.Region(box))
        cell.shapes(lw).insert(box)
        a, b = pya.Point(round(g.x1), round(g.y1)), pya.Point(round(g.x2), round(g.y2))
        cell.shapes(lg).insert(pya.Path([a, b], 0))
        cell.shapes(lg).insert(pya.Text("#%d %s cd=%.4g score=%.4g norm=%.4g tiebreak=%.4g"
                                        % (g.rank, g.type, g.cd * dbu, g.score * dbu, g.norm_score, g.tiebreak * dbu),
                                        pya.Trans(pya.Point(round(g.cx), round(g.cy)))))
        for m in p.markers:
            cell.shapes(lm).insert(pya.DBox(m[0] * dbu, m[1] * dbu, m[2] * dbu, m[3] * dbu))
    lib.end_changes()
    output.save(lib, path)
    return names
