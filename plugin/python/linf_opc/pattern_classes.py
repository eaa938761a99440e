"""Pattern classes of the chosen selection run's windows (ICCAD 2016's pattern classification,
in the core: classify_patterns): windows whose clips are alike under a symmetry of the square
are one class, so that thousands of marker windows become the few patterns they are.

in:  the Input's polygons, the run's windows (in gauge order: the most critical first), the rule
     (arguments.class_args: by "area" or "edge", the area fraction, the edge in DBU)
out: PatternClasses: the class of each window (0-based), each class's representative (its first
     window) and count; summary() for stats.json and the report."""
from array import array

from . import core
from .polygons import core_input


def integer_windows(run):
    """The run's windows as squares on the DBU grid, array('q') x1, y1, x2, y2 each: the side is
    k pitches, rarely a whole number of DBU, and a pattern is compared at its centre."""
    side = max(1, int(round(run.side)))
    boxes = run.windows.boxes()
    out = array("q")
    for i in range(len(boxes) // 4):
        x1, y1, x2, y2 = boxes[4 * i:4 * i + 4]
        bx, by = int(round((x1 + x2) / 2 - side / 2)), int(round((y1 + y2) / 2 - side / 2))
        out.extend((bx, by, bx + side, by + side))
    return out


class PatternClasses:
    def __init__(self, raw, rule, run, dbu):
        self.by, self.area_fraction, self.edge = rule
        self.of_window = memoryview(raw["of_window"]).cast("i")
        self.representative = memoryview(raw["representative"]).cast("i")
        self.count = memoryview(raw["count"]).cast("i")
        self.compared = raw["compared"]
        self.seconds = raw["seconds"]
        # Markers each class's windows cover first, summed: what the class stands for.
        self.markers = [0] * len(self.count)
        for i, w in enumerate(run.windows):
            self.markers[self.of_window[i]] += len(w[5])
        self.dbu = dbu

    def __len__(self):
        return len(self.count)

    def largest(self, n=10):
        """Class ids (0-based) by count, largest first (ties: the more critical first)."""
        return sorted(range(len(self.count)), key=lambda k: (-self.count[k], k))[:n]

    def rule_text(self):
        if self.by == "area":
            return "XOR area at most %g%% of the window" % (100 * self.area_fraction)
        return "edges moved by at most %g um" % round(self.edge * self.dbu, 6)

    def summary(self):
        return {"rule": self.by, "area_fraction": self.area_fraction, "edge_um": round(self.edge * self.dbu, 6),
                "windows": len(self.of_window), "classes": len(self), "compared": self.compared,
                "largest": [{"class": k + 1, "windows": self.count[k], "markers": self.markers[k],
                             "representative_window": self.representative[k] + 1} for k in self.largest()],
                "seconds": self.seconds}


def classify(polygons, run, rule, dbu):
    """The PatternClasses of `run`'s windows under `rule`, or None if the rule is None
    (-rd pattern_classes=off)."""
    if rule is None:
        return None
    by, fraction, edge = rule
    raw = core.classify_patterns(core_input(polygons), integer_windows(run), by, fraction, edge)
    return PatternClasses(raw, rule, run, dbu)
