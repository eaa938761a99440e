"""The batch entry point behind macros/linf_opc.py.

  klayout -b -r macros/linf_opc.py -rd cmd=voronoi|gauges -rd input=FILE -rd layer=L/D
          [-rd cell=NAME] -rd out=DIR [-rd window=X1,Y1,X2,Y2 (um, gauges: per-pattern mode)]

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
from . import output


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


COMMANDS = {"voronoi": cmd_voronoi, "gauges": cmd_gauges}


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
