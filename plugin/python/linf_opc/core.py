"""Locates the compiled core (linf_opc_core), installed beside this package or on sys.path,
and calls it — in this process (batch, tests), or, in the editor, in a worker process
(worker.py) so that a crash, a hang or runaway memory in the core cannot take KLayout down."""
import contextlib

try:
    from . import linf_opc_core as _core  # installed KLayout package
except ImportError:  # a checkout: the build directory is on sys.path
    import linf_opc_core as _core

DiagramError = _core.DiagramError
MODULE_DIR = __import__("os").path.dirname(_core.__file__)

_runner = None  # while set: a callable (name, args, kwargs) -> result, running the call elsewhere


def _call(name):
    def call(*args, **kwargs):
        if _runner is not None:
            return _runner(name, args, kwargs)
        return getattr(_core, name)(*args, **kwargs)
    call.__name__ = name
    call.__doc__ = getattr(_core, name).__doc__
    return call


voronoi_polygons = _call("voronoi_polygons")
voronoi_sites = _call("voronoi_sites")
gauges_polygons = _call("gauges_polygons")
write_gauges_gds = _call("write_gauges_gds")
oasis_from_drawing = _call("oasis_from_drawing")
write_clip_library = _call("write_clip_library")
picture_coverage = _call("picture_coverage")
select_windows = _call("select_windows")
cover_points = _call("cover_points")
free_windows = _call("free_windows")
estimate_pitch = _call("estimate_pitch")
estimate_pitch_of_gauges = _call("estimate_pitch_of_gauges")
farthest_voronoi = _call("farthest_voronoi")
cgal_construction_seconds = _call("cgal_construction_seconds")


@contextlib.contextmanager
def running_with(runner):
    """Routes every core call through `runner` inside the block (the editor's worker)."""
    global _runner
    previous, _runner = _runner, runner
    try:
        yield
    finally:
        _runner = previous
