# The budgeted gauge plan (the split's default mode) through the batch macro:
#   klayout -b -r tests/klayout/check_plan.py -rd input=FILE -rd layer=L/D -rd markers=SPEC [-rd cell=NAME]
#           -rd work=DIR
# - cmd=flow -rd all_gauges=1: every row of calibration_gauges.csv and verification_gauges.csv is
#   its gauge's line of gauges.csv plus context and count; the context recomputed in-process from
#   the gauge table, the count recounted over the whole table (the counts of all contexts add up
#   to the gauges); split.json's numbers from the rows;
# - the calibration list: the marker windows' gauges first (rank order, a context once), never a
#   context twice; verification: no calibration gauge, each context once, either another gauge of
#   a calibration context or a context calibration left out;
# - contexts against KLayout: gauges with one id see the same layer within the radius up to the
#   square's symmetries (XOR), the first calibration gauges of one type pairwise different ones;
# - clips: one cell a row, its window centred on the gauge, of the window size;
# - cmd=split writes the same plan files as cmd=flow, and the same again in a second run;
# - budget=1, budget and verify beyond the contexts; bad budget/verify/context_radius: exit 2, one
#   "linf_opc: error:" line, no file.
import csv
import filecmp
import json
import os
import sys
from collections import Counter

import pya

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from harness import arg, batch, expect, finish  # noqa: E402

from linf_opc import contexts as ctx  # noqa: E402
from linf_opc import gauges as gauge_stage  # noqa: E402
from linf_opc import layout as layer_io  # noqa: E402
from linf_opc import polygons as polygons_io  # noqa: E402
from linf_opc.inputs import load  # noqa: E402

work = arg("work", "/tmp/linf_plan_check")
SETS = ("calibration", "verification")
PLAN_FILES = ["calibration.oas", "verification.oas", "calibration_gauges.csv", "verification_gauges.csv", "split.json"]


def run(out, *extra, cmd="split", ok=True):
    return batch(out, cmd, "markers=" + arg("markers"), "halves=0", *extra, ok=ok)


def rows_of(d, which):
    with open(os.path.join(d, "%s_gauges.csv" % which), newline="") as f:
        return list(csv.reader(f))


# Bad values first: they stop before any work.
for bad in ("budget=0", "budget=-3", "budget=x", "verify=-1", "context_radius=0", "context_radius=-0.1"):
    r = run(os.path.join(work, "bad"), bad, ok=False)
    lines = r.stderr.strip().splitlines()
    expect(r.returncode == 2 and [line for line in lines if line.startswith("linf_opc: error:")] == lines[-1:]
           and not os.listdir(os.path.join(work, "bad")),
           "-rd %s: exit %d, %r, files %s" % (bad, r.returncode, lines[-1:], os.listdir(os.path.join(work, "bad"))))

flow_dir, split_dir, again_dir = (os.path.join(work, n) for n in ("flow", "split", "again"))
print(run(flow_dir, "all_gauges=1", cmd="flow").stdout.strip())
print(run(split_dir).stdout.strip())
run(again_dir)
for f in PLAN_FILES:
    expect(filecmp.cmp(os.path.join(flow_dir, f), os.path.join(split_dir, f), shallow=False),
           "%s: cmd=split writes cmd=flow's bytes" % f)
    expect(filecmp.cmp(os.path.join(split_dir, f), os.path.join(again_dir, f), shallow=False),
           "%s is byte-identical in a second run" % f)

s = json.load(open(os.path.join(flow_dir, "split.json")))
p = s["parameters"]
expect(s["mode"] == "plan" and p["budget"] == 1000 and p["verify"] == 1000, "split.json: the plan, its defaults")

# The gauge table in-process, its contexts recomputed and recounted. (No global named as an
# argument, -rd layer or cell: the harness reads them from the script's globals.)
ly, top_cell, index, _ = load({"input": arg("input"), "layer": arg("layer"), "cell": arg("cell", None),
                           "markers": arg("markers")})
