"""A layer's polygons as two flat integer arrays, the form the core reads fastest.

points: array('q') x0, y0, x1, y1, ...; rings: array('q') of point counts, each outer ring
followed by its holes with negative counts. A million rectangles as [(outer, [holes])] lists
take ~700 MB of Python objects; here they take 70 MB. Iterating gives (outer, [holes]) lists,
so code written for the list form reads it unchanged.
"""
from array import array

from . import drawing

# Layers of more shapes than this are spilled (Polygons.spill) once read: the batch's limit.
SPILL_SHAPES = 200000


class Polygons:
    def __init__(self):
        self.points = array("q")
        self.rings = array("q")
        self._count = 0

    @classmethod
    def of(cls, polygons):
        """From [(outer, [holes])] with rings as [(x, y)]."""
        out = cls()
        for outer, holes in polygons:
            out.add(outer, holes)
        return out

    @classmethod
    def from_flat(cls, points, rings):
        """From the two flat arrays (or bytes of int64), as the core gives them back."""
        out = cls()
        out.points, out.rings = array("q", points), array("q", rings)
        out._count = sum(1 for c in out.rings if c >= 0)
        return out

    def add(self, outer, holes=()):
        self._ring(outer, 1)
        for h in holes:
            self._ring(h, -1)
        self._count += 1

    def _ring(self, pts, sign):
        n = 0
        for x, y in pts:
            self.points.append(x)
            self.points.append(y)
            n += 1
        self.rings.append(sign * n)

    def spill(self):
        """Moves the two arrays into a mapped temporary file, read-only from here on (add() no
        longer works): a layer of millions of shapes is hundreds of MB, which the kernel may
        then drop and read again instead of the process holding them to the end of the flow.
        The core reads them in place either way."""
        if not self.rings:
            return
        path = drawing.temporary("linf_opc-layer-", ".flat")
        with open(path, "wb") as f:
            self.points.tofile(f)
            self.rings.tofile(f)
        n = 8 * len(self.points)
        self._map = drawing.mapped(path)
        self.points, self.rings = memoryview(self._map)[:n].cast("q"), memoryview(self._map)[n:].cast("q")

    def flat(self):
        """(points, rings): what the core's *_polygons functions take."""
        return (self.points, self.rings)

    def __len__(self):
        return self._count

    def __iter__(self):
        pts, at, cur = self.points, 0, None
        for c in self.rings:
            n = abs(c)
            ring = [(pts[2 * k], pts[2 * k + 1]) for k in range(at, at + n)]
            at += n
            if c >= 0:
                if cur is not None:
                    yield cur
                cur = (ring, [])
            else:
                cur[1].append(ring)
        if cur is not None:
            yield cur


def core_input(polygons):
    """What to hand the core: the flat arrays of a Polygons, a list as it is."""
    return polygons.flat() if isinstance(polygons, Polygons) else polygons
