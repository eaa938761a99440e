# Printability in the commands (-rd litho=PRESET|DIR) through the batch macro:
#   klayout -b -r tests/klayout/check_litho_flow.py -rd input=FILE -rd layer=L/D -rd markers=SPEC
#           [-rd litho=euv] [-rd cell=NAME] -rd work=DIR
# - bad model input (an unknown preset, a folder without kernels, a kernel file cut short, and with
#   -rd unresolved=MODEL a model that cannot print the layer's typical line): exit 2, one
#   "linf_opc: error:" line, nothing in the output folder;
# - cmd=gauges without litho: gauges.csv has the 13 columns of old and is byte for byte the file the
#   core writes for the same layer in this process (the litho code path changes nothing);
# - cmd=gauges with litho: the header gains geo_score,printed_cd,pv_band,fails; ids and ranks 1..n in
#   order; scores never decrease; norm_score = score / the highest; the same gauges as without litho,
#   each with geo_score = its geometric score; fails in {none, pinch, bridge}, pinch only on width
#   gauges and bridge only on spaces, fails != none exactly where score <= 0; a measured printed_cd
#   bounds the score (the least over the conditions); pv_band >= 0, and where a width pinches at a
#   corner only, pv_band >= the nominal printed cd (the failed corner's width is 0); summary.json's
#   counts of fails; the first gauges re-simulated one by one in this process (no sharing) give the
#   same printed_cd and fails;
# - -rd opc=1: refused without a model or as another value than 0/1; with a model the same gauges,
#   summary.json's litho.opc with the rms edge placement error at least halved, no more nominal
#   failures than the drawn layer's; the flow's report outlines the corrected layer in its pictures;
# - cmd=flow with litho and split=threshold: every calibration gauge has fails none; a verification
#   gauge has fails != none or its window covers a marker (a selection window); split.json names the
#   separator; with split=plan both gauge lists carry the litho columns after context and count.
import csv
import filecmp
import json
import math
import os
import shutil
import sys
from array import array
from collections import Counter

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from harness import arg, batch, expect, finish, repo  # noqa: E402

work = arg("work", "/tmp/linf_litho_check")
MODEL = arg("litho", "euv")
BASE = ["id", "type", "x1", "y1", "x2", "y2", "cx", "cy", "cd", "score", "norm_score", "tiebreak", "rank"]
LITHO = ["geo_score", "printed_cd", "pv_band", "fails"]
WIDTHS = ("internal", "sandwich", "comb", "T")


def run(out, cmd, *extra, ok=True):
    return batch(out, cmd, *extra, ok=ok)


def rows_of(path):
    with open(path, newline="") as f:
        return list(csv.reader(f))


# Bad model input: one line, exit 2, nothing written.
os.makedirs(work, exist_ok=True)
empty = os.path.join(work, "no_kernels")
os.makedirs(empty, exist_ok=True)
cut = os.path.join(work, "cut_kernels")
shutil.rmtree(cut, ignore_errors=True)
shutil.copytree(os.path.join(repo, "models", "iccad13", "M1OPC"), cut)
with open(os.path.join(cut, "fh3.bin"), "r+b") as f:
    f.truncate(1000)
for bad, cmds in (("nonsense", ("gauges", "flow")), (empty, ("gauges",)), (cut, ("flow",)),
                  (os.path.join(work, "missing_folder"), ("gauges",))):
    for cmd in cmds:
        out = os.path.join(work, "bad")
        r = run(out, cmd, "litho=" + bad, "markers=" + arg("markers"), ok=False)
        lines = r.stderr.strip().splitlines()
        files = os.listdir(out) if os.path.isdir(out) else []  # the model is read before the folder is made
        expect(r.returncode == 2 and len(lines) == 1 and lines[0].startswith("linf_opc: error: litho")
               and not files, "%s -rd litho=%s: exit %d, stderr %r, files %s" % (cmd, bad, r.returncode, lines, files))

# A model that cannot print the layer's typical line (-rd unresolved=MODEL, where one is known): the same.
if arg("unresolved", None):
    out = os.path.join(work, "unresolved")
    r = run(out, "flow", "litho=" + arg("unresolved"), "markers=" + arg("markers"), ok=False)
    lines = r.stderr.strip().splitlines()
    files = os.listdir(out) if os.path.isdir(out) else []
    expect(r.returncode == 2 and len(lines) == 1 and "cannot print the layer's typical line" in lines[0]
           and not files, "flow -rd litho=%s on a layer it does not resolve: exit %d, stderr %r, files %s"
           % (arg("unresolved"), r.returncode, lines, files))

