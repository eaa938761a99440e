"""The diagram stage.

in:  polygons [(outer, [holes])] in integer DBU, or a polygons.Polygons
out: Diagram: site count, clip box, checker report, timings, piece counts per kind; the pieces
     as a GDSII file to draw (draw_layer=...) and/or as a list of Piece (with_pieces=True)
A wrong diagram is never returned: the core's independent checker raises DiagramError.
"""
import time
import weakref
from collections import namedtuple

from . import core, drawing
from .polygons import core_input

KINDS = ("internal", "external", "notch", "adjacent")

Piece = namedtuple("Piece", "kind x1 y1 x2 y2 d1 d2 a_x1 a_y1 a_x2 a_y2 b_x1 b_y1 b_x2 b_y2 site_a site_b")


class Diagram:
    def __init__(self, raw, seconds_total, csv_path=None, gds_path=None):
        self.csv_path = csv_path  # where the core already wrote the pieces as CSV, if it did
        # The pieces as GDSII, for diagram_output; a temporary file, removed with the Diagram.
        self.gds_path = gds_path
        if gds_path:
            weakref.finalize(self, drawing.remove, gds_path)
        self.pieces = [Piece(*p) for p in raw["pieces"]] if isinstance(raw["pieces"], list) else None
        self.n_pieces = raw["pieces"] if self.pieces is None else len(self.pieces)
        self.drawn = raw.get("drawn")  # pieces per kind in the GDSII file
        self.sites = raw["sites"]
        self.polygons = raw["polygons"]  # after merging
        self.clip = raw["clip"]
        self.check = raw["check"]
        self.tiles = raw["tiles"]
        self.builder = raw["builder"]  # which built it: "sweep" or "subdivision"
        self._counts = raw["counts"]
        self.seconds = dict(raw["seconds"], total=seconds_total)

    def counts(self):
        return {k: self._counts.get(k, 0) for k in KINDS}


def compute(polygons, check=True, check_pairs=2000, tile=-1, csv_path=None, dbu=1.0, with_pieces=True,
            draw_layer=None, draw_cell="VORONOI", threads=0, progress=None, builder="sweep"):
    """tile: side of the builder's tiles in DBU; 0 one tile, -1 automatic. The diagram is the
    same for every tile size; tiles bound the memory the builder holds at once.
    builder: "sweep" or "subdivision"
    (arguments.parse_builder; the same diagram).
    check: True or "sample" (the default), "full" (arguments.parse_check), False none.
    csv_path: the core also writes voronoi.csv there (micrometres, `dbu`).
    draw_layer: a layer number: the core also writes the pieces as GDSII for diagram_output
    (datatypes 200 + kind; one cell named draw_cell).
    with_pieces=False: no Python object per piece (a full layer has tens of millions of them):
    Diagram.pieces is None, n_pieces and counts() remain.
    threads: builder workers, 0 one a core (benchmarks compare at equal threads).
    progress: callable(stage, done, total), told how far the core is (Progress.core)."""
    t0 = time.perf_counter()
    raw, gds = drawing.drawn_by(
        lambda gds: core.voronoi_polygons(core_input(polygons), check, check_pairs, threads, tile=tile, csv=csv_path or "",
                                          dbu=dbu, pieces=with_pieces, gds=gds, gds_layer=draw_layer or 0,
                                          gds_cell=draw_cell, progress=progress, builder=builder),
        draw_layer is not None)
    return Diagram(raw, time.perf_counter() - t0, csv_path, gds)
