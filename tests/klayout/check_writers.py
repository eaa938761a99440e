# The core's writers (C++, used by the batch and the editor) against Python and KLayout, on
# one layout:
#   klayout -b -r tests/klayout/check_writers.py -rd input=FILE -rd layer=L/D -rd work=DIR
# - voronoi.csv and gauges.csv, and a subset's gauges.csv (the per-pattern mode's, a split
#   set's): the same bytes as the Python writers row by row, the test oracles (oracles.py);
# - the GDSII drawing: read by KLayout and drawn by diagram_output.add_layers, each kind's layer
#   holds exactly the pieces rounded to the grid by Python (ties to even), as zero-width paths, a
#   piece rounding to one point left out, copied in or read straight into a fresh layout (the
#   oracle's way); the temporary file goes with the Diagram;
# - gauges.lyrdb: written directly, loaded and saved by KLayout, the same bytes as the report
#   database filled through KLayout's API and saved;
#   capped at N gauges a type, it holds the N most critical of each;
# - flow.lyrdb joined as text from gauges.lyrdb and the selection's part: the bytes KLayout saves;
#   the selection's part written directly: the bytes of the database filled through the API;
# - the gauge layer drawn through GDSII: each gauge's line rounded by Python and its label;
# - output.save: no OASIS shape compaction above its shape limit, the same shapes.
import filecmp
import gc
import os
import sys
from array import array
from collections import Counter

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from harness import arg, expect, finish  # noqa: E402

import pya  # noqa: E402

from linf_opc import diagram, diagram_output, gauge_output, gauges, layout, output, report_db, selection  # noqa: E402
from linf_opc import markers as marker_io, selection_output, split as split_stage  # noqa: E402
import oracles  # noqa: E402

work = arg("work")
os.makedirs(work, exist_ok=True)
ly = pya.Layout()
ly.read(arg("input"))
L, D = layout.parse_layer(arg("layer"))
polygons = layout.polygons_of(layout.region_of(ly.top_cells()[0], ly.find_layer(L, D)))
core_csv, py_csv = os.path.join(work, "core.csv"), os.path.join(work, "python.csv")
d = diagram.compute(polygons, csv_path=core_csv, dbu=ly.dbu, draw_layer=L, draw_cell="TOP")
oracles.write_voronoi_csv(d, py_csv, ly.dbu)
same = filecmp.cmp(core_csv, py_csv, shallow=False)
rows = sum(1 for _ in open(core_csv)) - 1
print("csv writer on %s: %d rows (%d pieces), core %.3f s, %s" % (os.path.basename(arg("input")), rows, len(d.pieces),
                                                                   d.seconds["csv"], "identical" if same else "DIFFERENT"))
ok = same and rows == len(d.pieces) and rows > 0

res = pya.Layout()
res.dbu = ly.dbu
top = res.create_cell("TOP")
drawn = diagram_output.add_layers(res, top, d, L, D)
for i, kind in enumerate(diagram.KINDS):
    want = Counter()
    for p in d.pieces:
        if p.kind != kind:
            continue
        a, b = (round(p.x1), round(p.y1)), (round(p.x2), round(p.y2))
        if a != b:
            want[(a, b)] += 1
    got = Counter()
    widths = set()
    for s in top.shapes(res.find_layer(L, 200 + i)).each():
        pts = [(q.x, q.y) for q in s.path.each_point()] if s.is_path() else []
        widths.add(s.path.width if s.is_path() else None)
        got[tuple(pts)] += 1
    # Read straight into a fresh layout (the oracle's way), the same shapes.
    direct = pya.Layout()
    direct.dbu = ly.dbu
    dtop = direct.create_cell("TOP")
    oracles.add_diagram_layers(direct, dtop, d, L, D)
    got_direct = Counter(tuple((q.x, q.y) for q in sh.path.each_point())
                         for sh in dtop.shapes(direct.find_layer(L, 200 + i)).each() if sh.is_path())
    match = got == want == got_direct and widths <= {0} and drawn[kind] == sum(want.values())
    print("gds drawing, %s: %d paths, %d pieces of %d drawn by Python, %s"
          % (kind, sum(got.values()), sum(want.values()), d.counts()[kind], "identical" if match else "DIFFERENT"))
    ok = ok and match

