"""Printability scoring of the gauge table (issue 34): with -rd litho=PRESET|DIR every gauge is
read on the lithography model's aerial image (core.gauge_printability: one simulation a type and
context), at nominal dose and focus and at the process window's two corners, and the table is
ranked again by the printability score (lower = worse, failures first). The geometric score
stays beside it (geo_score). Everything downstream (selection, plan, split, report, editor)
reads the re-ranked table as it reads the geometric one.

in:  the gauge stage's result (gauges.Gauges), the layer's polygons, the chosen Model
out: the result with .gauges replaced by the re-ranked GaugeTable, whose .litho holds the
     columns geo_score, printed_cd, pv_band, fails (by row = rank - 1), and .litho_summary.

Rules and their reasons: docs/design.md, "Printability in the flow".
"""
import itertools
import operator
import os
import time
from array import array
from concurrent.futures import Future, ThreadPoolExecutor

from . import core
from . import selection as selection_stage
from .arguments import UsageError, switch
from .gauges import GaugeTable
from .polygons import core_input

# The process window: dose +-2% (the ICCAD 2013 contest's DoseMin / DoseMax); the defocus corner
# per preset (nm). duv193: 25 nm, the contest's defocused kernels (M1OPC_def) for the same
# scanner class; euv: 30 nm, the same share (0.24) of lambda / NA^2 (124 nm at 13.5 nm, NA 0.33).
DOSE = 0.02
DEFOCUS_NM = {"duv193": 25.0, "euv": 30.0}
# The resist's blur per preset (a Gaussian's standard deviation, nm): the acid's diffusion in a
# chemically amplified resist, usually quoted at 10-20 nm for 193 nm immersion resists and 5-15 nm
# for EUV ones; each preset takes the low end. Kernel folders (iccad13 too) have none: the
# contest's model is a bare threshold.
BLUR_NM = {"duv193": 10.0, "euv": 5.0}
PRESETS = ("duv193", "euv", "iccad13")
# The emulated OPC's iterations: on testcase 3 the edge placement error's rms falls 2.25 → 0.78 →
# 0.43 → 0.27 → 0.18 nm over four; each costs a reading of every fragment.
OPC_ITERATIONS = 4
FAILS = ("none", "pinch", "bridge")


class Model:
    """A lithography model chosen by name: focus kernels, defocus kernels (None: a dose-only
    process window), the resist's blur (nm) and what to call it. The kernels may be given as
    futures (a preset's, being computed while the layer is read); reading them waits."""

    def __init__(self, name, kernels, defocus, defocus_nm, source, blur_nm=0.0, opc=False):
        self.name, self._kernels, self._defocus, self.defocus_nm, self.source = name, kernels, defocus, defocus_nm, source
        self.blur_nm = blur_nm
        self.opc = opc  # read the layer after an emulated OPC (-rd opc=1), not as drawn

    @property
    def kernels(self):
        if isinstance(self._kernels, Future):
            self._kernels = self._kernels.result()
        return self._kernels

    @property
    def defocus(self):
        if isinstance(self._defocus, Future):
            self._defocus = self._defocus.result()
        return self._defocus

    def __getstate__(self):
        return dict(self.__dict__, _kernels=self.kernels, _defocus=self.defocus)


# Computes the presets' kernels beside the command's own work: two independent
# eigen-decompositions (the core lets go of Python's lock), started as soon as the name is read,
# done by the time the gauges are ranked (both cores are rarely both busy while the layer is
# read and the diagram built).
_KERNELS = ThreadPoolExecutor(2, thread_name_prefix="linf_opc-kernels")


def models_dir():
    """The shipped kernels: models/ of the checkout, or of the installed KLayout package."""
    here = os.path.dirname(os.path.abspath(__file__))
    for up in (os.path.join(here, "..", ".."), os.path.join(here, "..", "..", "..")):
        d = os.path.normpath(os.path.join(up, "models"))
        if os.path.isdir(os.path.join(d, "iccad13")):
            return d
    return None


def _kernels_folder(folder, what):
    try:
        return core.litho_kernels(folder=folder, period=2048.0)
    except ValueError as e:
        raise UsageError("litho=%s: %s" % (what, e))


