"""Runs core calls in a separate process that the editor starts and watches.

The editor's session must survive anything the core does: a crash (signal), a hang, runaway
memory. Each call is pickled to a child `python3` that imports the compiled core; the parent
waits while keeping KLayout's event loop and progress bar alive (its cancel button kills the
child), enforces a time limit and, through RLIMIT_AS, a memory limit. When the child fails,
the call's input is saved under KLayout's home (linf_opc_failures/) for a bug report and a
WorkerError with a clear message is raised; the layout has not been touched.

Limits: LINF_OPC_WORKER_SECONDS (default: none), LINF_OPC_WORKER_MEMORY_MB (default: 3/4 of
the machine's memory). LINF_OPC_WORKER_FAULT=crash|hang makes the child fail on purpose (the
GUI test proves the editor survives it).
"""
import os
import pickle
from array import array
import signal
import subprocess
import sys
import tempfile
import time

from . import core

PACKAGE_PARENT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))  # for linf_opc.cluster
PYTHON = "/usr/bin/python3" if os.path.exists("/usr/bin/python3") else sys.executable

RECORD = 128  # bytes of the progress file's record: "step<TAB>done<TAB>total", padded

CHILD = r"""
import os, pickle, sys
RECORD = RECORD_BYTES
sys.path.insert(0, sys.argv[1])
fault = os.environ.get("LINF_OPC_WORKER_FAULT")
if fault == "crash":
    os.kill(os.getpid(), 11)
if fault == "hang":
    import time
    time.sleep(3600)
import linf_opc_core as core
# Core objects pickled by the editor (a model's LithoKernels) name the module as KLayout's
# package holds it, linf_opc.linf_opc_core: the package importable, that module the one here.
sys.path.append(sys.argv[2])
sys.modules.setdefault("linf_opc.linf_opc_core", core)
name, args, kwargs = pickle.load(sys.stdin.buffer)
scheduler = kwargs.pop("scheduler", None)
told = kwargs.pop("progress_file", None)
if told:  # the core's steps for the parent's bar: one fixed-size record, rewritten in place
    fd = os.open(told, os.O_WRONLY)
    kwargs["progress"] = lambda step, done, total: os.pwrite(
        fd, ("%s\t%d\t%d\n" % (step, done, total)).encode()[:RECORD].ljust(RECORD), 0)
try:
    if scheduler:  # the tiles on a Dask cluster (cluster.py): this process is its client
        from linf_opc import cluster
        from linf_opc.core import CHUNKED
        try:
            tiles = cluster.Tiles(cluster.connect(scheduler))
            if name in CHUNKED:  # its points in chunks on the workers
                result = ("ok", getattr(tiles, CHUNKED[name])(*args, **kwargs))
            else:
                kwargs["tiles"] = tiles
                result = ("ok", getattr(core, name)(*args, **kwargs))
        except cluster.ClusterError as e:
            result = ("ClusterError", str(e))
    else:
        result = ("ok", getattr(core, name)(*args, **kwargs))
except core.DiagramError as e:
    result = ("DiagramError", str(e))
except ValueError as e:
    result = ("ValueError", str(e))
except Exception as e:
    result = ("Error", "%s: %s" % (type(e).__name__, e))
pickle.dump(result, sys.stdout.buffer, protocol=pickle.HIGHEST_PROTOCOL)
""".replace("RECORD_BYTES", str(RECORD))


def _picklable(value):
    """Memoryviews (the gauge table's columns, a spilled layer's arrays) cannot be pickled: the
    same values as an array."""
    if isinstance(value, memoryview):
        out = array(value.format)
        out.frombytes(value.cast("B") if value.contiguous else value.tobytes())
        return out
    if isinstance(value, tuple):
        return tuple(_picklable(v) for v in value)
    return value


def _step(path):
    """The core's last step (step, done, total) from the progress file, or None (not written
    yet, or caught while being rewritten)."""
    try:
        with open(path, "rb") as f:
            fields = f.read(RECORD).decode(errors="replace").split("\n")[0].split("\t")
        return (fields[0], int(fields[1]), int(fields[2])) if len(fields) == 3 else None
    except (OSError, ValueError):
        return None


class WorkerError(RuntimeError):
    pass


class Cancelled(RuntimeError):
    pass