# Without litho: the old columns, the core's own bytes.
plain = os.path.join(work, "plain")
run(plain, "gauges")
import pya  # noqa: E402

from linf_opc import core, gauges as gauge_stage, layout as layer_io  # noqa: E402
from linf_opc.inputs import load  # noqa: E402

ly, top_cell, layer_index, _ = load({"input": arg("input"), "layer": arg("layer"), "cell": arg("cell", None)})
polys = layer_io.polygons_of(layer_io.region_of(top_cell, layer_index))
own = os.path.join(work, "own_gauges.csv")
G = gauge_stage.compute(polys, dbu=ly.dbu, gauges_csv=own)
expect(filecmp.cmp(own, os.path.join(plain, "gauges.csv"), shallow=False),
       "without litho gauges.csv is the core's file byte for byte")
plain_rows = rows_of(os.path.join(plain, "gauges.csv"))
expect(plain_rows[0] == BASE, "without litho the header is the 13 columns: %s" % plain_rows[0])

# With litho.
lit = os.path.join(work, "litho")
print(run(lit, "gauges", "litho=" + MODEL).stdout.strip())
rows = rows_of(os.path.join(lit, "gauges.csv"))
expect(rows[0] == BASE + LITHO, "with litho the header gains %s: %s" % (LITHO, rows[0]))
head = {k: j for j, k in enumerate(rows[0])}
body = rows[1:]
expect(len(body) == len(plain_rows) - 1, "the same number of gauges with and without litho")
expect(all(int(r[head["id"]]) == k + 1 == int(r[head["rank"]]) for k, r in enumerate(body)), "ids and ranks are 1..n")
score = [float(r[head["score"]]) for r in body]
expect(all(a <= b for a, b in zip(score, score[1:])), "scores never decrease with rank")
top = max(score)
expect(all(abs(float(r[head["norm_score"]]) - s / top) < 1e-5 for r, s in zip(body, score)),
       "norm_score = score / the highest")
key = lambda r, h: (r[h["type"]],) + tuple(r[h[k]] for k in ("x1", "y1", "x2", "y2"))  # noqa: E731
# Two gauges can share a type and a line (gauges.oas: "gauges that measure the same line overlap"): multisets.
plain_head = {k: j for j, k in enumerate(BASE)}
expect(Counter(key(r, plain_head) for r in plain_rows[1:]) == Counter(key(r, head) for r in body),
       "the same gauges (type and line) with and without litho")
expect(Counter(key(r, plain_head) + (r[plain_head["score"]],) for r in plain_rows[1:])
       == Counter(key(r, head) + (r[head["geo_score"]],) for r in body), "geo_score is each gauge's geometric score")
fails = [r[head["fails"]] for r in body]
expect(set(fails) <= {"none", "pinch", "bridge"}, "fails values: %s" % sorted(set(fails)))
expect(fails.count("none") < len(fails), "the layer pinches or bridges somewhere under %s (else the checks of "
       "failures below say nothing)" % MODEL)
expect(all(f != "pinch" or r[head["type"]] in WIDTHS for f, r in zip(fails, body)), "pinch only on width gauges")
expect(all(f != "bridge" or r[head["type"]] == "external" for f, r in zip(fails, body)), "bridge only on spaces")
expect(all((f != "none") == (s <= 0) for f, s in zip(fails, score)), "fails != none exactly where score <= 0")
bad_bound = [r[head["id"]] for r, s in zip(body, score) if r[head["printed_cd"]]
             and s > float(r[head["printed_cd"]]) / float(r[head["cd"]]) + 1e-5]
expect(not bad_bound, "a measured printed_cd / cd bounds the score from above (ids %s)" % bad_bound[:5])
bands = [float(r[head["pv_band"]]) for r in body if r[head["pv_band"]]]
expect(bands and min(bands) >= 0, "pv_band >= 0 (%d measured)" % len(bands))
corner_pinch = [r for r, f in zip(body, fails) if f == "pinch" and r[head["printed_cd"]] and r[head["pv_band"]]]
expect(all(float(r[head["pv_band"]]) >= float(r[head["printed_cd"]]) - 1e-6 for r in corner_pinch),
       "a width pinching at a corner only: pv_band >= its nominal printed cd (%d such)" % len(corner_pinch))
