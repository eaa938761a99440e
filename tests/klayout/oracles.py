"""Writers of outputs the core writes, kept as test oracles: voronoi.csv and gauges.csv row by
row in Python, and voronoi.oas, gauges.oas and windows.oas built in a KLayout layout and saved
by KLayout (as the batch once wrote the small ones). check_writers.py and check_core_oasis.py
compare the core's files with theirs. Needs linf_opc and pya (run under klayout -b)."""
import csv

import pya

from linf_opc import diagram_output, flow, gauge_output, gauges, inputs, output, selection_output
from linf_opc import diagram as diagram_stage
from linf_opc.diagram import KINDS

VORONOI_CSV_HEADER = ["kind", "x1", "y1", "x2", "y2", "d1", "d2",
                      "a_x1", "a_y1", "a_x2", "a_y2", "b_x1", "b_y1", "b_x2", "b_y2"]


def write_voronoi_csv(diagram, path, dbu):
    """The pieces as CSV, row by row (the core's write_pieces_csv must write the same bytes);
    the diagram computed with its pieces."""
    if diagram.pieces is None:
        raise ValueError("the diagram was computed without its pieces")
    with open(path, "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(VORONOI_CSV_HEADER)
        for p in diagram.pieces:
            w.writerow([p.kind] + ["%.6f" % (v * dbu) for v in p[1:15]])


GAUGES_CSV_HEADER = ["id", "type", "x1", "y1", "x2", "y2", "cx", "cy", "cd", "score", "norm_score", "tiebreak",
                     "rank"]


def write_gauges_csv(gauges, path, dbu):
    """Gauge records as gauges.csv, row by row, id and rank each gauge's rank (the core's
    write_gauges_csv must write the same bytes for the whole table, write_gauges_csv_rows for
    any of its gauges)."""
    with open(path, "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(GAUGES_CSV_HEADER)
        for g in gauges:
            um = ["%.6f" % (v * dbu) for v in (g.x1, g.y1, g.x2, g.y2, g.cx, g.cy, g.cd, g.score)]
            w.writerow([g.rank, g.type] + um + ["%.6f" % g.norm_score, "%.6f" % (g.tiebreak * dbu), g.rank])


def read_drawing(cell, path):
    """The shapes of a GDSII drawing the core wrote, read straight into cell's layout, which
    holds them once instead of twice on the way: the file's cell must be named as `cell`, and
    its layers are matched by layer and datatype."""
    layout = cell.layout()
    cells = sum(1 for _ in layout.each_cell())
    layout.read(path)
    if sum(1 for _ in layout.each_cell()) != cells:
        raise ValueError("the drawing %s is not for cell %s" % (path, cell.name))


def add_diagram_layers(layout, cell, diagram, layer, datatype):
    """diagram_output.add_layers' layers, the drawing read straight in (read_drawing)."""
    for kind in KINDS:
        layout.insert_layer(diagram_output.diagram_layer_info(layer, datatype, kind))
    read_drawing(cell, diagram.gds_path)


def result_layout(inp):
    """A layout with one top cell holding the Input's merged layer, to add result layers to."""
    res = pya.Layout()
    res.dbu = inp.dbu
    top = res.create_cell(inp.cell.name)
    top.shapes(res.insert_layer(pya.LayerInfo(inp.layer, inp.datatype))).insert(inp.region)
    return res, top


def voronoi_oas(inp, diagram, path):
    res, top = result_layout(inp)
    add_diagram_layers(res, top, diagram, inp.layer, inp.datatype)
    output.save(res, path)


def gauges_oas(inp, gs, path):
    res, top = result_layout(inp)
    res.insert_layer(gauge_output.gauge_layer_info(inp.layer, inp.datatype))
    with gauge_output.drawn(gs, inp.dbu, inp.layer, inp.cell.name) as gds:
        read_drawing(top, gds)
    output.save(res, path)


def windows_oas(inp, run, path):
    res, top = result_layout(inp)
    selection_output.add_layer(res, top, run, inp.layer, inp.datatype)
    output.save(res, path)


def result_layouts(args, out):
    """voronoi.oas, gauges.oas and, given markers, windows.oas into `out` as KLayout builds and
    saves them, from the batch's arguments (the selection's as in cmd=select, without halves)."""
    inp = inputs.Input.from_args(dict(args, out=out))
    try:
        d = diagram_stage.compute(inp.polygons, tile=inp.tile, dbu=inp.dbu, with_pieces=False,
                                  draw_layer=inp.layer, draw_cell=inp.cell.name)
        voronoi_oas(inp, d, inp.file("voronoi.oas"))
        result = gauges.compute(inp.polygons, tile=inp.tile, dbu=inp.dbu)
        gauges_oas(inp, result.gauges, inp.file("gauges.oas"))
        if args.get("markers"):
            windows_oas(inp, flow.Selected(inp, dict(args, halves="0"), result).chosen, inp.file("windows.oas"))
        inp.out.commit()
    finally:
        inp.out.abort()
