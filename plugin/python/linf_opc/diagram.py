"""The diagram stage.

in:  polygons [(outer, [holes])] in integer DBU, or a polygons.Polygons
out: Diagram: pieces [Piece], site count, clip box, checker report, timings
A wrong diagram is never returned: the core's independent checker raises DiagramError.
"""
import time
from collections import Counter, namedtuple

from . import core
from .polygons import core_input

KINDS = ("internal", "external", "notch", "adjacent")

Piece = namedtuple("Piece", "kind x1 y1 x2 y2 d1 d2 a_x1 a_y1 a_x2 a_y2 b_x1 b_y1 b_x2 b_y2 site_a site_b")


class Diagram:
    def __init__(self, raw, seconds_total, csv_path=None):
        self.csv_path = csv_path  # where the core already wrote the pieces as CSV, if it did
        self.pieces = [Piece(*p) for p in raw["pieces"]]
        self.sites = raw["sites"]
        self.clip = raw["clip"]
        self.check = raw["check"]
        self.tiles = raw["tiles"]
        self.seconds = dict(raw["seconds"], total=seconds_total)

    def counts(self):
        c = Counter(p.kind for p in self.pieces)
        return {k: c.get(k, 0) for k in KINDS}


def compute(polygons, check=True, check_pairs=2000, tile=-1, csv_path=None, dbu=1.0):
    """tile: side of the builder's tiles in DBU; 0 one tile, -1 automatic. The diagram is the
    same for every tile size; tiles bound the memory the builder holds at once.
    csv_path: the core also writes voronoi.csv there (micrometres, `dbu`)."""
    t0 = time.perf_counter()
    raw = core.voronoi_polygons(core_input(polygons), check, check_pairs, tile=tile, csv=csv_path or "", dbu=dbu)
    return Diagram(raw, time.perf_counter() - t0, csv_path)
