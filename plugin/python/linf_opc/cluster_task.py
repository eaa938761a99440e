"""What a Dask worker runs: one tile (build_tile: the core's build_tile_job on the job's bytes),
one chunk of the gauges' printability (read_gauges: core.gauge_printability on its part) or of
their contexts (context_ids: core.gauge_contexts on its part).

Sent to the workers by value (cluster.py registers this module with cloudpickle), so a worker
needs only the compiled core (linf_opc_core) on its Python path, not this package; a worker
without it answers with what to install instead of failing to unpickle the task. Plain tuples
come back, never the core's exception objects: the submitting host re-raises them as its own
(the same classes and messages as a local run)."""


# glibc's mmap and trim thresholds as its dynamic rule leaves them at most (64-bit): large
# arrays come from the heap again after they are freed, and up to 64 MB of freed heap is kept.
M_TRIM_THRESHOLD, M_MMAP_THRESHOLD = -1, -3
MMAP_THRESHOLD = 32 << 20
TRIM_THRESHOLD = 2 * MMAP_THRESHOLD


def reuse_freed_memory():
    """Undo the Dask nanny's MALLOC_TRIM_THRESHOLD_=65536 for this worker process. Setting any
    threshold switches glibc's dynamic mmap threshold off, so it stays at 128 KB: every large
    array of every tile is then mapped afresh and its pages faulted in and zeroed, which doubled
    a tile's build (design.md, "Tiles elsewhere"). A tile's memory is bounded, and the next tile
    reuses what this one freed. Elsewhere than glibc, nothing to do."""
    import ctypes
    try:
        libc = ctypes.CDLL(None)  # the process's own symbols: no library search on every task
        libc.mallopt(M_MMAP_THRESHOLD, MMAP_THRESHOLD)
        libc.mallopt(M_TRIM_THRESHOLD, TRIM_THRESHOLD)
    except (OSError, AttributeError):
        pass


def _core():
    """The compiled core, on the worker's path or beside the installed KLayout package (where
    the module sits beside the package's sources); without it, the first ImportError."""
    try:
        import linf_opc_core as core
        return core
    except ImportError as first:
        try:
            from linf_opc import linf_opc_core as core
            return core
        except ImportError:
            raise first from None


def _answered(work):
    """work(core) on this worker, as a task answers: ('ok', its result), ('missing', host, why)
    without the core, or ('error', class name, message)."""
    import socket
    reuse_freed_memory()
    try:
        core = _core()
    except ImportError as e:
        return ("missing", socket.gethostname(), str(e))
    try:
        return ("ok", work(core))
    except Exception as e:  # noqa: BLE001 - handed back whole, re-raised on the submitting host
        return ("error", type(e).__name__, str(e))


def build_tile(job, threads):
    """One tile's result bytes, answered as _answered."""
    return _answered(lambda core: core.build_tile_job(job, threads))


def read_gauges(part, columns, models, threshold, dose, blur, dbu, threads):
    """One chunk of the gauges' printability: core.gauge_printability on the part of the layer
    the chunk's windows see, answered as _answered. columns: (cx, cy, x1, y1, x2, y2, cd)
    arrays('d') and types array('i'); models: [kernels, defocus], LithoKernels states (plain
    tuples, so that a worker needs only the core, whatever module path the host's kernels were
    pickled under; defocus None)."""
    def read(core):
        def made(state):
            if state is None:
                return None
            k = core.LithoKernels.__new__(core.LithoKernels)
            k.__setstate__(state)
            return k
        cx, cy, x1, y1, x2, y2, cd, types = columns
        return core.gauge_printability(part, dbu, cx, cy, x1, y1, x2, y2, types, cd, made(models[0]), threshold,
                                       None, threads, made(models[1]), dose, blur)
    return _answered(read)


def context_ids(part, points, radius, threads):
    """One chunk of the gauges' context ids: core.gauge_contexts on the part of the layer within
    the points' squares, answered as _answered (bytes, one id a point)."""
    return _answered(lambda core: core.gauge_contexts(part, points, radius, threads))
