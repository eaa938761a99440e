"""Records: a sequence of records made on access from flat columns.

A full layer's stages hand on hundreds of thousands of records (gauges, windows, patterns);
held in a list, a Python object each would be hundreds of MB. Their tables (GaugeTable,
selection.Windows, split.Patterns) keep columns and make a record when it is asked for; a
Subset picks from such a table the same way.
"""
from collections.abc import Sequence


class Records(Sequence):
    """len() and _record(i) come from the table; indexing (negative, slices as lists) here."""

    def __getitem__(self, i):
        n = len(self)
        if isinstance(i, slice):
            return [self._record(k) for k in range(*i.indices(n))]
        if i < 0:
            i += n
        if not 0 <= i < n:
            raise IndexError("%s index out of range" % type(self).__name__)
        return self._record(i)


class Subset(Records):
    """Some items of a sequence, by index."""

    def __init__(self, items, indices):
        self._items, self._indices = items, indices

    def __len__(self):
        return len(self._indices)

    def _record(self, i):
        return self._items[self._indices[i]]
