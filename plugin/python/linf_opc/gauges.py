"""The gauge stage (thesis 5.1).

in:  polygons [(outer, [holes])] in integer DBU
out: Gauges: every gauge candidate of the layer, ranked (rank 1 = most likely to pinch or
     bridge), with the diagram's summary and timings. The diagram is built and checked first.
The rules where the thesis leaves a choice open are in the README, "Gauges".
"""
import time
from collections import namedtuple

from . import core

TYPES = ("internal", "external", "sandwich", "comb", "T")

Gauge = namedtuple("Gauge", "type x1 y1 x2 y2 cx cy cd score norm_score tiebreak rank teeth "
                            "site_a_geom site_b_geom site_a site_b stretch")


class Gauges:
    def __init__(self, raw, seconds_total):
        self.gauges = [Gauge(*g) for g in raw["gauges"]]
        self.stretches = raw["stretches"]
        self.typical_width = raw["typical_width"]
        self.space_limit = raw["space_limit"]
        self.diagram = raw["diagram"]
        self.seconds = dict(self.diagram["seconds"], total=seconds_total)

    def counts(self):
        c = dict.fromkeys(TYPES, 0)
        for g in self.gauges:
            c[g.type] += 1
        return c

    def score_ranges(self):
        """{type: (lowest score, highest score)} in DBU, types that have gauges only."""
        r = {}
        for g in self.gauges:
            lo, hi = r.get(g.type, (g.score, g.score))
            r[g.type] = (min(lo, g.score), max(hi, g.score))
        return r


def compute(polygons, check=True, tooth_fraction=0.5, space_limit_widths=10.0, with_diagram=False,
            with_paths=False, tile=-1, csv_path=None, dbu=1.0):
    """with_diagram: also keep the diagram's pieces (Gauges.pieces_diagram, a diagram.Diagram),
    so that a flow writes both without building the diagram twice. with_paths: each gauge's
    `stretch` is its stretch's path [(x, y)] (else None). tile, csv_path, dbu: as in
    diagram.compute (the gauges are the same for every tile size)."""
    t0 = time.perf_counter()
    raw = core.gauges_polygons(polygons, check, 2000, 0, tooth_fraction, space_limit_widths, with_diagram,
                               with_paths, tile=tile, csv=csv_path or "", dbu=dbu)
    out = Gauges(raw, time.perf_counter() - t0)
    if with_diagram:
        from .diagram import Diagram
        out.pieces_diagram = Diagram(raw["diagram"], out.seconds["total"], csv_path)
        raw["diagram"]["pieces"] = len(raw["diagram"]["pieces"])
    return out


def most_critical_in(gauges, window):
    """Per-pattern mode: the most critical gauge of each type whose point lies in window
    (x1, y1, x2, y2) in DBU, in rank order (at most five)."""
    x1, y1, x2, y2 = window
    seen, out = set(), []
    for g in gauges:
        if g.type not in seen and x1 <= g.cx <= x2 and y1 <= g.cy <= y2:
            seen.add(g.type)
            out.append(g)
    return out
