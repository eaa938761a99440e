"""The diagram's tiles, the gauges' contexts and their printability on a Dask cluster
(-rd scheduler=tcp://HOST:PORT).

in:  the scheduler's address; the core's tile jobs (bytes: one tile's sites and halo, never the
     layer's), taken one at a time while the core plans the tiles; core.gauge_contexts'
     arguments; with -rd litho, the gauges' printability columns (core.gauge_printability's)
out: each job's result bytes (the tile's pieces, classified and read for the gauges' stretches
     on the worker when the gauge stage asks), handed back to the core in the order the jobs
     were taken; the core then merges, checks and writes exactly as in a local run (same files).
     The contexts' bytes and the printability's dict, as the core gives them (same bytes).

Tiles.contexts and Tiles.printability send their points in chunks of nearby ones, each with the
part of the layer its squares or windows see (core.litho_layer_parts): an id and a window's
reading depend on those shapes alone. Everything else (the far field, the merge, the check, the
gauges, the writers, every later stage) runs here. A lost worker's tasks are rerun by Dask on
the others. Errors a user can meet are ClusterError (one line, exit code 2, as a UsageError),
raised before anything is written when the scheduler cannot be reached."""
import collections
from array import array
import contextlib
import logging
import math
import re
import socket
import uuid
import warnings

from . import cluster_task, core

CONNECT_SECONDS = 5  # the scheduler's answer; with KLayout's start, one line within 10 s
WORKERS_SECONDS = 60  # for the first worker to join a scheduler that has none yet

MIN_SIDE = 512  # DBU: the contexts' chunks' windows, at least (Tiles.contexts)

_ADDRESS = re.compile(r"^(tcp|tls)://[^\s:/]+:\d+$")


class ClusterError(Exception):
    """A cluster the run cannot use: one line, exit code 2 (commands.main), as a UsageError.
    Not a UsageError itself: this module is also imported where KLayout is not (the editor's
    worker process), and arguments.py needs it."""


def parse_address(text):
    """-rd scheduler=tcp://HOST:PORT (or tls://); None if not given."""
    if text in (None, ""):
        return None
    if not _ADDRESS.match(text):
        raise ClusterError("scheduler must be a Dask scheduler's address tcp://HOST:PORT, not %r" % text)
    return text


def _quiet():
    # Dask's own log lines (reconnects, a worker lost and its tasks rerun) are not the tool's
    # output: only errors that end the run are said, in one line.
    # Dask's logging configuration gives some children a level of their own (distributed.client:
    # warning, which said "Couldn't gather 1 keys, rescheduling" when a worker was lost), so
    # every logger of theirs is set, not only the roots.
    roots = ("distributed", "tornado", "asyncio")
    for name in list(roots) + list(logging.root.manager.loggerDict):
        if name.split(".")[0] in roots:
            logging.getLogger(name).setLevel(logging.CRITICAL)


def _reachable(address):
    """A plain TCP connection first: a refused or unrouted address is said at once, before
    Dask (slow to import) is even loaded."""
    host, port = address.split("://", 1)[1].rsplit(":", 1)
    try:
        socket.create_connection((host, int(port)), timeout=CONNECT_SECONDS).close()
    except OSError as e:
        raise ClusterError("cannot reach the Dask scheduler at %s (%s); nothing written"
                           % (address, e.strerror or str(e) or type(e).__name__))


def connect(address):
    """A distributed.Client on the scheduler, with at least one worker; ClusterError if not."""
    _reachable(address)
    try:
        import distributed
    except ImportError:
        raise ClusterError("-rd scheduler needs Dask on this host: install python3-distributed "
                           "(apt-get install python3-distributed)")
    _quiet()
    try:
        client = distributed.Client(address, timeout=CONNECT_SECONDS, set_as_default=False)
    except Exception as e:  # noqa: BLE001 - OSError, TimeoutError, or Dask's own on a bad address
        reason = str(e).splitlines()[0] if str(e) else type(e).__name__
        raise ClusterError("cannot reach the Dask scheduler at %s within %d s (%s); nothing written"
                           % (address, CONNECT_SECONDS, reason))
    try:
        client.wait_for_workers(1, timeout=WORKERS_SECONDS)
    except Exception:  # noqa: BLE001
        client.close()
        raise ClusterError("no Dask worker joined the scheduler at %s within %d s: start workers with "
                           "dask-worker %s (see the README); nothing written" % (address, WORKERS_SECONDS, address))
    return client


