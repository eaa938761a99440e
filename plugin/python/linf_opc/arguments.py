"""The commands' arguments read into values. The batch gets them as strings (-rd name=value);
the editor's dialogs give the same strings. Anything that does not parse, or names what is not
there, is a UsageError: the batch stops with its message (exit code 2), the editor shows it."""
from . import gauge_output
from . import selection as selection_stage


class UsageError(Exception):
    pass


def parse_tile(text, dbu):
    """-rd tile=UM (the builder's tile side in micrometres), 0 (one tile) or auto (default)."""
    if text in (None, "", "auto"):
        return -1
    try:
        v = float(text)
    except ValueError:
        raise UsageError("tile must be a size in micrometres, 0 or auto, not %r" % text)
    if v < 0:
        raise UsageError("tile must not be negative: %r" % text)
    return v / dbu


def parse_builder(text):
    """-rd builder=sweep|subdivision: the diagram's construction (the same diagram either way).
    sweep (the default): the sweep-line builder, on any layer, tile by tile on the worker
    threads or a cluster's workers. subdivision: the subdivision builder."""
    if text in (None, "", "sweep"):
        return "sweep"
    if text == "subdivision":
        return "subdivision"
    raise UsageError("builder must be sweep or subdivision, not %r" % text)


def parse_check(text):
    """-rd check=sample|full: how much of the independent check runs. sample (the default): every
    piece's owners and clearances and the completeness pairs, and the search for a closer site on
    one piece in 16; full: that search on every piece too (about four times the check's time)."""
    if text in (None, "", "sample"):
        return "sample"
    if text == "full":
        return "full"
    raise UsageError("check must be sample or full, not %r" % text)


def parse_window(text, dbu):
    """'x1,y1,x2,y2' in micrometres -> a box in DBU."""
    try:
        x1, y1, x2, y2 = (float(v) / dbu for v in text.split(","))
    except ValueError:
        raise UsageError("window must be x1,y1,x2,y2 in micrometres, not %r" % text)
    return min(x1, x2), min(y1, y2), max(x1, x2), max(y1, y2)


def report_max(args, default=gauge_output.REPORT_MAX_PER_TYPE):
    """-rd rdb_max=N: the report database's gauges per type, the most critical (0: all)."""
    text = args.get("rdb_max")
    if text in (None, ""):
        return default
    try:
        n = int(text)
    except ValueError:
        n = -1
    if n < 0:
        raise UsageError("rdb_max must be a count of gauges per type (0: all), not %r" % text)
    return n


def switch(args, name, default=False):
    """-rd NAME=0|1: an output or an experiment made on request (anything else is a UsageError)."""
    text = args.get(name)
    if text in (None, ""):
        return default
    if text not in ("0", "1"):
        raise UsageError("%s must be 0 or 1, not %r" % (name, text))
    return text == "1"


def _ints(text, name):
    try:
        v = [int(x) for x in text.split(",")]
    except ValueError:
        raise UsageError("%s must be a comma-separated list of integers, not %r" % (name, text))
    if not v or min(v) <= 0:
        raise UsageError("%s must be positive" % name)
    return v


def select_args(args, dbu):
    """(sizes, modes, chosen mode, chosen size or None, pitch in DBU or None, halves)."""
    sizes = _ints(args.get("sizes") or "5,6,7,8", "sizes")
    modes = [m.strip().upper() for m in (args.get("modes") or "A,B,C").split(",")]
    if any(m not in selection_stage.MODES for m in modes):
        raise UsageError("modes must be among A, B, C, not %r" % args.get("modes"))
    mode = (args.get("mode") or modes[0]).upper()
    if mode not in modes:
        raise UsageError("mode %s is not among the evaluated modes %s" % (mode, ",".join(modes)))
    size = _ints(args["size"], "size")[0] if args.get("size") else None
    if size is not None and size not in sizes:
        raise UsageError("size %d is not among the evaluated sizes %s" % (size, ",".join(map(str, sizes))))
    pitch = None
    if args.get("pitch"):
        try:
            pitch = float(args["pitch"]) / dbu
        except ValueError:
            raise UsageError("pitch must be a number in micrometres, not %r" % args["pitch"])
        if pitch <= 0:
            raise UsageError("pitch must be positive")
    return sizes, modes, mode, size, pitch, switch(args, "halves")


def max_norm(args):
    """-rd max_norm=X: only gauges at most this critical (normalised score) open windows; 1 all."""
    try:
        return float(args.get("max_norm") or 1)
    except ValueError:
        raise UsageError("max_norm must be a number, not %r" % args["max_norm"])


def number(args, key, default, kind=float):
    try:
        return kind(args.get(key) or default)
    except ValueError:
        raise UsageError("%s must be a number, not %r" % (key, args[key]))


SPLIT_MODES = ("plan", "threshold", "stratified")


def split_mode(args):
    """-rd split=plan (default) | threshold | stratified."""
    mode = (args.get("split") or "plan").lower()
    if mode not in SPLIT_MODES:
        raise UsageError("split must be plan, threshold or stratified, not %r" % args.get("split"))
    return mode


def _count(args, key, default):
    text = args.get(key)
    if text in (None, ""):
        return default
    try:
        return int(text)
    except ValueError:
        raise UsageError("%s must be a whole number of gauges, not %r" % (key, text))


def plan_args(args, dbu):
    """The plan's (budget, verify, context radius in DBU or None for half the window):
    -rd budget=N (1000), -rd verify=M (the budget), -rd context_radius=UM."""
    budget = _count(args, "budget", 1000)
    if budget <= 0:
        raise UsageError("budget must be a positive number of gauges, not %r" % args.get("budget"))
    verify = _count(args, "verify", budget)
    if verify < 0:
        raise UsageError("verify must not be negative: %r" % args.get("verify"))
    radius = None
    if args.get("context_radius") not in (None, ""):
        try:
            radius = float(args["context_radius"])
        except ValueError:
            raise UsageError("context_radius must be a size in micrometres, not %r" % args["context_radius"])
        if not radius > 0:
            raise UsageError("context_radius must be positive, not %r" % args["context_radius"])
        radius /= dbu
        if radius < 1:
            raise UsageError("context_radius must be at least one database unit (%g um)" % dbu)
    return budget, verify, radius


def class_args(args, dbu):
    """The pattern classes' rule, or None: -rd pattern_classes=area (default) | edge | off,
    -rd class_area=0.05 (the XOR's share of the window), -rd class_edge=UM (default 2 DBU)."""
    by = args.get("pattern_classes") or "area"
    if by not in ("area", "edge", "off"):
        raise UsageError("pattern_classes must be area, edge or off, not %r" % by)
    if by == "off":
        return None
    fraction = number(args, "class_area", 0.05)
    if not 0 <= fraction < 1:
        raise UsageError("class_area must be a fraction from 0 to below 1, not %r" % args.get("class_area"))
    edge = 2
    if args.get("class_edge") not in (None, ""):
        um = number(args, "class_edge", 0.0)
        if um < 0:
            raise UsageError("class_edge must not be negative: %r" % args["class_edge"])
        edge = int(round(um / dbu))
    return by, fraction, edge
