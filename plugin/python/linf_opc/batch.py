"""The batch entry point behind macros/linf_opc.py.

  klayout -b -r macros/linf_opc.py -rd cmd=COMMAND -rd input=FILE -rd layer=L/D [-rd cell=NAME] -rd out=DIR
           [-rd tile=UM|0|auto]  (the diagram builder's tiles; every output is the same for any size)
  voronoi  the diagram: voronoi.csv, voronoi.oas, summary.json
  gauges   [-rd window=X1,Y1,X2,Y2] (um: the per-pattern mode) [-rd rdb_max=100000] (gauges.lyrdb holds the
           most critical rdb_max of each type, 0 all): gauges.csv, gauges.lyrdb, gauges.oas, summary.json
  select   -rd markers=SPEC [-rd sizes=5,6,7,8] [-rd modes=A,B,C] [-rd mode=A] [-rd size=K] [-rd pitch=UM]
           [-rd max_norm=1] [-rd halves=0|1]: windows.csv, windows.lyrdb, windows.oas, stats.json, report.html
  split    the select arguments and [-rd split=stratified|threshold] [-rd fraction=0.3] [-rd seed=1]
           [-rd threshold=0.1] [-rd bin=0.025]: the select outputs, calibration.oas, verification.oas,
           calibration_gauges.csv, verification_gauges.csv, split.json (windows.lyrdb items tagged)
  flow     voronoi -> gauges -> select -> split in one run, every output above, summary.json
  farthest [-rd box=X1,Y1,X2,Y2] (um: shapes meeting the box): farthest.csv, farthest.oas, summary.json

Each command is a function of the parsed arguments returning a short summary line; the stages
are the same functions the editor's menu calls.
"""
import os
import shutil
import sys
import tempfile
import time
from array import array
from collections import namedtuple

import pya

from . import clips
from . import diagram as diagram_stage
from . import farthest as farthest_stage
from . import gauge_output
from . import glp
from . import gauges as gauge_stage
from . import layout as layer_io
from . import markers as marker_io
from . import output
from . import picture as layout_picture
from . import polygons as polygons_io
from . import report as html_report
from . import report_db
from . import selection as selection_stage
from . import selection_output
from . import split as split_stage


class UsageError(Exception):
    pass


def load(args):
    """Reads input/cell/layer; returns (layout, cell, layer index, (L, D))."""
    path = args.get("input")
    if not path:
        raise UsageError("missing -rd input=FILE")
    if not os.path.isfile(path):
        raise UsageError("input file not found: %s" % path)
    layer, datatype = layer_io.parse_layer(args.get("layer") or "")
    try:
        ly = layer_io.read_layout(path, only_layers([(layer, datatype), marker_io.layer_of(args.get("markers"))]))
    except glp.GlpError as e:
        raise UsageError("cannot read %s" % e)
    except RuntimeError as e:
        raise UsageError("cannot read %s: %s" % (path, str(e).splitlines()[0]))
    for i in list(ly.layer_indexes()):  # a layer the map made that the file does not have
        if all(c.shapes(i).is_empty() for c in ly.each_cell()):
            ly.delete_layer(i)
    name = args.get("cell")
    if name:
        cell = ly.cell(name)
        if cell is None:
            raise UsageError("no cell named %r in %s" % (name, path))
    else:
        tops = ly.top_cells()
        if len(tops) != 1:
            raise UsageError("%s has %d top cells; choose one with -rd cell=NAME" % (path, len(tops)))
        cell = tops[0]
    index = ly.find_layer(layer, datatype)
    if index is None:
        raise UsageError("layer %d/%d is not in %s" % (layer, datatype, path))
    return ly, cell, index, (layer, datatype)


def only_layers(layers):
    """Reading options for the given (L, D) layers only (None entries ignored): a design file
    holds dozens of layers, and a command needs its layer and perhaps a marker layer."""
    opt = pya.LoadLayoutOptions()
    lm = pya.LayerMap()
    for i, ld in enumerate(x for x in layers if x is not None):
        lm.map(pya.LayerInfo(*ld), i)
    opt.layer_map = lm
    opt.create_other_layers = False
    return opt


def out_dir(args):
    d = args.get("out")
    if not d:
        raise UsageError("missing -rd out=DIR")
    try:
        os.makedirs(d, exist_ok=True)
    except OSError as e:
        raise UsageError("cannot create the output folder %s: %s" % (d, e.strerror))
    return d


