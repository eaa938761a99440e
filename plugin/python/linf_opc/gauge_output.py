"""Writing gauges: gauges.csv (micrometres), gauges.oas, the gauge layer in the editor's layout, the
report database for the marker browser (gauges.lyrdb, or the editor's own)."""
import contextlib
import time
from array import array
from xml.sax import saxutils

import pya

from . import core, drawing, report_db
from .gauges import TYPES, GaugeTable
from .output import copy_drawing, write_by_core
from .records import Subset

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


def write_csv_rows(gauges, path, dbu, rows=None, contexts=None, counts=None, litho=None):
    """gauges.csv of some gauges (the per-pattern mode's, a split set's), written by the core
    from the columns: `rows` of `gauges` (a GaugeTable or Gauge records) by index, in that order,
    all if None. Each line is the one the whole table's gauges.csv (gauges.compute's gauges_csv)
    holds for that gauge, its id and rank the gauge's rank in the table; with contexts and
    counts (array('Q'), one a row: a plan's), followed by the columns context and count; with
    `litho` (litho.LithoColumns of a table ranked by printability; a table's own by default),
    then by geo_score, printed_cd, pv_band, fails."""
    if litho is None:
        litho = getattr(gauges, "litho", None)
    if not isinstance(gauges, GaugeTable):
        gauges = GaugeTable.of(list(gauges) if rows is None else [gauges[i] for i in rows])
        rows = None
    if rows is None:
        rows = array("i", range(len(gauges)))
    if contexts is None:
        core.write_gauges_csv_rows(path, dbu, *gauges.columns(), rows)
    else:
        core.write_gauges_csv_rows(path, dbu, *gauges.columns(), rows, contexts, counts)
    if litho is not None:
        litho.append_to_csv(path, dbu)


def add_layer(layout, cell, gauges, layer, datatype):
    """Draws each measurement line (a zero-width path) and its rank text on the gauge layer,
    cleared first so that the action can be repeated, through a GDSII file (output.copy_drawing).
    Returns the layer index."""
    info = gauge_layer_info(layer, datatype)
    index = layout.find_layer(info)
    if index is None:
        index = layout.insert_layer(info)
    cell.shapes(index).clear()
    with drawn(gauges, layout.dbu, layer, cell.name) as path:
        copy_drawing(cell, path, {(layer, DATATYPE): index})
    return index


# The editor draws for reading: the representatives of the most critical (type, context)
# groups, each type on its own layer, short labels on a layer of their own (hidden at first).
EDITOR_DATATYPES = {t: DATATYPE + i for i, t in enumerate(TYPES)}  # 210-214
LABEL_DATATYPE = DATATYPE + len(TYPES)                             # 215
EDITOR_MAX = 1000
LETTERS = {"internal": "W", "external": "S", "sandwich": "SW", "comb": "C", "T": "T"}


def short_label(g, dbu, count):
    """What a CD-SEM engineer reads at a gauge: type letter (W width, S space, SW sandwich, C
    comb, T), cd in nm, and how often its context repeats on the layer: "W 16 nm ×2,400"."""
    return "%s %.4g nm \u00d7%s" % (LETTERS[g.type], g.cd * dbu * 1000, format(count, ","))


def label_box(x, y, text, height):
    """The box a label centred at (x, y) covers at its own height: 0.6 of the height a character."""
    w = 0.3 * height * len(text)
    return (x - w, y - height / 2.0, x + w, y + height / 2.0)