core_gcsv, py_gcsv = os.path.join(work, "core_gauges.csv"), os.path.join(work, "python_gauges.csv")
gs = gauges.compute(polygons, dbu=ly.dbu, gauges_csv=core_gcsv).gauges
oracles.write_gauges_csv(gs, py_gcsv, ly.dbu)
same = filecmp.cmp(core_gcsv, py_gcsv, shallow=False) and sum(1 for _ in open(core_gcsv)) == len(gs) + 1
print("gauges.csv, %d gauges: the core's %s the Python writer's" % (len(gs), "is" if same else "DIFFERS FROM"))
ok = ok and same
# A subset out of rank order (every 7th gauge, backwards), from the columns and from records.
picked = list(range(len(gs) - 1, -1, -7))
core_sub, rec_sub, py_sub = (os.path.join(work, n) for n in ("core_sub.csv", "rec_sub.csv", "python_sub.csv"))
gauge_output.write_csv_rows(gs, core_sub, ly.dbu, array("i", picked))
gauge_output.write_csv_rows([gs[i] for i in picked], rec_sub, ly.dbu)
oracles.write_gauges_csv([gs[i] for i in picked], py_sub, ly.dbu)
same = (filecmp.cmp(core_sub, py_sub, shallow=False) and filecmp.cmp(rec_sub, py_sub, shallow=False) and
        sum(1 for _ in open(core_sub)) == len(picked) + 1 and len(picked) > 1)
print("a subset's gauges.csv, %d gauges: the core's %s the Python writer's" % (len(picked),
                                                                             "is" if same else "DIFFERS FROM"))
