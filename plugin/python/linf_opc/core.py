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
_tiles = None  # while set: the diagram's tiles are built by it (cluster.Tiles), this process only
_scheduler = None  # while set: the same, for calls run by _runner (the editor's worker process)
_TILED = ("voronoi_polygons", "gauges_polygons")  # the calls that build the diagram
# Read in chunks of nearby points on the cluster: the core's call, and cluster.Tiles' method.
CHUNKED = {"gauge_printability": "printability", "gauge_contexts": "contexts"}


def _call(name):
    def call(*args, **kwargs):
        if _runner is not None:
            if _scheduler is not None and (name in CHUNKED or name in _TILED and not kwargs.get("pieces")):
                kwargs["scheduler"] = _scheduler  # the worker process connects (worker.py)
            return _runner(name, args, kwargs)
        if _tiles is not None and name in CHUNKED:
            return getattr(_tiles, CHUNKED[name])(*args, **kwargs)
        if _tiles is not None and name in _TILED and not kwargs.get("pieces"):
            kwargs["tiles"] = _tiles
        return getattr(_core, name)(*args, **kwargs)
    call.__name__ = name
    call.__doc__ = getattr(_core, name).__doc__
    return call


voronoi_polygons = _call("voronoi_polygons")
voronoi_sites = _call("voronoi_sites")
gauges_polygons = _call("gauges_polygons")
gauge_contexts = _call("gauge_contexts")
neighbour_spaces = _call("neighbour_spaces")
write_gauges_gds = _call("write_gauges_gds")
write_gauges_csv_rows = _call("write_gauges_csv_rows")
oasis_from_drawing = _call("oasis_from_drawing")
write_clip_library = _call("write_clip_library")
picture_coverage = _call("picture_coverage")
select_windows = _call("select_windows")
cover_points = _call("cover_points")
classify_patterns = _call("classify_patterns")
free_windows = _call("free_windows")
estimate_pitch = _call("estimate_pitch")
estimate_pitch_of_gauges = _call("estimate_pitch_of_gauges")
farthest_voronoi = _call("farthest_voronoi")
gauge_printability = _call("gauge_printability")
opc_correct = _call("opc_correct")
# The model's kernels are a core object held in the process that made them (the batch's).
litho_kernels = _core.litho_kernels
calibrate_threshold = _core.calibrate_threshold
litho_window_images = _core.litho_window_images
litho_layer_parts = _core.litho_layer_parts
litho_chunks = _core.litho_chunks
litho_rank = _core.litho_rank
litho_contours = _core.litho_contours
# Arithmetic on one segment, called once a drawn edge: always in this process.
cut_to_drawable = _core.cut_to_drawable
# Copies of the gauge table's records or columns in another order: always in this process.
permute_records = _core.permute_records
take_records = _core.take_records


@contextlib.contextmanager
def running_with(runner):
    """Routes every core call through `runner` inside the block (the editor's worker)."""
    global _runner
    previous, _runner = _runner, runner
    try:
        yield
    finally:
        _runner = previous


@contextlib.contextmanager
def tiles_with(tiles):
    """Inside the block, the calls that build the diagram have its tiles built by `tiles`
    (cluster.Tiles: on a Dask cluster); the same results."""
    global _tiles
    previous, _tiles = _tiles, tiles
    try:
        yield
    finally:
        _tiles = previous


@contextlib.contextmanager
def tiles_at(address):
    """Inside the block, calls run by a runner (the editor's worker process) have the diagram's
    tiles built on the Dask cluster at `address`; the worker process connects to it."""
    global _scheduler
    previous, _scheduler = _scheduler, address
    try:
        yield
    finally:
        _scheduler = previous
