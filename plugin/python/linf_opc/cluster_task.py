"""What a Dask worker runs for one tile: the core's build_tile_job on the job's bytes.

Sent to the workers by value (cluster.py registers this module with cloudpickle), so a worker
needs only the compiled core (linf_opc_core) on its Python path, not this package; a worker
without it answers with what to install instead of failing to unpickle the task. Plain tuples
come back, never the core's exception objects: the submitting host re-raises them as its own
(the same classes and messages as a local run)."""


def build_tile(job, threads):
    """('ok', result bytes), ('missing', host, why) or ('error', class name, message)."""
    import socket
    try:
        import linf_opc_core as core
    except ImportError as first:
        try:  # the installed KLayout package: the module sits beside the package's sources
            from linf_opc import linf_opc_core as core
        except ImportError:
            return ("missing", socket.gethostname(), str(first))
    try:
        return ("ok", core.build_tile_job(job, threads))
    except Exception as e:  # noqa: BLE001 - handed back whole, re-raised on the submitting host
        return ("error", type(e).__name__, str(e))
