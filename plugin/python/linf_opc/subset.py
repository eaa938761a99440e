"""Subset: some items of a sequence, by index, each made on access.

A full layer's stages hand on hundreds of thousands of records (gauges, patterns); held in a
list, a Python object each would be hundreds of MB. The tables they come from (GaugeTable,
split.Patterns) make a record when it is asked for; a Subset picks from such a table the same way.
"""
from collections.abc import Sequence


class Subset(Sequence):
    def __init__(self, items, indices):
        self._items, self._indices = items, indices

    def __len__(self):
        return len(self._indices)

    def __getitem__(self, i):
        if isinstance(i, slice):
            return [self[k] for k in range(*i.indices(len(self)))]
        return self._items[self._indices[i]]
