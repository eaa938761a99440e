# Printability against real hotspots (issue 34): does ranking gauges by a lithography simulation
# find the ICCAD 2016 hotspots better than the geometric score? For each scorer (the geometric
# score, and the printability score with each model preset) the ROC AUC and the hit rate of the
# 1,000 best gauges against the base rate, printed as a table.
#   klayout -b -r bench/eval_litho.py [-rd input=FILE -rd hotspots=CSV -rd layer=L/D]
#                                     [-rd presets=euv,iccad13] [-rd radius=NM] [-rd threads=N] [-rd near=linf|euclid]
#                                     [-rd opc=1 [-rd opc_iterations=N]]
# Default: ../shared/data/iccad16/testcase3.oas, 1000/0, test3.csv.
# Positives: gauges whose point lies within 32 nm (L-inf, as the issue counted) of a hotspot point. Lower scores
# rank first (worse). The models are the fixed presets; the threshold is calibrate_threshold on
# the layer's typical width and pitch (the gauge stage's typical_width, selection.pitch_of):
# nothing is fitted to the hotspots. Gauges of one type and one context (the layer within
# `radius` nm of the point, default half the model's period, up to the square's symmetries)
# share one simulation (radius=0: every gauge simulated). A gauge whose measurement line does not fit in the model's window
# (a width or space longer than the period) cannot be simulated: it ranks last (it can neither
# pinch nor bridge at that model's resolution); the table counts them. A preset whose threshold
# cannot be calibrated (the model does not resolve the layer's typical line and pitch) gets a row
# "not resolved" and no figures. The models are the commands' (litho.model_of: the process window, dose
# +-2% and the preset's defocus corner). Diagnostic rows per preset rank by other readings of the same
# simulation (the printed cd in nm, the nominal ratio, the deviation either way, the pv band, the
# failure flag), to tell the model's reading from the score's rule. A line counts the positives
# whose own measurement line passes near a hotspot point (those that measure it, not its
# neighbours): what a score read on each gauge's line can rank first. -rd opc=1: each preset again,
# read after the emulated OPC (litho.opc_mask, as -rd opc=1 reads: contexts of the drawn layer).
# -rd opc_iterations=N: the OPC's iterations instead of the commands' (litho.OPC_ITERATIONS), to
# see how much the figures after it depend on where it stopped.
import csv
import math
import os
import sys
import time
from array import array

repo = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(repo, "build"))
sys.path.insert(0, os.path.join(repo, "plugin", "python"))

import pya  # noqa: E402

import linf_opc_core as _core  # noqa: E402
from linf_opc import core, gauges, layout, litho, selection  # noqa: E402

g = globals()
data = os.path.join(repo, "..", "shared", "data", "iccad16")
path = g.get("input") or os.path.join(data, "testcase3.oas")
hot_path = g.get("hotspots") or os.path.join(data, "test3.csv")
L, D = layout.parse_layer(g.get("layer") or "1000/0")
presets = (g.get("presets") or "euv,iccad13").split(",")
threads = int(g.get("threads") or 0)
LINF = (g.get("near") or "linf") == "linf"  # how "within 32 nm" is measured: linf (default, the 6.8% base rate) or euclid
NEAR_NM, BEST = 32.0, 1000


def log(*a):
    print(*a, file=sys.stderr, flush=True)


def read_hotspots(p):
    with open(p, newline="") as f:
        return sorted({(float(r["x"]), float(r["y"])) for r in csv.DictReader(f)})  # identical points count once


class Grid:
    """Points bucketed in squares of side r: the points within r of (x, y) are among near(x, y)."""

    def __init__(self, points, r):
        self.r, self.cells = r, {}
        for x, y in points:
            self.cells.setdefault((math.floor(x / r), math.floor(y / r)), []).append((x, y))

    def near(self, x, y):
        gx, gy = math.floor(x / self.r), math.floor(y / self.r)
        for ax in (gx - 1, gx, gx + 1):
            for ay in (gy - 1, gy, gy + 1):
                yield from self.cells.get((ax, ay), ())


def near_flags(xs, ys, points, r, linf=False):
    """1 where (x, y) lies within r (Euclidean; L-inf with linf) of one of the points."""
    grid = Grid(points, r)
    return bytearray(any((max(abs(px - x), abs(py - y)) <= r) if linf else ((px - x) ** 2 + (py - y) ** 2 <= r * r)
                         for px, py in grid.near(x, y)) for x, y in zip(xs, ys))


