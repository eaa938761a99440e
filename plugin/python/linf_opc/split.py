"""The split stage: the selected patterns divided into a calibration and a verification set
for model-based OPC (thesis 5.4 and the separator of Figure 6.2).

in:  the chosen selection Run (selection.py), the ranked gauges, the markers
out: Split: patterns (window, gauge, markers inside), each assigned to "calibration" or
     "verification", with the per-class counts and the classes each set covers.

The patterns are the selection's windows (each covers a marker first) and, so that
calibration has material, the windows of the failed gauges (critical spots whose window shows
no marker) that overlap no other pattern, taken in rank order. The rules of the two modes are
in docs/design.md, "Split rules". The split's default mode, the budgeted gauge plan, is plan.py
(a Split too).
"""
import random
from array import array

from . import core
from .records import Records, Subset

SETS = ("calibration", "verification")


class Pattern:
    """A selected window: box (x1, y1, x2, y2) in DBU, its gauge (gauges[index], made when asked
    for), the markers inside, and whether it covers a marker first (a selection window) or not
    (a failed gauge's window). Made by Patterns on access."""
    __slots__ = ("box", "index", "markers", "covers_marker", "_gauges")

    def __init__(self, box, gauges, index, markers, covers_marker):
        self.box, self._gauges, self.index = box, gauges, index
        self.markers, self.covers_marker = markers, covers_marker

    @property
    def gauge(self):
        return self._gauges[self.index]


class Patterns(Records):
    """The patterns as columns (boxes, gauge indices, the markers inside as indices into the
    markers), a Pattern made on access: a full layer's split has hundreds of thousands of
    patterns, and a Pattern each with its tuples and lists would be most of the flow's memory
    at its end."""

    def __init__(self, gauges, markers):
        self._gauges, self._markers = gauges, markers
        self._boxes, self._index, self._covers = array("d"), array("i"), bytearray()
        self._starts, self._inside = array("i", [0]), array("i")

    def append(self, box, index, inside, covers_marker):
        self._boxes.extend(box)
        self._index.append(index)
        self._covers.append(bool(covers_marker))
        self._inside.extend(inside)
        self._starts.append(len(self._inside))

    def __len__(self):
        return len(self._index)

    def _record(self, i):
        inside = self._inside[self._starts[i]:self._starts[i + 1]]
        return Pattern(tuple(self._boxes[4 * i:4 * i + 4]), self._gauges, self._index[i],
                       [self._markers[j] for j in inside], bool(self._covers[i]))

    def covering(self):
        """One byte a pattern: 1 where it covers a marker first."""
        return self._covers


class MarkerGrid:
    """The markers on a grid of the window side, for "the markers inside" a window."""

    def __init__(self, markers, side):
        self.markers, self.side = markers, side
        self.buckets = {}  # marker indices by grid cell
        for k, m in enumerate(markers):
            for i in range(int(m[0] // side), int(m[2] // side) + 1):
                for j in range(int(m[1] // side), int(m[3] // side) + 1):
                    self.buckets.setdefault((i, j), []).append(k)

    def inside(self, b):
        """The markers meeting box b: by value, one index per distinct box, in the boxes' order
        (equal boxes are one marker)."""
        found, side, markers = {}, self.side, self.markers
        for i in range(int(b[0] // side) - 1, int(b[2] // side) + 2):
            for j in range(int(b[1] // side) - 1, int(b[3] // side) + 2):
                for k in self.buckets.get((i, j), ()):
                    found.setdefault(tuple(markers[k]), k)
        return [k for m, k in sorted(found.items()) if m[0] <= b[2] and m[2] >= b[0] and m[1] <= b[3] and m[3] >= b[1]]


def patterns_of(run, gauges, markers):
    """The selection's windows, then the failed gauges' windows that overlap no pattern."""
    side = run.side
    markers_in = MarkerGrid(markers, side).inside
    out = Patterns(gauges, markers)
    for x1, y1, x2, y2, gi, ms in run.windows:
        out.append((x1, y1, x2, y2), gi, markers_in((x1, y1, x2, y2)), True)
    # Millions of failed spots on a large layer: the core reads their centres in the table's
    # columns, picked by index.
    failed = run.failed_spots
    taken = run.windows.boxes()
    if hasattr(gauges, "centres"):
        cx, cy = gauges.centres()
        kept = core.free_windows(taken, cx, cy, side, ids=failed)
    else:
        kept = core.free_windows(taken, array("d", (gauges[gi].cx for gi in failed)),
                                 array("d", (gauges[gi].cy for gi in failed)), side)
    h = 0.5 * side
    for k in memoryview(kept).cast("i"):
        gi = failed[k]
        g = gauges[gi]
        out.append((g.cx - h, g.cy - h, g.cx + h, g.cy + h), gi, (), False)
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
        """The patterns of one set, in order, each made on access."""
        return Subset(self.patterns, array("i", (i for i, a in enumerate(self.assign) if a == which)))

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
        covers = self.patterns.covering()  # a column: no Pattern made per count
        return {
            "mode": self.mode,
            "parameters": self.params,
            "patterns": len(self.patterns),
            "covering_markers": sum(covers),
            "counts": {s: self.assign.count(s) for s in SETS},
            "covering_markers_per_set": {s: sum(1 for c, a in zip(covers, self.assign) if c and a == s) for s in SETS},
            "classes": cls,
            "classes_covered": {s: ["%s %.6g" % (c["type"], c["bin"]) for c in cls if c[s] > 0] for s in SETS},
        }


def by_threshold(patterns, threshold=0.1, bin_width=0.01, fails=None):
    """Verification: patterns covering a marker, or whose gauge is fault-prone: its normalised
    score at or below `threshold` or, with `fails` (pattern -> 0 none, 1 pinch, 2 bridge: the
    lithography model's reading), its gauge pinching or bridging; calibration: the rest."""
    if fails is None:
        faulty = lambda p: p.gauge.norm_score <= threshold + 1e-12  # noqa: E731
        params = {"threshold": threshold, "bin": bin_width}
    else:
        faulty = lambda p: fails(p) != 0  # noqa: E731
        params = {"separator": "fails", "bin": bin_width}
    assign = ["verification" if p.covers_marker or faulty(p) else "calibration" for p in patterns]
    return Split("threshold", params, patterns, assign, bin_width)


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
