# The editor's worker process, outside KLayout:
#   PYTHONPATH=plugin/python:build python3 tests/python/test_worker.py
# A call gives the same result as in-process; the core's errors come back as the same
# exceptions; a crash, a hang past the time limit and a memory limit each give a WorkerError
# with a clear message and the input saved; cancelling (an exception from the wait callback)
# stops the child.
import os
import sys
import tempfile
import unittest

from linf_opc import core, worker

BOX = [([(0, 0), (100, 0), (100, 20), (0, 20)], [])]


class Worker(unittest.TestCase):
    def setUp(self):
        self.dir = tempfile.mkdtemp(prefix="linf_worker_")

    def runner(self, **kw):
        return worker.Runner(failures=self.dir, **kw)

    def test_same_result_as_in_process(self):
        with core.running_with(self.runner()):
            far = core.farthest_voronoi([[(0, 0), (100, 0)], [(0, 50), (0, 200)]])
            gauges = core.gauges_polygons(BOX)
        self.assertEqual(far, core.farthest_voronoi([[(0, 0), (100, 0)], [(0, 50), (0, 200)]]))
        self.assertEqual(gauges["gauges"], core.gauges_polygons(BOX)["gauges"])

    def test_errors_come_back(self):
        with core.running_with(self.runner()):
            with self.assertRaises(ValueError):
                core.voronoi_polygons([([(0, 0), (2 ** 31, 0), (2 ** 31, 10)], [])])

    def fault(self, kind, **kw):
        os.environ["LINF_OPC_WORKER_FAULT"] = kind
        try:
            with core.running_with(self.runner(**kw)):
                with self.assertRaises(worker.WorkerError) as e:
                    core.gauges_polygons(BOX)
        finally:
            del os.environ["LINF_OPC_WORKER_FAULT"]
        return str(e.exception)

    def test_crash(self):
        msg = self.fault("crash")
        self.assertIn("crashed (signal 11", msg)
        self.assertIn("not changed", msg)
        self.assertTrue(any(f.endswith("gauges_polygons.pickle") for f in os.listdir(self.dir)))

    def test_hang_is_stopped(self):
        self.assertIn("did not finish within 1 s", self.fault("hang", seconds=1))

    def test_memory_limit(self):
        os.environ["LINF_OPC_WORKER_MEMORY_MB"] = "20"
        try:
            with core.running_with(self.runner()):
                with self.assertRaises(worker.WorkerError):
                    core.gauges_polygons(BOX)
        finally:
            del os.environ["LINF_OPC_WORKER_MEMORY_MB"]

    def test_cancel(self):
        def wait(elapsed):
            raise KeyboardInterrupt()  # what KLayout's progress raises on cancel, in effect
        os.environ["LINF_OPC_WORKER_FAULT"] = "hang"
        try:
            with core.running_with(worker.Runner(wait, self.dir)):
                with self.assertRaises(worker.Cancelled):
                    core.gauges_polygons(BOX)
        finally:
            del os.environ["LINF_OPC_WORKER_FAULT"]


STEPS = ["merging the polygons", "building the diagram", "building the far field", "joining and checking the pieces",
         "checking the diagram", "joining the stretches", "placing the gauges"]
WIRES = [([(x, 0), (x + 20, 0), (x + 20, 2000), (x, 2000)], []) for x in range(0, 40 * 400, 40)]


class CoreSteps(unittest.TestCase):
    """The core tells a watcher its steps, in order, in this process and through the worker."""

    def test_in_process(self):
        told = []
        gauges = core.gauges_polygons(WIRES, progress=lambda step, done, total: told.append((step, done, total)))
        self.assertEqual(gauges["gauges"], core.gauges_polygons(WIRES)["gauges"])  # told, not changed
        names = [s for s, _, _ in told]
        self.assertEqual(sorted(set(names), key=names.index), STEPS)
        self.assertEqual(sorted(names, key=STEPS.index), names)  # never back to an earlier step
        self.assertTrue(all(0 <= d <= t for _, d, t in told if t))
        self.assertGreater(max(t for _, _, t in told), 1)  # the builder counted its tasks

    def test_a_raising_watcher_is_dropped(self):
        def watcher(step, done, total):
            raise RuntimeError("a watcher's own fault")
        self.assertEqual(core.gauges_polygons(WIRES, progress=watcher)["gauges"], core.gauges_polygons(WIRES)["gauges"])

    def test_through_the_worker(self):
        told = []
        with core.running_with(worker.Runner(failures=tempfile.mkdtemp(prefix="linf_worker_"))):
            core.gauges_polygons(WIRES, progress=lambda *step: told.append(step))
        self.assertTrue(told)
        self.assertTrue(all(s in STEPS for s, _, _ in told), told)
        self.assertEqual(told[-1][0], "placing the gauges")


if __name__ == "__main__":
    unittest.main(verbosity=2)
