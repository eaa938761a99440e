"""The budgeted gauge plan: the split's default mode. Gauges of one type and one context (what
the gauge sees of the layer within the context radius, up to translation and the square's
symmetries: contexts.py) are one representative with a count, so that engineers get a list of
different situations, not the same gauge repeated down a rail.

in:  the gauge table (every gauge of the layer, rank order), the layer's polygons, the chosen
     selection run (its windows cover the markers), the markers; budget, verify, radius
out: Plan (a split.Split of mode "plan"): calibration patterns then verification patterns, one
     window each centred on its representative gauge, with each gauge's context and count.

The rules (order, strata, verification) are in docs/design.md, "Split rules".
"""
from array import array

from . import contexts as ctx
from .gauges import TYPES
from .split import MarkerGrid, Patterns, Split

# Why a gauge is in its set, and the name split.json counts it under.
KINDS = (("marker", "marker_windows"), ("context", "new_contexts"), ("other", "other_instances"),
         ("held-out", "held_out_contexts"))
TOP_CONTEXTS = 20  # the report's and split.json's table of the most repeated contexts


def _first(indices, keys, taken, limit):
    """The indices whose key is not yet taken, in order, at most `limit`; marks their keys."""
    out = []
    for i in indices:
        if len(out) >= limit:
            break
        k = keys(i)
        if k not in taken:
            taken.add(k)
            out.append(i)
    return out


class Plan(Split):
    """A split whose patterns are representatives: the calibration list first, then the
    verification list. rows(which) gives the gauge table's rows with their contexts and counts."""

    def __init__(self, params, patterns, assign, table, contexts, neighbours, kind):
        super().__init__("plan", params, patterns, assign, None)
        self.table, self.contexts = table, contexts
        self._neighbours = neighbours  # every gauge the plan holds had its space found when it was made
        self._kind = kind  # per pattern: one of KINDS

    def rows(self, which):
        """(array('i') table rows, array('Q') context ids, array('Q') counts) of one set, in order."""
        rows = array("i", (p.index for p, a in zip(self.patterns, self.assign) if a == which))
        c = self.contexts
        return (rows, array("Q", (c.ids[i] for i in rows)),
                array("Q", (c.count[c.key(i)] for i in rows)))

    def space(self, i):
        return self._neighbours.space(i)

    def _set_summary(self, which, dbu):
        rows = [p.index for p, a in zip(self.patterns, self.assign) if a == which]
        kinds = [k for k, a in zip(self._kind, self.assign) if a == which]
        keys = [self.contexts.key(i) for i in rows]
        distinct = list(dict.fromkeys(keys))
        cd, _, _ = self.table.cd_extension_type()
        cds = [cd[i] for i in rows]
        spaces = [s for s in (self.space(i) for i in rows) if s is not None]
        out = {
            "gauges": len(rows),
            "contexts": len(distinct),
            "contexts_in_first_100": len(set(keys[:100])),
            "share_of_gauges": round(sum(self.contexts.count[k] for k in distinct) / max(1, len(self.table)), 6),
            "cd_range_um": _range(cds, dbu),
            "space_range_um": _range(spaces, dbu),
            "by_type": {t: sum(1 for k in distinct if TYPES[k[0]] == t) for t in TYPES},
        }
        for kind, name in KINDS:
            if kind in kinds:
                out[name] = kinds.count(kind)
        return out

    def summary(self, dbu=1.0):
        c = self.contexts
        cd, _, _ = self.table.cd_extension_type()
        covers = self.patterns.covering()
        reps = c.representatives
        spaces = [s for s in (self.space(i) for i in reps) if s is not None]
        by_count = sorted(reps, key=lambda i: (-c.count[c.key(i)], i))[:TOP_CONTEXTS]
        sets = {}
        for which, s in (("calibration", "calibration"), ("verification", "verification")):
            sets[which] = set(c.key(p.index) for p, a in zip(self.patterns, self.assign) if a == s)
        return {
            "mode": "plan",
            "parameters": self.params,
            "patterns": len(self.patterns),
            "covering_markers": sum(covers),
            "counts": {s: self.assign.count(s) for s in ("calibration", "verification")},
            "covering_markers_per_set": {s: sum(1 for v, a in zip(covers, self.assign) if v and a == s)
                                         for s in ("calibration", "verification")},
            "layer": {"gauges": len(self.table), "contexts": len(c), "context_ids": len(set(c.ids)),
                      "contexts_by_type": {t: sum(1 for k in c.count if TYPES[k[0]] == t) for t in TYPES},
                      "cd_range_um": _range([cd[i] for i in reps], dbu), "space_range_um": _range(spaces, dbu),
                      "contexts_without_space": len(reps) - len(spaces)},
            "sets": {s: self._set_summary(s, dbu) for s in ("calibration", "verification")},
            "top_contexts": [{"context": "%016x" % c.ids[i], "type": TYPES[c.types[i]], "cd_um": round(cd[i] * dbu, 6),
                              "score_um": round(self.table.scores()[i] * dbu, 6), "count": c.count[c.key(i)],
                              "rank": i + 1, "in": [s for s in sets if c.key(i) in sets[s]]} for i in by_count],
        }

    def points(self, dbu):
        """(cd, space) in micrometres of the layer's representatives and of each set's gauges,
        where there is a space: the report's plot."""
        cd, _, _ = self.table.cd_extension_type()

        def of(rows):
            return [(cd[i] * dbu, s * dbu) for i, s in ((i, self.space(i)) for i in rows) if s is not None]
        return {"layer": of(self.contexts.representatives),
                **{w: of([p.index for p, a in zip(self.patterns, self.assign) if a == w])
                   for w in ("calibration", "verification")}}


