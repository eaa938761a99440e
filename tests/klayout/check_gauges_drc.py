# Proof of the gauges against KLayout's own DRC (README, "Gauges", "Proof against DRC").
#   klayout -b -r tests/klayout/check_gauges_drc.py -rd input=FILE -rd layer=L/D [-rd cell=NAME]
#           [-rd factors=1.5,2.0,3.0]
# The layer's narrowest width (space) is KLayout's own: the least L-inf distance of the
# width_check (space_check) edge pairs whose two edges are axis-parallel, the check's threshold
# doubled from 1 DBU until it flags such a pair (the gauges play no part in the thresholds).
# For thresholds t = factor x that width (space) + 1 DBU, with metrics Square (L-inf), whole
# edges, KLayout's default shielding and ignore_angle 90:
#  recall:    every width_check edge pair is explained by an internal gauge on the same two
#             boundary features with cd <= distance + 1 DBU (a vertex stands for its two edges);
#             where the distance is attained at the edges' end corners (kissing corners, offset
#             line ends), the next edge at such a corner is just as near and the diagram's tie
#             rule may give the gap to it: an internal gauge on the edges or their neighbours
#             at the corners explains the pair;
#             where the two edges are not Voronoi neighbours (the shape is narrower the other
#             way: a 40x60 bar at t = 70 flags its 60 sides too; a stub or a step shorter than
#             its width), by an internal gauge with cd <= distance + 1 whose stretch comes
#             within distance/2 of the pair (of the convex hull of the two edges): a place at
#             least as narrow, as near as the flagged width's own centre line;
#  precision: every internal gauge with cd < t lies on a width_check edge pair of its features;
# and the same for external gauges against space_check (which covers notches).
# 45-degree and other slanted edges: KLayout's Square metric measures in the edge's own frame
# (a rotated square), the diagram in the axis frame; DRC pairs and gauges that involve a slanted
# edge are counted and printed but left out of the 100% claim.
# Prints recall and precision per threshold; exits non-zero unless all are 100%, and where a
# factor compares no pair (no DRC pair of axis-parallel edges for both width and space).
import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from harness import arg, expect, finish  # noqa: E402

import pya  # noqa: E402

from linf_opc import gauges as gauge_stage  # noqa: E402
from linf_opc import layout as layer_io  # noqa: E402


def dist_point_segment(x, y, a, b):
    """L-inf distance from (x, y) to the closed segment a-b (piecewise linear: breakpoints)."""
    ax, ay = a
    dx, dy = b[0] - ax, b[1] - ay
    ux, uy = x - ax, y - ay

    def f(t):
        t = min(1.0, max(0.0, t))
        return max(abs(ux - t * dx), abs(uy - t * dy))
    ts = [0.0, 1.0]
    if dx:
        ts.append(ux / dx)
    if dy:
        ts.append(uy / dy)
    if dx - dy:
        ts.append((ux - uy) / (dx - dy))
    if dx + dy:
        ts.append((ux + uy) / (dx + dy))
    return min(f(t) for t in ts)


def dist_edges(e, f):
    # Edges of a merged region never cross, so the distance is attained at an endpoint.
    return min(dist_point_segment(p[0], p[1], f[0], f[1]) for p in e) if e and f else math.inf


def edist(e, f):
    return min(dist_edges(e, f), dist_edges(f, e))


def key(p, q):
    return (p, q) if p <= q else (q, p)


def edge_key(e):
    return key((e.p1.x, e.p1.y), (e.p2.x, e.p2.y))


def features(geom, edges_at):
    """Edge keys a site stands for: a segment itself, a vertex its two edges."""
    x1, y1, x2, y2 = geom
    if (x1, y1) == (x2, y2):
        return edges_at.get((x1, y1), set())
    return {key((x1, y1), (x2, y2))}


def cross(o, a, b):
    return (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0])


def hull_of(e, f):
    """Convex hull (counter-clockwise) of the two edges' endpoints."""
    pts = sorted(set([e[0], e[1], f[0], f[1]]))
    lower, upper = [], []
    for p in pts:
        while len(lower) >= 2 and cross(lower[-2], lower[-1], p) <= 0:
            lower.pop()
        lower.append(p)
    for p in reversed(pts):
        while len(upper) >= 2 and cross(upper[-2], upper[-1], p) <= 0:
            upper.pop()
        upper.append(p)
    return lower[:-1] + upper[:-1]


def inside(hull, p, tol):
    if len(hull) < 3:
        return dist_point_segment(p[0], p[1], hull[0], hull[-1]) <= tol
    for i in range(len(hull)):
        a, b = hull[i], hull[(i + 1) % len(hull)]
        if cross(a, b, p) < -tol * math.hypot(b[0] - a[0], b[1] - a[1]):
            return False
    return True


