"""The batch commands, one function each: the parsed arguments in, the outputs written into the
staging folder, a short summary line out (commands.main prints it), each stage's line on stderr
as it ends (progress.py; -rd quiet=1 none). The stages and writers are the ones the editor calls."""
import os
import time

import pya

from . import arguments
from . import diagram as diagram_stage
from . import diagram_output
from . import farthest as farthest_stage
from . import flow
from . import gauge_output
from . import gauges as gauge_stage
from . import litho
from . import markers as marker_io
from . import output
from . import selection_output
from . import split_output
from .arguments import UsageError
from .inputs import Input, load
from .progress import Progress, count
from .staging import Staging


def progress_of(args, *switches):
    """The command's progress lines on stderr, or none with -rd quiet=1; the command's other
    0|1 switches checked before anything is read (a bad value is a UsageError)."""
    for name in switches:
        arguments.switch(args, name)
    return Progress(quiet=arguments.switch(args, "quiet"))


def read(args, p):
    """The command's Input, read and said so."""
    p.start("read")
    inp = Input.from_args(args)
    p.done("%s polygons on %s of %s" % (count(len(inp.polygons)), inp.name,
                                        os.path.basename(inp.path) or inp.cell.name))
    return inp


def read_for_markers(args, p):
    """read() for the commands that take markers; a marker layer equal to the working layer is
    legal (each of its shapes' boxes a marker, every window covering its own gauge's shape) but
    rarely meant: said in a warning line."""
    inp = read(args, p)
    if marker_io.same_as_working(args.get("markers"), inp.layer, inp.datatype):
        marker_io.warn("the marker layer %s is the working layer: every shape of it is a marker" % inp.name)
    return inp


def computed(p, what, inp, compute):
    """A stage that is one core call (the diagram, the gauges): said when it starts and ends."""
    p.start(what, "%s polygons" % count(len(inp.polygons)))
    result = compute()
    raw = result.diagram if hasattr(result, "gauges") else None  # a gauges.Gauges, else a diagram.Diagram
    polygons, pieces = (raw["polygons"], raw["pieces"]) if raw else (result.polygons, result.n_pieces)
    p.done("%s polygons, %s pieces%s" % (count(polygons), count(pieces),
                                         ", %s gauges" % count(len(result.gauges)) if raw else ""))
    return result


def printability(p, inp, result, model):
    """The gauge table ranked by printability on `model` (litho.rescore), said on stderr; the
    result as it is without a model."""
    if model is None:
        return result
    p.start("printability", "%s gauges on %s" % (count(len(result.gauges)), model.name))
    litho.rescore(result, inp.polygons, inp.dbu, model)
    s = result.litho_summary
    p.done("%s windows simulated for %s gauges (%s shared a context); %s pinch, %s bridge"
           % (count(s["images"]), count(s["simulated"]), count(s["shared"]), count(s["fails"]["pinch"]),
              count(s["fails"]["bridge"])))
    return result


def voronoi_line(s, d):
    c = s["counts"]
    return ("voronoi: %d polygons, %d sites -> %d pieces (internal %d, external %d, notch %d, adjacent %d), "
            "checked, %.2f s; outputs in %s" % (s["polygons"], s["sites"], s["pieces"], c["internal"],
                                               c["external"], c["notch"], c["adjacent"], s["seconds"]["total"],
                                               os.path.abspath(d)))


def cmd_voronoi(args):
    p = progress_of(args)
    inp = read(args, p)
    s = diagram_output.write_voronoi(inp, computed(p, "diagram", inp, lambda: diagram_stage.compute(
        inp.polygons, tile=inp.tile, builder=inp.builder, check=inp.check, csv_path=inp.file("voronoi.csv"), dbu=inp.dbu,
        with_pieces=False, draw_layer=inp.layer, draw_cell=inp.cell.name, progress=p.core)))
    output.write_json(s, inp.file("summary.json"))
    return voronoi_line(s, inp.dir)


def gauges_line(s, gauges, dbu, d):
    c = s["counts"]
    best = ", ".join("%s %s" % (g.type, "%.4g" % (g.cd * dbu)) for g in gauges[:3])
    return ("gauges: %d polygons -> %d gauges (internal %d, external %d, sandwich %d, comb %d, T %d)%s; "
            "most critical: %s; %.2f s; outputs in %s"
            % (s["polygons"], s["gauges"], c["internal"], c["external"], c["sandwich"], c["comb"], c["T"],
               "" if "window_um" not in s else ", %d in the window" % s["written"], best or "none",
               s["seconds"]["total"], os.path.abspath(d)))