class Tiles:
    """The core's TileRunner (convert.hpp, runner_of): callable(next, done); and printability(),
    core.gauge_printability on the workers (core.py routes it here while the cluster is on)."""

    def __init__(self, client, threads=1):
        self.client = client
        self.threads = threads  # the builder's threads in a task; Dask runs --nthreads tasks a worker
        self.address = client.scheduler.address
        import cloudpickle
        import dask
        cloudpickle.register_pickle_by_value(cluster_task)  # the workers need the core only
        # Dask reads the source of the code that submits each task, for its dashboard's list of
        # computations: 10 ms of this host's time a task in a profile. No frame of ours is worth
        # it: every module is passed over.
        dask.config.set({"distributed.diagnostics.computations.ignore-modules": [".*"]})

    def _slots(self):
        workers = self.client.scheduler_info().get("workers", {})
        return max(1, sum(w.get("nthreads", 1) for w in workers.values()))

    def _gathered(self, future, what):
        try:
            # Straight from the worker that holds it: through the scheduler (Dask's default for
            # a client outside the cluster), every tile's pieces were copied by its one process.
            return self.client.gather(future, direct=True)
        except Exception as e:  # noqa: BLE001 - KilledWorker (lost too often), a task that cannot run
            raise ClusterError("%s failed on the Dask cluster at %s: %s: %s"
                               % (what, self.address, type(e).__name__, str(e).splitlines()[0] if str(e) else ""))

    def _answer(self, answer, rows=None):
        """A task's answer (cluster_task): its result, or its error raised here. rows: the
        chunk's gauge numbers, so that a gauge the core names is named as locally."""
        if answer[0] == "ok":
            return answer[1]
        if answer[0] == "missing":
            raise ClusterError("the Dask worker on %s cannot import the core module linf_opc_core (%s): put the "
                               "build's linf_opc_core*.so (the build/ folder, or the installed package's linf_opc "
                               "folder) on the workers' PYTHONPATH and restart them" % (answer[1], answer[2]))
        name, message = answer[1], answer[2]
        if rows is not None:
            message = re.sub(r"\bgauge (\d+) ", lambda m: "gauge %d " % rows[int(m.group(1))], message, count=1)
        if name == "DiagramError":
            raise core.DiagramError(message)
        if name == "ValueError":
            raise ValueError(message)
        raise RuntimeError(message)

    def __call__(self, next_job, done):
        with warnings.catch_warnings():
            # A job is a tile's sites, a few MB: Dask's warning about large task arguments is
            # meant for data better scattered, which a lost worker would take with it.
            warnings.simplefilter("ignore", UserWarning)
            self._run(next_job, done)

    def _run(self, next_job, done):
        run = uuid.uuid4().hex[:12]
        ahead = 2 * self._slots() + 2  # queued beyond the running ones: workers never wait on this host
        pending = collections.deque()  # (tile number, future), in the order the jobs were taken
        taken, exhausted = 0, False
        try:
            while True:
                while not exhausted and len(pending) < ahead:
                    job = next_job()
                    if job is None:
                        exhausted = True
                        break
                    pending.append((taken, self.client.submit(cluster_task.build_tile, job, self.threads,
                                                              key="linf-tile-%s-%d" % (run, taken), pure=False)))
                    taken += 1
                if not pending:
                    return
                k, future = pending.popleft()
                result = self._answer(self._gathered(future, "tile %d" % k))
                future.release()
                done(result)
        finally:
            for _, future in pending:
                future.cancel()

    def _parts(self, polygons, dbu, period, cx, cy, starts):
        """Each chunk's part of the layer (core.litho_layer_parts; cx, cy the chunks' points one
        chunk after the other): the first few chunks' in a call of their own, so that the workers
        start while the others' are found (a call indexes the whole layer first: 0.9 s at 10^6
        wires, the parts of 708 chunks 5 s)."""
        first = min(len(starts) - 1, 2 * self._slots())
        for at in (starts[:first + 1], starts[first:]):
            if len(at) > 1:
                a, b = at[0], at[-1]
                yield from core.litho_layer_parts(polygons, dbu, period, cx[a:b], cy[a:b],
                                                  array("q", (s - a for s in at)))

    def _read(self, futures, what, rows=None):
        """The chunks' answers in order, each released once read; those not read yet are
        cancelled if one fails. rows: (gauges, starts), to name a gauge as locally."""
        pending = collections.deque(enumerate(futures))
        try:
            while pending:
                k, future = pending[0]
                yield self._answer(self._gathered(future, "%s of chunk %d" % (what, k)),
                                   rows and rows[0][rows[1][k]:rows[1][k + 1]])
                pending.popleft()
                future.release()
        finally:
            for _, future in pending:
                future.cancel()

    def contexts(self, polygons, points, radius, threads=0):
        """core.gauge_contexts with its points read on the workers: the same bytes. The points
        go out in chunks of nearby ones (litho_chunks' rule, every point its own source), each
        with the part of the layer within its points' squares: an id depends on that alone."""
        n = len(points) // 2
        if n == 0:
            return core.gauge_contexts(polygons, points, radius, threads)
        xy = memoryview(points).cast("B").cast("d")
        # The windows one DBU wider than the squares (the core rounds the radius), so that a
        # polygon that only touches a square is in the part too, and at least MIN_SIDE: the
        # parts' index has cells of half a window, and a polygon crossing thousands of them made
        # a radius of 1 DBU take seconds. More of the layer than a square sees changes no id.
        side = max(2 * (math.ceil(radius) + 1), MIN_SIDE)
        zeros = array("i", bytes(4 * n))
        flat, starts, at = (array("q", b) for b in core.litho_chunks(xy[0::2], xy[1::2], zeros, None, 64 * side,
                                                                     4 * self._slots()))
        mine = array("d", core.take_records(xy, 16, flat))  # the points, chunk after chunk
        cx, cy = memoryview(mine)[0::2], memoryview(mine)[1::2]
        run = uuid.uuid4().hex[:12]
        futures = []
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", UserWarning)  # a chunk's part of the layer, as a tile's job
            for k, (a, b, (shapes, rings)) in enumerate(zip(starts[:-1], starts[1:],
                                                           self._parts(polygons, 1.0, side, cx, cy, starts))):
                futures.append(self.client.submit(cluster_task.context_ids, (array("q", shapes), array("q", rings)),
                                                  mine[2 * a:2 * b], radius, self.threads,
                                                  key="linf-context-%s-%d" % (run, k), pure=False))
        ids = b"".join(self._read(futures, "the contexts"))
        return core.take_records(ids, 8, at)

    def printability(self, polygons, dbu, cx, cy, x1, y1, x2, y2, types, cd, kernels, threshold, contexts=None,
                     threads=0, defocus=None, dose=0.0, blur=0.0):
        """core.gauge_printability with its windows read on the workers: the same dict, the same
        bytes. The gauges that simulate (the first of each type and context, as the core picks
        them) go out in chunks, each with the part of the layer its windows see
        (core.litho_layer_parts); the others take their source's reading here."""
        import time
        t0 = time.perf_counter()
        n = len(cx)
        # Who simulates and the chunks (the core's rule, litho_chunks): nearby points together,
        # so that a chunk's part of the layer is small, about four chunks a worker thread.
        band = 64 * max(1.0, kernels.period / dbu)
        flat, starts, at = (array("q", b) for b in core.litho_chunks(cx, cy, types, contexts, band, 4 * self._slots()))
        # The chunks' columns gathered once in chunk order (loops of C: a layer has millions of
        # gauges), then cut.
        cols = [array("d", core.take_records(c, 8, flat)) for c in (cx, cy, x1, y1, x2, y2, cd)]
        cols.append(array("i", core.take_records(types, 4, flat)))
        bounds = list(zip(starts[:-1], starts[1:]))
        run = uuid.uuid4().hex[:12]
        futures = []
        # The kernels (1.7 MB for euv's two sets) once to every worker, not in every chunk's task:
        # each worker keeps a copy, so a lost one takes nothing the others need.
        states = [kernels.__getstate__(), None if defocus is None else defocus.__getstate__()]
        models = self.client.scatter([states], broadcast=True, hash=False)[0] if bounds else None
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", UserWarning)  # a chunk's part of the layer, as a tile's job
            for k, ((a, b), (points, rings)) in enumerate(zip(bounds, self._parts(polygons, dbu, kernels.period,
                                                                                 cols[0], cols[1], starts))):
                part = (array("q", points), array("q", rings))
                columns = tuple(col[a:b] for col in cols)
                futures.append(self.client.submit(cluster_task.read_gauges, part, columns, models, threshold, dose,
                                                  blur, dbu, self.threads, key="linf-litho-%s-%d" % (run, k),
                                                  pure=False))
        # The chunks' readings, one after the other in `flat` order.
        got = {name: array("d") for name in ("printed_cd", "pv_band", "score")}
        got.update(fails=array("B"), fails_nominal=array("B"))
        images = 0
        try:
            for r in self._read(futures, "the printability", (flat, starts)):
                images += r["images"]
                for name, column in got.items():
                    column.frombytes(r[name])
        finally:
            if models is not None:
                models.release()
        # Each gauge takes its source's reading, where the chunks' order put it.
        out = {name: core.take_records(column, column.itemsize, at) for name, column in got.items()}
        out.update(simulations=len(flat), shared=n - len(flat), images=images, seconds=time.perf_counter() - t0)
        return out


_client = None


@contextlib.contextmanager
def tiles_on(address):
    """Inside the block, the core calls that build the diagram send its tiles to the cluster."""
    global _client
    client = connect(address)
    _client = client
    try:
        with core.tiles_with(Tiles(client)):
            yield
    finally:
        _client = None
        try:
            client.close(timeout=5)
        except Exception:  # noqa: BLE001 - a scheduler gone by now: nothing to release
            pass
