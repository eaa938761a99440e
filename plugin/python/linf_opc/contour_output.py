"""The editor's printed contours: after a flow with a lithography model, the nominal printed
contour (dose 1, in focus, at the threshold the flow calibrated) inside each of the plan's first
windows, drawn as edges on L/216 so that a person sees where the layer prints thin or merges.

in:  the flow's input and folder (summary.json: the threshold), its values (-rd litho), the
     chosen selection run (its windows)
out: segments in DBU; add_layer draws them
"""
import json
import os
from array import array

import pya

from . import core
from . import layout
from . import litho
from . import progress
from .litho_report import GRID, contours_of, region_of
from .polygons import core_input

CONTOUR_DATATYPE = 216  # the editor's printed contours of the plan's windows
MASK_DATATYPE = 217     # with the OPC: the corrected layer inside those windows
CONTOUR_WINDOWS = 200   # windows simulated for the editor at most, the plan's first


def contour_edges(polygons, dbu_um, model, threshold, boxes, scale=1):
    """The nominal printed contour (dose 1, in focus, at `threshold`) inside each window box
    (x1, y1, x2, y2 in DBU), simulated at the box's centre: segments (x1, y1, x2, y2) in DBU, those
    of a window kept where their midpoint lies in its box and in the simulation's valid centre.
    `scale`: the polygons are in DBU / scale (the OPC's corrected layer, litho.opc_mask)."""
    if not boxes:
        return []
    dbu_nm = dbu_um * 1000.0
    P = model.kernels.period
    m = GRID
    lo, hi = m // 4, 3 * m // 4 + 1
    xs = [(b[0] + b[2]) / 2.0 for b in boxes]
    ys = [(b[1] + b[3]) / 2.0 for b in boxes]
    images = core.litho_window_images(core_input(polygons), dbu_nm / scale, [x * scale for x in xs],
                                      [y * scale for y in ys], model.kernels, m, blur=model.blur_nm)
    step = P / m / dbu_nm  # DBU a grid unit
    out = []
    for k, b in enumerate(boxes):
        progress.breathe(k, len(boxes))  # marching squares in Python: the editor's loop turns
        x0, y0 = xs[k] - P / 2 / dbu_nm, ys[k] - P / 2 / dbu_nm  # grid (0, 0)
        for a, c, d, e in contours_of(array("d", images[k]), m, lo, hi, threshold):
            seg = (x0 + a * step, y0 + c * step, x0 + d * step, y0 + e * step)
            mx, my = (seg[0] + seg[2]) / 2, (seg[1] + seg[3]) / 2
            if b[0] <= mx <= b[2] and b[1] <= my <= b[3]:
                out.append(seg)
    return out


def printed_contours(inp, values, chosen):
    """The nominal printed contours of the plan's first windows on the model the flow used, at
    the threshold it calibrated (summary.json): segments in DBU; with the OPC also the corrected
    layer inside those windows (pya.Polygons, rounded to the DBU), else None."""
    with open(os.path.join(inp.dir, "summary.json")) as f:
        lit = json.load(f)["gauges"]["litho"]
    threshold = lit["threshold"]
    boxes = [w[:4] for w in chosen.windows[:CONTOUR_WINDOWS]]
    model = litho.model_of(values)
    polygons, scale, mask = inp.polygons, 1, None
    if model.opc and boxes:
        # The flow read the layer after its OPC: corrected again here around the windows only,
        # a period beyond them (what lies farther moves a window's edges by nothing measurable).
        grow = model.kernels.period / (inp.dbu * 1000.0)
        around, inside = pya.Region(), pya.Region()
        for b in boxes:
            around.insert(pya.Box(int(b[0] - grow), int(b[1] - grow), int(b[2] + grow), int(b[3] + grow)))
            inside.insert(pya.Box(int(b[0]), int(b[1]), int(b[2]), int(b[3])))
        polygons, scale, _ = litho.opc_mask(layout.polygons_of(inp.region & around.merged()), inp.dbu * 1000.0, model,
                                            threshold, lit["calibration"]["width_nm"])
        mask = region_of(*polygons, scale) & inside.merged()
    return contour_edges(polygons, inp.dbu, model, threshold, boxes, scale), mask


def _cleared(ly, cell, layer, datatype, kind, name, drawing):
    """The shapes of L/kind, cleared, made with `name` when missing; None when it is missing and
    nothing is to be drawn (a run without them leaves no stale ones, and makes no empty layer)."""
    index = ly.find_layer(layer, kind)
    if index is None and not drawing:
        return None
    if index is None:
        index = ly.insert_layer(pya.LayerInfo(layer, kind, "%s %d/%d" % (name, layer, datatype)))
    shapes = cell.shapes(index)
    shapes.clear()
    return shapes


def add_layer(ly, cell, layer, datatype, model, segments):
    """The printed contours as edges on L/216, cleared first (also when this run has none)."""
    shapes = _cleared(ly, cell, layer, datatype, CONTOUR_DATATYPE, "printed contours (%s)" % model, bool(segments))
    for x1, y1, x2, y2 in segments:  # none when shapes is None
        shapes.insert(pya.Edge(round(x1), round(y1), round(x2), round(y2)))


def add_mask_layer(ly, cell, layer, datatype, model, mask):
    """The corrected layer inside the windows on L/217, cleared first (also when this run has
    none: a flow without the OPC leaves no stale mask)."""
    shapes = _cleared(ly, cell, layer, datatype, MASK_DATATYPE, "OPC-corrected layer (%s)" % model, mask is not None)
    if mask is not None:  # shapes is None only without a mask
        shapes.insert(mask)
