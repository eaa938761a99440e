"""Writing a selection Study: windows.csv, a windows layer, report-database items, stats.json."""
import csv
import re
import shutil
import tempfile
from array import array
from xml.sax import saxutils

import pya

from . import report_db
from .selection import MODE_NAMES

CSV_HEADER = ["id", "x1", "y1", "x2", "y2", "gauge_id", "type", "score", "markers_covered"]

# The windows layer sits on the input's layer number, datatype 220, next to the gauges (210).
DATATYPE = 220


def window_layer_info(layer, datatype, run):
    return pya.LayerInfo(layer, DATATYPE, "windows %s %dx%d (%d/%d)" % (run.mode, run.size, run.size, layer, datatype))


def write_csv(run, gauges, path, dbu):
    """One row per kept window, in gauge order; gauge_id is the gauge's rank in gauges.csv;
    markers_covered counts the markers this window covers first."""
    with open(path, "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(CSV_HEADER)
        for i, (x1, y1, x2, y2, gi, ms) in enumerate(run.windows):
            g = gauges[gi]
            w.writerow([i + 1] + ["%.6f" % (v * dbu) for v in (x1, y1, x2, y2)] +
                       [g.rank, g.type, "%.6f" % (g.score * dbu), len(ms)])


def window_boxes(run, dbu):
    """The run's windows on the DBU grid, as add_layer puts them into a layout: array('q')
    x1, y1, x2, y2 a window."""
    out = array("q")
    for x1, y1, x2, y2, gi, ms in run.windows:
        b = pya.DBox(x1 * dbu, y1 * dbu, x2 * dbu, y2 * dbu).to_itype(dbu)
        out.extend((b.left, b.bottom, b.right, b.top))
    return out


def add_layer(layout, cell, run, layer, datatype):
    """The run's windows as boxes on L/220, cleared first. Returns the layer index."""
    info = window_layer_info(layer, datatype, run)
    index = layout.find_layer(pya.LayerInfo(layer, DATATYPE))
    if index is None:
        index = layout.insert_layer(info)
    else:
        layout.set_info(index, info)
    shapes = cell.shapes(index)
    shapes.clear()
    for x1, y1, x2, y2, gi, ms in run.windows:
        shapes.insert(pya.DBox(x1 * layout.dbu, y1 * layout.dbu, x2 * layout.dbu, y2 * layout.dbu))
    return index


def report(study, gauges, dbu, cell_name, rdb, markers=None):
    """Adds category "patterns" with one sub-category per (mode, size), e.g. "A 7x7"; each item
    is a window (a box, µm) tagged mode_X and size_K, with the named values gauge_rank, type,
    score and markers_covered. Markers go to category "markers" when given."""
    rcell = rdb.cell_by_qname(cell_name) or rdb.create_cell(cell_name)
    top = rdb.category_by_path("patterns") or rdb.create_category("patterns")
    top.description = "pattern windows around ranked gauges that cover the markers"
    tags = {k: rdb.user_tag_id(k) for k in ("gauge_rank", "type", "score", "markers_covered")}
    for (mode, size), run in sorted(study.runs.items()):
        cat = rdb.create_category(top, "%s %dx%d" % (mode, size, size))
        cat.description = "mode %s (%s), windows of %dx%d pitches (%.4g um)" % (
            mode, MODE_NAMES[mode], size, size, run.side * dbu)
        for x1, y1, x2, y2, gi, ms in run.windows:
            g = gauges[gi]
            item = rdb.create_item(rcell.rdb_id(), cat.rdb_id())
            item.add_value(pya.DBox(x1 * dbu, y1 * dbu, x2 * dbu, y2 * dbu))
            for k, v in (("gauge_rank", float(g.rank)), ("type", g.type), ("score", g.score * dbu),
                         ("markers_covered", float(len(ms)))):
                value = pya.RdbItemValue(v)
                value.tag_id = tags[k]
                item.add_value(value)
            item.add_tag(rdb.tag_id("mode_%s" % mode))
            item.add_tag(rdb.tag_id("size_%d" % size))
    if markers is not None:
        cat = rdb.category_by_path("markers") or rdb.create_category("markers")
        cat.description = "markers (%s)" % markers.source
        for x1, y1, x2, y2 in markers.boxes:
            item = rdb.create_item(rcell.rdb_id(), cat.rdb_id())
            item.add_value(pya.DBox(x1 * dbu, y1 * dbu, x2 * dbu, y2 * dbu))
    return rdb


def _g(v):
    """A number as KLayout writes it in a report database."""
    return "%.12g" % v


def _name(n):
    """A category name in an item's category path: quoted unless it is a plain word."""
    return n if re.fullmatch(r"[A-Za-z0-9_]+", n) else "'%s'" % n.replace("\\", "\\\\").replace("'", "\\'")


def write_report(path, study, gauges, dbu, cell_name, source, generator, markers=None, split=None):
    """The report database report() and report_split() fill in a new database, written directly
    as KLayout saves it (tested: the same bytes): through KLayout's API each item cost ~50 us,
    seconds on a layer with thousands of markers. The items go to a temporary file first, as the
    tags they use come before them in the file (a full layer's items are hundreds of MB)."""
    with tempfile.TemporaryFile("w+", encoding="utf-8") as items:
        _write_report(path, items, study, gauges, dbu, cell_name, source, generator, markers, split)


def _write_report(path, items, study, gauges, dbu, cell_name, source, generator, markers, split):
    esc = saxutils.escape
    user = ["gauge_rank", "type", "score", "markers_covered"]
    plain = []
    cell = esc(cell_name)

    def item(tags, category, values):
        for t in tags:
            if t not in plain:
                plain.append(t)
        # KLayout lists an item's tags in the order the tags were made.
        tags = sorted(tags, key=plain.index)
        items.write(report_db.item_head(tags, category, cell) + "".join("    <value>%s</value>\n" % v for v in values)
                    + report_db.ITEM_END)

    def box(x1, y1, x2, y2):
        return "box: (%s,%s;%s,%s)" % (_g(x1 * dbu), _g(y1 * dbu), _g(x2 * dbu), _g(y2 * dbu))

    def category(name, description, children=()):
        inner = "".join(children)
        return ("<category>\n <name>%s</name>\n <description>%s</description>\n <categories>\n%s </categories>\n"
                "</category>\n" % (esc(name), esc(description), inner))

    def indent(text, n):
        return "".join(" " * n + line + "\n" for line in text.splitlines())

    runs = []
    for (mode, size), run in sorted(study.runs.items()):
        name = "%s %dx%d" % (mode, size, size)
        runs.append(category(name, "mode %s (%s), windows of %dx%d pitches (%.4g um)"
                             % (mode, MODE_NAMES[mode], size, size, run.side * dbu)))
        for x1, y1, x2, y2, gi, ms in run.windows:
            g = gauges[gi]
            item(["mode_%s" % mode, "size_%d" % size], "patterns.%s" % _name(name),
                 [box(x1, y1, x2, y2), "[#gauge_rank] float: %s" % _g(g.rank), "[#type] text: %s" % g.type,
                  "[#score] float: %s" % _g(g.score * dbu), "[#markers_covered] float: %s" % _g(len(ms))])
    cats = [category("patterns", "pattern windows around ranked gauges that cover the markers",
                     [indent(c, 2) for c in runs])]
    if markers is not None:
        cats.append(category("markers", "markers (%s)" % markers.source))
        for b in markers.boxes:
            item([], "markers", [box(*b)])
    if split is not None:
        user += ["norm_score", "set"]
        cats.append(category("split", "calibration / verification split (%s)" % split.mode))
        for pt, which in zip(split.patterns, split.assign):
            g = pt.gauge
            item([which], "split", [box(*pt.box), "[#gauge_rank] float: %s" % _g(g.rank), "[#type] text: %s" % g.type,
                                    "[#score] float: %s" % _g(g.score * dbu),
                                    "[#norm_score] float: %s" % _g(g.norm_score), "[#set] text: %s" % which])
    tags = user[:4] + [t for t in plain if t.startswith(("mode_", "size_"))] + user[4:] + \
        [t for t in plain if not t.startswith(("mode_", "size_"))]
    with open(path, "w", encoding="utf-8") as f:
        f.write(report_db.head(source, generator, cell_name) + " <tags>\n")
        f.writelines(report_db.tag(t) for t in tags)
        f.write(" </tags>\n <categories>\n%s </categories>\n" % "".join(indent(c, 2) for c in cats))
        f.write(report_db.cells(cell_name) + " <items>\n")
        items.seek(0)
        shutil.copyfileobj(items, f)
        f.write(report_db.END)


def stats(study, dbu, chosen, similarity=None):
    """Everything of Tables 5.2-5.9 as plain data."""
    out = {
        "pitch_um": round(study.pitch * dbu, 6),
        "markers": len(study.markers),
        "coverage": [r.row(dbu) for _, r in sorted(study.runs.items())],
        "distribution": {"%s %dx%d" % (m, k, k): r.distribution() for (m, k), r in sorted(study.runs.items())},
        "heuristic": {"%dx%d" % (k, k): h for k, h in sorted(study.heuristic.items())},
        "representatives": {"%s %dx%d" % (m, k, k): r.representatives() for (m, k), r in sorted(study.runs.items())},
        "chosen": {"mode": chosen.mode, "size": chosen.size, "windows": len(chosen.windows)},
        "seconds": {"selection_total": study.seconds,
                    "per_run": {"%s %dx%d" % (m, k, k): r.seconds for (m, k), r in sorted(study.runs.items())}},
    }
    if similarity is not None:
        out["similarity"] = similarity
    return out


def report_split(split, dbu, cell_name, rdb):
    """Category "split" with every pattern (its window, µm) tagged "calibration" or
    "verification", with the named values gauge_rank, type, score, norm_score and set."""
    rcell = rdb.cell_by_qname(cell_name) or rdb.create_cell(cell_name)
    cat = rdb.create_category("split")
    cat.description = "calibration / verification split (%s)" % split.mode
    tags = {k: rdb.user_tag_id(k) for k in ("gauge_rank", "type", "score", "norm_score", "set")}
    for p, which in zip(split.patterns, split.assign):
        g = p.gauge
        item = rdb.create_item(rcell.rdb_id(), cat.rdb_id())
        x1, y1, x2, y2 = p.box
        item.add_value(pya.DBox(x1 * dbu, y1 * dbu, x2 * dbu, y2 * dbu))
        for k, v in (("gauge_rank", float(g.rank)), ("type", g.type), ("score", g.score * dbu),
                     ("norm_score", g.norm_score), ("set", which)):
            value = pya.RdbItemValue(v)
            value.tag_id = tags[k]
            item.add_value(value)
        item.add_tag(rdb.tag_id(which))
