"""The batch entry point behind macros/linf_opc.py.

  klayout -b -r macros/linf_opc.py -rd cmd=voronoi|gauges|select -rd input=FILE -rd layer=L/D
          [-rd cell=NAME] -rd out=DIR
  gauges: [-rd window=X1,Y1,X2,Y2] (um: the per-pattern mode)
  select: -rd markers=SPEC [-rd sizes=5,6,7,8] [-rd modes=A,B,C] [-rd mode=A] [-rd size=K]
          [-rd pitch=UM] [-rd max_norm=1] [-rd halves=0|1]

Each command is a function of the parsed arguments returning a short summary line; later
commands (gauges, select, split, farthest) register here the same way.
"""
import os
import sys
import time

import pya

from . import diagram as diagram_stage
from . import gauge_output
from . import gauges as gauge_stage
from . import layout as layer_io
from . import markers as marker_io
from . import output
from . import report as html_report
from . import selection as selection_stage
from . import selection_output


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
    ly = pya.Layout()
    try:
        ly.read(path)
    except RuntimeError as e:
        raise UsageError("cannot read %s: %s" % (path, str(e).splitlines()[0]))
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


def out_dir(args):
    d = args.get("out")
    if not d:
        raise UsageError("missing -rd out=DIR")
    os.makedirs(d, exist_ok=True)
    return d


def read_polygons(cell, index, layer, datatype):
    """(merged region, polygons, seconds) of the layer; an empty layer is a usage error."""
    t0 = time.perf_counter()
    region = layer_io.region_of(cell, index)
    polygons = layer_io.polygons_of(region)
    if not polygons:
        raise UsageError("layer %d/%d is empty in cell %s" % (layer, datatype, cell.name))
    return region, polygons, time.perf_counter() - t0


def parse_window(text, dbu):
    """'x1,y1,x2,y2' in micrometres -> a box in DBU."""
    try:
        x1, y1, x2, y2 = (float(v) / dbu for v in text.split(","))
    except ValueError:
        raise UsageError("window must be x1,y1,x2,y2 in micrometres, not %r" % text)
    return min(x1, x2), min(y1, y2), max(x1, x2), max(y1, y2)


def cmd_voronoi(args):
    ly, cell, index, (layer, datatype) = load(args)
    d = out_dir(args)
    region, polygons, t_read = read_polygons(cell, index, layer, datatype)
    diagram = diagram_stage.compute(polygons)
    t0 = time.perf_counter()
    output.write_csv(diagram, os.path.join(d, "voronoi.csv"), ly.dbu)
    # voronoi.oas: the input layer (flattened, merged) and the diagram layers, in one top cell.
    res = pya.Layout()
    res.dbu = ly.dbu
    top = res.create_cell(cell.name)
    top.shapes(res.insert_layer(pya.LayerInfo(layer, datatype))).insert(region)
    drawn = output.add_layers(res, top, diagram, layer, datatype)
    res.write(os.path.join(d, "voronoi.oas"))
    t_write = time.perf_counter() - t0
    s = output.summary(diagram, ly.dbu, input=os.path.abspath(args["input"]), cell=cell.name,
                       layer="%d/%d" % (layer, datatype), polygons=len(polygons), drawn=drawn)
    s["seconds"].update(read=t_read, write=t_write)
    output.write_json(s, os.path.join(d, "summary.json"))
    c = s["counts"]
    return ("voronoi: %d polygons, %d sites -> %d pieces (internal %d, external %d, notch %d, adjacent %d), "
            "checked, %.2f s; outputs in %s" % (len(polygons), diagram.sites, len(diagram.pieces), c["internal"],
                                               c["external"], c["notch"], c["adjacent"], diagram.seconds["total"],
                                               os.path.abspath(d)))


