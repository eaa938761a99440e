"""Gauge contexts: the gauges of a layer grouped by type and context, and what the plan sorts
them by (docs/design.md, "Gauge contexts" and "Split rules").

in:  the ranked gauge table (gauges.GaugeTable), the layer's polygons, a context radius in DBU
out: Contexts: each gauge's context id (core.gauge_contexts), the groups of one type and one
     context with their best-ranked gauge and their size; Neighbours: a gauge's neighbouring
     space; Strata: the bins of type x cd quantile x space quantile.

A full layer has millions of gauges: the groups are found from the table's columns by C-level
loops (zip, Counter, dict), no Python object a gauge is kept.
"""
from array import array
from bisect import bisect_right
from collections import Counter

from . import core
from .gauges import TYPES
from .polygons import core_input

QUANTILES = 4  # cd and space bins per type: quartiles of the distinct values


def context_ids(table, polygons, radius):
    """array('Q'): the context id of each gauge of `table`, in its order, at `radius` DBU."""
    cx, cy = table.centres()
    points = array("d", bytes(16 * len(table)))
    m = memoryview(points)
    m[0::2] = cx
    m[1::2] = cy
    ids = array("Q")
    ids.frombytes(core.gauge_contexts(core_input(polygons), points, radius))
    return ids


class Contexts:
    """The groups of gauges of one type and one context. A group's key is (type index, context
    id); its representative is its best-ranked gauge (the lowest index in rank order)."""

    def __init__(self, table, ids):
        self.table, self.ids = table, ids
        self.types = table.type_indices()
        n = len(table)
        keys = zip(self.types, ids)
        self.count = Counter(keys)
        # Reversed, the last index a key gets is its first in rank order.
        self.first = dict(zip(zip(self.types[::-1], ids[::-1]), range(n - 1, -1, -1)))
        self.representatives = array("i", sorted(self.first.values()))  # rank order

    def key(self, i):
        return self.types[i], self.ids[i]

    def __len__(self):
        return len(self.first)

    def others(self, wanted):
        """{key: index} for each key of `wanted` ({key: index}): the best-ranked gauge of the key
        that is not wanted[key], where there is one."""
        found = {}
        if not wanted:
            return found
        for i, key in enumerate(zip(self.types, self.ids)):
            w = wanted.get(key)
            if w is not None and w != i and key not in found:
                found[key] = i
                if len(found) == len(wanted):
                    break
        return found


class Neighbours:
    """A gauge's neighbouring space: for a width gauge (internal, sandwich, comb, T: their cd is
    a width) the least cd of the external gauges whose points lie within `radius` (L-inf) of its
    point; for an external gauge the least cd of the internal gauges there. None where there is
    none. Found by the core (core.neighbour_spaces), many gauges a call (each call indexes the
    layer's gauges), and kept in `known` ({row: space})."""

    def __init__(self, table, radius):
        self.radius = radius
        x, y = table.centres()
        cd, _, types = table.cd_extension_type()
        self._columns = (x, y, cd, types)
        self.known = {}

    def spaces(self, rows):
        """{row: space} for the table rows `rows` (any iterable), None where there is none."""
        rows = list(rows)
        todo = array("i", (i for i in dict.fromkeys(rows) if i not in self.known))
        if todo:
            got = array("d")
            got.frombytes(core.neighbour_spaces(*self._columns, todo, self.radius))
            self.known.update((i, None if v != v else v) for i, v in zip(todo, got))  # NaN: none
        return {i: self.known[i] for i in rows}

    def space(self, i):
        return self.known[i] if i in self.known else self.spaces((i,))[i]


def edges(values, q=QUANTILES):
    """The q-quantile edges of the distinct values: a bin each for rare and common values alike."""
    distinct = sorted(set(values))
    return [distinct[k * len(distinct) // q] for k in range(1, q)] if distinct else []


class Strata:
    """Bins of gauge type x cd quantile x neighbouring-space quantile (a bin of its own for no
    space nearby), the quantiles per type over the groups' representatives."""

    def __init__(self, contexts, cd, space):
        """cd, space: {gauge index: value} of every representative (space None where none)."""
        by_type = {}
        for i in contexts.representatives:
            by_type.setdefault(contexts.types[i], []).append(i)
        self.cd_edges = {t: edges([cd[i] for i in members]) for t, members in by_type.items()}
        self.space_edges = {t: edges([space[i] for i in members if space[i] is not None])
                            for t, members in by_type.items()}
        self.types = contexts.types

    def of(self, i, cd, space):
        t = self.types[i]
        return (t, bisect_right(self.cd_edges.get(t, ()), cd),
                -1 if space is None else bisect_right(self.space_edges.get(t, ()), space))


def spread(indices, bin_of):
    """`indices` (rank order) in rounds: each round takes the next of every bin, the bins in the
    order of their best-ranked member; so a prefix of the result covers as many bins as it can."""
    bins = {}
    for i in indices:
        bins.setdefault(bin_of(i), []).append(i)
    queues = list(bins.values())
    depth = max((len(q) for q in queues), default=0)
    return [q[d] for d in range(depth) for q in queues if d < len(q)]
