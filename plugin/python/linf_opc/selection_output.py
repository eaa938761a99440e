"""Writing a selection Study: windows.csv, windows.oas, the windows layer in the editor's
layout, the report database's items, stats.json, report.html."""
import csv
import os
import re
import shutil
import tempfile
import time
from array import array
from xml.sax import saxutils

import pya

from . import output
from . import picture as layout_picture
from . import report as html_report
from . import report_db
from .progress import breathe
from .gauges import TYPES
from .selection import MODE_NAMES

CSV_HEADER = ["id", "x1", "y1", "x2", "y2", "gauge_id", "type", "score", "markers_covered"]

# The windows layer sits on the input's layer number, datatype 220, next to the gauges (210).
DATATYPE = 220


def window_layer_info(layer, datatype, run):
    return pya.LayerInfo(layer, DATATYPE, "windows %s %dx%d (%d/%d)" % (run.mode, run.size, run.size, layer, datatype))


def write_csv(run, gauges, path, dbu, classes=None):
    """One row per kept window, in gauge order; gauge_id is the gauge's rank in gauges.csv;
    markers_covered counts the markers this window covers first; pattern_class (with classes) is
    the window's class in pattern_classes.csv."""
    with open(path, "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(CSV_HEADER + (["pattern_class"] if classes else []))
        for i, (x1, y1, x2, y2, gi, ms) in enumerate(run.windows):
            g = gauges[gi]
            w.writerow([i + 1] + ["%.6f" % (v * dbu) for v in (x1, y1, x2, y2)] +
                       [g.rank, g.type, "%.6f" % (g.score * dbu), len(ms)] +
                       ([classes.of_window[i] + 1] if classes else []))


CLASSES_HEADER = ["class", "windows", "markers_covered", "representative", "x1", "y1", "x2", "y2", "gauge_id",
                   "type", "score"]


def write_classes_csv(classes, run, gauges, path, dbu):
    """One row per pattern class, in order of creation (its representative's gauge order): its windows,
    the markers they cover first, and the representative window (its id in windows.csv, its box
    and gauge)."""
    with open(path, "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(CLASSES_HEADER)
        for k in range(len(classes)):
            r = classes.representative[k]
            x1, y1, x2, y2, gi, _ = run.windows[r]
            g = gauges[gi]
            w.writerow([k + 1, classes.count[k], classes.markers[k], r + 1] +
                       ["%.6f" % (v * dbu) for v in (x1, y1, x2, y2)] + [g.rank, g.type, "%.6f" % (g.score * dbu)])


def window_boxes(run, dbu):
    """The run's windows on the DBU grid, as add_layer puts them into a layout: array('q')
    x1, y1, x2, y2 a window (windows.oas)."""
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


def _gauge_fields(gauges):
    """gauge index -> (rank, type, score) of `gauges`: read from a GaugeTable's columns (no record
    a gauge), else from its records."""
    columns = getattr(gauges, "columns", None)
    if columns is None:
        return lambda i: (gauges[i].rank, gauges[i].type, gauges[i].score)
    reals, ints = columns()
    return lambda i: (ints[13 * i], TYPES[ints[13 * i + 12]], reals[10 * i + 7])


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
        breathe()
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

    fields = _gauge_fields(gauges)
    runs = []
    for (mode, size), run in sorted(study.runs.items()):
        name = "%s %dx%d" % (mode, size, size)
        runs.append(category(name, "mode %s (%s), windows of %dx%d pitches (%.4g um)"
                             % (mode, MODE_NAMES[mode], size, size, run.side * dbu)))
        # A run's items share their tags and category: their head is made once.
        tags = ["mode_%s" % mode, "size_%d" % size]
        for t in tags:
            if t not in plain:
                plain.append(t)
        head = report_db.item_head(sorted(tags, key=plain.index), "patterns.%s" % _name(name), cell)
        for x1, y1, x2, y2, gi, ms in run.windows:
            breathe()
            rank, kind, score = fields(gi)
            items.write("%s    <value>%s</value>\n    <value>[#gauge_rank] float: %s</value>\n"
                        "    <value>[#type] text: %s</value>\n    <value>[#score] float: %s</value>\n"
                        "    <value>[#markers_covered] float: %s</value>\n%s"
                        % (head, box(x1, y1, x2, y2), _g(rank), kind, _g(score * dbu), _g(len(ms)), report_db.ITEM_END))
    cats = [category("patterns", "pattern windows around ranked gauges that cover the markers",
                     [indent(c, 2) for c in runs])]
    if markers is not None:
        cats.append(category("markers", "markers (%s)" % markers.source))
        for b in markers.boxes:
            item([], "markers", [box(*b)])
    if split is not None:
        user += ["norm_score", "set", "cd", "count"]
        cats.append(category("split", "calibration / verification split (%s)" % split.mode))
        for pt, which in zip(split.patterns, split.assign):
            g = pt.gauge
            item([which], "split", [box(*pt.box), "[#gauge_rank] float: %s" % _g(g.rank), "[#type] text: %s" % g.type,
                                    "[#score] float: %s" % _g(g.score * dbu),
                                    "[#norm_score] float: %s" % _g(g.norm_score), "[#set] text: %s" % which]
                 + ["[#%s] text: %s" % (k, esc(_quoted(v))) for k, v in split_readings(split, pt, dbu)])
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


def split_readings(split, p, dbu):
    """A split pattern's values for reading, as text: (("cd", "16 nm"),) and, for the plan,
    ("count", "2,400"): the layer's gauges of its gauge's type and context."""
    out = (("cd", "%.4g nm" % (p.gauge.cd * dbu * 1000)),)
    contexts = getattr(split, "contexts", None)
    if contexts is not None:
        out += (("count", format(contexts.count[contexts.key(p.index)], ",")),)
    return out


def _quoted(text):
    """A text value as KLayout writes it (tl::to_quoted_string)."""
    return "'%s'" % text.replace("\\", "\\\\").replace("'", "\\'")


def report_split(split, dbu, cell_name, rdb):
    """Category "split" with every pattern (its window, µm) tagged "calibration" or
    "verification", with the named values gauge_rank, type, score, norm_score, set and, as text
    for reading, cd in nm and (the plan) count."""
    rcell = rdb.cell_by_qname(cell_name) or rdb.create_cell(cell_name)
    cat = rdb.create_category("split")
    cat.description = "calibration / verification split (%s)" % split.mode
    tags = {k: rdb.user_tag_id(k) for k in ("gauge_rank", "type", "score", "norm_score", "set", "cd", "count")}
    for p, which in zip(split.patterns, split.assign):
        g = p.gauge
        item = rdb.create_item(rcell.rdb_id(), cat.rdb_id())
        x1, y1, x2, y2 = p.box
        item.add_value(pya.DBox(x1 * dbu, y1 * dbu, x2 * dbu, y2 * dbu))
        for k, v in (("gauge_rank", float(g.rank)), ("type", g.type), ("score", g.score * dbu),
                     ("norm_score", g.norm_score), ("set", which)) + split_readings(split, p, dbu):
            value = pya.RdbItemValue(v)
            value.tag_id = tags[k]
            item.add_value(value)
        item.add_tag(rdb.tag_id(which))


def write_selection(inp, sel, split=None):
    """windows.csv, windows.oas (the core), stats.json, report.html of the Input `inp` and the
    flow's Selected `sel` (the report database: write_windows_report); report.html shows the
    split too when it is a plan. Returns the stats."""
    t0 = time.perf_counter()
    classes = getattr(sel, "classes", None)
    write_csv(sel.chosen, sel.gauges, inp.file("windows.csv"), inp.dbu, classes)
    if classes:
        write_classes_csv(classes, sel.chosen, sel.gauges, inp.file("pattern_classes.csv"), inp.dbu)
    info = window_layer_info(inp.layer, inp.datatype, sel.chosen)
    output.write_by_core(inp.file("windows.oas"), None, inp.polygons, inp.layer, inp.datatype,
                         [(info.layer, info.datatype, info.name)], inp.dbu, inp.cell.name,
                         [(info.layer, info.datatype, window_boxes(sel.chosen, inp.dbu))])
    st = stats(sel.study, inp.dbu, sel.chosen, sel.similarity)
    st.update(input=inp.path, cell=inp.cell.name, layer=inp.name, gauges=len(sel.gauges), max_norm=sel.max_norm,
              marker_source=sel.markers.summary(), pitch_source="given" if sel.pitch_given else "estimated")
    st["seconds"].update(read=inp.t_read, gauges=sel.result.seconds["total"], halves=sel.t_halves)
    if classes:
        st["pattern_classes"] = classes.summary()
    chosen = sel.study.runs[(st["chosen"]["mode"], st["chosen"]["size"])]
    png = None
    if not html_report.svg_picture_fits(inp.polygons, chosen, sel.study.markers):
        png = layout_picture.picture(inp.polygons, inp.dbu, sel.study.markers, chosen.windows)
    plan = split if getattr(split, "mode", None) == "plan" else None
    extra = None
    if getattr(sel.result, "litho_model", None) is not None:  # -rd litho: the printed contours of the top contexts
        from . import litho_report
        table = sel.result.gauges
        # The pictures image the layer the scores read: after the OPC with -rd opc=1.
        extra = litho_report.section(table, inp.region, inp.polygons, inp.dbu, sel.result.litho_model,
                                     sel.result.litho_threshold, litho_report.rows_to_draw(table, plan),
                                     getattr(sel.result, "litho_mask", None))
    html_report.write(inp.file("report.html"), "Pattern selection: %s %s" % (os.path.basename(inp.path), inp.name),
                      st, sel.study, inp.polygons, inp.dbu, png, plan, extra)
    st["seconds"]["write"] = time.perf_counter() - t0
    output.write_json(st, inp.file("stats.json"))
    return st


def write_windows_report(inp, sel, split, generator, path):
    """The selection's (and the split's, if given) report database: every run's windows, the
    markers, the split's patterns."""
    write_report(path, sel.study, sel.gauges, inp.dbu, inp.cell.name, inp.path, generator, sel.markers, split)