def euclid_point_segment(p, a, b):
    dx, dy = b[0] - a[0], b[1] - a[1]
    l2 = dx * dx + dy * dy
    t = 0.0 if l2 == 0 else max(0.0, min(1.0, ((p[0] - a[0]) * dx + (p[1] - a[1]) * dy) / l2))
    return math.hypot(p[0] - a[0] - t * dx, p[1] - a[1] - t * dy)


def segments_cross(a, b, c, d):
    return (cross(a, b, c) * cross(a, b, d) <= 0) and (cross(c, d, a) * cross(c, d, b) <= 0)


def path_meets_hull(path, hull, reach):
    """Does the polyline come within Euclidean distance `reach` of the convex hull?"""
    ring = [(hull[i], hull[(i + 1) % len(hull)]) for i in range(len(hull))] if len(hull) > 1 else [(hull[0], hull[0])]
    for i, p in enumerate(path):
        if inside(hull, p, 0.0):
            return True
        q = path[i - 1] if i else p
        for a, b in ring:
            if segments_cross(p, q, a, b) and (p != q or a != b):
                return True
            if min(euclid_point_segment(p, a, b), euclid_point_segment(q, a, b),
                   euclid_point_segment(a, p, q), euclid_point_segment(b, p, q)) <= reach:
                return True
    return False


def slanted(e):
    return e[0][0] != e[1][0] and e[0][1] != e[1][1]


def compare(name, pairs, gauges, edges_at, t, grid):
    """pairs: [(e, f, d)] from DRC; gauges: gauges of the matching type. Returns failures."""
    all_pairs = len(pairs)
    pairs = [(e, f, d) for e, f, d in pairs if not slanted(e) and not slanted(f)]
    by_pair = {}
    neighbours = {}
    for es in edges_at.values():
        for e in es:
            neighbours.setdefault(e, set()).update(es)
    for g in gauges:
        for e in features(g.site_a_geom, edges_at):
            for f in features(g.site_b_geom, edges_at):
                by_pair.setdefault(key(e, f), []).append(g)
    same = corner = between = 0
    missed = []
    for e, f, d in pairs:
        cands = by_pair.get(key(e, f), [])
        if any(g.cd <= d + 1 + 1e-6 for g in cands):
            same += 1
            continue
        if any(g.cd <= d + 1 + 1e-6 for e2 in neighbours.get(e, ()) for f2 in neighbours.get(f, ())
               for g in by_pair.get(key(e2, f2), ())):
            corner += 1
            continue
        hull = hull_of(e, f)
        gx = [g for g in grid.near(e, f) if g.cd <= d + 1 + 1e-6 and path_meets_hull(g.stretch, hull, 0.5 * d + 1)]
        if gx:
            between += 1
        else:
            missed.append((e, f, d, sorted(g.cd for g in cands)[:1]))
    drc = set(key(e, f) for e, f, d in pairs)
    critical = [g for g in gauges if g.cd < t]
    all_critical = len(critical)
    critical = [g for g in critical
                if not any(slanted(e) for e in features(g.site_a_geom, edges_at) | features(g.site_b_geom, edges_at))]
    off = []
    for g in critical:
        fa, fb = features(g.site_a_geom, edges_at), features(g.site_b_geom, edges_at)
        if not any(key(e, f) in drc for e in fa for f in fb):
            off.append(g)
    n = len(pairs)
    recall = 100.0 * (same + corner + between) / n if n else 100.0
    precision = 100.0 * (len(critical) - len(off)) / len(critical) if critical else 100.0
    print("  %-5s t=%-8g DRC pairs %6d: same features %6d, at corners %4d, narrower near %5d -> recall %6.2f%%; "
          "gauges cd<t %6d, on a DRC pair %6d -> precision %6.2f%%; slanted, not compared: %d pairs, %d gauges"
          % (name, t, n, same, corner, between, recall, len(critical), len(critical) - len(off), precision,
             all_pairs - n, all_critical - len(critical)))
    for e, f, d, c in missed[:5]:
        print("    missed: %s | %s d=%g (gauges on these features: %s)" % (e, f, d, c))
    for g in off[:5]:
        print("    off: %s at (%.1f, %.1f) cd=%.2f owners %s %s" % (g.type, g.cx, g.cy, g.cd, g.site_a_geom,
                                                                   g.site_b_geom))
    return len(missed) + len(off)


