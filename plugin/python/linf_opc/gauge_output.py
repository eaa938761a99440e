"""Writing gauges: gauges.csv (micrometres), a gauge layer, a report database for the marker browser."""
import csv

import pya

from .gauges import TYPES

CSV_HEADER = ["id", "type", "x1", "y1", "x2", "y2", "cx", "cy", "cd", "score", "norm_score", "tiebreak", "rank"]

# The gauge layer sits on the input's layer number, datatype 210, next to the diagram's 200-203.
DATATYPE = 210

DESCRIPTIONS = {
    "internal": "width: the L-inf medial axis at its narrowest (score = width)",
    "external": "space between shapes or within one shape (score = space)",
    "sandwich": "a shape between two neighbours (score = 0.5 x distance between the neighbours' stretches)",
    "comb": "a base with two or more teeth on one side (score = 0.75 x tooth-to-base distance)",
    "T": "a base with one tooth on one side (score = 0.80 x tooth-to-base distance)",
}


def gauge_layer_info(layer, datatype):
    return pya.LayerInfo(layer, DATATYPE, "gauges (%d/%d)" % (layer, datatype))


def label(g, dbu):
    return "#%d %s %.4g" % (g.rank, g.type, g.cd * dbu)


def write_csv(gauges, path, dbu):
    with open(path, "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(CSV_HEADER)
        for g in gauges:
            um = ["%.6f" % (v * dbu) for v in (g.x1, g.y1, g.x2, g.y2, g.cx, g.cy, g.cd, g.score)]
            w.writerow([g.rank, g.type] + um + ["%.6f" % g.norm_score, "%.6f" % (g.tiebreak * dbu), g.rank])


def add_layer(layout, cell, gauges, layer, datatype):
    """Draws each measurement line (a zero-width path) and its rank text on the gauge layer,
    cleared first so that the action can be repeated. Returns the layer index."""
    info = gauge_layer_info(layer, datatype)
    index = layout.find_layer(info)
    if index is None:
        index = layout.insert_layer(info)
    shapes = cell.shapes(index)
    shapes.clear()
    for g in gauges:
        a, b = pya.Point(round(g.x1), round(g.y1)), pya.Point(round(g.x2), round(g.y2))
        shapes.insert(pya.Path([a, b], 0))
        shapes.insert(pya.Text(label(g, layout.dbu), pya.Trans(pya.Point(round(g.cx), round(g.cy)))))
    return index


def report(gauges, dbu, cell_name, source="", rdb=None):
    """Fills a report database (a new one unless given, e.g. the view's own) with one
    category per gauge type; each item holds the measurement line in micrometres and the
    named values score, norm_score, cd, tiebreak and rank."""
    if rdb is None:
        rdb = pya.ReportDatabase("gauges")
    rdb.generator = "linf_opc gauges"
    rdb.original_file = source
    rdb.top_cell_name = cell_name
    rcell = rdb.create_cell(cell_name)
    cats = {}
    for t in TYPES:
        cats[t] = rdb.create_category(t)
        cats[t].description = DESCRIPTIONS[t]
    tags = {k: rdb.user_tag_id(k) for k in ("score", "norm_score", "cd", "tiebreak", "rank")}
    for g in gauges:
        item = rdb.create_item(rcell.rdb_id(), cats[g.type].rdb_id())
        item.add_value(pya.DEdge(g.x1 * dbu, g.y1 * dbu, g.x2 * dbu, g.y2 * dbu))
        for k, v in (("score", g.score * dbu), ("norm_score", g.norm_score), ("cd", g.cd * dbu),
                     ("tiebreak", g.tiebreak * dbu), ("rank", float(g.rank))):
            value = pya.RdbItemValue(v)
            value.tag_id = tags[k]
            item.add_value(value)
    return rdb


def summary(result, dbu):
    ranges = result.score_ranges()
    return {
        "gauges": len(result.gauges),
        "counts": result.counts(),
        "score_range_um": {t: [round(lo * dbu, 9), round(hi * dbu, 9)] for t, (lo, hi) in ranges.items()},
        "stretches": result.stretches,
        "typical_width_um": round(result.typical_width * dbu, 9),
        "space_limit_um": round(result.space_limit * dbu, 9) if result.space_limit < float("inf") else None,
        "diagram": {k: result.diagram[k] for k in ("sites", "pieces", "counts", "tiles")},
        "check": {k: v for k, v in result.diagram["check"].items() if k != "messages"},
        "seconds": result.seconds,
    }