class Staging:
    """Output files are written into a hidden folder inside the output folder and moved into
    place only when the whole command has succeeded: a failed or interrupted run leaves no
    half-written file behind (and the files of an earlier run stay as they were)."""
    open_ones = []

    def __init__(self, out):
        self.final = os.path.abspath(out_dir({"out": out}))
        try:
            self.dir = tempfile.mkdtemp(prefix=".linf_opc-partial-", dir=self.final)
        except OSError as e:
            raise UsageError("cannot write into the output folder %s: %s" % (self.final, e.strerror))
        Staging.open_ones.append(self)

    def file(self, name):
        return os.path.join(self.dir, name)

    def commit(self):
        for name in sorted(os.listdir(self.dir)):
            os.replace(os.path.join(self.dir, name), os.path.join(self.final, name))
        self.abort()

    def abort(self):
        shutil.rmtree(self.dir, ignore_errors=True)
        if self in Staging.open_ones:
            Staging.open_ones.remove(self)

    @classmethod
    def finish_all(cls, ok):
        for st in list(cls.open_ones):
            st.commit() if ok else st.abort()


class Input:
    """The layer to work on: layout, cell, layer, its region and polygons (as drawn: the core
    merges them), the out dir. The batch builds it from its arguments (from_args), the editor from the current view."""
    def __init__(self, ly, cell, index, path, out, tile=-1):
        self.ly, self.cell, self.index = ly, cell, index
        self.tile = tile  # the builder's tile side in DBU, 0 one tile, -1 automatic
        info = ly.get_info(index)
        self.layer, self.datatype = info.layer, info.datatype
        self.path = os.path.abspath(path) if path else ""
        self.out = Staging(out)
        self.dir = self.out.final  # where the files end up (named in messages)
        t0 = time.perf_counter()
        self.region = layer_io.region_of(self.cell, self.index)
        self.polygons = layer_io.polygons_of(self.region, polygons_io.SPILL_SHAPES)
        if not self.polygons:
            raise UsageError("layer %d/%d is empty in cell %s" % (self.layer, self.datatype, self.cell.name))
        self.t_read = time.perf_counter() - t0
        self.dbu = self.ly.dbu
        self.name = "%d/%d" % (self.layer, self.datatype)

    @classmethod
    def from_args(cls, args):
        ly, cell, index, _ = load(args)
        if not args.get("out"):
            raise UsageError("missing -rd out=DIR")
        return cls(ly, cell, index, args["input"], args["out"], parse_tile(args.get("tile"), ly.dbu))

    def file(self, name):
        return self.out.file(name)

    def result_layout(self):
        """A layout with one top cell holding the merged input layer, to add result layers to."""
        res = pya.Layout()
        res.dbu = self.dbu
        top = res.create_cell(self.cell.name)
        top.shapes(res.insert_layer(pya.LayerInfo(self.layer, self.datatype))).insert(self.region)
        return res, top


def parse_tile(text, dbu):
    """-rd tile=UM (the builder's tile side in micrometres), 0 (one tile) or auto (default)."""
    if text in (None, "", "auto"):
        return -1
    try:
        v = float(text)
    except ValueError:
        raise UsageError("tile must be a size in micrometres, 0 or auto, not %r" % text)
    if v < 0:
        raise UsageError("tile must not be negative: %r" % text)
    return v / dbu


def parse_window(text, dbu):
    """'x1,y1,x2,y2' in micrometres -> a box in DBU."""
    try:
        x1, y1, x2, y2 = (float(v) / dbu for v in text.split(","))
    except ValueError:
        raise UsageError("window must be x1,y1,x2,y2 in micrometres, not %r" % text)
    return min(x1, x2), min(y1, y2), max(x1, x2), max(y1, y2)


def write_voronoi(inp, diagram):
    t0 = time.perf_counter()
    output.write_csv(diagram, inp.file("voronoi.csv"), inp.dbu)
    if output.needs_core_writer(diagram.n_pieces + len(inp.polygons)):
        names = [(inp.layer, output.DATATYPE_BASE + i, output.diagram_layer_info(inp.layer, inp.datatype, k).name)
                 for i, k in enumerate(diagram_stage.KINDS)]
        output.write_by_core(inp.file("voronoi.oas"), diagram.gds_path, inp.polygons, inp.layer, inp.datatype,
                             names, inp.dbu, inp.cell.name)
        drawn = {k: diagram.drawn[k] for k in diagram_stage.KINDS}
    else:
        res, top = inp.result_layout()
        drawn = output.add_layers(res, top, diagram, inp.layer, inp.datatype, direct=True)
        output.save(res, inp.file("voronoi.oas"))
    s = output.summary(diagram, inp.dbu, input=inp.path, cell=inp.cell.name, layer=inp.name,
                       polygons=diagram.polygons, drawn=drawn)
    s["seconds"].update(read=inp.t_read, write=time.perf_counter() - t0)
    return s