def _range(values, dbu):
    return [round(min(values) * dbu, 6), round(max(values) * dbu, 6)] if values else None


def plan(table, polygons, run, window_rows, markers, budget, verify, radius, max_norm=1.0, params=None):
    """The Plan of the gauge `table` on `polygons`. run: the chosen selection run (its window
    side is the clips'); window_rows: the table rows of its windows' gauges, in the windows'
    order; budget, verify: the calibration and verification sizes; radius: the context radius
    in DBU; max_norm: only gauges at most this critical are picked."""
    contexts = ctx.Contexts(table, ctx.context_ids(table, polygons, radius))
    norm = table.spots()[3]
    eligible = (lambda i: True) if max_norm >= 1 else (lambda i: norm[i] <= max_norm + 1e-12)
    neighbours = ctx.Neighbours(table, radius)
    cd, _, _ = table.cd_extension_type()
    reps = [i for i in contexts.representatives if eligible(i)]
    # Spaces are found many gauges a call (each call indexes the layer's gauges): the
    # representatives now, the other gauges the plan may take as they become known.
    neighbours.spaces(contexts.representatives)
    strata = ctx.Strata(contexts, cd, neighbours.known)

    def bin_of(i):
        return strata.of(i, cd[i], neighbours.space(i))

    key = contexts.key
    # Calibration: the marker windows' gauges (rank order), each (type, context) once; then
    # every other (type, context) once, spread over the strata where they exceed the budget. A
    # context is never repeated: where the budget exceeds the contexts, the list is shorter.
    taken = set()
    marker_rows = sorted(window_rows)
    neighbours.spaces(marker_rows)
    cal = _first(marker_rows, key, taken, budget)
    kind = ["marker"] * len(cal)
    rest = [i for i in reps if key(i) not in taken]
    room = budget - len(cal)
    order = rest if len(rest) <= room else ctx.spread(rest, bin_of)
    more = _first(order, key, taken, room)
    cal += more
    kind += ["context"] * len(more)
    in_cal = set(cal)
    deferred = [i for i in marker_rows if i not in in_cal]
    # Verification: for each calibration context another of its gauges (a marker window's first),
    # and the contexts calibration left out, spread over the strata where they exceed `verify`.
    wanted = {}
    for i in cal:
        wanted.setdefault(key(i), i)
    other = {}
    for i in deferred:
        if i not in in_cal and key(i) in wanted and key(i) not in other:
            other[key(i)] = i
    lacking = {k: i for k, i in wanted.items() if k not in other}
    other.update({k: i for k, i in contexts.others(lacking).items() if eligible(i) and i not in in_cal})
    candidates = sorted(set(other.values()) | set(i for i in reps if key(i) not in taken))
    neighbours.spaces(candidates)
    order = candidates if len(candidates) <= verify else ctx.spread(candidates, bin_of)
    ver = order[:verify]
    kind += ["other" if key(i) in wanted else "held-out" for i in ver]
    # The patterns: a window of the run's side centred on each gauge, with the markers inside.
    h = 0.5 * run.side
    grid = MarkerGrid(markers, run.side)
    patterns = Patterns(table, markers)
    cx, cy = table.centres()
    for i, k in zip(cal + ver, kind):
        box = (cx[i] - h, cy[i] - h, cx[i] + h, cy[i] + h)
        patterns.append(box, i, grid.inside(box), k == "marker")
    assign = ["calibration"] * len(cal) + ["verification"] * len(ver)
    return Plan(dict(params or {}, budget=budget, verify=verify), patterns, assign, table, contexts, neighbours,
                kind)


def of_selection(sel, polygons, dbu, budget, verify, radius=None):
    """The Plan of a flow's selection (flow.Selected) on the layer's `polygons`: every gauge of
    the layer, the chosen run's windows and markers; radius in DBU, None for half the window."""
    table, run = sel.result.gauges, sel.chosen
    radius = radius or 0.5 * run.side
    # The selection's gauges are the table or, with max_norm < 1, some of its records.
    window_rows = [w[4] if sel.gauges is table else sel.gauges[w[4]].rank - 1 for w in run.windows]
    params = {"context_radius_um": round(radius * dbu, 9), "window": "%dx%d" % (run.size, run.size),
              "window_um": round(run.side * dbu, 9), "quantiles": ctx.QUANTILES, "max_norm": sel.max_norm}
    return plan(table, polygons, run, window_rows, sel.markers.boxes, budget, verify, radius, sel.max_norm, params)
