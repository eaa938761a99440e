"""The flow: diagram -> gauges -> selection -> split on one Input, the diagram built once, the
plan and its report written (run); the whole diagram and gauge table only on request (Outputs).
The batch's cmd=flow and the editor's "Run OPC pattern flow..." both call run(); the select and
split commands use its selection (Selected) and split (split_of) steps.
args are the commands' arguments as strings (arguments.py)."""
import os
import time

from . import arguments
from . import diagram_output
from . import gauge_output
from . import gauges as gauge_stage
from . import litho
from . import markers as marker_io
from . import output
from . import pattern_classes
from . import plan as plan_stage
from . import report_db
from . import selection as selection_stage
from . import selection_output
from . import split as split_stage
from . import split_output
from .arguments import UsageError
from .diagram import Diagram
from .halves import halves_similarity
from .progress import Progress, count

# flow.lyrdb holds the plan and, to browse, the most critical gauges of each type: on a large
# layer the whole table there is hundreds of MB (the table is -rd all_gauges=1's gauges.csv).
REPORT_MAX_PER_TYPE = 100


class Selected:
    """What the selection produced on the Input `inp` from the gauge stage's `result`, for
    writing (selection_output.write_selection) and for the split. progress: as run's."""
    def __init__(self, inp, args, result, progress=None):
        p = Progress.of(progress)
        sizes, modes, mode, size, pitch, halves = arguments.select_args(args, inp.dbu)
        rule = arguments.class_args(args, inp.dbu)
        try:
            self.markers = marker_io.load(args.get("markers"), inp.ly, inp.cell)
        except marker_io.MarkerError as e:
            raise UsageError(str(e))
        if not self.markers.boxes:
            raise UsageError("no markers in %s" % self.markers.source)
        self.max_norm = arguments.max_norm(args)
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
        p.start("selection", "%s gauges, %s markers, %d runs" % (count(len(self.gauges)),
                                                               count(len(self.markers.boxes)), len(sizes) * len(modes)))
        self.study = selection_stage.study(self.gauges, self.markers.boxes, pitch, sizes, modes)
        self.chosen = self.study.runs[(mode, size)] if size else self.study.best(mode)
        p.done("mode %s %dx%d: %s windows cover %s of %s markers"
               % (self.chosen.mode, self.chosen.size, self.chosen.size, count(len(self.chosen.windows)),
                  count(self.chosen.covered), count(len(self.markers.boxes))))
        self.classes = None
        if rule is not None:
            p.start("pattern classes", "%s windows, by %s" % (count(len(self.chosen.windows)), rule[0]))
            self.classes = pattern_classes.classify(inp.polygons, self.chosen, rule, inp.dbu)
            p.done("%s windows in %s classes" % (count(len(self.chosen.windows)), count(len(self.classes))))
        t0 = time.perf_counter()
        self.similarity = None
        if halves:
            p.start("halves", "the two-layouts experiment: the gauges of each half")
            self.similarity = halves_similarity(inp, self.markers.boxes, pitch, 7 if 7 in sizes else sizes[-1])
            p.done("S_12 %.1f%%" % self.similarity["S_12"])
        self.t_halves = time.perf_counter() - t0
        self.result = result


def split_args(args, dbu):
    """(mode, parameters) of the split from -rd split=plan (default) | threshold | stratified and
    its arguments; read before any work, so that a bad value stops a run before anything is made."""
    mode = arguments.split_mode(args)
    bin_width = arguments.number(args, "bin", 0.025)
    if bin_width <= 0:
        raise UsageError("bin must be positive")
    if mode == "plan":
        budget, verify, radius = arguments.plan_args(args, dbu)
        return mode, {"budget": budget, "verify": verify, "radius": radius}
    if mode == "threshold":
        return mode, {"threshold": arguments.number(args, "threshold", 0.1), "bin": bin_width}
    fraction = arguments.number(args, "fraction", 0.3)
    if not 0 < fraction < 1:
        raise UsageError("fraction must lie between 0 and 1, not %g" % fraction)
    return mode, {"fraction": fraction, "seed": arguments.number(args, "seed", 1, int), "bin": bin_width}


def split_of(args, sel, inp):
    """The Split of the chosen selection run on the Input `inp`: the budgeted gauge plan
    (plan.py) or the thesis's patterns split by threshold or stratified (split.py)."""
    mode, p = split_args(args, inp.dbu)
    if mode == "plan":
        return plan_stage.of_selection(sel, inp.polygons, inp.dbu, p["budget"], p["verify"], p["radius"])
    patterns = split_stage.patterns_of(sel.chosen, sel.gauges, sel.markers.boxes)
    if mode == "threshold":
        lit = getattr(sel.result.gauges, "litho", None)
        # With a lithography model the thesis's separator is the simulation's: a gauge that pinches
        # or bridges (at nominal or a process-window corner) is faulty and goes to verification.
        fails = (lambda p: lit.fails[p.gauge.rank - 1]) if lit is not None else None
        return split_stage.by_threshold(patterns, p["threshold"], p["bin"], fails)
    return split_stage.stratified(patterns, p["fraction"], p["seed"], p["bin"])