def _memory_limit():
    mb = os.environ.get("LINF_OPC_WORKER_MEMORY_MB")
    if mb:
        return int(mb) * 2 ** 20
    try:
        return int(os.sysconf("SC_PAGE_SIZE") * os.sysconf("SC_PHYS_PAGES") * 3 // 4)
    except (ValueError, OSError):
        return None


def _limits():
    import resource
    limit = _memory_limit()
    if limit:
        resource.setrlimit(resource.RLIMIT_AS, (limit, limit))


class Runner:
    """A core runner for core.running_with(): one child process per call. `wait(elapsed)` is
    called about ten times a second while the child works (keep the UI alive there); it may
    raise to cancel. `failures` is where failed inputs are saved."""

    def __init__(self, wait=None, failures=None, seconds=None):
        self.wait = wait or (lambda elapsed: None)
        self.failures = failures or os.path.join(tempfile.gettempdir(), "linf_opc_failures")
        env = os.environ.get("LINF_OPC_WORKER_SECONDS")
        self.seconds = seconds if seconds is not None else (float(env) if env else None)

    def __call__(self, name, args, kwargs):
        # A progress callable stays here: the child writes the core's steps to a file that the
        # wait loop reads and hands to it.
        kwargs = dict(kwargs)
        watcher = kwargs.pop("progress", None)
        told = None
        if watcher is not None:
            fd, told = tempfile.mkstemp(prefix="linf_opc-progress-")
            os.close(fd)
            kwargs["progress_file"] = told
        try:
            return self._call(name, args, kwargs, watcher, told)
        finally:
            if told:
                os.unlink(told)

    def _call(self, name, args, kwargs, watcher, told):
        payload = pickle.dumps((name, [_picklable(a) for a in args], {k: _picklable(v) for k, v in kwargs.items()}),
                               protocol=pickle.HIGHEST_PROTOCOL)
        # Output and messages go to files, not pipes: a pipe the parent does not drain while it
        # waits would block the child.
        with tempfile.TemporaryFile() as out, tempfile.TemporaryFile() as err:
            with subprocess.Popen([PYTHON, "-c", CHILD, core.MODULE_DIR, PACKAGE_PARENT], stdin=subprocess.PIPE, stdout=out,
                                  stderr=err, preexec_fn=_limits) as child:
                self._watch(child, payload, name, watcher, told)
            err.seek(0)
            message = err.read().decode(errors="replace").strip()
            if child.returncode != 0:
                why = ("crashed (signal %d: %s)" % (-child.returncode, signal.Signals(-child.returncode).name)
                       if child.returncode < 0 else "stopped with exit code %d" % child.returncode)
                if "MemoryError" in message or "bad_alloc" in message:
                    why = "ran out of its memory limit"
                raise WorkerError(self._saved(why + (": " + message.splitlines()[-1] if message else ""),
                                              payload, name))
            out.seek(0)
            status, value = pickle.load(out)
        if status == "ok":
            return value
        if status == "DiagramError":
            raise core.DiagramError(value)
        if status == "ValueError":
            raise ValueError(value)
        if status == "ClusterError":
            from .arguments import UsageError
            raise UsageError(value)
        raise WorkerError(self._saved("failed: " + value, payload, name))

    def _watch(self, child, payload, name, watcher=None, told=None):
        """Feeds the child and waits for it: the time limit, and cancel (any exception from
        the wait callback) kill it. The core's steps in the file `told` go to `watcher`."""
        try:
            child.stdin.write(payload)
            child.stdin.close()
        except BrokenPipeError:
            pass  # the child died at once: its exit code tells
        t0 = time.monotonic()
        last = None
        try:
            while child.poll() is None:
                elapsed = time.monotonic() - t0
                if self.seconds is not None and elapsed > self.seconds:
                    child.kill()
                    child.wait()
                    raise WorkerError(self._saved("did not finish within %g s and was stopped" % self.seconds,
                                                  payload, name))
                last = self._tell(watcher, told, last)
                self.wait(elapsed)
                time.sleep(0.1)
            self._tell(watcher, told, last)  # the last step, also of a call shorter than a poll
        except WorkerError:
            raise
        except BaseException:
            child.kill()
            child.wait()
            raise Cancelled("cancelled")

    @staticmethod
    def _tell(watcher, told, last):
        """The core's step, if it changed since `last`, to the watcher; the step told."""
        if watcher is None:
            return last
        step = _step(told)
        if step is not None and step != last:
            watcher(*step)
            return step
        return last

    def _saved(self, why, payload, name):
        try:
            os.makedirs(self.failures, exist_ok=True)
            path = os.path.join(self.failures, "%s-%s.pickle" % (time.strftime("%Y%m%d-%H%M%S"), name))
            with open(path, "wb") as f:
                f.write(payload)
            where = "; its input is saved in %s for a bug report" % path
        except OSError:
            where = ""
        return "the computation (%s) %s%s. Your layout was not changed." % (name, why, where)
