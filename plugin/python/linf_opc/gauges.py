"""The gauge stage (thesis 5.1).

in:  polygons [(outer, [holes])] in integer DBU, or a polygons.Polygons
out: Gauges: every gauge candidate of the layer, ranked (rank 1 = most likely to pinch or
     bridge), with the diagram's summary and timings. The diagram is built and checked first.
The rules where the thesis leaves a choice open are in docs/design.md, "Gauge rules".
"""
import time
from array import array
from collections import namedtuple
from itertools import compress

from . import core, drawing
from .polygons import core_input
from .records import Records

TYPES = ("internal", "external", "sandwich", "comb", "T")

Gauge = namedtuple("Gauge", "type x1 y1 x2 y2 cx cy cd score norm_score tiebreak rank teeth "
                            "site_a_geom site_b_geom site_a site_b stretch")


class GaugeTable(Records):
    """The ranked gauges as the core's columns (see gauges_polygons), a Gauge made on access:
    a large layer has millions of gauges, and a tuple each would be most of the flow's memory.
    A read-only sequence: len, indexing (slices give lists), iteration in rank order.
    Columns the core wrote to a file (columns["file"]) are mapped, not read: the file is removed
    at once and its pages stay the kernel's to drop and read again, so that a layer of millions
    of gauges does not hold them in memory (132 bytes a gauge)."""

    def __init__(self, columns):
        self._n = columns["count"]
        if columns.get("file"):
            reals, ints = self._mapped(columns["file"], self._n)
        else:
            reals, ints = columns["reals"], columns["ints"]
        self._reals = memoryview(reals).cast("d")
        self._ints = memoryview(ints).cast("i")
        self._paths = columns["paths"]

    def _mapped(self, path, n):
        self._map = drawing.mapped(path)
        if len(self._map) != (80 + 52) * n:
            raise ValueError("the gauge columns file %s held %d bytes, not %d" % (path, len(self._map), 132 * n))
        whole = memoryview(self._map)
        return whole[:80 * n], whole[80 * n:]

    @classmethod
    def of(cls, gauges):
        """The columns of Gauge records (a per-pattern subset, say), without their paths."""
        reals = array("d", (v for g in gauges for v in (g.x1, g.y1, g.x2, g.y2, g.cx, g.cy, g.cd, g.score,
                                                        g.norm_score, g.tiebreak)))
        ints = array("i", (v for g in gauges for v in (g.rank, g.teeth, g.site_a, g.site_b, *g.site_a_geom,
                                                       *g.site_b_geom, TYPES.index(g.type))))
        return cls({"count": len(reals) // 10, "reals": reals.tobytes(), "ints": ints.tobytes(), "paths": None})

    def columns(self):
        """The core's columns as they came: (reals float64 x10, ints int32 x13 a gauge)."""
        return self._reals, self._ints

    def __len__(self):
        return self._n

    def _record(self, i):
        r = self._reals[10 * i:10 * i + 10]
        k = self._ints[13 * i:13 * i + 13]
        return Gauge(TYPES[k[12]], *r, k[0], k[1], tuple(k[4:8]), tuple(k[8:12]), k[2], k[3],
                     self._paths[i] if self._paths is not None else None)

    def __iter__(self):
        for i in range(self._n):
            yield self[i]

    # Whole columns, made without a Python object per gauge (the selection's inputs).
    def spots(self):
        """(x, y, type index in TYPES, norm_score): the selection's columns, rank order, as views
        into the table (no copy)."""
        return self._reals[4::10], self._reals[5::10], self._ints[12::13], self._reals[8::10]

    def centres(self):
        """(cx, cy): the gauge points' coordinates, two sequences indexed by gauge."""
        return self._reals[4::10], self._reals[5::10]

    def scores(self):
        """The score of each gauge, rank order."""
        return self._reals[7::10]

    def type_indices(self):
        """The type of each gauge as its index in TYPES, rank order."""
        return self._ints[12::13]

    def cd_extension_type(self):
        """(cd, tiebreak, type index in TYPES): three columns, rank order, as views into the
        table (no copy)."""
        return self._reals[6::10], self._reals[9::10], self._ints[12::13]

    def cd_extension(self, type_name):
        """array('d'): cd, tiebreak pairs of the gauges of one type, rank order."""
        k = TYPES.index(type_name)
        mask = array("B", self._ints[12::13]).tobytes().translate(bytes(int(c == k) for c in range(256)))
        out = array("d", bytes(16 * mask.count(1)))
        m = memoryview(out)
        m[0::2] = memoryview(array("d", compress(self._reals[6::10], mask)))
        m[1::2] = memoryview(array("d", compress(self._reals[9::10], mask)))
        return out


class Gauges:
    def __init__(self, raw, seconds_total):
        self.gauges = GaugeTable(raw["gauges"])
        self.stretches = raw["stretches"]
        self.typical_width = raw["typical_width"]
        self.space_limit = raw["space_limit"]
        self.diagram = raw["diagram"]
        self.seconds = dict(self.diagram["seconds"], total=seconds_total)

    def counts(self):
        return {t: n for t, (n, lo, hi) in zip(TYPES, self._tally())}

    def score_ranges(self):
        """{type: (lowest score, highest score)} in DBU, types that have gauges only."""
        return {t: (lo, hi) for t, (n, lo, hi) in zip(TYPES, self._tally()) if n}

    def _tally(self):
        """[(count, lowest score, highest score)] per type index, in one pass over the columns a
        block at a time: a full layer has millions of gauges, and a list of a type's scores
        would be hundreds of MB."""
        types, scores = self.gauges.type_indices(), self.gauges.scores()
        tally = [(0, float("inf"), float("-inf"))] * len(TYPES)
        block = TALLY_BLOCK
        for at in range(0, len(self.gauges), block):
            kinds = array("B", types[at:at + block]).tobytes()
            values = scores[at:at + block]
            for k in set(kinds):
                of_type = list(compress(values, kinds.translate(_ONE_TYPE[k])))
                n, lo, hi = tally[k]
                tally[k] = (n + len(of_type), min(lo, min(of_type)), max(hi, max(of_type)))
        return tally


TALLY_BLOCK = 1 << 16
_ONE_TYPE = [bytes(int(c == k) for c in range(256)) for k in range(len(TYPES))]


def columns_file():
    """A fresh temporary file for the core to write the gauge columns into (GaugeTable maps it)."""
    return drawing.temporary("linf_opc-gauges-", ".columns")


def compute(polygons, check=True, tooth_fraction=0.5, space_limit_widths=10.0, draw_layer=None,
            with_paths=False, tile=-1, csv_path=None, dbu=1.0, gauges_csv=None, draw_cell="VORONOI", threads=0,
            progress=None, builder="sweep"):
    """draw_layer: a layer number: also keep the diagram, drawable (Gauges.pieces_diagram, a
    diagram.Diagram with its GDSII file, see diagram.compute, also for draw_cell), so that a flow writes both
    without building the diagram twice. with_paths: each gauge's `stretch` is its stretch's
    path [(x, y)] (else None). check, tile, csv_path, dbu, builder: as in diagram.compute (the gauges
    are the same for every tile size and builder). gauges_csv: the core also writes gauges.csv there (micrometres,
    `dbu`; Gauges.csv_path). threads: builder workers, 0 one a core. progress: as in
    diagram.compute."""
    from .diagram import Diagram
    t0 = time.perf_counter()
    columns = columns_file()
    try:
        raw, gds = drawing.drawn_by(
            lambda gds: core.gauges_polygons(core_input(polygons), check, 2000, threads, tooth_fraction, space_limit_widths,
                                             False, with_paths, tile=tile, csv=csv_path or "", dbu=dbu, gds=gds,
                                             gds_layer=draw_layer or 0, gds_cell=draw_cell,
                                             gauges_csv=gauges_csv or "", columns=columns, progress=progress,
                                             builder=builder),
            draw_layer is not None)
    except BaseException:
        drawing.remove(columns)
        raise
    out = Gauges(raw, time.perf_counter() - t0)
    out.csv_path = gauges_csv  # where the core already wrote gauges.csv, if it did
    if gds:
        out.pieces_diagram = Diagram(raw["diagram"], out.seconds["total"], csv_path, gds)
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
