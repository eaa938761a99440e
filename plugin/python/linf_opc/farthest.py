"""The farthest-site stage (thesis 3.1): the farthest Voronoi diagram in L-inf of a set of
shapes, and the smallest axis-parallel square that touches every one of them — the size at
which one random defect meets (opens or shorts) all the selected wires.

in:  sites [[(x, y), ...]] in integer DBU: a point, a segment or a convex polygon each (a
     layout shape is taken by its convex hull: exact for boxes, wires and other convex shapes)
out: Farthest: faces (owner sites, unbounded direction), vertices (position, weight), edges
     (bounded or rays) and the root (the locus of square centres and the half-side)
"""
from collections import namedtuple

import pya

from . import core

Face = namedtuple("Face", "owners dx dy")
Vertex = namedtuple("Vertex", "x y weight faces")
Edge = namedtuple("Edge", "left right start end dx dy")  # end = -1 for a ray


class Farthest:
    def __init__(self, raw, n_sites):
        self.faces = [Face(*f) for f in raw["faces"]]
        self.vertices = [Vertex(*v) for v in raw["vertices"]]
        self.edges = [Edge(*e) for e in raw["edges"]]
        x1, y1, x2, y2, self.half_side = raw["root"]
        self.root = ((x1, y1), (x2, y2))
        self.n_sites = n_sites

    def square(self):
        """The smallest touching square centred at the root's first point (x1, y1, x2, y2)."""
        (x, y), _ = self.root
        r = self.half_side
        return (x - r, y - r, x + r, y + r)

    def faces_per_site(self):
        per = [0] * self.n_sites
        for f in self.faces:
            for o in f.owners:
                per[o] += 1
        return per


def compute(sites, l1=False):
    return Farthest(core.farthest_voronoi(sites, l1), len(sites))


def site_of(polygon):
    """A layout polygon (pya.Polygon, DBU) as a site: the points of its hull."""
    return [(p.x, p.y) for p in polygon.each_point_hull()]


def sites_of_shapes(shapes):
    """[(pya.Shape, pya.ICplxTrans or Trans)] -> sites; texts and empty shapes are skipped."""
    out = []
    for shape, trans in shapes:
        if shape.is_text() or not (shape.is_polygon() or shape.is_box() or shape.is_path()):
            continue
        poly = shape.polygon.transformed(trans)
        if poly.num_points_hull() > 0:
            out.append(site_of(poly))
    return out


def sites_of_layer(cell, layer_index, box=None):
    """The layer's shapes in `cell` and below (flattened), those meeting `box` (pya.Box) if given."""
    it = cell.begin_shapes_rec_overlapping(layer_index, box) if box is not None else cell.begin_shapes_rec(layer_index)
    shapes = []
    while not it.at_end():
        shapes.append((it.shape(), it.trans()))
        it.next()
    return sites_of_shapes(shapes)


def clip_for(sites):
    """Rays end on the sites' box enlarged by its larger side, as in the diagram stage."""
    xs = [p[0] for s in sites for p in s]
    ys = [p[1] for s in sites for p in s]
    m = max(max(xs) - min(xs), max(ys) - min(ys), 1)
    return (min(xs) - m, min(ys) - m, max(xs) + m, max(ys) + m)


def ray_end(x, y, dx, dy, clip):
    """Where the ray from (x, y) along (dx, dy) leaves the clip box (or its start if outside)."""
    t = float("inf")
    if dx > 0:
        t = min(t, (clip[2] - x) / dx)
    if dx < 0:
        t = min(t, (clip[0] - x) / dx)
    if dy > 0:
        t = min(t, (clip[3] - y) / dy)
    if dy < 0:
        t = min(t, (clip[1] - y) / dy)
    t = max(0.0, t if t != float("inf") else 0.0)
    return x + t * dx, y + t * dy


def segments(result, clip):
    """Every edge as (kind, x1, y1, x2, y2, w1, left owners, right owners), rays cut at `clip`."""
    out = []
    for e in result.edges:
        a = result.vertices[e.start]
        if e.end >= 0:
            b = result.vertices[e.end]
            x2, y2, kind = b.x, b.y, "edge"
        else:
            x2, y2 = ray_end(a.x, a.y, e.dx, e.dy, clip)
            kind = "ray"
        out.append((kind, a.x, a.y, x2, y2, a.weight, result.faces[e.left].owners, result.faces[e.right].owners))
    return out


LAYER_DATATYPE, SQUARE_DATATYPE = 240, 241


def add_layers(layout, cell, result, clip, layer):
    """The diagram (zero-width paths) on L/240 and the smallest touching square on L/241,
    both cleared first; edges and rays cut to +-(2^31 - 1) DBU (core.cut_to_drawable). Returns
    the number of edges drawn."""
    li = layout.find_layer(pya.LayerInfo(layer, LAYER_DATATYPE))
    li = li if li is not None else layout.insert_layer(pya.LayerInfo(layer, LAYER_DATATYPE, "farthest voronoi"))
    ls = layout.find_layer(pya.LayerInfo(layer, SQUARE_DATATYPE))
    ls = ls if ls is not None else layout.insert_layer(pya.LayerInfo(layer, SQUARE_DATATYPE, "smallest touching square"))
    cell.shapes(li).clear()
    cell.shapes(ls).clear()
    n = 0
    for kind, *ends, w, lo, ro in segments(result, clip):
        # Rays reach the clip box, beyond 32 bits for sites near +-2^30: cut where layouts can
        # hold them (pya.Point would wrap the coordinate around); farthest.csv keeps them whole.
        ends = core.cut_to_drawable(*ends)
        if ends is None:
            continue
        x1, y1, x2, y2 = ends
        a, b = pya.Point(round(x1), round(y1)), pya.Point(round(x2), round(y2))
        if a != b:
            cell.shapes(li).insert(pya.Path([a, b], 0))
            n += 1
    x1, y1, x2, y2 = result.square()
    dbu = layout.dbu
    cell.shapes(ls).insert(pya.DBox(x1 * dbu, y1 * dbu, x2 * dbu, y2 * dbu))
    (rx1, ry1), (rx2, ry2) = result.root
    if (rx1, ry1) != (rx2, ry2):  # the root is a segment: every square centred on it touches all
        cell.shapes(ls).insert(pya.DPath([pya.DPoint(rx1 * dbu, ry1 * dbu), pya.DPoint(rx2 * dbu, ry2 * dbu)], 0))
    return n


def write_csv(result, clip, path, dbu):
    import csv
    with open(path, "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["kind", "x1", "y1", "x2", "y2", "w1", "owner_left", "owner_right"])
        for kind, x1, y1, x2, y2, w1, lo, ro in segments(result, clip):
            w.writerow([kind] + ["%.6f" % (v * dbu) for v in (x1, y1, x2, y2, w1)] +
                       [";".join(map(str, lo)), ";".join(map(str, ro))])


def summary(result, dbu, sites):
    (x1, y1), (x2, y2) = result.root
    per = result.faces_per_site()
    return {
        "sites": len(sites),
        "faces": len(result.faces),
        "vertices": len(result.vertices),
        "edges": len(result.edges),
        "faces_per_site_max": max(per) if per else 0,
        "root": {"p_um": [round(x1 * dbu, 9), round(y1 * dbu, 9)], "q_um": [round(x2 * dbu, 9), round(y2 * dbu, 9)],
                 "half_side_um": round(result.half_side * dbu, 9), "side_um": round(2 * result.half_side * dbu, 9),
                 "square_um": [round(v * dbu, 9) for v in result.square()]},
    }