def model_of(args):
    """-rd litho=duv193|euv|iccad13|DIR, or None without it. DIR: kernels in the ICCAD 2013 format
    (scales.txt, fh*.bin, 2048 nm period), either in DIR itself (a dose-only process window) or
    in DIR/M1OPC with the defocused ones in DIR/M1OPC_def. -rd opc=1: the layer is read after an
    emulated OPC (opc_mask). Read at once: a bad model stops the command before the layer is read
    (UsageError, exit 2)."""
    model = _model_of(args)
    if switch(args, "opc"):
        if model is None:
            raise UsageError("opc=1 needs a lithography model: add -rd litho=duv193|euv|iccad13|DIR")
        model.opc = True
    return model


def opc_mask(polygons, dbu_nm, model, threshold, width_nm, threads=0):
    """The layer after the emulated OPC on `model` (core.opc_correct; docs/design.md, "OPC before
    the reading"): (points, rings) as the core takes them but in DBU / scale, the scale, and what
    the core says of the run. The core reads such a layer with dbu_nm / scale and every
    coordinate given to it times the scale."""
    r = core.opc_correct(core_input(polygons), dbu_nm, model.kernels, threshold, model.blur_nm, width_nm,
                         iterations=OPC_ITERATIONS, threads=threads)
    points, rings = array("q"), array("q")
    points.frombytes(r["points"])
    rings.frombytes(r["rings"])
    about = {"fragments": r["fragments"], "kept_as_drawn": r["kept"], "iterations": len(r["rms_epe"]) - 1,
             "rms_epe_nm": [round(v, 4) for v in r["rms_epe"]], "max_epe_nm": round(r["max_epe"][-1], 4)}
    return (points, rings), r["scale"], about


def _model_of(args):
    text = args.get("litho")
    if text in (None, ""):
        return None
    if text in DEFOCUS_NM:
        # A preset's optics are fixed and valid: nothing here can fail on the user's input.
        focus = _KERNELS.submit(core.litho_kernels, preset=text)
        blurred = _KERNELS.submit(core.litho_kernels, preset=text, defocus=DEFOCUS_NM[text])
        return Model(text, focus, blurred, DEFOCUS_NM[text], "preset", BLUR_NM[text])
    folder = text
    if text == "iccad13":
        base = models_dir()
        if base is None:
            raise UsageError("litho=iccad13: the shipped kernels (models/iccad13) are not installed")
        folder = os.path.join(base, "iccad13")
    elif not os.path.isdir(text):
        raise UsageError("litho must be one of %s or a folder of ICCAD 2013 kernels, not %r"
                         % (", ".join(PRESETS), text))
    if os.path.isdir(os.path.join(folder, "M1OPC")):
        focus = _kernels_folder(os.path.join(folder, "M1OPC"), text)
        blurred = None
        if os.path.isdir(os.path.join(folder, "M1OPC_def")):
            blurred = _kernels_folder(os.path.join(folder, "M1OPC_def"), text)
            if blurred.size != focus.size:
                raise UsageError("litho=%s: the defocused kernels are %d x %d, the focused %d x %d"
                                 % (text, blurred.size, blurred.size, focus.size, focus.size))
        # The contest's defocused kernels are 25 nm from focus; another folder's distance is not known.
        defocus_nm = 0.0 if blurred is None else (25.0 if text == "iccad13" else None)
        return Model(text, focus, blurred, defocus_nm, "files")
    return Model(text, _kernels_folder(folder, text), None, 0.0, "files")