def voronoi_line(s, d):
    c = s["counts"]
    return ("voronoi: %d polygons, %d sites -> %d pieces (internal %d, external %d, notch %d, adjacent %d), "
            "checked, %.2f s; outputs in %s" % (s["polygons"], s["sites"], s["pieces"], c["internal"],
                                               c["external"], c["notch"], c["adjacent"], s["seconds"]["total"],
                                               os.path.abspath(d)))


def report_max(args):
    """-rd rdb_max=N: the report database's gauges per type, the most critical (0: all)."""
    text = args.get("rdb_max")
    if text in (None, ""):
        return gauge_output.REPORT_MAX_PER_TYPE
    try:
        n = int(text)
    except ValueError:
        n = -1
    if n < 0:
        raise UsageError("rdb_max must be a count of gauges per type (0: all), not %r" % text)
    return n


def write_gauges(inp, result, gauges, args, window=None):
    t0 = time.perf_counter()
    if not (gauges is result.gauges and result.csv_path == inp.file("gauges.csv")):  # else the core wrote it
        gauge_output.write_csv(gauges, inp.file("gauges.csv"), inp.dbu)
    cap = report_max(args)
    in_report = gauge_output.write_report(gauges, inp.dbu, inp.cell.name, inp.path, inp.file("gauges.lyrdb"), cap)
    if output.needs_core_writer(2 * len(gauges) + len(inp.polygons)):
        gauge_output.write_oasis(inp.file("gauges.oas"), gauges, inp.polygons, inp.layer, inp.datatype, inp.dbu,
                                 inp.cell.name)
    else:
        res, top = inp.result_layout()
        gauge_output.add_layer(res, top, gauges, inp.layer, inp.datatype, direct=True)
        output.save(res, inp.file("gauges.oas"))
    s = gauge_output.summary(result, inp.dbu)
    s.update(input=inp.path, cell=inp.cell.name, layer=inp.name, polygons=result.diagram["polygons"],
             dbu=round(inp.dbu, 12), written=len(gauges), report_items=in_report, report_max_per_type=cap)
    if window is not None:
        s["window_um"] = [round(v * inp.dbu, 9) for v in window]
    s["seconds"].update(read=inp.t_read, write=time.perf_counter() - t0)
    return s


def gauges_line(s, gauges, dbu, d):
    c = s["counts"]
    best = ", ".join("%s %s" % (g.type, "%.4g" % (g.cd * dbu)) for g in gauges[:3])
    return ("gauges: %d polygons -> %d gauges (internal %d, external %d, sandwich %d, comb %d, T %d)%s; "
            "most critical: %s; %.2f s; outputs in %s"
            % (s["polygons"], s["gauges"], c["internal"], c["external"], c["sandwich"], c["comb"], c["T"],
               "" if "window_um" not in s else ", %d in the window" % s["written"], best or "none",
               s["seconds"]["total"], os.path.abspath(d)))


def cmd_voronoi(args):
    inp = Input.from_args(args)
    s = write_voronoi(inp, diagram_stage.compute(inp.polygons, tile=inp.tile, csv_path=inp.file("voronoi.csv"),
                                                 dbu=inp.dbu, with_pieces=False, draw_layer=inp.layer,
                                                 draw_cell=inp.cell.name))
    output.write_json(s, inp.file("summary.json"))
    return voronoi_line(s, inp.dir)


def cmd_gauges(args):
    inp = Input.from_args(args)
    window = parse_window(args["window"], inp.dbu) if args.get("window") else None
    result = gauge_stage.compute(inp.polygons, tile=inp.tile, dbu=inp.dbu,
                                 gauges_csv=inp.file("gauges.csv") if window is None else None)
    gauges = result.gauges if window is None else gauge_stage.most_critical_in(result.gauges, window)
    s = write_gauges(inp, result, gauges, args, window)
    output.write_json(s, inp.file("summary.json"))
    return gauges_line(s, gauges, inp.dbu, inp.dir)


