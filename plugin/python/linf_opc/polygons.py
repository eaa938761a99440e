"""A layer's polygons as two flat integer arrays, the form the core reads fastest.

points: array('q') x0, y0, x1, y1, ...; rings: array('q') of point counts, each outer ring
followed by its holes with negative counts. A million rectangles as [(outer, [holes])] lists
take ~700 MB of Python objects; here they take 70 MB. Iterating gives (outer, [holes]) lists,
so code written for the list form reads it unchanged.
"""
import tempfile
from array import array

from . import drawing

# Layers of more shapes than this are spilled (Polygons.spill) as they are read: the batch's limit.
SPILL_SHAPES = 200000
# Past the limit, the arrays are written out whenever the points reach this many values (8 MB).
CHUNK = 1 << 20


class Polygons:
    def __init__(self, spill_over=None):
        """spill_over: once more shapes than this are added, the arrays go to temporary files a
        chunk at a time as they grow, so that a layer of millions of shapes is never all in
        memory; done() then maps them. None: they stay in memory (until spill())."""
        self.points = array("q")
        self.rings = array("q")
        self._count = 0
        self._spill_over = spill_over
        self._files = None  # (points, rings) temporary files, open while chunks are written

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
        if len(self.points) >= CHUNK and self._over():
            self._write_chunk()

    def _over(self):
        return self._spill_over is not None and self._count > self._spill_over

    def _ring(self, pts, sign):
        n = 0
        for x, y in pts:
            self.points.append(x)
            self.points.append(y)
            n += 1
        self.rings.append(sign * n)

    def _write_chunk(self):
        if self._files is None:  # unlinked at once: they go when closed, also when the process dies
            self._files = [tempfile.TemporaryFile(prefix="linf_opc-layer-") for _ in range(2)]
        for f, a in zip(self._files, (self.points, self.rings)):
            a.tofile(f)
            del a[:]

    def spill(self):
        """Moves the arrays (what is left of them, if chunks went ahead) into mapped temporary
        files, read-only from here on (add() no longer works): a layer of millions of shapes is
        hundreds of MB, which the kernel may then drop and read again instead of the process
        holding them to the end of the flow. The core reads them in place either way."""
        if not self.rings and self._files is None:
            return
        self._write_chunk()
        files, self._files = self._files, None
        self._maps = [drawing.mapped_file(f) for f in files]
        self.points, self.rings = (memoryview(m).cast("q") for m in self._maps)

    def done(self):
        """The layer is read: past spill_over it is spilled (spill()), else it stays in memory.
        Returns self."""
        if self._over():
            self.spill()
        return self

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