def auc(scores, positive):
    """P(a positive scores lower than a negative), ties counting half (Mann-Whitney)."""
    order = sorted(range(len(scores)), key=scores.__getitem__)
    rank_sum, n_pos, i = 0.0, 0, 0
    while i < len(order):
        j = i
        while j + 1 < len(order) and scores[order[j + 1]] == scores[order[i]]:
            j += 1
        mid = (i + j) / 2 + 1  # ranks i+1 .. j+1, from the worst
        for k in range(i, j + 1):
            if positive[order[k]]:
                rank_sum += mid
                n_pos += 1
        i = j + 1
    n_neg = len(scores) - n_pos
    # Rank 1 is the lowest score: a low rank sum for positives is a good predictor.
    u = rank_sum - n_pos * (n_pos + 1) / 2  # pairs where a positive ranks after a negative
    return 1 - u / (n_pos * n_neg)


def best_hits(scores, positive, k):
    """Share of positives among the k lowest scores (ties by rank order: a stable sort)."""
    order = sorted(range(len(scores)), key=scores.__getitem__)[:k]
    return sum(positive[i] for i in order) / len(order)


t0 = time.perf_counter()
ly = pya.Layout()
ly.read(path)
cell = ly.top_cells()[0]
li = ly.find_layer(L, D)
dbu_nm = ly.dbu * 1000
merged = pya.Region(cell.begin_shapes_rec(li)).merged()
polys = layout.polygons_of(merged)
G = gauges.compute(polys, dbu=ly.dbu)
table = G.gauges
n = len(table)
reals, ints = table.columns()
cx, cy = reals[4::10], reals[5::10]
pitch = selection.pitch_of(table)
width = G.typical_width
log("eval_litho: %s %d/%d: %d gauges, typical width %.1f nm, pitch %.1f nm (%.1f s)"
    % (os.path.basename(path), L, D, n, width * dbu_nm, pitch * dbu_nm, time.perf_counter() - t0))
hot = read_hotspots(hot_path)
positive = near_flags(list(cx), list(cy), hot, NEAR_NM / dbu_nm, LINF)
base = sum(positive) / n


def measuring(points, r_nm):
    """How many positives have their measurement line within each distance of r_nm (nm) of a
    hotspot point: the gauges that measure the failing place, not its neighbours."""
    grid = Grid(points, NEAR_NM / dbu_nm)
    counts = [0] * len(r_nm)
    for i in range(n):
        if not positive[i]:
            continue
        x1, y1, x2, y2 = reals[10 * i:10 * i + 4]
        dx, dy = x2 - x1, y2 - y1
        length = dx * dx + dy * dy
        best = math.inf
        for px, py in grid.near(cx[i], cy[i]):
            t = 0.0 if length == 0 else max(0.0, min(1.0, ((px - x1) * dx + (py - y1) * dy) / length))
            best = min(best, math.hypot(px - x1 - t * dx, py - y1 - t * dy))
        for k, d in enumerate(r_nm):
            counts[k] += best * dbu_nm <= d
    return counts


MEASURING_NM = (2, 5, 10)
measures = measuring(hot, MEASURING_NM)
rows = [("geometric score", "", auc(list(table.scores()), positive), best_hits(list(table.scores()), positive, BEST),
         "", "")]

flat = polys.flat()
if g.get("opc_iterations"):
    litho.OPC_ITERATIONS = int(g["opc_iterations"])
