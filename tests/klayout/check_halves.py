# The two-layouts experiment (Table 5.9, halves.halves_similarity) against a plain reading of it:
#   klayout -b -r tests/klayout/check_halves.py -rd input=FILE -rd layer=L/D -rd markers=SPEC -rd work=DIR
# The batch reads both halves in one pass, clipping only the polygons across the cut, spills
# them when large, and classifies the used gauges from the table's columns. Here both halves
# are cut by KLayout's boolean of the merged layer with each half's box, their gauges computed
# from plain polygon lists, the used gauges made as records and classified on the highest score
# of both: the two must give the same classes, counts and S_12, also as a large layer is read
# (as drawn, not merged by KLayout, and every half spilled: layout.MERGE_IN_KLAYOUT_MAX and
# polygons.SPILL_SHAPES at 0).
import os
import sys

import pya

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from harness import arg, expect, finish  # noqa: E402

from linf_opc import gauges, halves, inputs, layout, markers as marker_io, polygons, selection  # noqa: E402


def plain(region, markers, pitch, size):
    box = region.bbox()
    xm = (box.left + box.right) // 2
    halves = [region & pya.Region(pya.Box(box.left - 1, box.bottom - 1, xm, box.top + 1)),
              region & pya.Region(pya.Box(xm, box.bottom - 1, box.right + 1, box.top + 1))]
    used = []
    for i, half in enumerate(halves):
        polys = list(layout.polygons_of(half))
        ms = [m for m in markers if ((m[0] + m[2]) / 2 < xm) == (i == 0)]
        if not polys or not ms:
            used.append([])
            continue
        gs = gauges.compute(polys).gauges
        used.append(selection.study(gs, ms, pitch, sizes=(size,), modes=("A",)).runs[("A", size)].used)
    top = max([x.score for u in used for x in u] or [1.0])
    c1, c2 = (selection.classes(u, norm=lambda x: x.score / top) for u in used)
    return c1, c2, selection.similarity(c1, c2)


os.makedirs(arg("work"), exist_ok=True)
args = {"input": arg("input"), "layer": arg("layer"), "out": arg("work"), "markers": arg("markers")}
inp = inputs.Input.from_args(args)
ms = marker_io.load(arg("markers"), inp.ly, inp.cell).boxes
pitch = selection.pitch_of(gauges.compute(inp.polygons).gauges)
size = 7
c1, c2, s12 = plain(layout.region_of(inp.cell, inp.index), ms, pitch, size)
inp.out.abort()
box = inp.region.bbox()
xm = (box.left + box.right) // 2
crossing = sum(1 for p in inp.region.each() if p.bbox().left < xm < p.bbox().right)
expect(crossing > 0, "some polygon lies across the cut (x = %d): the check needs one" % xm)
expect(c1 and c2, "both halves have used gauges (%d and %d classes): the check needs both" % (len(c1), len(c2)))
inp.out.abort()
print("%d polygons across the cut" % crossing)
for large in (False, True):
    if large:
        layout.MERGE_IN_KLAYOUT_MAX = polygons.SPILL_SHAPES = 0
    inp = inputs.Input.from_args(args)
    got = halves.halves_similarity(inp, ms, pitch, size)
    inp.out.abort()
    n1 = {(t, s): n for t, s, n in c1}
    n2 = {(t, s): n for t, s, n in c2}
    want = [[t, s, n1.get((t, s), 0), n2.get((t, s), 0)] for t, s in sorted(set(n1) | set(n2))]
    expect(got["classes"] == want, "large %s: classes %s, the plain reading %s" % (large, got["classes"][:5], want[:5]))
    expect((got["N_t1"], got["N_t2"]) == (sum(n1.values()), sum(n2.values())),
           "large %s: N_t %s, the plain reading %s" % (large, (got["N_t1"], got["N_t2"]),
                                                        (sum(n1.values()), sum(n2.values()))))
    expect(abs(got["S_12"] - round(s12, 4)) < 1e-9, "large %s: S_12 %s, the plain reading %.4f" % (large, got["S_12"], s12))
    expect(0 < got["S_12"] <= 100, "S_12 %s in (0, 100]" % got["S_12"])
    print("large %s: %d classes, N_t %d + %d, S_12 %.4f" % (large, len(got["classes"]), got["N_t1"], got["N_t2"],
                                                            got["S_12"]))
finish()
