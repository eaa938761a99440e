"""Markers: regions an optical rule check or a litho simulation flagged, as boxes in DBU.

A marker SPEC is one of
  L/D               a layer of the layout (boxes, polygons, paths: their bounding boxes);
  FILE.lyrdb        a KLayout report database (each item: the bounding box of its shapes);
  FILE.csv          points or boxes in DBU of the layout (decimals allowed): columns x,y (points, e.g. the
                    ICCAD16 hotspot files def,id,category,x,y) or x1,y1,x2,y2 (boxes); a
                    suffix @um reads micrometres instead.
Identical markers (the same hotspot under several process conditions) count once. Rows that
do not parse, or hold a coordinate that is not a finite number (nan, inf), are skipped and
counted; a file with no usable row is an error. Markers wholly outside the layout are kept (they
are simply never covered) and counted, with a warning line on stderr.
"""
import csv
import math
import os
import sys

import pya


class MarkerError(ValueError):
    pass


class Markers:
    def __init__(self, boxes, source, skipped=0, duplicates=0):
        self.boxes = boxes          # [(x1, y1, x2, y2)] in DBU, a point as a box of zero size
        self.source = source
        self.skipped = skipped      # malformed rows
        self.duplicates = duplicates
        self.outside = 0            # markers sharing no point with the layout's box (load sets it)

    def summary(self):
        return {"source": self.source, "markers": len(self.boxes), "skipped_rows": self.skipped,
                "duplicates_merged": self.duplicates, "outside_layout": self.outside}


def warn(text):
    """A warning on stderr: the run goes on (also under -rd quiet=1, which silences progress only)."""
    sys.stderr.write("linf_opc: warning: %s\n" % text)
    sys.stderr.flush()


def outside(boxes, box):
    """How many markers share no point with `box` (x1, y1, x2, y2; closed)."""
    x1, y1, x2, y2 = box
    return sum(1 for b in boxes if b[2] < x1 or b[0] > x2 or b[3] < y1 or b[1] > y2)


def _unique(boxes):
    seen, out = set(), []
    for b in boxes:
        if b not in seen:
            seen.add(b)
            out.append(b)
    return out, len(boxes) - len(out)


def layer_of(spec):
    """(L, D) if the SPEC names a layer of the layout, else None (a file)."""
    if not spec or spec.lower().endswith((".csv", ".csv@um", ".lyrdb", ".lyrdb@um", ".rdb", ".rdb@um")):
        return None
    try:
        l, d = (int(v) for v in spec.split("/"))
    except ValueError:
        return None
    return l, d


def from_layer(cell, layout, spec):
    ld = layer_of(spec)
    if ld is None:
        raise MarkerError("marker layer must be L/D, not %r" % spec)
    l, d = ld
    index = layout.find_layer(l, d)
    if index is None:
        raise MarkerError("marker layer %s is not in the layout" % spec)
    boxes = []
    it = cell.begin_shapes_rec(index)
    while not it.at_end():
        if not it.shape().is_text():
            b = it.shape().bbox().transformed(it.trans())
            boxes.append((b.left, b.bottom, b.right, b.top))
        it.next()
    boxes, dup = _unique(boxes)
    return Markers(boxes, "layer " + spec, 0, dup)


def from_rdb(path, dbu):
    rdb = pya.ReportDatabase("markers")
    try:
        rdb.load(path)
    except RuntimeError as e:
        raise MarkerError("cannot read marker database %s: %s" % (path, str(e).splitlines()[0]))
    boxes, skipped = [], 0
    for item in rdb.each_item():
        box = pya.DBox()
        for v in item.each_value():
            for kind, get in (("is_box", "box"), ("is_polygon", "polygon"), ("is_edge", "edge"),
                              ("is_edge_pair", "edge_pair"), ("is_path", "path")):
                if getattr(v, kind)():
                    box += getattr(v, get)().bbox()
        if box.empty():
            skipped += 1
            continue
        b = tuple(c / dbu for c in (box.left, box.bottom, box.right, box.top))
        if not all(math.isfinite(c) for c in b):
            skipped += 1
            continue
        boxes.append(b)
    boxes, dup = _unique(boxes)
    return Markers(boxes, path, skipped, dup)


def from_csv(path, dbu, micrometres=False):
    scale = 1.0 / dbu if micrometres else 1.0
    try:
        f = open(path, newline="")
    except OSError as e:
        raise MarkerError("cannot read marker file %s: %s" % (path, e.strerror))
    with f:
        try:
            rows = list(csv.reader(f))
        except (csv.Error, UnicodeDecodeError) as e:  # binary data, a NUL byte, a field of megabytes
            raise MarkerError("cannot read marker file %s: %s" % (path, e))
    if not rows:
        raise MarkerError("marker file %s is empty" % path)
    head = [h.strip().lower() for h in rows[0]]
    if all(k in head for k in ("x1", "y1", "x2", "y2")):
        cols = [head.index(k) for k in ("x1", "y1", "x2", "y2")]
    elif "x" in head and "y" in head:
        cols = [head.index("x"), head.index("y"), head.index("x"), head.index("y")]
    else:
        raise MarkerError("marker file %s needs columns x,y or x1,y1,x2,y2 in its header, not %s"
                          % (path, ",".join(rows[0])))
    boxes, skipped = [], 0
    for r in rows[1:]:
        try:
            x1, y1, x2, y2 = (float(r[c]) * scale for c in cols)
        except (ValueError, IndexError):
            skipped += 1
            continue
        if not (math.isfinite(x1) and math.isfinite(y1) and math.isfinite(x2) and math.isfinite(y2)):
            skipped += 1  # nan, inf, or a number that overflows once scaled (1e308 um)
            continue
        boxes.append((min(x1, x2), min(y1, y2), max(x1, x2), max(y1, y2)))
    if not boxes:
        raise MarkerError("marker file %s has no usable row (%d skipped)" % (path, skipped))
    boxes, dup = _unique(boxes)
    return Markers(boxes, path, skipped, dup)


def load(spec, layout, cell):
    """Markers from a SPEC (see the module's doc), in the layout's DBU. Markers wholly outside
    the cell's box are counted (Markers.outside) and warned about."""
    m = _load(spec, layout, cell)
    b = cell.bbox()
    m.outside = outside(m.boxes, (b.left, b.bottom, b.right, b.top)) if not b.empty() else len(m.boxes)
    if m.outside:
        warn("%d of %d markers of %s lie wholly outside the layout (cell %s): they cannot be covered"
             % (m.outside, len(m.boxes), m.source, cell.name))
    return m


def _load(spec, layout, cell):
    if not spec:
        raise MarkerError("no marker source given")
    micrometres = spec.endswith("@um")
    path = spec[:-3] if micrometres else spec
    low = path.lower()
    if os.path.isdir(path):
        raise MarkerError("the marker source %s is a folder, not a file" % path)
    if low.endswith(".csv"):
        return from_csv(path, layout.dbu, micrometres)
    if low.endswith(".lyrdb") or low.endswith(".rdb"):
        if not os.path.isfile(path):
            raise MarkerError("marker file not found: %s" % path)
        return from_rdb(path, layout.dbu)
    return from_layer(cell, layout, path)


def same_as_working(spec, layer, datatype):
    """True where the marker SPEC names the working layer itself: then every shape of the layer
    is a marker (its bounding box), which is legal but rarely meant."""
    return layer_of(spec) == (layer, datatype)
