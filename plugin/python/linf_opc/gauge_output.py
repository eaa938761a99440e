"""Writing gauges: gauges.csv (micrometres), a gauge layer, a report database for the marker browser."""
import contextlib
import csv
from array import array
from xml.sax import saxutils

import pya

from . import core, drawing, report_db
from .gauges import TYPES, GaugeTable
from .output import copy_drawing, write_by_core
from .records import Subset

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
    """The gauge's text on the gauge layer (the core writes the same, see write_gauges_gds)."""
    return "#%d %s %.4g" % (g.rank, g.type, g.cd * dbu)


def write_csv(gauges, path, dbu):
    """gauges.csv row by row (the core's write_gauges_csv writes the same bytes, faster: batch
    runs over a whole layer ask the core to write it; this one writes subsets)."""
    with open(path, "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(CSV_HEADER)
        for g in gauges:
            um = ["%.6f" % (v * dbu) for v in (g.x1, g.y1, g.x2, g.y2, g.cx, g.cy, g.cd, g.score)]
            w.writerow([g.rank, g.type] + um + ["%.6f" % g.norm_score, "%.6f" % (g.tiebreak * dbu), g.rank])


def add_layer(layout, cell, gauges, layer, datatype, direct=False):
    """Draws each measurement line (a zero-width path) and its rank text on the gauge layer,
    cleared first so that the action can be repeated, through a GDSII file (output.copy_drawing,
    also for `direct`).
    Returns the layer index."""
    info = gauge_layer_info(layer, datatype)
    index = layout.find_layer(info)
    if index is None:
        index = layout.insert_layer(info)
    cell.shapes(index).clear()
    with _drawing(gauges, layout.dbu, layer, cell.name) as path:
        copy_drawing(cell, path, {(layer, DATATYPE): index}, direct)
    return index


def write_oasis(path, gauges, polygons, layer, datatype, dbu, cell_name):
    """gauges.oas for a layer of millions of gauges, written by the core (output.write_by_core):
    the input layer and the gauge layer as add_layer draws it."""
    with _drawing(gauges, dbu, layer, cell_name) as gds:
        write_by_core(path, gds, polygons, layer, datatype,
                      [(layer, DATATYPE, gauge_layer_info(layer, datatype).name)], dbu, cell_name)


@contextlib.contextmanager
def _drawing(gauges, dbu, layer, cell_name):
    """The gauge layer (lines and labels) as a temporary GDSII file the core writes, removed after."""
    table = gauges if isinstance(gauges, GaugeTable) else GaugeTable.of(gauges)
    path = drawing.temporary()
    try:
        core.write_gauges_gds(path, dbu, layer, DATATYPE, *table.columns(), cell=cell_name)
        yield path
    finally:
        drawing.remove(path)


# A marker browser is for reading: as a DRC deck's maximum results per check, the report
# database holds the most critical gauges of each type, gauges.csv and the gauge layer all.
REPORT_MAX_PER_TYPE = 100000


def most_critical(gauges, max_per_type):
    """The first max_per_type gauges of each type, in rank order (all if max_per_type is 0)."""
    if not max_per_type:
        return gauges
    types = gauges.type_indices() if isinstance(gauges, GaugeTable) else [TYPES.index(g.type) for g in gauges]
    picked, seen = array("i"), [0] * len(TYPES)
    for i, k in enumerate(types):
        if seen[k] < max_per_type:
            seen[k] += 1
            picked.append(i)
    return gauges if len(picked) == len(gauges) else Subset(gauges, picked)


def report(gauges, dbu, cell_name, source="", rdb=None, max_per_type=REPORT_MAX_PER_TYPE):
    """Fills a report database (a new one unless given, e.g. the view's own) with one
    category per gauge type holding its max_per_type most critical gauges (0: all); each item
    holds the measurement line in micrometres and the named values score, norm_score, cd,
    tiebreak and rank."""
    gauges = most_critical(gauges, max_per_type)
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


def write_report(gauges, dbu, cell_name, source, path, max_per_type=REPORT_MAX_PER_TYPE):
    """The report database of report(), written directly as KLayout's XML: filled item by
    item through KLayout's API it costs ~50 us a gauge, minutes on a full layer. Loaded, it is
    the database report() fills (saved, the same bytes). The tags are not declared: KLayout
    loads declared tags as plain tags but "[#score]" values as user tags, which would give
    every name twice. Returns the number of items written."""
    gauges = most_critical(gauges, max_per_type)
    esc = saxutils.escape
    with open(path, "w", encoding="utf-8") as f:
        w = f.write
        w(report_db.head(source, "linf_opc gauges", cell_name) + " <tags>\n </tags>\n <categories>\n")
        for t in TYPES:
            w("  <category>\n   <name>%s</name>\n   <description>%s</description>\n   <categories>\n"
              "   </categories>\n  </category>\n" % (t, esc(DESCRIPTIONS[t])))
        w(" </categories>\n" + report_db.cells(cell_name) + " <items>\n")
        item = (report_db.item_head([], "%s", esc(cell_name).replace("%", "%%")) +
                "    <value>edge: (%.12g,%.12g;%.12g,%.12g)</value>\n"
                "    <value>[#score] float: %.12g</value>\n    <value>[#norm_score] float: %.12g</value>\n"
                "    <value>[#cd] float: %.12g</value>\n    <value>[#tiebreak] float: %.12g</value>\n"
                "    <value>[#rank] float: %.12g</value>\n" + report_db.ITEM_END)
        for g in gauges:
            w(item % (g.type, g.x1 * dbu, g.y1 * dbu, g.x2 * dbu, g.y2 * dbu, g.score * dbu, g.norm_score,
                      g.cd * dbu, g.tiebreak * dbu, float(g.rank)))
        w(report_db.END)
    return len(gauges)


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
