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


if __name__ == "__main__":
    unittest.main(verbosity=2)
