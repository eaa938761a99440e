"""Table 5.9's experiment, two layouts compared: the layer cut at the x-midpoint of its extent
into two halves, each with its own gauges and the markers whose centre lies on its side, and
the similarity S_12 of the representative classes their mode A windows use (stats.json's
"similarity", the select command's -rd halves=1)."""
from array import array
from collections import namedtuple

from . import gauges as gauge_stage
from . import layout as layer_io
from . import polygons as polygons_io
from . import selection as selection_stage

TypeScore = namedtuple("TypeScore", "type score")  # what classes() reads of a gauge


def halves_similarity(inp, markers, pitch, size):
    """The experiment on the Input `inp`: mode A windows of `size` pitches; classes on a common
    normalisation (the highest score of both halves).
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
        gs = gauge_stage.compute(polys, tile=inp.tile, builder=inp.builder, check=inp.check).gauges
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