s = json.load(open(os.path.join(lit, "summary.json")))["litho"]
expect(s["fails"] == {k: fails.count(k) for k in ("none", "pinch", "bridge")}, "summary.json counts the fails")
expect(s["simulations"] + s["shared"] == s["simulated"] and s["simulations"] <= len(body),
       "summary.json: simulations + shared = simulated gauges")
expect(0 < s["images"] <= s["simulations"], "summary.json: one image a line, at most one a simulation")
print("litho %s: threshold %s, %d gauges, %d windows, fails %s, printed %d, pv_band %d"
      % (MODEL, s["threshold"], len(body), s["simulations"], s["fails"], sum(1 for r in body if r[head["printed_cd"]]),
         len(bands)))

# The first gauges, and every failing one among the first 200, simulated alone in this process.
from linf_opc import litho  # noqa: E402

model = litho.model_of({"litho": MODEL})
dbu_nm = ly.dbu * 1000
picked = [k for k in range(min(len(body), 200)) if k < 20 or fails[k] != "none"][:60]
col = lambda name: array("d", (float(body[k][head[name]]) / ly.dbu for k in picked))  # noqa: E731
types = array("i", (gauge_stage.TYPES.index(body[k][head["type"]]) for k in picked))
alone = core.gauge_printability(polys.flat(), dbu_nm, col("cx"), col("cy"), col("x1"), col("y1"), col("x2"), col("y2"),
                                types, col("cd"), model.kernels, s["threshold"], None, 0, model.defocus, litho.DOSE,
                                model.blur_nm)
p_alone, f_alone = array("d", alone["printed_cd"]), array("B", alone["fails"])
mismatch = []
for j, k in enumerate(picked):
    want = "" if p_alone[j] != p_alone[j] else "%.6f" % (p_alone[j] / 1000)
    got = body[k][head["printed_cd"]]
    if litho.FAILS[f_alone[j]] != fails[k] or (want == "") != (got == "") or (
            want and abs(float(want) - float(got)) > 5e-5):
        mismatch.append((k + 1, want, got, litho.FAILS[f_alone[j]], fails[k]))
expect(not mismatch, "%d gauges re-simulated alone read as in gauges.csv (mismatches: %s)" % (len(picked), mismatch[:5]))

# The emulated OPC (-rd opc=1): refused without a model or with another value; with one, the same
# gauges, the error falling over its iterations, and no more nominal failures than the drawn
# layer's (the OPC prints every fragment at its drawn edge; what it leaves is the process window's).
for extra, says in ((("opc=1",), "opc=1 needs a lithography model"), (("litho=" + MODEL, "opc=2"), "opc must be 0 or 1")):
    out = os.path.join(work, "bad_opc")
    r = run(out, "gauges", *extra, ok=False)
    lines = r.stderr.strip().splitlines()
    files = os.listdir(out) if os.path.isdir(out) else []
    expect(r.returncode == 2 and len(lines) == 1 and says in lines[0] and not files,
           "gauges -rd %s: exit %d, stderr %r, files %s" % (" -rd ".join(extra), r.returncode, lines, files))
opc_dir = os.path.join(work, "litho_opc")
print(run(opc_dir, "gauges", "litho=" + MODEL, "opc=1").stdout.strip())
opc_rows = rows_of(os.path.join(opc_dir, "gauges.csv"))
expect(opc_rows[0] == BASE + LITHO, "with opc=1 the header is the litho one: %s" % opc_rows[0])
opc_head = {k: j for j, k in enumerate(opc_rows[0])}
expect(Counter(key(r, opc_head) + (r[opc_head["geo_score"]],) for r in opc_rows[1:])
       == Counter(key(r, head) + (r[head["geo_score"]],) for r in body), "with opc=1 the same gauges and geo_scores")
so = json.load(open(os.path.join(opc_dir, "summary.json")))["litho"]
opc = so["opc"]
expect(opc and opc["fragments"] > 0 and opc["iterations"] == len(opc["rms_epe_nm"]) - 1 >= 1,
       "summary.json: litho.opc with fragments and one error an iteration and after: %s" % opc)