variants = [(p, False) for p in presets] + ([(p, True) for p in presets] if g.get("opc") == "1" else [])
for preset, after_opc in variants:
    t1 = time.perf_counter()
    model = litho.model_of({"litho": preset})  # the commands' own models, with their process windows
    mask, S, opc_about = flat, 1, None
    label = preset + (" after OPC" if after_opc else "")
    kernels = model.kernels
    P = kernels.period
    try:
        cal = _core.calibrate_threshold(kernels, width * dbu_nm, pitch * dbu_nm, model.blur_nm)
    except ValueError as e:  # the model cannot print the layer's own lines: no score to compare
        log("eval_litho: %s: %s" % (preset, e))
        rows.append(("litho " + label, "not resolved", None, None, "", ""))
        continue
    if after_opc:
        mask, S, opc_about = litho.opc_mask(polys, dbu_nm, model, cal["threshold"], width * dbu_nm, threads)
        log("eval_litho: %s: OPC %s" % (preset, opc_about))
    # The gauges whose line fits in the window centred on the point (with a unit to spare for
    # the corner's rounding).
    half = P / dbu_nm / 2 - 1
    fits = array("B", (int(max(abs(reals[10 * i + 0] - cx[i]), abs(reals[10 * i + 2] - cx[i]),
                                abs(reals[10 * i + 1] - cy[i]), abs(reals[10 * i + 3] - cy[i])) <= half)
                       for i in range(n)))
    idx = [i for i in range(n) if fits[i]]
    col = lambda k: array("d", (reals[10 * i + k] * S for i in idx))  # noqa: E731 (in the mask's units)
    types = array("i", (ints[13 * i + 12] for i in idx))
    radius = float(g.get("radius") if g.get("radius") is not None else P / 2) / dbu_nm
    pts = array("d")
    for i in idx:
        pts.append(cx[i])
        pts.append(cy[i])
    ids = array("Q", _core.gauge_contexts(flat, pts, radius, threads)) if radius > 0 else None  # radius=0: every gauge
    r = core.gauge_printability(mask, dbu_nm / S, col(4), col(5), col(0), col(1), col(2), col(3), types, col(6),
                                kernels, cal["threshold"], ids, threads, model.defocus, litho.DOSE, model.blur_nm)
    s = array("d", r["score"])
    fails = array("B", r["fails"])
    printed = array("d", r["printed_cd"])
    score = [math.inf] * n
    for k, i in enumerate(idx):
        # As the commands rank (litho.rescore): a reading with no edge within reach ranks last.
        score[i] = s[k] if fails[k] or printed[k] == printed[k] else math.inf
    if g.get("dump"):  # -rd dump=PREFIX: the scores, one a line in rank order, to PREFIX_<preset>.txt
        with open("%s_%s.txt" % (g["dump"], label.replace(" ", "_")), "w") as f:
            f.write("".join("%r\n" % v for v in score))
    log("eval_litho: %s: threshold %.4f (pitch %.1f nm, contrast %.3f), %d of %d gauges simulated in %d windows "
        "(%d shared), %d pinch, %d bridge, %.1f s"
        % (preset, cal["threshold"], cal["pitch"], cal["contrast"], len(idx), n, r["simulations"], r["shared"],
           fails.count(1), fails.count(2), time.perf_counter() - t1))
    rows.append(("litho " + label, "%.4f" % cal["threshold"], auc(score, positive), best_hits(score, positive, BEST),
                 "%d/%d" % (fails.count(1), fails.count(2)), "%d" % (n - len(idx))))
    # Diagnostics, not the printability score, to tell the model's reading from the score's rule:
    # the nominal printed cd in nm (failures first), the nominal ratio alone, the deviation from the
    # drawn cd either way (-|printed / drawn - 1|: a line-end pullback widens a space), the pv band
    # relative to the cd (larger = worse), and the failure flag alone.
    printed = array("d", r["printed_cd"])
    band = array("d", r["pv_band"])
    nominal_fail = array("B", r["fails_nominal"])
    cds = array("d", (v / S for v in col(6)))  # DBU

    def spread(values):
        out = [math.inf] * n
        for k, i in enumerate(idx):
            out[i] = values[k]
        return out

    def finite(v, worst=math.inf):
        return v if v == v else worst
    diag = {
        "printed_cd nm": [s[k] if fails[k] else finite(printed[k]) for k in range(len(idx))],
        "nominal ratio": [(-2 if nominal_fail[k] else finite(printed[k] / (cds[k] * dbu_nm))) for k in range(len(idx))],
        "-|ratio - 1|": [(-2 if fails[k] else -abs(finite(printed[k] / (cds[k] * dbu_nm), 1.0) - 1))
                         for k in range(len(idx))],
        "-pv_band / cd": [(-2 if fails[k] else -finite(band[k], 0.0) / (cds[k] * dbu_nm)) for k in range(len(idx))],
        "fails (then geometric)": [(-1 if fails[k] else 0) for k in range(len(idx))],
    }
    geo = list(table.scores())
    for name, values in diag.items():
        v = spread(values)
        if name.startswith("fails"):
            v = [v[i] * 1e9 + geo[i] if v[i] != math.inf else math.inf for i in range(n)]
        rows.append(("(diagnostic) %s %s" % (label, name), "", auc(v, positive), best_hits(v, positive, BEST), "", ""))

print("Printability against hotspots: %s layer %d/%d, %s" % (os.path.basename(path), L, D, os.path.basename(hot_path)))
print(("gauges %d, distinct hotspot points %d, positives (within %g nm, " + ("L-inf" if LINF else "Euclidean") + ") %d, base rate %.2f%%; typical width %.1f nm, pitch %.1f nm"
      ) % (n, len(hot), NEAR_NM, sum(positive), 100 * base, width * dbu_nm, pitch * dbu_nm))
print("positives whose measurement line passes within %s nm of a hotspot point: %s (the rest are its neighbours)"
      % ("/".join(str(d) for d in MEASURING_NM), "/".join(str(c) for c in measures)))
print("| scorer | threshold | ROC AUC | hit rate of best %d | vs base rate | pinch/bridge | not simulable |" % BEST)
print("|---|---|---|---|---|---|---|")
for name, thr, a, hit, fb, ns in rows:
    if a is None:
        print("| %s | %s | - | - | - | | |" % (name, thr))
        continue
    print("| %s | %s | %.3f | %.2f%% | %.2fx | %s | %s |" % (name, thr, a, 100 * hit, hit / base if base else 0, fb, ns))