class Outputs:
    """The flow's files on request, from its arguments: all_gauges (-rd all_gauges=1: gauges.csv,
    gauges.lyrdb, gauges.oas), diagram (-rd diagram=1: voronoi.csv, voronoi.oas), and the most
    critical gauges of each type in the report databases (-rd rdb_max, 0 all)."""
    def __init__(self, args):
        self.all_gauges = arguments.switch(args, "all_gauges")
        self.diagram = arguments.switch(args, "diagram")
        self.cap = arguments.report_max(args, REPORT_MAX_PER_TYPE)


def run(inp, args, progress=None, model=None):
    """voronoi -> gauges -> select -> split on `inp`, the diagram built once; writes the plan,
    the windows, the reports and the files Outputs asks for into inp's staging folder. progress:
    a progress.Progress (the batch's lines on stderr), or step(stage), called as each stage
    begins (the editor's progress bar, whose cancel raises). Returns (summary line, flow.lyrdb's
    name in inp.dir, chosen selection run). model: the litho.Model of -rd litho (read from args
    when None)."""
    p = Progress.of(progress)
    want = Outputs(args)
    if model is None:
        model = litho.model_of(args)
    split_args(args, inp.dbu)  # a bad split argument stops the run before any work
    # What is not written is not made: without diagram=1 the core neither writes voronoi.csv nor
    # draws the pieces, and the pieces only stream past the gauges.
    p.start("diagram and gauges", "%s polygons" % count(len(inp.polygons)))
    result = gauge_stage.compute(inp.polygons, draw_layer=inp.layer if want.diagram else None, tile=inp.tile,
                                 builder=inp.builder, check=inp.check, csv_path=inp.file("voronoi.csv") if want.diagram else None,
                                 dbu=inp.dbu,
                                 gauges_csv=inp.file("gauges.csv") if want.all_gauges and model is None else None,
                                 draw_cell=inp.cell.name, progress=p.core)
    p.done("%s polygons, %s pieces, %s gauges" % (count(result.diagram["polygons"]), count(result.diagram["pieces"]),
                                                  count(len(result.gauges))))
    if model is not None:
        from .runs import printability
        printability(p, inp, result, model)
    if want.diagram:
        p.start("writing the diagram")
        sv = diagram_output.write_voronoi(inp, result.pieces_diagram)
        p.done("voronoi.csv, voronoi.oas")
    else:
        sv = diagram_output.layer_summary(inp, Diagram(result.diagram, result.seconds["total"]))
    # flow.lyrdb: the gauge report followed by the selection's and the split's categories and
    # items, joined as text (report_db.py): the gauges are not loaded into KLayout only to be saved again
    gauge_report = inp.file("gauges.lyrdb" if want.all_gauges else "flow_gauges.lyrdb")
    if want.all_gauges:
        p.start("writing the gauges", "%s gauges" % count(len(result.gauges)))
        sg = gauge_output.write_gauges(inp, result, result.gauges, want.cap, tick=p.fraction)
        p.done("gauges.csv, gauges.lyrdb (%s items), gauges.oas" % count(sg["report_items"]))
    else:
        sg = gauge_output.layer_summary(inp, result, 0, gauge_output.write_report(
            result.gauges, inp.dbu, inp.cell.name, inp.path, gauge_report, want.cap), want.cap)
    sel = Selected(inp, args, result, p)
    p.start("split")
    split = split_of(args, sel, inp)
    p.done("%s patterns" % count(len(split.patterns)) if hasattr(split, "patterns") else "")
    p.start("writing the plan")
    stats = selection_output.write_selection(inp, sel, split)
    ss = split_output.write_split(inp, split, sel.gauges, getattr(result.gauges, "litho", None))
    parts = inp.file("flow_parts.lyrdb")
    selection_output.write_windows_report(inp, sel, split, "linf_opc flow", parts)
    report_db.merge(gauge_report, parts, inp.file("flow.lyrdb"), "linf_opc flow")
    os.remove(parts)
    if not want.all_gauges:
        os.remove(gauge_report)
    if model is not None:
        sg["litho"] = result.litho_summary
    output.write_json({"voronoi": sv, "gauges": sg, "select": {k: stats[k] for k in ("pitch_um", "markers", "chosen")},
                       "split": {k: ss[k] for k in ("mode", "patterns", "counts")}}, inp.file("summary.json"))
    written = os.listdir(inp.out.dir)
    p.done("%d files, %.1f MB" % (len(written), sum(os.path.getsize(inp.file(f)) for f in written) / 1e6))
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
