"""Writing a Split: its two clip libraries (calibration.oas, verification.oas), its two gauge
lists (calibration_gauges.csv, verification_gauges.csv; a plan's with the columns context and
count) and split.json.

A clip library holds one cell per pattern, for OPC model calibration or verification. Each
clip cell holds, in layout coordinates (so that it overlays the source):
  L/D     the layer's merged shapes clipped to the window (hierarchy flattened);
  L/210   the gauge's measurement line and a text with the gauge's values;
  L/220   the window outline;
  L/230   the markers that meet the window.
Cells are named SET_rRANK_TYPE_SCORE, e.g. CAL_r000042_sandwich_0p0245 (score in µm, '.' -> 'p').
"""
from array import array

import pya

from . import core, gauge_output, output
from . import split as split_stage
from .polygons import core_input
from .progress import breathe
from .gauge_output import DATATYPE as GAUGE_DATATYPE
from .selection_output import DATATYPE as WINDOW_DATATYPE

MARKER_DATATYPE = 230
PREFIX = {"calibration": "CAL", "verification": "VER"}


def window_box(b):
    """A pattern window on the integer DBU grid (the clip boundary)."""
    return pya.Box(int(round(b[0])), int(round(b[1])), int(round(b[2])), int(round(b[3])))


def write_library(path, which, patterns, polygons, layer, datatype, dbu):
    """Writes the clips of one set, cut from the layer's polygons (polygons.Polygons, as drawn);
    returns the number of clips. The core writes the file: a library of hundreds of thousands of
    clips built in a KLayout layout kept about 2 KB a cell even after the layout was deleted. The
    core also names and labels the cells (linf::clip_name, clip_label) from the gauges' numbers:
    their text, made here, was most of this step's memory on a full layer."""
    if not patterns:  # the core writes a library of one clip or more
        lib = pya.Layout()
        lib.dbu = dbu
        output.save(lib, path)
        return 0
    windows, lines, at, counts, markers = array("q"), array("q"), array("q"), array("q"), array("d")
    ranks, types, values, type_index = array("q"), bytearray(), array("d"), {}
    for k, p in enumerate(patterns):
        breathe(k, len(patterns))
        g = p.gauge
        ranks.append(g.rank)
        types.append(type_index.setdefault(g.type, len(type_index)))
        values.extend((g.score, g.cd, g.norm_score, g.tiebreak))
        b = window_box(p.box)
        windows.extend((b.left, b.bottom, b.right, b.top))
        lines.extend((round(g.x1), round(g.y1), round(g.x2), round(g.y2)))
        at.extend((round(g.cx), round(g.cy)))
        counts.append(len(p.markers))
        for m in p.markers:
            markers.extend(m[:4])
    core.write_clip_library(path, dbu, core_input(polygons), layer, datatype, GAUGE_DATATYPE, WINDOW_DATATYPE,
                            MARKER_DATATYPE, PREFIX[which], list(type_index), windows, lines, at, ranks,
                            bytes(types), values, counts, markers)
    return len(counts)


def write_split(inp, split, gauges, litho=None):
    """The two clip libraries, the two gauge lists and split.json of the Input `inp`; `gauges`
    are those the split's patterns index (the selection's; a plan's are its own table, and its
    gauge lists add each gauge's context and count; with `litho`, the printability columns of
    the re-ranked table, litho.LithoColumns, are added too). Returns the split's summary."""
    for which in split_stage.SETS:
        members = split.members(which)
        write_library(inp.file("%s.oas" % which), which, members, inp.polygons, inp.layer, inp.datatype, inp.dbu)
        path = inp.file("%s_gauges.csv" % which)
        if split.mode == "plan":
            gauge_output.write_csv_rows(split.table, path, inp.dbu, *split.rows(which), litho=litho)
        else:
            gauge_output.write_csv_rows(gauges, path, inp.dbu, array("i", (p.index for p in members)), litho=litho)
    s = split.summary(inp.dbu) if split.mode == "plan" else split.summary()
    output.write_json(s, inp.file("split.json"))
    return s