class LithoColumns:
    """The printability columns of a re-ranked table, by row (rank - 1): geo_score (DBU),
    printed_cd and pv_band (nm, NaN where not measured), fails (0 none, 1 pinch, 2 bridge)."""

    def __init__(self, geo_score, printed_cd, pv_band, fails):
        self.geo_score, self.printed_cd, self.pv_band, self.fails = geo_score, printed_cd, pv_band, fails

    HEADER = "geo_score,printed_cd,pv_band,fails"

    def fields(self, row, dbu):
        """The four CSV fields of a row: µm with six decimals (empty where not measured), fails by name."""
        def um(nm):
            return "" if nm != nm else "%.6f" % (nm / 1000.0)
        return "%.6f,%s,%s,%s" % (self.geo_score[row] * dbu, um(self.printed_cd[row]), um(self.pv_band[row]),
                                 FAILS[self.fails[row]])

    def append_to_csv(self, path, dbu):
        """Adds the four columns to a gauges.csv the core wrote (its id is the gauge's rank)."""
        with open(path, "rb") as f:
            lines = f.read().split(b"\r\n")
        out = [lines[0] + b"," + self.HEADER.encode()]
        for line in lines[1:]:
            if not line:
                continue
            row = int(line[:line.index(b",")]) - 1
            out.append(line + b"," + self.fields(row, dbu).encode())
        with open(path, "wb") as f:
            f.write(b"\r\n".join(out) + b"\r\n")


def _fits(reals, n, half):
    """1 where the gauge's measurement line fits in the model's window centred on its point."""
    x1, y1, x2, y2, cx, cy = (reals[k:10 * n:10] for k in range(6))

    def off(a, c):  # loops of C: a layer has millions of gauges
        return map(abs, map(operator.sub, a, c))
    return bytearray(map(operator.le, map(max, off(x1, cx), off(x2, cx), off(y1, cy), off(y2, cy)),
                         itertools.repeat(half)))