def cmd_gauges(args):
    ly, cell, index, (layer, datatype) = load(args)
    window = parse_window(args["window"], ly.dbu) if args.get("window") else None
    d = out_dir(args)
    region, polygons, t_read = read_polygons(cell, index, layer, datatype)
    result = gauge_stage.compute(polygons)
    gauges = result.gauges if window is None else gauge_stage.most_critical_in(result.gauges, window)
    t0 = time.perf_counter()
    gauge_output.write_csv(gauges, os.path.join(d, "gauges.csv"), ly.dbu)
    gauge_output.report(gauges, ly.dbu, cell.name, os.path.abspath(args["input"])).save(
        os.path.join(d, "gauges.lyrdb"))
    res = pya.Layout()
    res.dbu = ly.dbu
    top = res.create_cell(cell.name)
    top.shapes(res.insert_layer(pya.LayerInfo(layer, datatype))).insert(region)
    gauge_output.add_layer(res, top, gauges, layer, datatype)
    res.write(os.path.join(d, "gauges.oas"))
    t_write = time.perf_counter() - t0
    s = gauge_output.summary(result, ly.dbu)
    s.update(input=os.path.abspath(args["input"]), cell=cell.name, layer="%d/%d" % (layer, datatype),
             polygons=len(polygons), dbu=round(ly.dbu, 12), written=len(gauges))
    if window is not None:
        s["window_um"] = [round(v * ly.dbu, 9) for v in window]
    s["seconds"].update(read=t_read, write=t_write)
    output.write_json(s, os.path.join(d, "summary.json"))
    c = s["counts"]
    best = ", ".join("%s %s" % (g.type, "%.4g" % (g.cd * ly.dbu)) for g in gauges[:3])
    return ("gauges: %d polygons -> %d gauges (internal %d, external %d, sandwich %d, comb %d, T %d)%s; "
            "most critical: %s; %.2f s; outputs in %s"
            % (len(polygons), len(result.gauges), c["internal"], c["external"], c["sandwich"], c["comb"], c["T"],
               "" if window is None else ", %d in the window" % len(gauges), best or "none",
               result.seconds["total"], os.path.abspath(d)))


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


def halves_similarity(region, markers, pitch, size, dbu):
    """Table 5.9's experiment: the layer cut at the x-midpoint of its extent into two layouts,
    each with its own gauges and the markers whose centre lies on its side; mode A windows of
    `size` pitches; classes on a common normalisation (the highest score of both halves)."""
    box = region.bbox()
    xm = (box.left + box.right) // 2
    halves = [region & pya.Region(pya.Box(box.left - 1, box.bottom - 1, xm, box.top + 1)),
              region & pya.Region(pya.Box(xm, box.bottom - 1, box.right + 1, box.top + 1))]
    used = []
    for i, half in enumerate(halves):
        polys = layer_io.polygons_of(half)
        ms = [m for m in markers if ((m[0] + m[2]) / 2 < xm) == (i == 0)]
        if not polys or not ms:
            used.append([])
            continue
        gs = gauge_stage.compute(polys).gauges
        st = selection_stage.study(gs, ms, pitch, sizes=(size,), modes=("A",))
        used.append(st.runs[("A", size)].used)
    top = max([g.score for u in used for g in u] or [1.0])
    c1, c2 = (selection_stage.classes(u, norm=lambda g: g.score / top) for u in used)
    n1 = {(t, s): n for t, s, n in c1}
    n2 = {(t, s): n for t, s, n in c2}
    keys = sorted(set(n1) | set(n2), key=lambda k: (k[0], k[1]))
    return {"x_split_um": round(xm * dbu, 6), "mode": "A", "size": size,
            "classes": [[t, s, n1.get((t, s), 0), n2.get((t, s), 0)] for t, s in keys],
            "N_t1": sum(n1.values()), "N_t2": sum(n2.values()),
            "S_12": round(selection_stage.similarity(c1, c2), 4)}


