"""The split stage: the selected patterns divided into a calibration and a verification set
for model-based OPC (thesis 5.4 and the separator of Figure 6.2).

in:  the chosen selection Run (selection.py), the ranked gauges, the markers
out: Split: patterns (window, gauge, markers inside), each assigned to "calibration" or
     "verification", with the per-class counts and the classes each set covers.

The patterns are the selection's windows (each covers a marker first) and, so that
calibration has material, the windows of the failed gauges (critical spots whose window shows
no marker) that overlap no other pattern, taken in rank order. The rules of the two modes are
in the README ("Calibration and verification").
"""
import random
from array import array
from collections import namedtuple

from . import core

SETS = ("calibration", "verification")

Pattern = namedtuple("Pattern", "box gauge markers covers_marker")  # box in DBU, gauge a Gauge


def patterns_of(run, gauges, markers):
    """The selection's windows, then the failed gauges' windows that overlap no pattern."""
    side = run.side
    buckets = {}  # markers by grid cell of the window side, for "the markers inside"
    for m in markers:
        for i in range(int(m[0] // side), int(m[2] // side) + 1):
            for j in range(int(m[1] // side), int(m[3] // side) + 1):
                buckets.setdefault((i, j), []).append(m)

    def markers_in(b):
        found = set(m for i in range(int(b[0] // side) - 1, int(b[2] // side) + 2)
                    for j in range(int(b[1] // side) - 1, int(b[3] // side) + 2) for m in buckets.get((i, j), ()))
        return sorted(m for m in found if m[0] <= b[2] and m[2] >= b[0] and m[1] <= b[3] and m[3] >= b[1])

    out = [Pattern((x1, y1, x2, y2), gauges[gi], markers_in((x1, y1, x2, y2)), True)
           for x1, y1, x2, y2, gi, ms in run.windows]
    # Millions of failed spots on a large layer: their centres as one array, the overlap test in the core.
    failed = run.failed_spots
    if hasattr(gauges, "centres"):
        cx, cy = gauges.centres()
        points = array("d", bytes(16 * len(failed)))
        m = memoryview(points)
        m[0::2] = array("d", (cx[gi] for gi in failed))
        m[1::2] = array("d", (cy[gi] for gi in failed))
    else:
        points = array("d", (v for gi in failed for v in (gauges[gi].cx, gauges[gi].cy)))
    taken = array("d", (v for w in run.windows for v in w[:4]))
    h = 0.5 * side
    for k in memoryview(core.free_windows(taken, points, side)).cast("i"):
        g = gauges[failed[k]]
        out.append(Pattern((g.cx - h, g.cy - h, g.cx + h, g.cy + h), g, [], False))
    return out


def score_bin(g, width):
    return round(round(g.norm_score / width) * width, 6)


class Split:
    def __init__(self, mode, params, patterns, assign, bin_width):
        self.mode = mode
        self.params = params
        self.patterns = patterns  # in rank order of their gauges
        self.assign = assign      # one of SETS per pattern
        self.bin_width = bin_width

    def members(self, which):
        return [p for p, a in zip(self.patterns, self.assign) if a == which]

    def classes(self):
        """[{type, bin, n, calibration, verification}] sorted by type and bin."""
        count = {}
        for p, a in zip(self.patterns, self.assign):
            k = (p.gauge.type, score_bin(p.gauge, self.bin_width))
            c = count.setdefault(k, {"calibration": 0, "verification": 0})
            c[a] += 1
        return [{"type": t, "bin": b, "n": c["calibration"] + c["verification"], **c}
                for (t, b), c in sorted(count.items())]

    def summary(self):
        cls = self.classes()
        return {
            "mode": self.mode,
            "parameters": self.params,
            "patterns": len(self.patterns),
            "covering_markers": sum(1 for p in self.patterns if p.covers_marker),
            "counts": {s: len(self.members(s)) for s in SETS},
            "covering_markers_per_set": {s: sum(1 for p in self.members(s) if p.covers_marker) for s in SETS},
            "classes": cls,
            "classes_covered": {s: ["%s %.6g" % (c["type"], c["bin"]) for c in cls if c[s] > 0] for s in SETS},
        }


def by_threshold(patterns, threshold=0.1, bin_width=0.01):
    """Verification: patterns covering a marker, or whose gauge's normalised score is at or
    below `threshold` (fault-prone); calibration: the rest."""
    assign = ["verification" if p.covers_marker or p.gauge.norm_score <= threshold + 1e-12 else "calibration"
              for p in patterns]
    return Split("threshold", {"threshold": threshold, "bin": bin_width}, patterns, assign, bin_width)


def stratified(patterns, fraction=0.3, seed=1, bin_width=0.01):
    """Within each class (gauge type x normalised-score bin of `bin_width`), round(fraction x n)
    patterns, at least one and at most n - 1, drawn with a seeded generator, go to verification;
    a class of one goes to calibration. The draw depends only on the seed and the patterns."""
    if not 0 < fraction < 1:
        raise ValueError("fraction must be between 0 and 1, not %g" % fraction)
    rng = random.Random(seed)
    assign = ["calibration"] * len(patterns)
    groups = {}
    for i, p in enumerate(patterns):
        groups.setdefault((p.gauge.type, score_bin(p.gauge, bin_width)), []).append(i)
    for key in sorted(groups):
        idx = groups[key]
        if len(idx) < 2:
            continue
        k = min(len(idx) - 1, max(1, int(round(fraction * len(idx)))))
        for i in rng.sample(idx, k):
            assign[i] = "verification"
    return Split("stratified", {"fraction": fraction, "seed": seed, "bin": bin_width}, patterns, assign, bin_width)