class Grid:
    """Gauges bucketed by the bounding boxes of their stretches, to find those passing
    between two edges."""
    def __init__(self, gauges, size):
        self.size = size
        self.cells = {}
        for g in gauges:
            xs = [p[0] for p in g.stretch]
            ys = [p[1] for p in g.stretch]
            for i in range(int(min(xs) // size), int(max(xs) // size) + 1):
                for j in range(int(min(ys) // size), int(max(ys) // size) + 1):
                    self.cells.setdefault((i, j), []).append(g)

    def near(self, e, f):
        xs = [p[0] for p in e + f]
        ys = [p[1] for p in e + f]
        s = self.size
        seen = set()
        for i in range(int(min(xs) // s) - 1, int(max(xs) // s) + 2):
            for j in range(int(min(ys) // s) - 1, int(max(ys) // s) + 2):
                for g in self.cells.get((i, j), ()):
                    if id(g) not in seen:
                        seen.add(id(g))
                        yield g


def drc_pairs(edge_pairs):
    out = []
    for ep in edge_pairs.each():
        e = edge_key(ep.first)
        f = edge_key(ep.second)
        out.append((e, f, edist(e, f)))
    return out


def least_axis_parallel(check, reach):
    """The least L-inf distance of the DRC edge pairs between two axis-parallel edges that
    `check(t)` flags (distance < t): t is doubled from 1 DBU until some such pair is flagged, so
    that the least is found without flagging every pair of the layer. None where none is
    flagged up to `reach`."""
    t = 1
    while True:
        near = [d for e, f, d in drc_pairs(check(t)) if not slanted(e) and not slanted(f)]
        if near:
            return min(near)
        if t > reach:
            return None
        t *= 2


def main():
    path, layer = arg("input"), arg("layer")
    ly = pya.Layout()
    ly.read(path)
    cell = ly.cell(arg("cell")) if arg("cell", None) else ly.top_cells()[0]
    l, d = (int(v) for v in layer.split("/"))
    drawn = layer_io.region_of(cell, ly.find_layer(l, d))
    # The gauges from the shapes as drawn (the core merges them, as in the flow); the features
    # and the DRC from KLayout's own merge of the layer.
    result = gauge_stage.compute(layer_io.polygons_of(drawn), with_paths=True)
    region = drawn.merged()
    polygons = layer_io.polygons_of(region)
    edges_at = {}
    for outer, holes in polygons:
        for ring in [outer] + holes:
            for i, p in enumerate(ring):
                q = ring[(i + 1) % len(ring)]
                k = key(p, q)
                edges_at.setdefault(p, set()).add(k)
                edges_at.setdefault(q, set()).add(k)
    internal = [g for g in result.gauges if g.type == "internal"]
    external = [g for g in result.gauges if g.type == "external"]
    box = region.bbox()
    reach = max(box.width(), box.height()) + 1
    w0 = least_axis_parallel(lambda t: region.width_check(t, True, pya.Region.Square), reach)
    s0 = least_axis_parallel(lambda t: region.space_check(t, True, pya.Region.Square), reach)
    factors = [float(v) for v in arg("factors", "1.5,2.0,3.0").split(",")]
    print("%s %s: %d polygons, %d gauges (internal %d, external %d); KLayout's narrowest axis-parallel width %s, "
          "space %s DBU (gauges' narrowest: width %g, space %g)"
          % (os.path.basename(path), layer, len(polygons), len(result.gauges), len(internal), len(external),
             w0, s0, min((g.cd for g in internal), default=0), min((g.cd for g in external), default=0)))
    expect(w0 is not None or s0 is not None, "KLayout finds an axis-parallel width or space on the layer")
    failures = 0
    for k in factors:
        compared = 0
        if w0 is not None:
            tw = math.floor(k * w0) + 1
            width = drc_pairs(region.width_check(tw, True, pya.Region.Square))
            compared += sum(1 for e, f, d in width if not slanted(e) and not slanted(f))
            failures += compare("width", width, internal, edges_at, tw,
                                Grid([g for g in internal if g.cd <= tw + 1], max(tw, 1) * 4))
        if s0 is not None:
            ts = math.floor(k * s0) + 1
            space = drc_pairs(region.space_check(ts, True, pya.Region.Square))
            compared += sum(1 for e, f, d in space if not slanted(e) and not slanted(f))
            failures += compare("space", space, external, edges_at, ts,
                                Grid([g for g in external if g.cd <= ts + 1], max(ts, 1) * 4))
        expect(compared > 0, "factor %g compares %d DRC pairs of axis-parallel edges" % (k, compared))
    expect(failures == 0, "%d DRC pairs unexplained or gauges off a DRC pair (above)" % failures)


main()
finish()