expect(opc["rms_epe_nm"][-1] < opc["rms_epe_nm"][0] / 2,
       "the OPC's rms edge placement error falls by half at least: %s" % opc["rms_epe_nm"])
drawn_nominal = sum(v for k, v in s["fails_nominal"].items() if k != "none")
opc_nominal = sum(v for k, v in so["fails_nominal"].items() if k != "none")
expect(opc_nominal <= drawn_nominal, "nominal failures after the OPC %d, drawn %d" % (opc_nominal, drawn_nominal))
expect(s.get("opc") is None, "without opc=1 summary.json's litho.opc is empty")
print("opc: %d fragments, rms error %s nm, nominal failures %d -> %d"
      % (opc["fragments"], opc["rms_epe_nm"], drawn_nominal, opc_nominal))
# The flow with the OPC: the report's pictures say so and outline the corrected layer (orange)
# over the drawn one in every left panel.
opc_flow = os.path.join(work, "flow_opc")
print(run(opc_flow, "flow", "litho=" + MODEL, "opc=1", "markers=" + arg("markers")).stdout.strip())
page = open(os.path.join(opc_flow, "report.html")).read()
pairs = page.count('class="litho-pair"')
outlined = page.count('<path fill="none" stroke="#ff7f0e"')
expect("after an emulated model-based OPC" in page and pairs >= 1 and outlined == pairs,
       "report.html with opc=1: the OPC said, the corrected layer outlined in each of the %d pictures (%d)"
       % (pairs, outlined))
expect(json.load(open(os.path.join(opc_flow, "summary.json")))["gauges"]["litho"]["opc"]["fragments"]
       == opc["fragments"], "the flow's OPC corrects the same fragments as the gauges command's")

# The flow: the threshold separator follows fails.
thr = os.path.join(work, "flow_threshold")
# threshold=1 puts every pattern in verification by the norm-score separator: only fails can leave
# some to calibration; small windows give patterns beyond the marker windows.
print(run(thr, "flow", "litho=" + MODEL, "markers=" + arg("markers"), "split=threshold", "threshold=1",
          "sizes=2").stdout.strip())
windows = set(int(r["gauge_id"]) for r in csv.DictReader(open(os.path.join(thr, "windows.csv"))))
cal = list(csv.DictReader(open(os.path.join(thr, "calibration_gauges.csv"))))
ver = list(csv.DictReader(open(os.path.join(thr, "verification_gauges.csv"))))
expect(cal and all(r["fails"] == "none" and int(r["id"]) not in windows for r in cal),
       "threshold split: %d calibration gauges, all fails none and none a marker window's" % len(cal))
expect(ver and all(r["fails"] != "none" or int(r["id"]) in windows for r in ver),
       "threshold split: %d verification gauges, each failing or a marker window's" % len(ver))
expect(json.load(open(os.path.join(thr, "split.json")))["parameters"].get("separator") == "fails",
       "split.json: the separator is fails")
failing = sum(1 for r in cal + ver if r["fails"] != "none")
expect(any(r["fails"] != "none" and int(r["id"]) not in windows for r in ver),
       "threshold split: some verification gauge is there for failing alone (not a marker window's)")
print("threshold split: calibration %d, verification %d (%d failing)" % (len(cal), len(ver), failing))

plan = os.path.join(work, "flow_plan")
print(run(plan, "flow", "litho=" + MODEL, "markers=" + arg("markers")).stdout.strip())
for which in ("calibration", "verification"):
    r = rows_of(os.path.join(plan, "%s_gauges.csv" % which))
    expect(r[0] == BASE + ["context", "count"] + LITHO, "plan %s_gauges.csv header: %s" % (which, r[0]))
sj = json.load(open(os.path.join(plan, "summary.json")))
expect("litho" in sj["gauges"], "flow summary.json: gauges.litho")
page = open(os.path.join(plan, "report.html")).read()
panels = page.count('class="litho"')
expect("Printability of the most critical contexts" in page and panels >= 2 and panels % 2 == 0
       and page.count('stroke="#1f77b4" stroke-width="1.4" d="M') >= 1,
       "report.html: printability pictures, two panels a context, contours drawn (%d panels)" % panels)

finish()