def _ints(text, name):
    try:
        v = [int(x) for x in text.split(",")]
    except ValueError:
        raise UsageError("%s must be a comma-separated list of integers, not %r" % (name, text))
    if not v or min(v) <= 0:
        raise UsageError("%s must be positive" % name)
    return v


def select_args(args, dbu):
    """(sizes, modes, chosen mode, chosen size or None, pitch in DBU or None, halves)."""
    sizes = _ints(args.get("sizes") or "5,6,7,8", "sizes")
    modes = [m.strip().upper() for m in (args.get("modes") or "A,B,C").split(",")]
    if any(m not in selection_stage.MODES for m in modes):
        raise UsageError("modes must be among A, B, C, not %r" % args.get("modes"))
    mode = (args.get("mode") or modes[0]).upper()
    if mode not in modes:
        raise UsageError("mode %s is not among the evaluated modes %s" % (mode, ",".join(modes)))
    size = _ints(args["size"], "size")[0] if args.get("size") else None
    if size is not None and size not in sizes:
        raise UsageError("size %d is not among the evaluated sizes %s" % (size, ",".join(map(str, sizes))))
    pitch = None
    if args.get("pitch"):
        try:
            pitch = float(args["pitch"]) / dbu
        except ValueError:
            raise UsageError("pitch must be a number in micrometres, not %r" % args["pitch"])
        if pitch <= 0:
            raise UsageError("pitch must be positive")
    halves = (args.get("halves") or "1") not in ("0", "false", "no")
    return sizes, modes, mode, size, pitch, halves


def halves_similarity(inp, markers, pitch, size):
    """Table 5.9's experiment: the layer cut at the x-midpoint of its extent into two layouts,
    each with its own gauges and the markers whose centre lies on its side; mode A windows of
    `size` pitches; classes on a common normalisation (the highest score of both halves).
    Both halves are read in one pass over the layer (spilled when large), each polygon across
    the cut clipped alone, and their gauges computed one half at a time: on a layer of millions
    of shapes each half is a whole gauge stage of its own."""
    box = inp.region.bbox()
    xm = (box.left + box.right) // 2
    halves = list(layer_io.halves_of(inp.region, xm, polygons_io.SPILL_SHAPES))
    used = []  # (type indices, scores) of each half's used gauges
    for i in range(2):
        ms = [m for m in markers if ((m[0] + m[2]) / 2 < xm) == (i == 0)]
        polys, halves[i] = halves[i], None  # dropped once its gauges are made
        if not polys or not ms:
            used.append((array("B"), array("d")))
            continue
        gs = gauge_stage.compute(polys, tile=inp.tile).gauges
        del polys
        run = selection_stage.study(gs, ms, pitch, sizes=(size,), modes=("A",)).runs[("A", size)]
        used.append(run.used_types_scores())
        del gs, run
    top = max([max(scores) for _, scores in used if scores] or [1.0])
    c1, c2 = (selection_stage.classes((TypeScore(gauge_stage.TYPES[t], s) for t, s in zip(*u)),
                                      norm=lambda g: g.score / top) for u in used)
    n1 = {(t, s): n for t, s, n in c1}
    n2 = {(t, s): n for t, s, n in c2}
    keys = sorted(set(n1) | set(n2), key=lambda k: (k[0], k[1]))
    return {"x_split_um": round(xm * inp.dbu, 6), "mode": "A", "size": size,
            "classes": [[t, s, n1.get((t, s), 0), n2.get((t, s), 0)] for t, s in keys],
            "N_t1": sum(n1.values()), "N_t2": sum(n2.values()),
            "S_12": round(selection_stage.similarity(c1, c2), 4)}


TypeScore = namedtuple("TypeScore", "type score")  # what classes() reads of a gauge