ok = ok and same
api, fast, resaved = (os.path.join(work, n) for n in ("api.lyrdb", "fast.lyrdb", "resaved.lyrdb"))
gauge_output.report(gs, ly.dbu, "TOP", arg("input")).save(api)
gauge_output.write_report(gs, ly.dbu, "TOP", arg("input"), fast)
rdb = pya.ReportDatabase("check")
rdb.load(fast)
rdb.save(resaved)
same = filecmp.cmp(api, resaved, shallow=False) and rdb.num_items() == len(gs)
print("gauges.lyrdb, %d gauges: written directly and loaded %s the API's" % (len(gs), "is" if same else "DIFFERS FROM"))
ok = ok and same
# The report's cap: the most critical `cap` gauges of each type, from the columns and from a
# plain list alike, and exactly those in the file.
cap = max(1, len(gs) // 20)
capped = os.path.join(work, "capped.lyrdb")
n = gauge_output.write_report(gs, ly.dbu, "TOP", arg("input"), capped, max_per_type=cap)
want_ranks = {}
for x in gs:
    want_ranks.setdefault(x.type, [])
    if len(want_ranks[x.type]) < cap:
        want_ranks[x.type].append(x.rank)
rdb = pya.ReportDatabase("capped")
rdb.load(capped)
got_ranks = {}
for item in rdb.each_item():
    rank = [v.float() for v in item.each_value() if v.tag_id == rdb.user_tag_id("rank")][0]
    got_ranks.setdefault(rdb.category_by_id(item.category_id()).name(), []).append(int(rank))
same = (got_ranks == want_ranks and n == sum(map(len, want_ranks.values())) and
        [x.rank for x in gauge_output.most_critical(list(gs), cap)] ==
        [x.rank for x in gauge_output.most_critical(gs, cap)])
print("gauges.lyrdb capped at %d a type: %d items, %s" % (cap, n, "the most critical" if same else "WRONG"))
ok = ok and same

# flow.lyrdb joined as text (report_db.merge): the same bytes as KLayout saves after loading
# gauges.lyrdb and adding a selection's and a split's categories and items through its API.
# Markers around every 40th gauge; the selection and the split of the smallest windows.
markers = [(x.cx - 5, x.cy - 5, x.cx + 5, x.cy + 5) for x in list(gs)[::40]]
study = selection.study(gs, markers, selection.pitch_of(gs), sizes=(5, 7), modes=("A", "C"))
split = split_stage.stratified(split_stage.patterns_of(study.runs[("A", 5)], gs, markers))
whole, parts, joined = (os.path.join(work, n) for n in ("whole.lyrdb", "parts.lyrdb", "joined.lyrdb"))
for path, base in ((whole, fast), (parts, None)):
    rdb = pya.ReportDatabase("flow")
    if base:
        rdb.load(base)
    rdb.generator = "linf_opc flow"
    rdb.original_file = arg("input")
    rdb.top_cell_name = "TOP"
    selection_output.report(study, gs, ly.dbu, "TOP", rdb, marker_io.Markers(markers, "test <1>"))
    selection_output.report_split(split, ly.dbu, "TOP", rdb)
    rdb.save(path)
report_db.merge(fast, parts, joined, "linf_opc flow")
same = filecmp.cmp(whole, joined, shallow=False) and len(split.patterns) > 0
print("flow.lyrdb joined as text (%d gauges, %d patterns) %s KLayout's" % (len(gs), len(split.patterns),
                                                                           "is" if same else "DIFFERS FROM"))
ok = ok and same
# The selection's and the split's part written directly: the bytes the API's database saves.
direct = os.path.join(work, "direct.lyrdb")
selection_output.write_report(direct, study, gs, ly.dbu, "TOP", arg("input"), "linf_opc flow",
                              marker_io.Markers(markers, "test <1>"), split)
same = filecmp.cmp(parts, direct, shallow=False)
print("selection report written directly (%d windows, %d markers) %s the API's" % (
    sum(len(r.windows) for r in study.runs.values()), len(markers), "is" if same else "DIFFERS FROM"))
ok = ok and same
# The same for the gauge plan's split, whose items also carry the text values cd and count.
from linf_opc import plan as plan_stage  # noqa: E402
run = study.runs[("A", 5)]
plan = plan_stage.plan(gs, polygons, run, [w[4] for w in run.windows], markers, 20, 10, 0.5 * run.side)
plan_api, plan_direct = os.path.join(work, "plan_api.lyrdb"), os.path.join(work, "plan_direct.lyrdb")
rdb = pya.ReportDatabase("flow")
rdb.generator = "linf_opc flow"
rdb.original_file = arg("input")
rdb.top_cell_name = "TOP"
selection_output.report(study, gs, ly.dbu, "TOP", rdb, marker_io.Markers(markers, "test <1>"))
selection_output.report_split(plan, ly.dbu, "TOP", rdb)
rdb.save(plan_api)
selection_output.write_report(plan_direct, study, gs, ly.dbu, "TOP", arg("input"), "linf_opc flow",
                              marker_io.Markers(markers, "test <1>"), plan)
with open(plan_direct) as f:
    counted = f.read().count("[#count] text: ")
same = filecmp.cmp(plan_api, plan_direct, shallow=False) and counted == len(plan.patterns) > 0
print("the plan's report written directly (%d patterns, %d with a count) %s the API's" % (
    len(plan.patterns), counted, "is" if same else "DIFFERS FROM"))
ok = ok and same

index = gauge_output.add_layer(res, top, gs, L, D)
want = Counter()
for x in gs:
    want[("path", (round(x.x1), round(x.y1)), (round(x.x2), round(x.y2)))] += 1
    want[("text", gauge_output.label(x, ly.dbu), (round(x.cx), round(x.cy)))] += 1
got = Counter()
for sh in top.shapes(index).each():
    if sh.is_path():
        pts = [(q.x, q.y) for q in sh.path.each_point()]
        got[("path", pts[0], pts[-1]) if sh.path.width == 0 and len(pts) == 2 else ("bad path", str(sh.path))] += 1
    elif sh.is_text():
        got[("text", sh.text.string, (sh.text.x, sh.text.y))] += 1
    else:
        got[("other", str(sh))] += 1
# From Gauge records (the per-pattern mode's subsets), the same layer.
records = pya.Layout()
records.dbu = ly.dbu
rtop = records.create_cell("TOP")
ri = gauge_output.add_layer(records, rtop, list(gs), L, D)
same = got == want and (Counter(str(sh) for sh in rtop.shapes(ri).each()) ==
                        Counter(str(sh) for sh in top.shapes(index).each()))
print("gauge layer: %d shapes for %d gauges, %s" % (sum(got.values()), len(gs), "identical" if same else "DIFFERENT"))
ok = ok and same

# output.save: a layout above COMPACT_MAX_SHAPES is written without OASIS shape compaction
# (which holds every shape while it writes), with the same shapes. A row of equal boxes at a
# fixed pitch is what compaction turns into one array: the file is far smaller with it.
row = pya.Layout()
rtop = row.create_cell("TOP")
rl = row.insert_layer(pya.LayerInfo(1, 0))
for i in range(1000):
    rtop.shapes(rl).insert(pya.Box(100 * i, 0, 100 * i + 50, 50))
files = {}
for limit in (output.shape_count(row), output.shape_count(row) - 1):
    output.COMPACT_MAX_SHAPES = limit
    files[limit] = os.path.join(work, "row_%d.oas" % limit)
    output.save(row, files[limit])
back = []
for f in files.values():
    r = pya.Layout()
    r.read(f)
    back.append(sorted(str(s.box) for s in r.top_cell().shapes(r.layer(1, 0)).each()))
compact, plain = (os.path.getsize(f) for f in files.values())
same = back[0] == back[1] == sorted(str(s.box) for s in rtop.shapes(rl).each()) and compact * 4 < plain
print("save: 1000 boxes in %d bytes with compaction, %d without it above the limit; same boxes: %s"
      % (compact, plain, same))
ok = ok and same

path = d.gds_path
del d
gc.collect()
gone = not os.path.exists(path)
print("temporary drawing file removed with the diagram: %s" % gone)
expect(ok, "the core's writers agree with Python's and KLayout's (above)")
expect(gone, "the temporary drawing file goes with the diagram")
finish()