def cmd_select(args):
    ly, cell, index, (layer, datatype) = load(args)
    sizes, modes, mode, size, pitch, halves = select_args(args, ly.dbu)
    try:
        markers = marker_io.load(args.get("markers"), ly, cell)
    except marker_io.MarkerError as e:
        raise UsageError(str(e))
    if not markers.boxes:
        raise UsageError("no markers in %s" % markers.source)
    d = out_dir(args)
    region, polygons, t_read = read_polygons(cell, index, layer, datatype)
    result = gauge_stage.compute(polygons)
    try:
        max_norm = float(args.get("max_norm") or 1)
    except ValueError:
        raise UsageError("max_norm must be a number, not %r" % args["max_norm"])
    # Only gauges at most this critical (normalised score) open windows; 1 = every gauge.
    gauges = [g for g in result.gauges if g.norm_score <= max_norm + 1e-12]
    if not gauges:
        raise UsageError("no gauge has a normalised score at or below max_norm=%g" % max_norm)
    if pitch is None:
        pitch = selection_stage.pitch_of(result.gauges)
        if pitch <= 0:
            raise UsageError("cannot estimate the pitch of layer %d/%d: give -rd pitch=UM" % (layer, datatype))
    st = selection_stage.study(gauges, markers.boxes, pitch, sizes, modes)
    chosen = st.runs[(mode, size)] if size else st.best(mode)
    t0 = time.perf_counter()
    sim = halves_similarity(region, markers.boxes, pitch, 7 if 7 in sizes else sizes[-1], ly.dbu) if halves else None
    t_halves = time.perf_counter() - t0
    t0 = time.perf_counter()
    selection_output.write_csv(chosen, gauges, os.path.join(d, "windows.csv"), ly.dbu)
    rdb = pya.ReportDatabase("patterns")
    rdb.generator = "linf_opc select"
    rdb.original_file = os.path.abspath(args["input"])
    rdb.top_cell_name = cell.name
    selection_output.report(st, gauges, ly.dbu, cell.name, rdb, markers)
    rdb.save(os.path.join(d, "windows.lyrdb"))
    res = pya.Layout()
    res.dbu = ly.dbu
    top = res.create_cell(cell.name)
    top.shapes(res.insert_layer(pya.LayerInfo(layer, datatype))).insert(region)
    selection_output.add_layer(res, top, chosen, layer, datatype)
    res.write(os.path.join(d, "windows.oas"))
    stats = selection_output.stats(st, ly.dbu, chosen, sim)
    stats.update(input=os.path.abspath(args["input"]), cell=cell.name, layer="%d/%d" % (layer, datatype),
                 gauges=len(gauges), max_norm=max_norm, marker_source=markers.summary(),
                 pitch_source="given" if args.get("pitch") else "estimated")
    stats["seconds"].update(read=t_read, gauges=result.seconds["total"], halves=t_halves)
    html_report.write(os.path.join(d, "report.html"), "Pattern selection: %s %d/%d" % (
        os.path.basename(args["input"]), layer, datatype), stats, st, polygons, ly.dbu)
    stats["seconds"]["write"] = time.perf_counter() - t0
    output.write_json(stats, os.path.join(d, "stats.json"))
    row = chosen.row(ly.dbu)
    return ("select: %d markers (%s), pitch %.4g um, %d gauges; mode %s %s: %d windows cover %d markers "
            "(P_d %.2f%%, u_g %.2f%%); %d size/mode runs in %.2f s%s; outputs in %s"
            % (len(markers.boxes), markers.source, pitch * ly.dbu, len(gauges), chosen.mode, row["W_s"],
               len(chosen.windows), chosen.covered, row["P_d"], row["u_g"], len(st.runs), st.seconds,
               "; halves S_12 %.1f%%" % sim["S_12"] if sim else "", os.path.abspath(d)))


COMMANDS = {"voronoi": cmd_voronoi, "gauges": cmd_gauges, "select": cmd_select}


def main(args):
    """Runs one command; returns the process exit code (0 ok, 2 usage/input, 3 core failure)."""
    cmd = args.get("cmd")
    try:
        if cmd not in COMMANDS:
            raise UsageError("unknown or missing -rd cmd=%s; one of: %s" % (cmd, ", ".join(sorted(COMMANDS))))
        print(COMMANDS[cmd](args))
        return 0
    except (UsageError, ValueError) as e:
        sys.stderr.write("linf_opc: error: %s\n" % e)
        return 2
    except diagram_stage.core.DiagramError as e:
        sys.stderr.write("linf_opc: the diagram failed its independent check, nothing written: %s\n" % e)
        return 3