class Selected:
    """What the selection produced, for writing and for the split."""
    def __init__(self, inp, args, result):
        sizes, modes, mode, size, pitch, halves = select_args(args, inp.dbu)
        try:
            self.markers = marker_io.load(args.get("markers"), inp.ly, inp.cell)
        except marker_io.MarkerError as e:
            raise UsageError(str(e))
        if not self.markers.boxes:
            raise UsageError("no markers in %s" % self.markers.source)
        try:
            self.max_norm = float(args.get("max_norm") or 1)
        except ValueError:
            raise UsageError("max_norm must be a number, not %r" % args["max_norm"])
        # Only gauges at most this critical (normalised score) open windows; 1 = every gauge.
        # Normalised scores are at most 1, so max_norm >= 1 keeps the table itself (a list of
        # every gauge would be most of the run's memory on a large layer).
        self.gauges = (result.gauges if self.max_norm >= 1 else
                       [g for g in result.gauges if g.norm_score <= self.max_norm + 1e-12])
        if not self.gauges:
            raise UsageError("no gauge has a normalised score at or below max_norm=%g" % self.max_norm)
        self.pitch_given = pitch is not None
        if pitch is None:
            pitch = selection_stage.pitch_of(result.gauges)
            if pitch <= 0:
                raise UsageError("cannot estimate the pitch of layer %s: give -rd pitch=UM" % inp.name)
        self.pitch = pitch
        self.study = selection_stage.study(self.gauges, self.markers.boxes, pitch, sizes, modes)
        self.chosen = self.study.runs[(mode, size)] if size else self.study.best(mode)
        t0 = time.perf_counter()
        self.similarity = (halves_similarity(inp, self.markers.boxes, pitch, 7 if 7 in sizes else sizes[-1])
                           if halves else None)
        self.t_halves = time.perf_counter() - t0
        self.result = result


def write_selection(inp, sel):
    """windows.csv, windows.oas, stats.json, report.html (the report database: write_windows_report)."""
    t0 = time.perf_counter()
    selection_output.write_csv(sel.chosen, sel.gauges, inp.file("windows.csv"), inp.dbu)
    if output.needs_core_writer(len(inp.polygons) + len(sel.chosen.windows)):
        info = selection_output.window_layer_info(inp.layer, inp.datatype, sel.chosen)
        output.write_by_core(inp.file("windows.oas"), None, inp.polygons, inp.layer, inp.datatype,
                             [(info.layer, info.datatype, info.name)], inp.dbu, inp.cell.name,
                             [(info.layer, info.datatype, selection_output.window_boxes(sel.chosen, inp.dbu))])
    else:
        res, top = inp.result_layout()
        selection_output.add_layer(res, top, sel.chosen, inp.layer, inp.datatype)
        output.save(res, inp.file("windows.oas"))
        del res, top  # a copy of the layer: gone before the picture makes its own
    stats = selection_output.stats(sel.study, inp.dbu, sel.chosen, sel.similarity)
    stats.update(input=inp.path, cell=inp.cell.name, layer=inp.name, gauges=len(sel.gauges), max_norm=sel.max_norm,
                 marker_source=sel.markers.summary(), pitch_source="given" if sel.pitch_given else "estimated")
    stats["seconds"].update(read=inp.t_read, gauges=sel.result.seconds["total"], halves=sel.t_halves)
    chosen = sel.study.runs[(stats["chosen"]["mode"], stats["chosen"]["size"])]
    png = None
    if not html_report.svg_picture_fits(inp.polygons, chosen, sel.study.markers):
        png = layout_picture.picture(inp.polygons, inp.dbu, sel.study.markers, chosen.windows)
    html_report.write(inp.file("report.html"), "Pattern selection: %s %s" % (os.path.basename(inp.path), inp.name),
                      stats, sel.study, inp.polygons, inp.dbu, png)
    stats["seconds"]["write"] = time.perf_counter() - t0
    output.write_json(stats, inp.file("stats.json"))
    return stats


def write_windows_report(inp, sel, split, generator, path):
    """The selection's (and the split's, if given) report database: every run's windows, the
    markers, the split's patterns."""
    selection_output.write_report(path, sel.study, sel.gauges, inp.dbu, inp.cell.name, inp.path, generator,
                                  sel.markers, split)


def select_line(sel, dbu, d):
    row = sel.chosen.row(dbu)
    return ("select: %d markers (%s), pitch %.4g um, %d gauges; mode %s %s: %d windows cover %d markers "
            "(P_d %.2f%%, u_g %.2f%%); %d size/mode runs in %.2f s%s; outputs in %s"
            % (len(sel.markers.boxes), sel.markers.source, sel.pitch * dbu, len(sel.gauges), sel.chosen.mode,
               row["W_s"], len(sel.chosen.windows), sel.chosen.covered, row["P_d"], row["u_g"], len(sel.study.runs),
               sel.study.seconds, "; halves S_12 %.1f%%" % sel.similarity["S_12"] if sel.similarity else "",
               os.path.abspath(d)))