dbu = ly.dbu
polygons = layer_io.polygons_of(layer_io.region_of(top_cell, index), polygons_io.SPILL_SHAPES)
table = gauge_stage.compute(polygons, dbu=dbu).gauges
radius = round(p["context_radius_um"] / dbu)
ids = ctx.context_ids(table, polygons, radius)
types = [gauge_stage.TYPES[t] for t in table.type_indices()]
recount = Counter(zip(types, ids))
expect(sum(recount.values()) == len(table), "the contexts' counts add up to the %d gauges" % len(table))
whole_layer = s["layer"]  # not `layer`: the harness reads -rd layer from the script's globals
expect(whole_layer["gauges"] == len(table) and whole_layer["contexts"] == len(recount)
       and whole_layer["context_ids"] == len(set(ids)),
       "split.json layer: %d gauges, %d contexts (%d recounted), %d ids"
       % (whole_layer["gauges"], whole_layer["contexts"], len(recount), whole_layer["context_ids"]))

with open(os.path.join(flow_dir, "gauges.csv"), newline="") as f:
    whole = list(csv.reader(f))
expect(len(whole) - 1 == len(table), "gauges.csv: %d rows, the table %d" % (len(whole) - 1, len(table)))
sets, keys = {}, {}
for which in SETS:
    rows = rows_of(flow_dir, which)
    expect(rows[0] == whole[0] + ["context", "count"], "%s_gauges.csv header" % which)
    sets[which] = rows[1:]
    keys[which] = []
    for row in rows[1:]:
        i = int(row[-3]) - 1  # rank
        key = (row[1], ids[i])
        keys[which].append(key)
        expect(row[:-2] == whole[i + 1], "%s: rank %s is its gauges.csv line" % (which, row[-3]))
        expect(row[-2] == "%016x" % ids[i] and int(row[-1]) == recount[key],
               "%s: rank %s context %s count %s (recomputed %016x, recounted %d)"
               % (which, row[-3], row[-2], row[-1], ids[i], recount[key]))
cal, ver = keys["calibration"], keys["verification"]
expect(len(set(cal)) == len(cal), "calibration never repeats a context")
expect(len(cal) == min(p["budget"], len(recount)), "calibration: %d gauges, budget %d, %d contexts"
       % (len(cal), p["budget"], len(recount)))
expect(len(set(ver)) == len(ver), "verification: each context once")
cal_ranks = set(int(r[-3]) for r in sets["calibration"])
expect(not cal_ranks & set(int(r[-3]) for r in sets["verification"]), "verification holds no calibration gauge")
held_out = [k for k in ver if k not in set(cal)]
others = len(ver) - len(held_out)
wanted = min(p["verify"], len(recount) - len(set(cal)) + sum(1 for k in set(cal) if recount[k] > 1))
expect(len(ver) == wanted, "verification: %d gauges (%d other instances, %d held out), expected %d"
       % (len(ver), others, len(held_out), wanted))

# The marker windows' gauges come first, in rank order, a context once.
with open(os.path.join(flow_dir, "windows.csv"), newline="") as f:
    window_ranks = sorted(int(r["gauge_id"]) for r in csv.DictReader(f))
first, seen = [], set()
for rank in window_ranks:
    k = (types[rank - 1], ids[rank - 1])
    if k not in seen and len(first) < p["budget"]:
        seen.add(k)
        first.append(rank)
expect([int(r[-3]) for r in sets["calibration"][:len(first)]] == first,
       "calibration opens with the %d marker windows' gauges of distinct contexts" % len(first))

st = s["sets"]
for which, ks in (("calibration", cal), ("verification", ver)):
    share = sum(recount[k] for k in set(ks)) / len(table)
    expect(st[which]["gauges"] == len(ks) and st[which]["contexts"] == len(set(ks))
           and abs(st[which]["share_of_gauges"] - share) < 1e-6,
           "split.json %s: %d gauges, %d contexts, share %.4f" % (which, len(ks), len(set(ks)), share))
expect(st["calibration"].get("marker_windows", 0) == len(first), "split.json: %d marker windows" % len(first))

# Contexts against KLayout's own clipping, in doubled coordinates (gauge points are half DBU).
region = pya.Region(top_cell.begin_shapes_rec(index))
region.merged_semantics = True
doubled = region.merged().transformed(pya.ICplxTrans(2.0))


def seen_from(i):
    x, y = round(2 * table.centres()[0][i]), round(2 * table.centres()[1][i])
    box = pya.Box(x - 2 * radius, y - 2 * radius, x + 2 * radius, y + 2 * radius)
    return (doubled & pya.Region(box)).moved(-x, -y)


