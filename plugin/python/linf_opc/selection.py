"""The pattern-selection stage (thesis 5.2-5.3).

in:  ranked gauges (gauges.py), markers (boxes in DBU, markers.py), the pitch in DBU, window
     sizes in pitches, coverage modes A/B/C
out: Study: one Run per (mode, size) with its windows and the columns of Tables 5.2-5.4, the
     gauge distribution by type (Tables 5.5-5.6), representative classes (Table 5.8), and per
     size the window-reduction heuristic (Table 5.7).
The selection itself runs in the core (an R-tree over the markers); this module counts.
"""
import time
from array import array
from collections.abc import Sequence

from . import core
from .gauges import TYPES as gauge_types
from .records import Records

SIZES = (5, 6, 7, 8)
MODES = ("A", "B", "C")
MODE_NAMES = {"A": "marker centre strictly inside the window", "B": "marker entirely inside the window",
              "C": "marker overlapping the window"}


def pitch_of(gauges):
    """Estimated pitch in DBU (core.estimate_pitch: weighted median width + space)."""
    if hasattr(gauges, "cd_extension"):  # a GaugeTable: its columns read in place by the core
        return core.estimate_pitch_of_gauges(*gauges.cd_extension_type())
    widths = [(g.cd, g.tiebreak) for g in gauges if g.type == "internal"]
    spaces = [(g.cd, g.tiebreak) for g in gauges if g.type == "external"]
    return core.estimate_pitch(widths, spaces)


def by_type(tally, types):
    """{type: {"n": count, "range": [lo, hi] of normalised scores}} (Tables 5.5, 5.6), from the
    core's tally [(count, lo, hi)] per type index."""
    return {t: {"n": n, "range": [round(lo, 6), round(hi, 6)] if n else None}
            for t, (n, lo, hi) in zip(types, tally)}


def overall(tally):
    """[lo, hi] over all types of a tally, or None."""
    live = [(lo, hi) for n, lo, hi in tally if n]
    return [round(min(l for l, h in live), 6), round(max(h for l, h in live), 6)] if live else None


def classes(gs, norm=None):
    """Representative classes (Table 5.8): gauges of one type with the same normalised score
    (rounded to 3 decimals). Returns [(type, S_n, N_g)], largest first. `norm` overrides each
    gauge's normalised score (for two layouts on a common scale)."""
    count = {}
    for g in gs:
        s = round(norm(g) if norm else g.norm_score, 3)
        count[(g.type, s)] = count.get((g.type, s), 0) + 1
    return sorted(((t, s, n) for (t, s), n in count.items()), key=lambda c: (-c[2], c[0], c[1]))


def similarity(c1, c2):
    """S_12 of Table 5.9: gauges of both layouts in classes they share (type and S_n), over all
    gauges of both: sum 2 min(N1, N2) / (N_t1 + N_t2) x 100."""
    n1 = {(t, s): n for t, s, n in c1}
    n2 = {(t, s): n for t, s, n in c2}
    total = sum(n1.values()) + sum(n2.values())
    common = sum(2 * min(n, n2[k]) for k, n in n1.items() if k in n2)
    return 100.0 * common / total if total else 0.0


class Windows(Records):
    """A run's windows as the core's columns (select_windows), each window made on access as
    (x1, y1, x2, y2, gauge index, [indices of the markers it covers first]): a full layer's study
    has twelve runs of tens of thousands of windows, and a tuple each would be hundreds of MB."""

    def __init__(self, columns):
        self._boxes = memoryview(columns["boxes"]).cast("d")
        self._gauges = memoryview(columns["gauges"]).cast("i")
        self._starts = memoryview(columns["starts"]).cast("i")
        self._markers = memoryview(columns["markers"]).cast("i")

    def __len__(self):
        return len(self._gauges)

    def _record(self, i):
        x1, y1, x2, y2 = self._boxes[4 * i:4 * i + 4]
        return x1, y1, x2, y2, self._gauges[i], list(self._markers[self._starts[i]:self._starts[i + 1]])

    def __eq__(self, other):
        return isinstance(other, Sequence) and len(self) == len(other) and all(a == b for a, b in zip(self, other))

    def boxes(self):
        """x1, y1, x2, y2 of every window, one flat float64 view (no copy)."""
        return self._boxes


