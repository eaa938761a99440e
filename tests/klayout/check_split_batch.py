# Runs the batch macro's split command twice on one layout and checks the split of the modes
# stratified (this script's default) and threshold; the plan, the command's default: check_plan.py.
#   klayout -b -r tests/klayout/check_split_batch.py -rd input=FILE -rd layer=L/D -rd markers=SPEC
#           [-rd split=stratified|threshold] [-rd cell=NAME] -rd work=DIR
# - invariants: the two sets are disjoint and together are the patterns of split.json; every
#   selected window's gauge is in one of them; stratified: a class of one goes to calibration,
#   every larger class is in both sets and its verification count is within one of fraction x n;
#   threshold: verification holds exactly the patterns covering a marker or at most threshold;
# - every clip of calibration.oas and verification.oas equals the layer within its window: the
#   XOR with KLayout's own layer & window is empty; cells are named SET_rRANK_TYPE_SCORE;
# - determinism: a second run gives byte-identical split files;
# - windows.lyrdb: one "split" item per pattern, tagged calibration or verification.
import csv
import filecmp
import json
import os
import subprocess
import sys

import pya

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from harness import BATCH, arg, expect, finish, repo  # noqa: E402

work = arg("work", "/tmp/linf_split_check")
mode = arg("split", "stratified")


def run(out):
    args = ["-rd", "cmd=split", "-rd", "input=" + arg("input"), "-rd", "layer=" + arg("layer"), "-rd", "out=" + out,
            "-rd", "markers=" + arg("markers"), "-rd", "split=" + mode, "-rd", "halves=0"]
    if arg("cell", None):
        args += ["-rd", "cell=" + arg("cell")]
    r = subprocess.run(BATCH + args,
                       capture_output=True, text=True)
    print(r.stdout.strip())
    if r.returncode != 0:
        print(r.stderr)
        sys.exit(1)


run(work)
run(work + "_again")
FILES = ["calibration.oas", "verification.oas", "calibration_gauges.csv", "verification_gauges.csv", "split.json",
         "windows.csv", "gauges.csv" if os.path.exists(os.path.join(work, "gauges.csv")) else "windows.csv"]
for f in FILES:
    expect(filecmp.cmp(os.path.join(work, f), os.path.join(work + "_again", f), shallow=False),
           "%s is byte-identical in a second run" % f)

s = json.load(open(os.path.join(work, "split.json")))
sets = {}
for which in ("calibration", "verification"):
    with open(os.path.join(work, "%s_gauges.csv" % which)) as f:
        sets[which] = {int(r["rank"]): r for r in csv.DictReader(f)}
cal, ver = set(sets["calibration"]), set(sets["verification"])
expect(not (cal & ver), "the sets are disjoint")
expect(len(cal) + len(ver) == s["patterns"] and s["counts"] == {"calibration": len(cal), "verification": len(ver)},
       "the sets make up the %d patterns" % s["patterns"])
with open(os.path.join(work, "windows.csv")) as f:
    selected = [int(r["gauge_id"]) for r in csv.DictReader(f)]
expect(set(selected) <= cal | ver, "every selected window is in a set")

p = s["parameters"]
if s["mode"] == "stratified":
    for c in s["classes"]:
        if c["n"] == 1:
            expect(c["calibration"] == 1, "a class of one goes to calibration: %s" % c)
        else:
            expect(c["calibration"] > 0 and c["verification"] > 0, "class %s %s in both sets" % (c["type"], c["bin"]))
            expect(abs(c["verification"] - p["fraction"] * c["n"]) <= 1, "ratio within one pattern: %s" % c)
else:
    covering = set(selected)
    for which, rows in sets.items():
        for rank, r in rows.items():
            fault_prone = rank in covering or float(r["norm_score"]) <= p["threshold"] + 1e-6
            expect(fault_prone == (which == "verification"), "threshold rule for rank %d (%s)" % (rank, which))

# Clips against KLayout's own layer & window.
ly = pya.Layout()
ly.read(arg("input"))
cell = ly.cell(arg("cell")) if arg("cell", None) else ly.top_cells()[0]
L, D = (int(v) for v in arg("layer").split("/"))
layer = pya.Region(cell.begin_shapes_rec(ly.find_layer(L, D)))
layer.merged_semantics = True
checked = 0
for which, prefix in (("calibration", "CAL"), ("verification", "VER")):
    lib = pya.Layout()
    lib.read(os.path.join(work, "%s.oas" % which))
    li, lw = lib.find_layer(L, D), lib.find_layer(L, 220)
    ranks = set()
    for c in lib.each_cell():
        parts = c.name.split("_")
        expect(parts[0] == prefix and parts[1].startswith("r"), "cell name %s" % c.name)
        ranks.add(int(parts[1][1:]))
        window = pya.Region(c.shapes(lw)).bbox() if lw is not None else pya.Box()
        clip = pya.Region(c.shapes(li)) if li is not None else pya.Region()
        xor = clip ^ (layer & pya.Region(window))
        expect(not window.empty() and xor.is_empty(), "clip %s equals the layer in its window" % c.name)
        # The gauge: one measurement line inside the window and its label naming the rank.
        lg, lm = lib.find_layer(L, 210), lib.find_layer(L, 230)
        paths = [x for x in c.shapes(lg).each() if x.is_path()] if lg is not None else []
        texts = [x.text_string for x in c.shapes(lg).each() if x.is_text()] if lg is not None else []
        expect(len(paths) == 1 and window.enlarged(1, 1).contains(paths[0].bbox().center()),
               "clip %s: one measurement line, in its window" % c.name)
        expect(len(texts) == 1 and texts[0].startswith("#%d " % int(parts[1][1:])), "clip %s: its label" % c.name)
        for m in (c.shapes(lm).each() if lm is not None else []):
            expect(m.bbox().touches(window), "clip %s: its markers meet the window" % c.name)
        checked += 1
    expect(ranks == set(sets[which]), "%s.oas holds one cell per %s pattern" % (which, which))

rdb = pya.ReportDatabase("check")
rdb.load(os.path.join(work, "windows.lyrdb"))
tagged = {"calibration": 0, "verification": 0}
for item in rdb.each_item():
    if rdb.category_by_id(item.category_id()).name() == "split":
        for t in tagged:
            if item.has_tag(rdb.tag_id(t)):
                tagged[t] += 1
expect(tagged == s["counts"], "report database tags %s vs %s" % (tagged, s["counts"]))

finish("%s, calibration %d, verification %d, %d clips XOR-checked" % (s["mode"], len(cal), len(ver), checked))
