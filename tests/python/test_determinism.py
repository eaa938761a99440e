# The same input gives the same results whatever the number of builder threads, to the last
# bit (the CSV and clip files are written from these values, so they are byte-identical):
#   PYTHONPATH=plugin/python:build python3 tests/python/test_determinism.py
import random
import unittest

import linf_opc_core as core


def layout(seed, n=150):
    rng = random.Random(seed)
    polys = []
    for _ in range(n):
        x, y = rng.randrange(0, 4000), rng.randrange(0, 4000)
        w, h = rng.randrange(10, 200), rng.randrange(10, 60)
        if rng.random() < 0.5:
            w, h = h, w
        polys.append(([(x, y), (x + w, y), (x + w, y + h), (x, y + h)], []))
    return polys


class Determinism(unittest.TestCase):
    def assert_same_pieces(self, a, b):
        # Pieces as tuples (kind, x1, y1, x2, y2, d1, d2, then integers): equal but for the floats,
        # which may differ by 1e-9.
        self.assertEqual(len(a), len(b))
        key = lambda p: (p[0], round(p[1], 6), round(p[2], 6), round(p[3], 6), round(p[4], 6), p[7:])
        for p, q in zip(sorted(a, key=key), sorted(b, key=key)):
            self.assertEqual((p[0], p[7:]), (q[0], q[7:]))
            for u, v in zip(p[1:7], q[1:7]):
                self.assertAlmostEqual(u, v, delta=1e-9, msg="%s != %s" % (p, q))

    def test_diagram_and_gauges_do_not_depend_on_threads(self):
        for seed in (1, 2, 3):
            p = layout(seed)
            one = core.voronoi_polygons(p, threads=1)["pieces"]
            self.assertEqual(one, core.voronoi_polygons(p, threads=2)["pieces"])
            self.assertEqual(one, core.voronoi_polygons(p, threads=3)["pieces"])
            g1 = core.gauges_polygons(p, threads=1)["gauges"]
            self.assertEqual(g1, core.gauges_polygons(p, threads=2)["gauges"])

    def test_same_input_same_result(self):
        p = layout(7)
        self.assertEqual(core.gauges_polygons(p)["gauges"], core.gauges_polygons(p)["gauges"])

    def test_the_builders_give_the_same_pieces(self):
        # The module builds polygons with the sweep unless told otherwise, plain sites with the
        # subdivision; either builder gives the same pieces (to 1e-9 DBU: the subdivision leaves
        # residues of 1e-15 in a clearance of 0).
        p = layout(5)
        r = core.voronoi_polygons(p, threads=1)
        self.assertEqual(r["builder"], "sweep")
        s = core.voronoi_polygons(p, threads=1, builder="subdivision")
        self.assertEqual(s["builder"], "subdivision")
        self.assert_same_pieces(r["pieces"], s["pieces"])
        points = [(0, 0), (30, 25), (-20, 40)]
        segments = [((0, 10), (40, 10)), ((-30, 0), (-30, 30)), ((10, 30), (20, 50))]
        plain = core.voronoi_sites(points, segments, threads=1)
        self.assertEqual(plain["builder"], "subdivision")
        swept = core.voronoi_sites(points, segments, threads=1, builder="sweep")
        self.assertEqual(swept["builder"], "sweep")
        self.assertTrue(swept["check"]["ok"])
        self.assert_same_pieces(plain["pieces"], swept["pieces"])
        with self.assertRaises(ValueError):
            core.voronoi_sites(points, segments, builder="fortune")


if __name__ == "__main__":
    unittest.main(verbosity=2)