class Run:
    def __init__(self, mode, size, side, raw, gauges, n_markers, types, failed_of=None):
        self.mode, self.size, self.side = mode, size, side
        self.windows = Windows(raw["windows"])
        self._used = memoryview(raw["used"]).cast("i")  # the used gauges' indices
        self._gauges = gauges
        self.n_failed = raw["failed"]
        self._failed_spots = raw["failed_spots"]
        self._failed_of = failed_of
        self.used_by_type = raw["used_by_type"]
        self.failed_by_type = raw["failed_by_type"]
        self.redundant = raw["redundant"]
        self.traversed = raw["traversed"]
        self.covered = raw["covered"]
        self.seconds = raw["seconds"]
        self.n_markers = n_markers
        self.types = types

    @property
    def n_used(self):
        return len(self._used)

    @property
    def used(self):
        """The used gauges, rank order, made on each call: twelve runs of a full layer's windows
        would otherwise hold a Gauge record per window each to the end of the flow."""
        return [self._gauges[i] for i in self._used]

    def used_types_scores(self):
        """(type indices in TYPES, scores) of the used gauges, rank order: two compact arrays,
        made from the table's columns without a record per gauge (the run's gauges a GaugeTable)."""
        types, scores = self._gauges.type_indices(), self._gauges.scores()
        return array("B", (types[i] for i in self._used)), array("d", (scores[i] for i in self._used))

    @property
    def failed_spots(self):
        """The failed gauges' indices (int32). On a large layer most gauges fail (4 bytes each),
        so a study keeps only their count, and this run's selection is made again each time
        they are asked for (once, by the split) and not kept."""
        spots = self._failed_spots if self._failed_spots is not None else self._failed_of(self.mode, self.side)
        return memoryview(spots).cast("i")

    def row(self, dbu):
        """The columns of Tables 5.2-5.4 (T in seconds, the core's selection time)."""
        gu, gf = self.n_used, self.n_failed
        return {"mode": self.mode, "W_s": "%dx%d" % (self.size, self.size), "side_um": round(self.side * dbu, 6),
                "M_c": self.covered, "markers": self.n_markers, "G_u": gu, "r_u": overall(self.used_by_type),
                "G_f": gf, "r_f": overall(self.failed_by_type), "redundant": self.redundant,
                "traversed": self.traversed,
                "P_d": round(100.0 * self.covered / self.n_markers, 4) if self.n_markers else 0.0,
                "u_g": round(100.0 * gu / (gu + gf), 4) if gu + gf else 0.0, "T": self.seconds}

    def distribution(self):
        return {"used": by_type(self.used_by_type, self.types), "failed": by_type(self.failed_by_type, self.types)}

    def representatives(self):
        total = self.n_used
        return [{"type": t, "S_n": s, "N_g": n, "similarity_pct": round(100.0 * n / total, 4)}
                for t, s, n in classes(self.used)]


class Study:
    def __init__(self, runs, heuristic, pitch, markers, seconds):
        self.runs = runs            # {(mode, size): Run}
        self.heuristic = heuristic  # {size: {"W_b", "W_a", "R_w", "W_m"}}
        self.pitch = pitch
        self.markers = markers
        self.seconds = seconds

    def best(self, mode):
        """The smallest size with the highest coverage for `mode`."""
        runs = [r for (m, s), r in sorted(self.runs.items()) if m == mode]
        return max(runs, key=lambda r: (r.covered, -r.size)) if runs else None


def study(gauges, markers, pitch, sizes=SIZES, modes=MODES, types=("internal", "external", "sandwich", "comb", "T")):
    """Runs every (mode, size); gauges in rank order; markers [(x1, y1, x2, y2)] in DBU.
    `seconds` covers the core's selections, the counting and the heuristic."""
    sizes, modes = list(sizes), list(modes)
    t0 = time.perf_counter()
    index = {t: i for i, t in enumerate(types)}
    if hasattr(gauges, "spots") and tuple(types) == gauge_types:  # a GaugeTable: its columns in place
        columns = gauges.spots()
    else:
        columns = (array("d", (g.cx for g in gauges)), array("d", (g.cy for g in gauges)),
                   array("i", (index[g.type] for g in gauges)), array("d", (g.norm_score for g in gauges)))
    boxes = array("d", [v for b in markers for v in b])

    def failed_of(mode, side):
        return core.select_windows(*columns, boxes, [side], [mode], failed=True)[0]["failed_spots"]

    raw = core.select_windows(*columns, boxes, [k * pitch for k in sizes], list(modes), failed=False)
    runs = {}
    for i, r in enumerate(raw):
        m, k = modes[i // len(sizes)], sizes[i % len(sizes)]
        runs[(m, k)] = Run(m, k, r["side"], r, gauges, len(markers), types, failed_of)
    centres = [((b[0] + b[2]) / 2, (b[1] + b[3]) / 2) for b in markers]
    heuristic = {}
    for k in sizes:
        base = runs.get(("A", k)) or next(r for (m, s), r in runs.items() if s == k)
        wb = len(base.windows)
        wa = len(core.cover_points([(g.cx, g.cy) for g in base.used], k * pitch))
        heuristic[k] = {"mode": base.mode, "W_b": wb, "W_a": wa,
                        "R_w": round(100.0 * (wb - wa) / wb, 4) if wb else 0.0,
                        "W_m": len(core.cover_points(centres, k * pitch))}
    return Study(runs, heuristic, pitch, markers, time.perf_counter() - t0)