def _free(placed, box, cell):
    """True if `box` overlaps no box in `placed` (a dict of grid cells of side `cell` -> boxes),
    and then it is added."""
    cells = [(i, j) for i in range(int(box[0] // cell), int(box[2] // cell) + 1)
             for j in range(int(box[1] // cell), int(box[3] // cell) + 1)]
    for c in cells:
        for b in placed.get(c, ()):
            if box[0] < b[2] and b[0] < box[2] and box[1] < b[3] and b[1] < box[3]:
                return False
    for c in cells:
        placed.setdefault(c, []).append(box)
    return True


def add_representatives(layout, cell, gauges, contexts, layer, datatype, most=EDITOR_MAX, label_height=0):
    """Draws the representatives of the `most` best-ranked (type, context) groups (contexts:
    contexts.Contexts of `gauges`): each measurement line as a zero-width path on its type's
    layer, each label on the label layer; every layer cleared first. label_height > 0 (DBU): the
    labels have that size and a label is left out where it would overlap a better-ranked one at
    that size (labels that overprint are read by nobody). Returns the gauge indices drawn, rank
    order."""
    chosen = contexts.representatives[:most]
    targets = {}
    for t, dt in list(EDITOR_DATATYPES.items()) + [("labels", LABEL_DATATYPE)]:
        info = pya.LayerInfo(layer, dt, "gauges %s (%d/%d)" % (t, layer, datatype))
        index = layout.find_layer(layer, dt)
        if index is None:
            index = layout.insert_layer(info)
        cell.shapes(index).clear()
        targets[t] = cell.shapes(index)
    dbu = layout.dbu
    placed = {}
    for i in chosen:
        g = gauges[i]
        a, b = pya.Point(round(g.x1), round(g.y1)), pya.Point(round(g.x2), round(g.y2))
        targets[g.type].insert(pya.Path([a, b], 0))
        words = short_label(g, dbu, contexts.count[contexts.key(i)])
        x, y = round(g.cx), round(g.cy)
        if label_height > 0 and not _free(placed, label_box(x, y, words, label_height), 8 * label_height):
            continue
        text = pya.Text(words, pya.Trans(x, y))
        if label_height > 0:
            text.size = round(label_height)
            text.halign, text.valign = pya.HAlign.HAlignCenter, pya.VAlign.VAlignCenter
        targets["labels"].insert(text)
    return chosen


def _nm(um):
    """A length for reading: micrometres as nm, four significant digits ("16 nm", "12.5 nm")."""
    return "%.4g nm" % (um * 1000)


def _quoted(text):
    """A text value as KLayout's report database writes it (tl::to_quoted_string)."""
    return "'%s'" % text.replace("\\", "\\\\").replace("'", "\\'")


def write_drawn_report(gauges, contexts, drawn, dbu, cell_name, source, path):
    """The editor's report database: the gauges add_representatives drew (`drawn`, indices in
    rank order; `contexts` their contexts.Contexts), one category per type, each item the
    measurement line with the values a person reads, as text: rank (an integer), cd and score in
    nm, count (the layer's gauges of its type and context: "2,400 (3.1% of the layer's gauges)").
    User tags, undeclared, as write_report's. Written as a file and loaded once: a thousand
    items, where the layer's millions filled item by item froze the editor. Returns the number
    of items."""
    esc = saxutils.escape
    total = max(len(gauges), 1)
    with open(path, "w", encoding="utf-8") as f:
        w = f.write
        w(report_db.head(source, "linf_opc gauges (editor)", cell_name) + " <tags>\n </tags>\n <categories>\n")
        for t in TYPES:
            w("  <category>\n   <name>%s</name>\n   <description>%s</description>\n   <categories>\n"
              "   </categories>\n  </category>\n" % (t, esc("%s (%s): %s" % (t, LETTERS[t], DESCRIPTIONS[t]))))
        w(" </categories>\n" + report_db.cells(cell_name) + " <items>\n")
        cell = esc(cell_name)
        for i in drawn:
            g = gauges[i]
            n = contexts.count[contexts.key(i)]
            w(report_db.item_head([], g.type, cell))
            w("    <value>edge: (%.12g,%.12g;%.12g,%.12g)</value>\n" % (g.x1 * dbu, g.y1 * dbu, g.x2 * dbu, g.y2 * dbu))
            for name, text in (("rank", "%d" % g.rank), ("cd", _nm(g.cd * dbu)), ("score", _nm(g.score * dbu)),
                               ("count", "%s (%.2g%% of the layer's gauges)" % (format(n, ","), 100.0 * n / total))):
                w("    <value>[#%s] text: %s</value>\n" % (name, esc(_quoted(text))))
            w(report_db.ITEM_END)
        w(report_db.END)
    return len(drawn)


def write_oasis(path, gauges, polygons, layer, datatype, dbu, cell_name):
    """gauges.oas, written by the core (output.write_by_core): the input layer and the gauge
    layer as add_layer draws it."""
    with drawn(gauges, dbu, layer, cell_name) as gds:
        write_by_core(path, gds, polygons, layer, datatype,
                      [(layer, DATATYPE, gauge_layer_info(layer, datatype).name)], dbu, cell_name)


@contextlib.contextmanager
def drawn(gauges, dbu, layer, cell_name):
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


def write_report(gauges, dbu, cell_name, source, path, max_per_type=REPORT_MAX_PER_TYPE, tick=None):
    """The report database of report(), written directly as KLayout's XML: filled item by
    item through KLayout's API it costs ~50 us a gauge, minutes on a full layer. Loaded, it is
    the database report() fills (saved, the same bytes). The tags are not declared: KLayout
    loads declared tags as plain tags but "[#score]" values as user tags, which would give
    every name twice. tick(done, total) is called every few thousand items (progress.Progress.
    fraction). Returns the number of items written."""
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
        n = len(gauges)
        for i, g in enumerate(gauges):
            if tick and not i & 4095:
                tick(i, n)
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
        "diagram": {k: result.diagram[k] for k in ("sites", "pieces", "counts", "tiles", "builder")},
        "check": {k: v for k, v in result.diagram["check"].items() if k != "messages"},
        "seconds": result.seconds,
    }


def write_gauges(inp, result, gauges, cap, window=None, tick=None):
    """gauges.csv, gauges.lyrdb (the `cap` most critical gauges of each type, 0 all) and
    gauges.oas of the Input `inp`: `gauges` are result.gauges or, in the per-pattern mode, those
    of `window` (a box in DBU). tick: as write_report's. Returns the summary."""
    t0 = time.perf_counter()
    if not (gauges is result.gauges and result.csv_path == inp.file("gauges.csv")):  # else the core wrote it
        write_csv_rows(gauges, inp.file("gauges.csv"), inp.dbu, litho=getattr(result.gauges, "litho", None))
    in_report = write_report(gauges, inp.dbu, inp.cell.name, inp.path, inp.file("gauges.lyrdb"), cap, tick)
    write_oasis(inp.file("gauges.oas"), gauges, inp.polygons, inp.layer, inp.datatype, inp.dbu, inp.cell.name)
    s = layer_summary(inp, result, len(gauges), in_report, cap)
    if window is not None:
        s["window_um"] = [round(v * inp.dbu, 9) for v in window]
    s["seconds"]["write"] = time.perf_counter() - t0
    return s


def layer_summary(inp, result, written, in_report, cap):
    """The summary of the Input `inp`'s gauge stage, its files written or not: `written` gauges
    listed, `in_report` of them in the report database (`cap` a type)."""
    s = summary(result, inp.dbu)
    s.update(input=inp.path, cell=inp.cell.name, layer=inp.name, polygons=result.diagram["polygons"],
             dbu=round(inp.dbu, 12), written=written, report_items=in_report, report_max_per_type=cap)
    s["seconds"].update(read=inp.t_read)
    return s