def rescore(result, polygons, dbu_um, model, threads=0):
    """The gauge stage's `result` with its table ranked by printability on `model`. The threshold
    is calibrated on the layer's typical width and pitch (core.calibrate_threshold); a model that
    does not resolve them is a UsageError. Gauges whose measurement line does not fit in the
    model's window (a width or space above about half its period) cannot be simulated, and a
    reading that finds no edge within a quarter window says nothing of the print: such gauges
    keep fails none and no printed_cd, and rank last, with the highest score of the others."""
    t0 = time.perf_counter()
    table = result.gauges
    n = len(table)
    dbu_nm = dbu_um * 1000.0
    kernels = model.kernels
    P = kernels.period
    width_nm = result.typical_width * dbu_nm
    pitch_nm = selection_stage.pitch_of(table) * dbu_nm
    try:
        cal = core.calibrate_threshold(kernels, width_nm, pitch_nm, model.blur_nm)
    except ValueError as e:
        raise UsageError("litho=%s cannot print the layer's typical line (%.4g nm at a pitch of %.4g nm): %s"
                         % (model.name, width_nm, pitch_nm, e))
    reals, ints = table.columns()
    half = P / dbu_nm / 2 - 1  # a unit to spare for the window's rounding to the half DBU
    fits = _fits(reals, n, half)
    idx = array("i", itertools.compress(range(n), fits))
    every = len(idx) == n  # the usual case: each column is a strided view of the table's

    def col(k, width=10, of=None, code="d"):
        v = (reals if of is None else of)[k:width * n:width]
        if not every:
            return array(code, (v[i] for i in idx))
        a = array(code)
        a.frombytes(v.tobytes())  # copies of C (an array of a strided view loops in Python)
        return a
    types = col(12, 13, ints, "i")
    drawn = mask = core_input(polygons)
    opc, S = None, 1
    if model.opc:
        t1 = time.perf_counter()
        mask, S, opc = opc_mask(polygons, dbu_nm, model, cal["threshold"], width_nm, threads)
        opc["seconds"] = round(time.perf_counter() - t1, 3)
        result.litho_mask = (mask, S)  # the report's pictures image it
    pts = array("d", bytes(16 * len(idx)))
    pts[0::2], pts[1::2] = col(4), col(5)
    # One simulation a type and context: the drawn layer within half the window of the point, up
    # to the square's symmetries (contexts.py); a repeated context costs nothing more. After the
    # OPC a context's first gauge is read on the corrected layer for all of them: the corrections
    # of one drawn context differ only by the far neighbours' pull (docs/design.md).
    ids = array("Q")
    ids.frombytes(core.gauge_contexts(drawn, pts, P / 2 / dbu_nm, threads))

    def on_mask(k):  # a column in the mask's units
        return col(k) if S == 1 else array("d", (v * S for v in col(k)))
    r = core.gauge_printability(mask, dbu_nm / S, on_mask(4), on_mask(5), on_mask(0), on_mask(1), on_mask(2),
                                on_mask(3), types, on_mask(6), kernels, cal["threshold"], ids, threads, model.defocus,
                                DOSE, model.blur_nm)
    s, printed, band = array("d", r["score"]), array("d", r["printed_cd"]), array("d", r["pv_band"])
    fails_sim = array("B", r["fails"])
    if every:
        score, pcd, pvb, fl = s, printed, band, fails_sim
    else:
        nan = float("nan")
        score = array("d", [nan]) * n
        pcd, pvb, fl = array("d", [nan]) * n, array("d", [nan]) * n, array("B", bytes(n))
        for k, i in enumerate(idx):
            score[i], pcd[i], pvb[i], fl[i] = s[k], printed[k], band[k], fails_sim[k]
    # Read: measured or failed at some condition. Not read: no edge within reach of the point (a
    # space or width wider than half the window: the core's score there is only a lower bound,
    # below 1 for a drawn cd above half the window, which would put wide spaces first) or not
    # simulable. The read ones rank by score, ties by geometric rank; the others follow by
    # geometric rank, with the highest score of the read ones, so that scores never decrease
    # (core.litho_rank: a sort of millions of gauges is no work for Python).
    ranked, ranked_score, n_read, highest = core.litho_rank(score, pcd, fl)
    perm = array("i")
    perm.frombytes(ranked)
    ranked_score = array("d", ranked_score)
    # Whole records moved in the new order (core.permute_records), then the changed columns
    # written over (a Python loop over every field of 83,458 rows took a third of a second).
    new_reals, new_ints = array("d"), array("i")
    new_reals.frombytes(core.permute_records(reals, 80, perm))
    new_ints.frombytes(core.permute_records(ints, 52, perm))
    geo = new_reals[7::10]
    # The table holds scores in DBU (every writer multiplies by the DBU): the ratio is held
    # divided by it, so that files and reports show the ratio itself.
    new_reals[7::10] = array("d", map(operator.truediv, ranked_score, itertools.repeat(dbu_um)))
    new_reals[8::10] = (array("d", map(operator.truediv, ranked_score, itertools.repeat(highest))) if highest > 0
                        else array("d", bytes(8 * n)))
    new_ints[0::13] = array("i", range(1, n + 1))
    p_cd, p_band = (array("d", core.permute_records(c, 8, perm)) for c in (pcd, pvb))
    p_fail = array("B", core.permute_records(fl, 1, perm))
    paths = None
    if table._paths is not None:
        paths = [table._paths[i] for i in perm]
    new = GaugeTable({"count": n, "reals": new_reals.tobytes(), "ints": new_ints.tobytes(), "paths": paths})
    new.litho = LithoColumns(geo, p_cd, p_band, p_fail)
    result.gauges = new
    result.csv_path = None  # a gauges.csv the core wrote during the stage is in the geometric order
    result.litho_summary = {
        "model": model.name, "kernels": model.source, "period_nm": P, "threshold": round(cal["threshold"], 9),
        "calibration": {"width_nm": round(width_nm, 6), "pitch_nm": round(cal["pitch"], 6),
                        "contrast": round(cal["contrast"], 6)},
        "process_window": {"dose": DOSE, "defocus_nm": model.defocus_nm}, "resist_blur_nm": model.blur_nm,
        "opc": opc,
        "simulated": len(idx), "not_simulable": n - len(idx), "not_read": n - n_read, "simulations": r["simulations"], "shared": r["shared"],
        "images": r["images"],
        "fails": {name: p_fail.count(k) for k, name in enumerate(FAILS)},
        "fails_nominal": {name: array("B", r["fails_nominal"]).count(k) for k, name in enumerate(FAILS)},
        "seconds": round(time.perf_counter() - t0, 3),
    }
    result.litho_model, result.litho_threshold = model, cal["threshold"]  # the report's pictures
    result.seconds["litho"] = time.perf_counter() - t0
    return result