def cmd_gauges(args):
    p = progress_of(args)
    model = litho.model_of(args)  # a bad model stops the command before the layer is read
    inp = read(args, p)
    window = arguments.parse_window(args["window"], inp.dbu) if args.get("window") else None
    result = printability(p, inp, computed(p, "diagram and gauges", inp, lambda: gauge_stage.compute(
        inp.polygons, tile=inp.tile, builder=inp.builder, check=inp.check, dbu=inp.dbu,
        gauges_csv=inp.file("gauges.csv") if window is None and model is None else None, progress=p.core)), model)
    gauges = result.gauges if window is None else gauge_stage.most_critical_in(result.gauges, window)
    p.start("writing the gauges", "%s gauges" % count(len(gauges)))
    s = gauge_output.write_gauges(inp, result, gauges, arguments.report_max(args), window, tick=p.fraction)
    p.done("gauges.csv, gauges.lyrdb (%s items), gauges.oas" % count(s["report_items"]))
    if model is not None:
        s["litho"] = result.litho_summary
    output.write_json(s, inp.file("summary.json"))
    return gauges_line(s, gauges, inp.dbu, inp.dir)


def select_line(sel, dbu, d):
    row = sel.chosen.row(dbu)
    return ("select: %d markers (%s), pitch %.4g um, %d gauges; mode %s %s: %d windows cover %d markers "
            "(P_d %.2f%%, u_g %.2f%%); %d size/mode runs in %.2f s%s; outputs in %s"
            % (len(sel.markers.boxes), sel.markers.source, sel.pitch * dbu, len(sel.gauges), sel.chosen.mode,
               row["W_s"], len(sel.chosen.windows), sel.chosen.covered, row["P_d"], row["u_g"], len(sel.study.runs),
               sel.study.seconds, "; halves S_12 %.1f%%" % sel.similarity["S_12"] if sel.similarity else "",
               os.path.abspath(d)))


def cmd_select(args):
    p = progress_of(args, "halves")
    model = litho.model_of(args)
    inp = read_for_markers(args, p)
    sel = flow.Selected(inp, args, printability(p, inp, computed(p, "diagram and gauges", inp,
                        lambda: gauge_stage.compute(inp.polygons, tile=inp.tile, builder=inp.builder, check=inp.check)), model), p)
    selection_output.write_selection(inp, sel)
    selection_output.write_windows_report(inp, sel, None, "linf_opc select", inp.file("windows.lyrdb"))
    return select_line(sel, inp.dbu, inp.dir)


def split_line(s, d):
    groups = ("%d of %d contexts" % (s["sets"]["calibration"]["contexts"], s["layer"]["contexts"])
              if s["mode"] == "plan" else "%d classes" % len(s["classes"]))
    return ("split (%s): %d patterns (%d cover markers) -> calibration %d, verification %d; %s; "
            "outputs in %s" % (s["mode"], s["patterns"], s["covering_markers"], s["counts"]["calibration"],
                               s["counts"]["verification"], groups, os.path.abspath(d)))


def cmd_split(args):
    p = progress_of(args, "halves")
    inp = read_for_markers(args, p)
    flow.split_args(args, inp.dbu)  # a bad split argument stops the command before any work
    model = litho.model_of(args)
    sel = flow.Selected(inp, args, printability(p, inp, computed(p, "diagram and gauges", inp,
                        lambda: gauge_stage.compute(inp.polygons, tile=inp.tile, builder=inp.builder, check=inp.check)), model), p)
    split = flow.split_of(args, sel, inp)
    selection_output.write_selection(inp, sel, split)
    s = split_output.write_split(inp, split, sel.gauges, getattr(sel.result.gauges, "litho", None))
    selection_output.write_windows_report(inp, sel, split, "linf_opc split", inp.file("windows.lyrdb"))
    return select_line(sel, inp.dbu, inp.dir) + "\n" + split_line(s, inp.dir)


def cmd_flow(args):
    p = progress_of(args, "halves")
    flow.Outputs(args)  # a bad switch or rdb_max stops the command before the layer is read
    model = litho.model_of(args)  # and so does a bad model
    return flow.run(read_for_markers(args, p), args, p, model=model)[0]


def cmd_farthest(args):
    """The farthest-site diagram of the layer's shapes (flattened, not merged: each shape is a
    site), or of those meeting -rd box, and the smallest square touching all of them."""
    progress_of(args)  # quiet=0|1 checked; one quick stage, nothing to say on the way
    ly, cell, index, (layer, datatype) = load(args)
    if not args.get("out"):
        raise UsageError("missing -rd out=DIR")
    out = Staging(args["out"])
    d = out.final
    box = None
    if args.get("box"):
        x1, y1, x2, y2 = arguments.parse_window(args["box"], ly.dbu)
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