def cmd_select(args):
    inp = Input.from_args(args)
    sel = Selected(inp, args, gauge_stage.compute(inp.polygons, tile=inp.tile))
    write_selection(inp, sel)
    write_windows_report(inp, sel, None, "linf_opc select", inp.file("windows.lyrdb"))
    return select_line(sel, inp.dbu, inp.dir)


def _number(args, key, default, kind=float):
    try:
        return kind(args.get(key) or default)
    except ValueError:
        raise UsageError("%s must be a number, not %r" % (key, args[key]))


def split_of(args, sel):
    """The Split of the chosen selection run, by -rd split=stratified (default) or threshold."""
    patterns = split_stage.patterns_of(sel.chosen, sel.gauges, sel.markers.boxes)
    mode = (args.get("split") or "stratified").lower()
    bin_width = _number(args, "bin", 0.025)
    if bin_width <= 0:
        raise UsageError("bin must be positive")
    if mode == "threshold":
        return split_stage.by_threshold(patterns, _number(args, "threshold", 0.1), bin_width)
    if mode == "stratified":
        fraction = _number(args, "fraction", 0.3)
        if not 0 < fraction < 1:
            raise UsageError("fraction must lie between 0 and 1, not %g" % fraction)
        return split_stage.stratified(patterns, fraction, _number(args, "seed", 1, int), bin_width)
    raise UsageError("split must be stratified or threshold, not %r" % args.get("split"))


def write_split(inp, split):
    """The two clip libraries, the two gauge lists, split.json."""
    for which in split_stage.SETS:
        members = split.members(which)
        clips.write_library(inp.file("%s.oas" % which), which, members, inp.polygons, inp.layer, inp.datatype,
                            inp.dbu)
        gauge_output.write_csv((p.gauge for p in members), inp.file("%s_gauges.csv" % which), inp.dbu)
    s = split.summary()
    output.write_json(s, inp.file("split.json"))
    return s


def split_line(s, d):
    return ("split (%s): %d patterns (%d cover markers) -> calibration %d, verification %d; %d classes; "
            "outputs in %s" % (s["mode"], s["patterns"], s["covering_markers"], s["counts"]["calibration"],
                               s["counts"]["verification"], len(s["classes"]), os.path.abspath(d)))


def cmd_split(args):
    inp = Input.from_args(args)
    sel = Selected(inp, args, gauge_stage.compute(inp.polygons, tile=inp.tile))
    split = split_of(args, sel)
    write_selection(inp, sel)
    s = write_split(inp, split)
    write_windows_report(inp, sel, split, "linf_opc split", inp.file("windows.lyrdb"))
    return select_line(sel, inp.dbu, inp.dir) + "\n" + split_line(s, inp.dir)


def flow(inp, args, progress=None):
    """voronoi -> gauges -> select -> split on `inp`, the diagram built once; writes every
    output into inp.dir. `progress(stage)` is called between stages (the editor's progress bar,
    whose cancel raises). Returns (summary line, flow.lyrdb's name in inp.dir, chosen selection run)."""
    step = progress or (lambda stage: None)
    step("diagram and gauges")
    result = gauge_stage.compute(inp.polygons, draw_layer=inp.layer, tile=inp.tile, csv_path=inp.file("voronoi.csv"),
                                 dbu=inp.dbu, gauges_csv=inp.file("gauges.csv"), draw_cell=inp.cell.name)
    step("writing the diagram and the gauges")
    sv = write_voronoi(inp, result.pieces_diagram)
    sg = write_gauges(inp, result, result.gauges, args)
    step("pattern selection")
    sel = Selected(inp, args, result)
    step("split")
    split = split_of(args, sel)
    # flow.lyrdb: gauges.lyrdb followed by the selection's and the split's categories and items,
    # joined as text (report_db.py): the gauges are not loaded into KLayout only to be saved again
    stats = write_selection(inp, sel)
    ss = write_split(inp, split)
    parts = inp.file("flow_parts.lyrdb")
    write_windows_report(inp, sel, split, "linf_opc flow", parts)
    report_db.merge(inp.file("gauges.lyrdb"), parts, inp.file("flow.lyrdb"), "linf_opc flow")
    os.remove(parts)
    output.write_json({"voronoi": sv, "gauges": sg, "select": {k: stats[k] for k in ("pitch_um", "markers", "chosen")},
                       "split": {k: ss[k] for k in ("mode", "patterns", "counts")}}, inp.file("summary.json"))
    row = sel.chosen.row(inp.dbu)
    c = sg["counts"]
    line = ("flow on %s %s: %d polygons; diagram %d pieces, checked; gauges %d (internal %d, external %d, "
            "sandwich %d, comb %d, T %d); markers covered %d of %d (mode %s %s, %d windows); patterns: "
            "calibration %d, verification %d; outputs in %s"
            % (os.path.basename(inp.path) or inp.cell.name, inp.name, sv["polygons"], sv["pieces"], sg["gauges"],
               c["internal"], c["external"], c["sandwich"], c["comb"], c["T"], sel.chosen.covered,
               len(sel.markers.boxes), sel.chosen.mode, row["W_s"], len(sel.chosen.windows),
               ss["counts"]["calibration"], ss["counts"]["verification"], os.path.abspath(inp.dir)))
    return line, "flow.lyrdb", sel.chosen