def alike(a, b):
    return any((a.transformed(pya.Trans(rot, mirror, 0, 0)) ^ b).is_empty() for rot in range(4)
               for mirror in (False, True))


members = {}
for i, k in enumerate(zip(types, ids)):
    if recount[k] > 1 and len(members.setdefault(k, [])) < 2:
        members[k].append(i)
pairs = [m for m in members.values() if len(m) == 2][:40]
for a, b in pairs:
    expect(alike(seen_from(a), seen_from(b)), "ranks %d and %d: one context id, the same neighbourhood" % (a + 1, b + 1))
heads = {}
for row in sets["calibration"][:60]:
    heads.setdefault(row[1], []).append(int(row[-3]) - 1)
differ = 0
for t, idx in heads.items():
    seen = [(i, seen_from(i)) for i in idx[:12]]
    for n, (a, ra) in enumerate(seen):
        for b, rb in seen[n + 1:]:
            differ += 1
            expect(not alike(ra, rb), "calibration ranks %d and %d (%s): different contexts, different neighbourhoods"
                   % (a + 1, b + 1, t))

# Clips: one cell a row, the window of the chosen size centred on the gauge.
side = p["window_um"]
for which in SETS:
    lib = pya.Layout()
    lib.read(os.path.join(flow_dir, "%s.oas" % which))
    lw = lib.find_layer(int(arg("layer").split("/")[0]), 220)
    centres = {}
    for c in lib.each_cell():
        b = pya.Region(c.shapes(lw)).bbox() if lw is not None else pya.Box()
        centres[int(c.name.split("_")[1][1:])] = (b.center().x * lib.dbu, b.center().y * lib.dbu,
                                                  b.width() * lib.dbu, b.height() * lib.dbu)
    expect(sorted(centres) == sorted(int(r[-3]) for r in sets[which]), "%s.oas: one clip a row" % which)
    for r in sets[which]:
        c = centres.get(int(r[-3]))
        expect(c is not None and abs(c[0] - float(r[6])) <= 1.5 * dbu and abs(c[1] - float(r[7])) <= 1.5 * dbu
               and abs(c[2] - side) <= 2 * dbu and abs(c[3] - side) <= 2 * dbu,
               "%s.oas: rank %s's window %s centred on (%s, %s), side %g" % (which, r[-3], c, r[6], r[7], side))
report = open(os.path.join(flow_dir, "report.html")).read()
expect("<h2>Gauge plan</h2>" in report and "<h2>Most repeated contexts</h2>" in report
       and report.count("<svg") >= 4, "report.html: the plan's plot and table")

# budget=1: the best-ranked marker window's gauge; budgets beyond the contexts.
one = os.path.join(work, "one")
run(one, "budget=1", "verify=2")
r1 = rows_of(one, "calibration")[1:]
expect(len(r1) == 1 and int(r1[0][-3]) == window_ranks[0], "budget=1: the first marker window's gauge %s"
       % [r[-3] for r in r1])
expect(len(rows_of(one, "verification")) - 1 == min(2, len(recount) - 1 + (recount[(types[window_ranks[0] - 1],
                                                                                    ids[window_ranks[0] - 1])] > 1)),
       "budget=1 verify=2: two verification gauges")
big = os.path.join(work, "big")
run(big, "budget=%d" % (10 * len(table)), "verify=%d" % (10 * len(table)))
rb = rows_of(big, "calibration")[1:]
kb = [(r[1], ids[int(r[-3]) - 1]) for r in rb]
vb = rows_of(big, "verification")[1:]
expect(len(kb) == len(set(kb)) == len(recount), "a budget beyond the contexts: every context once (%d)" % len(kb))
expect(len(vb) == sum(1 for n in recount.values() if n > 1),
       "verify beyond the contexts: another gauge of each context that has one (%d)" % len(vb))

finish("%d gauges, %d contexts; calibration %d (%d contexts in the first 100), verification %d (%d held out); "
       "%d same-id pairs and %d different pairs XOR-checked"
       % (len(table), len(recount), len(cal), len(set(cal[:100])), len(ver), len(held_out), len(pairs), differ))
