"""Writing a selection Study: windows.csv, a windows layer, report-database items, stats.json."""
import csv

import pya

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