def cmd_flow(args):
    return flow(Input.from_args(args), args)[0]


def cmd_farthest(args):
    """The farthest-site diagram of the layer's shapes (flattened, not merged: each shape is a
    site), or of those meeting -rd box, and the smallest square touching all of them."""
    ly, cell, index, (layer, datatype) = load(args)
    if not args.get("out"):
        raise UsageError("missing -rd out=DIR")
    out = Staging(args["out"])
    d = out.final
    box = None
    if args.get("box"):
        x1, y1, x2, y2 = parse_window(args["box"], ly.dbu)
        box = pya.Box(int(x1), int(y1), int(round(x2)), int(round(y2)))
    t0 = time.perf_counter()
    sites = farthest_stage.sites_of_layer(cell, index, box)
    if not sites:
        raise UsageError("no shapes on layer %d/%d%s" % (layer, datatype, " in the box" if box else ""))
    result = farthest_stage.compute(sites)
    seconds = time.perf_counter() - t0
    clip = farthest_stage.clip_for(sites)
    farthest_stage.write_csv(result, clip, out.file("farthest.csv"), ly.dbu)
    res = pya.Layout()
    res.dbu = ly.dbu
    top = res.create_cell(cell.name)
    li = res.insert_layer(pya.LayerInfo(layer, datatype))
    it = cell.begin_shapes_rec_overlapping(index, box) if box else cell.begin_shapes_rec(index)
    while not it.at_end():
        top.shapes(li).insert(it.shape().polygon.transformed(it.trans()))
        it.next()
    farthest_stage.add_layers(res, top, result, clip, layer)
    output.save(res, out.file("farthest.oas"))
    s = farthest_stage.summary(result, ly.dbu, sites)
    s.update(input=os.path.abspath(args["input"]), cell=cell.name, layer="%d/%d" % (layer, datatype),
             seconds=seconds)
    output.write_json(s, out.file("summary.json"))
    r = s["root"]
    return ("farthest: %d shapes -> %d faces, %d vertices, %d edges; smallest touching square: side %.6g um "
            "centred at (%.6g, %.6g)%s; outputs in %s"
            % (len(sites), s["faces"], s["vertices"], s["edges"], r["side_um"], r["p_um"][0], r["p_um"][1],
               "" if r["p_um"] == r["q_um"] else " (any centre up to (%.6g, %.6g))" % tuple(r["q_um"]),
               os.path.abspath(d)))


COMMANDS = {"farthest": cmd_farthest, "voronoi": cmd_voronoi, "gauges": cmd_gauges, "select": cmd_select, "split": cmd_split,
            "flow": cmd_flow}


def main(args):
    """Runs one command; returns the process exit code (0 ok, 2 usage/input, 3 core failure)."""
    cmd = args.get("cmd")
    try:
        if cmd not in COMMANDS:
            raise UsageError("unknown or missing -rd cmd=%s; one of: %s" % (cmd, ", ".join(sorted(COMMANDS))))
        line = COMMANDS[cmd](args)
        Staging.finish_all(True)
        print(line)
        return 0
    except (UsageError, ValueError) as e:
        Staging.finish_all(False)
        sys.stderr.write("linf_opc: error: %s\n" % e)
        return 2
    except diagram_stage.core.DiagramError as e:
        Staging.finish_all(False)
        sys.stderr.write("linf_opc: the diagram failed its independent check, nothing written: %s\n" % e)
        return 3
    except BaseException:
        Staging.finish_all(False)
        raise
