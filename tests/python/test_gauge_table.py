# The gauges reach Python as flat columns (gauges.GaugeTable): the per-gauge view, the whole
# columns the selection reads (spots, cd/extension pairs) and the flat polygon input must all
# say the same as the plain lists they replace.
#   PYTHONPATH=plugin/python:build python3 tests/python/test_gauge_table.py
import os
import tempfile
import unittest
from array import array

import linf_opc_core as core
from linf_opc import gauges, polygons, selection, worker
from linf_opc.polygons import Polygons
from test_determinism import layout as random_boxes


def layout(seed):
    """Random boxes (tests/python/test_determinism.py) and one shape with a hole."""
    return random_boxes(seed, 120) + [([(4000, 0), (4400, 0), (4400, 400), (4000, 400)],
                                        [[(4100, 100), (4100, 300), (4300, 300), (4300, 100)]])]


class GaugeTableColumns(unittest.TestCase):
    def setUp(self):
        self.polys = layout(5)
        self.table = gauges.compute(self.polys).gauges
        self.rows = list(self.table)

    def test_rows_are_ranked_and_typed(self):
        self.assertGreater(len(self.rows), 100)
        self.assertEqual([g.rank for g in self.rows], list(range(1, len(self.rows) + 1)))
        self.assertEqual(set(g.type for g in self.rows), set(gauges.TYPES))
        self.assertEqual(self.table[-1], self.rows[-1])
        self.assertEqual(self.table[3:6], self.rows[3:6])
        with self.assertRaises(IndexError):
            self.table[len(self.rows)]

    def test_counts_and_score_ranges_match_the_rows(self):
        result = gauges.compute(self.polys)
        want_n = {t: sum(1 for g in self.rows if g.type == t) for t in gauges.TYPES}
        want_r = {t: (min(g.score for g in self.rows if g.type == t), max(g.score for g in self.rows if g.type == t))
                  for t in gauges.TYPES if want_n[t]}
        for block in (gauges.TALLY_BLOCK, 7, 1):  # one block, and many
            gauges.TALLY_BLOCK = block
            try:
                self.assertEqual(result.counts(), want_n)
                self.assertEqual(result.score_ranges(), want_r)
            finally:
                gauges.TALLY_BLOCK = 1 << 16

    def test_spots_match_the_rows(self):
        index = {t: i for i, t in enumerate(gauges.TYPES)}
        x, y, t, n = self.table.spots()
        self.assertEqual(list(x), [g.cx for g in self.rows])
        self.assertEqual(list(y), [g.cy for g in self.rows])
        self.assertEqual(list(t), [index[g.type] for g in self.rows])
        self.assertEqual(list(n), [g.norm_score for g in self.rows])

    def test_cd_extension_and_pitch_match_the_rows(self):
        for t in ("internal", "external", "T"):
            expected = array("d", [v for g in self.rows if g.type == t for v in (g.cd, g.tiebreak)])
            self.assertEqual(self.table.cd_extension(t), expected)
        self.assertEqual(selection.pitch_of(self.table), selection.pitch_of(self.rows))
        self.assertGreater(selection.pitch_of(self.table), 0)

    def test_selection_same_from_table_and_rows(self):
        markers = [(g.cx - 5, g.cy - 5, g.cx + 5, g.cy + 5) for g in self.rows[::40]]
        pitch = selection.pitch_of(self.rows)
        a = selection.study(self.table, markers, pitch, sizes=(5, 7), modes=("A", "C"))
        b = selection.study(self.rows, markers, pitch, sizes=(5, 7), modes=("A", "C"))
        for key in a.runs:
            self.assertEqual(a.runs[key].windows, b.runs[key].windows)
            # The failed gauges, made again on demand, are the ones the study counted.
            failed = list(a.runs[key].failed_spots)
            self.assertEqual(len(failed), a.runs[key].n_failed)
            self.assertEqual(failed, list(b.runs[key].failed_spots))
            self.assertGreater(len(failed), 0)

    def test_mapped_columns_are_the_bytes_and_leave_no_file(self):
        # gauges.compute has the core write the columns to a file it maps (a full layer's
        # columns are gigabytes); they must be the very bytes the core hands over in memory.
        raw = core.gauges_polygons(self.polys)["gauges"]
        self.assertIsNone(raw["file"])
        reals, ints = self.table.columns()
        self.assertEqual(reals.tobytes(), raw["reals"])
        self.assertEqual(ints.tobytes(), raw["ints"])
        self.assertEqual(len(self.table), raw["count"])
        # The file is removed once mapped, and so is the file of a call that fails.
        path = gauges.columns_file()
        got = gauges.GaugeTable(core.gauges_polygons(self.polys, columns=path)["gauges"])
        self.assertFalse(os.path.exists(path))
        self.assertEqual(list(got), self.rows)
        path = gauges.columns_file()
        with open(path, "wb") as f:
            f.write(b"short")
        with self.assertRaises(ValueError):
            gauges.GaugeTable({"count": 3, "file": path, "reals": None, "ints": None, "paths": None})
        self.assertFalse(os.path.exists(path))
        made = []
        real = gauges.columns_file
        gauges.columns_file = lambda: made.append(real()) or made[-1]
        try:
            with self.assertRaises(ValueError):
                gauges.compute([([(0, 0), (2 ** 31, 0), (2 ** 31, 10), (0, 10)], [])])  # beyond the core's range
        finally:
            gauges.columns_file = real
        self.assertEqual(len(made), 1)
        self.assertFalse(os.path.exists(made[0]))

    def test_flat_polygons_give_the_same_gauges(self):
        flat = Polygons.of(self.polys)
        self.assertEqual(len(flat), len(self.polys))
        self.assertEqual(list(flat), [(o, h) for o, h in self.polys])
        self.assertEqual(list(gauges.compute(flat).gauges), self.rows)
        self.assertEqual(core.voronoi_polygons(flat.flat())["pieces"], core.voronoi_polygons(self.polys)["pieces"])

    def test_spilled_polygons_are_the_same_and_leave_no_file(self):
        # A large layer's arrays go to mapped files the kernel may drop (Polygons.spill): whole
        # once read, or a chunk at a time while it is read (spill_over), never all in memory.
        old_dir, old_chunk = tempfile.tempdir, polygons.CHUNK
        with tempfile.TemporaryDirectory() as d:
            tempfile.tempdir = d
            try:
                whole = Polygons.of(self.polys)
                whole.spill()
                polygons.CHUNK = 7  # chunks that end inside rings and inside points
                chunked = Polygons(spill_over=3)
                for outer, holes in self.polys:
                    chunked.add(outer, holes)
                held = len(chunked.points)
                self.assertEqual(os.listdir(d), [])  # the files are unlinked as they are made
                chunked.done()
            finally:
                tempfile.tempdir, polygons.CHUNK = old_dir, old_chunk
        self.assertLess(held, 8)  # at most a chunk was in memory when the last shape was added
        for flat in (whole, chunked):
            self.assertIsInstance(flat.points, memoryview)
            self.assertEqual(len(flat), len(self.polys))
            self.assertEqual(list(flat), [(o, h) for o, h in self.polys])
        self.assertEqual(list(gauges.compute(chunked).gauges), self.rows)
        # The editor's worker pickles a call's arguments: the arrays go as plain arrays.
        points, rings = worker._picklable(chunked.flat())
        self.assertEqual((points, rings), Polygons.of(self.polys).flat())
        few = Polygons(spill_over=len(self.polys))  # not over the limit: stays in memory
        for outer, holes in self.polys:
            few.add(outer, holes)
        few.done()
        self.assertIsInstance(few.points, array)
        empty = Polygons()
        empty.spill()
        self.assertEqual(list(empty), [])

    def test_records_in_another_order(self):
        # core.permute_records (the printability ranking's reorder): record k of the result is
        # record order[k], for the table's reals and ints alike; a non-permutation is refused.
        reals, ints = self.table.columns()
        n = len(self.rows)
        order = array("i", reversed(range(n)))
        order[0], order[n // 2] = order[n // 2], order[0]
        new_reals = array("d")
        new_reals.frombytes(core.permute_records(reals, 80, order))
        new_ints = array("i")
        new_ints.frombytes(core.permute_records(ints, 52, order))
        for k in (0, 1, n // 2, n - 1):
            self.assertEqual(new_reals[10 * k:10 * k + 10], reals[10 * order[k]:10 * order[k] + 10])
            self.assertEqual(new_ints[13 * k:13 * k + 13], ints[13 * order[k]:13 * order[k] + 13])
        self.assertEqual(sorted(new_reals), sorted(reals))
        for bad, says in [(array("i", [0] * n), "every record once"), (array("i", range(n - 1)), "every record once"),
                          (array("i", [n] + list(range(1, n))), "every record once")]:
            with self.assertRaisesRegex(ValueError, says):
                core.permute_records(reals, 80, bad)
        with self.assertRaisesRegex(ValueError, "whole records"):
            core.permute_records(reals, 7, order)

    def test_flat_arrays_that_do_not_add_up_are_refused(self):
        # The core reads the arrays in place: each way they can disagree is a ValueError.
        box = [0, 0, 10, 0, 10, 10, 0, 10]
        for points, rings, says in [(box, [5], "more points"), (box, [-4], "outer ring"),
                                    (box + [20, 20], [4], "left over"),
                                    ([0, 0, 1 << 30, 0, 10, 10], [3], r"2\^30")]:
            with self.assertRaisesRegex(ValueError, says):
                core.voronoi_polygons((array("q", points), array("q", rings)))
        with self.assertRaisesRegex(ValueError, "64-bit"):
            core.voronoi_polygons((array("i", box), array("q", [4])))


class TakeRecords(unittest.TestCase):
    """core.take_records, the gathers of the printability on a cluster: record k of the result is
    record index[k], from whole records or from a strided column of the gauge table."""

    def test_records_and_strided_columns(self):
        table = gauges.compute(layout(7)).gauges
        reals, ints = table.columns()
        n = len(table)
        index = array("q", [n - 1, 0, 3, 3, n // 2])
        got = array("d", core.take_records(reals, 80, index))
        self.assertEqual(got, array("d", [v for i in index for v in reals[10 * i:10 * i + 10]]))
        for k in (4, 5, 7):  # a column read in place: every tenth double
            column = reals[k::10]
            self.assertEqual(array("d", core.take_records(column, 8, index)), array("d", [column[i] for i in index]))
        kinds = ints[12::13]
        self.assertEqual(array("i", core.take_records(kinds, 4, index)), array("i", [kinds[i] for i in index]))
        self.assertEqual(core.take_records(reals, 80, array("q")), b"")
        with self.assertRaises(ValueError):
            core.take_records(reals, 80, array("q", [n]))
        with self.assertRaises(ValueError):
            core.take_records(reals[4::10], 16, index)  # a strided view is a column of single values


if __name__ == "__main__":
    unittest.main(verbosity=2)
