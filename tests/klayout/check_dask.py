# The diagram's tiles on a Dask cluster (-rd scheduler=...) give the local run's files.
#   klayout -b -r tests/klayout/check_dask.py -rd input=FILE -rd layer=L/D -rd markers=SPEC [-rd cell=NAME]
#           -rd work=DIR [-rd parts=4] [-rd kill=1] [-rd kill_parts=32] [-rd faults=1] [-rd editor=1] [-rd plain=1]
# Starts a dask-scheduler on 127.0.0.1 (a free port) and two dask-workers (--nthreads 1, only the
# build's core module on their PYTHONPATH), runs cmd=gauges and cmd=flow locally and on the
# cluster with tiles of the layer's extent / parts, and compares every output file byte for byte
# (JSON files with their timings left out; summary.json's builder, tiles and check included:
# the cluster's tiles are built by the local run's builder).
# kill=1: one worker is SIGKILLed while it builds a tile, at least two seconds into the run; the
# flow's files must still be the same. The run has tiles of the extent / kill_parts: smaller
# ones, so that the tiles last past two seconds (the sweep builds them fast); the files do not
# depend on the tile size, but summary.json's tile counts and the check's worst rounding and
# pairs (drawn from a sample of each tile's clearances).
# faults=1: an unreachable scheduler gives one error line, exit 2, within 10 s and nothing
# written; a worker without the core module gives an error naming it.
# plain=1: gauges and flow also from plain Python (python3 macros/linf_opc.py), the same files.
# litho=NAME [opc=1]: gauges and flow with -rd litho=NAME (and the OPC) give the local run's files,
# the printability read on the workers.
# editor=1: the editor's path (the core in its worker process, which connects to the cluster)
# writes the same voronoi.csv; an unreachable scheduler is a UsageError there.
# Every process started here is stopped (finally).
import json
import os
import shutil
import signal
import socket
import subprocess
import sys
import tempfile
import time

import pya

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from harness import BATCH, arg, expect, finish, ok, repo, same_files  # noqa: E402

work = arg("work", "/tmp/linf_dask_check")
MACRO = os.path.join(repo, "macros", "linf_opc.py")
BUILD = os.path.join(repo, "build")


def free_port():
    s = socket.socket()
    s.bind(("127.0.0.1", 0))
    port = s.getsockname()[1]
    s.close()
    return port


started = []  # every process started here, stopped in the end


def start(cmd, log, env=None):
    p = subprocess.Popen(cmd, stdout=open(log, "w"), stderr=subprocess.STDOUT, env=env, start_new_session=True)
    started.append(p)
    return p


def signal_group(p, sig):
    """The process and its children (a dask-worker's nanny runs the worker as a child): each
    cluster process was started in a session of its own."""
    try:
        os.killpg(p.pid, sig)
    except ProcessLookupError:
        pass


def stop_all():
    for p in started:
        signal_group(p, signal.SIGTERM)
    deadline = time.time() + 10
    for p in started:
        try:
            p.wait(max(0.1, deadline - time.time()))
        except subprocess.TimeoutExpired:
            pass
        signal_group(p, signal.SIGKILL)  # whatever is left of its group
        if p.poll() is None:
            p.wait()


def cluster(name, workers, pythonpath):
    """A scheduler and `workers` workers; their address."""
    port = free_port()
    address = "tcp://127.0.0.1:%d" % port
    logs = os.path.join(work, "logs")
    os.makedirs(logs, exist_ok=True)
    start(["dask-scheduler", "--host", "127.0.0.1", "--port", str(port), "--no-dashboard"],
          os.path.join(logs, name + "_scheduler.log"))
    env = dict(os.environ, PYTHONPATH=pythonpath, PYTHONDONTWRITEBYTECODE="1")
    procs = []
    for k in range(workers):
        procs.append(start(["dask-worker", address, "--nthreads", "1", "--nworkers", "1", "--no-dashboard",
                            "--memory-limit", "0", "--local-directory", os.path.join(work, "dask-%s-%d" % (name, k)),
                            "--name", "%s-%d" % (name, k)],
                           os.path.join(logs, "%s_worker%d.log" % (name, k)), env))
    import distributed
    with distributed.Client(address, timeout=30, set_as_default=False) as c:
        c.wait_for_workers(workers, timeout=60)
    return address, procs


def run(cmd, out, extra=(), background=False, launcher="klayout"):
    """launcher: "klayout" (klayout -b -r) or "python3" (BATCH: the README's command, which runs the
    macro again under KLayout's own Python, the one with Dask)."""
    start = ["klayout", "-b", "-r", MACRO] if launcher == "klayout" else BATCH
    args = start + ["-rd", "cmd=" + cmd, "-rd", "input=" + arg("input"), "-rd",
            "layer=" + arg("layer"), "-rd", "out=" + out, "-rd", "quiet=1"] + list(extra)
    if cmd == "flow":
        args += ["-rd", "markers=" + arg("markers"), "-rd", "all_gauges=1", "-rd", "diagram=1"]
    if arg("cell", None):
        args += ["-rd", "cell=" + arg("cell")]
    env = dict(os.environ, KLAYOUT_HOME=home, PYTHONDONTWRITEBYTECODE="1")
    if background:
        p = subprocess.Popen(args, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, env=env,
                             start_new_session=True)
        started.append(p)
        return p
    return subprocess.run(args, capture_output=True, text=True, env=env, timeout=1200)


def wire_rows(rows, columns):
    """Staggered rows of wires 450 x 50 DBU on a 100 DBU pitch as the core takes a layer, and a
    space gauge in the gap above each wire (its point, its line across the gap, type external,
    cd 50) as gauge_printability's columns."""
    import array
    pts, rings = array.array("q"), array.array("q")
    for k in range(rows):
        for i in range(columns):
            x, y = 700 * i + 37 * (k % 5), 100 * k
            pts.extend((x, y, x + 450, y, x + 450, y + 50, x, y + 50))
            rings.append(4)
    px = array.array("d", (700.0 * i + 225 + k % 7 for i in range(columns) for k in range(rows)))
    py = array.array("d", (100.0 * k + 75 for i in range(columns) for k in range(rows)))
    line = [array.array("d", (v + d for v in c)) for c, d in ((px, 0), (py, -25), (px, 0), (py, 25))]
    return (pts, rings), (px, py, *line, array.array("i", [1]) * len(px), array.array("d", [50.0]) * len(px))


ly = pya.Layout()
ly.read(arg("input"))
top = ly.cell(arg("cell")) if arg("cell", None) else ly.top_cells()[0]
L, D = (int(v) for v in arg("layer").split("/"))
box = top.dbbox_per_layer(ly.find_layer(L, D))
tile = "%.4f" % (max(box.width(), box.height()) / float(arg("parts", "4")))

shutil.rmtree(work, ignore_errors=True)
os.makedirs(work)
home = tempfile.mkdtemp(prefix="klayout_home_", dir=work)
try:
    address, workers = cluster("main", 2, BUILD)
    for cmd in ("gauges", "flow"):
        ref, got = os.path.join(work, cmd + "_local"), os.path.join(work, cmd + "_dask")
        ok(run(cmd, ref, ["-rd", "tile=" + tile]), cmd + " locally")
        t0 = time.time()
        r = run(cmd, got, ["-rd", "tile=" + tile, "-rd", "scheduler=" + address])
        ok(r, cmd + " on the cluster")
        warnings = [l for l in r.stderr.splitlines() if not l.startswith("linf_opc: warning: the marker layer")]
        expect(not warnings, "%s on the cluster with quiet=1: nothing on stderr (Dask's log lines, warnings), "
               "not %r" % (cmd, warnings[:3]))
        print("%s on the cluster: %.1f s; %s" % (cmd, time.time() - t0, r.stdout.strip()[:200]))
        with open(os.path.join(got, "summary.json")) as f:
            summary = json.load(f)
        tiles = (summary["voronoi"] if cmd == "flow" else summary["diagram"])["tiles"]
        expect(tiles["tiles"] > 1, "%s: tile=%s um cuts the layer into %d tiles" % (cmd, tile, tiles["tiles"]))
        same_files(ref, got, cmd + " on the cluster")
        if arg("plain", "0") == "1":  # the batch in plain Python sends its tiles as well
            plain = got + "_python3"
            r = run(cmd, plain, ["-rd", "tile=" + tile, "-rd", "scheduler=" + address], launcher="python3")
            ok(r, cmd + " on the cluster from plain Python")
            same_files(ref, plain, cmd + " on the cluster from plain Python")

    # The gauges' contexts read on the workers in chunks of nearby points, each with the part of
    # the layer within its points' squares (cluster.Tiles.contexts): the flow's plan sent them
    # as tasks, and here the same ids as in this process at radii from 1 DBU to past the rows'
    # pitch, on points at whole and half DBU; a radius the core refuses gives its error.
    import array
    import random
    import distributed
    from linf_opc import cluster as dask_runner, core
    with distributed.Client(address, timeout=30, set_as_default=False) as client:
        prefixes = client.run_on_scheduler(lambda dask_scheduler: sorted(dask_scheduler.task_prefixes))
        expect("linf-context" in prefixes, "the flow's contexts ran as tasks (the scheduler saw %s)" % prefixes)
        polys, _ = wire_rows(60, 40)
        rng = random.Random(7)
        points = array.array("d")
        for _ in range(20000):
            points.extend((rng.randrange(-200, 28400) + 0.5 * rng.randrange(2),
                           rng.randrange(-200, 6200) + 0.5 * rng.randrange(2)))
        tiles = dask_runner.Tiles(client)
        for radius in (1, 40.5, 300, 2000):
            here = core.gauge_contexts(polys, points, radius, 1)
            there = tiles.contexts(polys, points, radius)
            distinct = len(set(array.array("Q", here)))
            expect(distinct > 1 and here == there, "contexts of radius %s on the cluster: the same ids as here "
                   "(%d distinct)" % (radius, distinct))
        refused = []
        for contexts in (lambda: core.gauge_contexts(polys, points, 0, 1), lambda: tiles.contexts(polys, points, 0)):
            try:
                contexts()
            except ValueError as e:
                refused.append(str(e))
        expect(len(refused) == 2 and refused[0] == refused[1],
               "a radius of 0 is refused on the cluster as here: %s" % refused)

    if arg("litho", "") != "":
        # The gauges' printability read on the workers in chunks, each with the part of the
        # layer its windows see (cluster.Tiles.printability): the same files. One tile, so
        # that only the chunks are on the cluster.
        for cmd in ("gauges", "flow"):
            ref, got = os.path.join(work, cmd + "_litho_local"), os.path.join(work, cmd + "_litho_dask")
            extra = ["-rd", "litho=" + arg("litho")] + (["-rd", "opc=1"] if arg("opc", "0") == "1" else [])
            ok(run(cmd, ref, extra), cmd + " with litho locally")
            t0 = time.time()
            ok(run(cmd, got, extra + ["-rd", "scheduler=" + address]), cmd + " with litho on the cluster")
            print("%s with litho=%s on the cluster: %.1f s" % (cmd, arg("litho"), time.time() - t0))
            with open(os.path.join(got, "summary.json")) as f:
                summary = json.load(f)
            lit = summary["litho"] if cmd == "gauges" else summary["gauges"]["litho"]
            expect(lit["simulated"] > 0, "%s: gauges were simulated (%s)" % (cmd, lit))
            same_files(ref, got, cmd + " with litho on the cluster")
        import distributed
        with distributed.Client(address, timeout=30, set_as_default=False) as c:
            prefixes = c.run_on_scheduler(lambda dask_scheduler: sorted(dask_scheduler.task_prefixes))
        expect("linf-litho" in prefixes, "the printability's chunks ran as tasks (the scheduler saw %s)" % prefixes)
        # A worker SIGKILLed (with its nanny) while the chunks are read: Dask reruns its chunks on
        # the other, which holds the kernels too; the same columns. 100,000 points on rows of
        # wires, about 7 s on one thread.
        import threading
        from linf_opc import cluster as dask_runner, core
        kaddress, kworkers = cluster("litho_kill", 2, BUILD)
        # (Not named `layer`: the -rd values are this script's globals.)
        wires, gauges = wire_rows(1000, 100)
        kernels, defocus = core.litho_kernels("euv"), core.litho_kernels("euv", defocus=30.0)
        args = (wires, 1.0, *gauges, kernels, core.calibrate_threshold(kernels, 50, 100, 5.0)["threshold"])
        how = dict(threads=1, dose=0.02, blur=5.0, defocus=defocus)
        here = core.gauge_printability(*args, **how)
        import distributed
        client = distributed.Client(kaddress, timeout=30, set_as_default=False)
        done = []

        def kill():
            time.sleep(1.0)
            if not done:
                signal_group(kworkers[0], signal.SIGKILL)
                done.append("killed")
        threading.Thread(target=kill, daemon=True).start()
        there = dask_runner.Tiles(client).printability(*args, **how)
        done.append("read")
        client.close()
        expect(done[0] == "killed", "a worker was killed while the chunks were read (%s)" % done)
        expect(all(here[k] == there[k] for k in ("printed_cd", "fails", "fails_nominal", "pv_band", "score", "images")),
               "the printability with a worker killed 1 s in: the same columns as in this process")

    if arg("editor", "0") == "1":
        # The editor's path: the core call in its watched worker process (worker.py), which
        # connects to the cluster itself (core.tiles_at); the same voronoi.csv as in this process.
        import array
        from linf_opc import core, worker
        polys, gauges = wire_rows(40, 12)
        local_csv, editor_csv = os.path.join(work, "editor_local.csv"), os.path.join(work, "editor_dask.csv")
        core.voronoi_polygons(polys, threads=1, tile=1000, csv=local_csv, pieces=False)
        with core.running_with(worker.Runner()), core.tiles_at(address):
            r = core.voronoi_polygons(polys, threads=1, tile=1000, csv=editor_csv, pieces=False)
        with open(local_csv, "rb") as f, open(editor_csv, "rb") as g:
            expect(f.read() == g.read(), "the editor's worker process on the cluster writes the same voronoi.csv")
        expect(r["tiles"]["tiles"] > 1, "the editor's run has several tiles (%s)" % r["tiles"])
        # The printability from the editor's worker process: read in chunks on the cluster, the
        # same columns as in this process: the spaces between the rows of wires.
        kernels = core.litho_kernels("euv")
        how = dict(threads=1, dose=0.02, blur=5.0)
        t = core.calibrate_threshold(kernels, 50, 100, 5.0)["threshold"]
        here = core.gauge_printability(polys, 1.0, *gauges, kernels, t, **how)
        with core.running_with(worker.Runner()), core.tiles_at(address):
            there = core.gauge_printability(polys, 1.0, *gauges, kernels, t, **how)
        measured = sum(v == v for v in array.array("d", here["printed_cd"]))
        expect(measured > 0, "the editor's printability points measure something (%d of %d)" % (measured, len(gauges[0])))
        expect(all(here[k] == there[k] for k in ("printed_cd", "fails", "fails_nominal", "pv_band", "score", "images")),
               "the editor's worker process reads the printability on the cluster as this process does")
        points = array.array("d", (v for xy in zip(gauges[0], gauges[1]) for v in xy))
        here = core.gauge_contexts(polys, points, 120, 1)
        with core.running_with(worker.Runner()), core.tiles_at(address):
            there = core.gauge_contexts(polys, points, 120)
        expect(len(set(array.array("Q", here))) > 1 and here == there,
               "the editor's worker process reads the contexts on the cluster as this process does")
        try:
            with core.running_with(worker.Runner()), core.tiles_at("tcp://127.0.0.1:%d" % free_port()):
                core.voronoi_polygons(polys, threads=1, tile=1000, pieces=False)
            expect(False, "the editor's worker process reports an unreachable scheduler")
        except Exception as e:  # noqa: BLE001
            expect(type(e).__name__ == "UsageError" and "cannot reach the Dask scheduler" in str(e),
                   "the editor gets a UsageError for an unreachable scheduler: %s: %s" % (type(e).__name__, e))

    if arg("kill", "0") == "1":
        # SIGKILL to worker main-0 while it builds a tile, at least two seconds into the run
        # (KLayout's start and the reading come first).
        import distributed
        got = os.path.join(work, "flow_killed")
        small = "%.4f" % (max(box.width(), box.height()) / float(arg("kill_parts", "32")))
        watch = distributed.Client(address, timeout=30, set_as_default=False)
        victim = [a for a, w in watch.scheduler_info()["workers"].items() if w.get("name") == "main-0"][0]
        started_at = time.time()
        p = run("flow", got, ["-rd", "tile=" + small, "-rd", "scheduler=" + address], background=True)
        first, killed = None, False
        while p.poll() is None and not killed:
            busy = watch.processing()
            tiles = {w: [k for k in keys if str(k).startswith("linf-tile")] for w, keys in busy.items()}
            if first is None and any(tiles.values()):
                first = time.time()
            if first is not None and time.time() - started_at >= 2 and tiles.get(victim):
                signal_group(workers[0], signal.SIGKILL)  # the worker and its nanny: no restart
                workers[0].wait()
                killed = True
                print("killed worker main-0 %.1f s into the run, %.1f s after the first tile, while it built %s"
                      % (time.time() - started_at, time.time() - first, tiles[victim][0]))
            time.sleep(0.02)
        watch.close()
        out, err = p.communicate(timeout=1200)
        print("flow with a worker killed: exit %d %s" % (p.returncode, (err or out).strip()[-300:]))
        expect(killed, "a worker was killed while it built a tile (the run ended first: make its tiles smaller)")
        expect(p.returncode == 0, "the flow survives a killed worker (exit %d)" % p.returncode)
        noise = [l for l in err.splitlines() if not l.startswith("linf_opc: warning: the marker layer")]
        expect(not noise, "a lost worker says nothing on stderr (Dask reran its tiles): %r" % noise[:3])
        if p.returncode == 0:
            same_files(os.path.join(work, "flow_local"), got, "flow with a worker killed",
                       ("tiles", "worst_error", "pairs_separated"))

    if arg("faults", "0") == "1":
        # KLayout's own start, for scale: a run that stops at its first argument (on a busy
        # machine it alone can take seconds).
        t0 = time.time()
        r = run("gauges", os.path.join(work, "bad_tile"), ["-rd", "tile=-5"])
        start_s = time.time() - t0
        expect(r.returncode == 2, "a negative tile exits 2 (the start's baseline)")
        # Nobody listens on a fresh free port.
        got = os.path.join(work, "unreachable")
        t0 = time.time()
        r = run("gauges", got, ["-rd", "scheduler=tcp://127.0.0.1:%d" % free_port()])
        took = time.time() - t0
        lines = r.stderr.strip().splitlines()
        print("unreachable: exit %d in %.1f s (KLayout's start and a bad argument: %.1f s): %s"
              % (r.returncode, took, start_s, r.stderr.strip()))
        expect(r.returncode == 2, "an unreachable scheduler exits 2, not %d" % r.returncode)
        expect(took < 10 or took - start_s < 10, "an unreachable scheduler is said within 10 s, not %.1f (%.1f after "
               "KLayout's start)" % (took, took - start_s))
        expect(len(lines) == 1 and lines[0].startswith("linf_opc: error: cannot reach the Dask scheduler"),
               "one clear line for an unreachable scheduler: %r" % lines)
        expect(not os.path.exists(got) or not os.listdir(got), "nothing written for an unreachable scheduler")
        r = run("gauges", os.path.join(work, "bad_address"), ["-rd", "scheduler=127.0.0.1"])
        expect(r.returncode == 2 and "tcp://HOST:PORT" in r.stderr, "a malformed address: %s" % r.stderr.strip())
        # A worker's core error comes back as (class, message) and is raised again here as the
        # same class with the same message (a DiagramError exits 3 with the local run's line).
        from linf_opc import cluster as dask_runner, core

        tiles = dask_runner.Tiles.__new__(dask_runner.Tiles)
        tiles.address = "tcp://test:1"
        for name, cls in (("DiagramError", core.DiagramError), ("ValueError", ValueError)):
            try:
                tiles._answer(("error", name, "the worker's message"))
                expect(False, "a worker's %s is raised here" % name)
            except Exception as e:  # noqa: BLE001
                expect(type(e) is cls and str(e) == "the worker's message",
                       "a worker's %s is raised here as %s: %s %s" % (name, cls.__name__, type(e).__name__, e))
        # A worker without the core module on its path.
        bare, _ = cluster("bare", 1, "")
        got = os.path.join(work, "no_core")
        r = run("gauges", got, ["-rd", "tile=" + tile, "-rd", "scheduler=" + bare])
        print("worker without the core: exit %d: %s" % (r.returncode, r.stderr.strip()))
        expect(r.returncode == 2, "a worker without the core exits 2, not %d" % r.returncode)
        expect("linf_opc_core" in r.stderr and "PYTHONPATH" in r.stderr and len(r.stderr.strip().splitlines()) == 1,
               "one line naming the core module and the workers' PYTHONPATH: %r" % r.stderr)
        expect(not os.path.exists(got) or not os.listdir(got), "nothing written when a worker lacks the core")
finally:
    stop_all()

finish("on %s %s, tiles of %s um" % (os.path.basename(arg("input")), arg("layer"), tile))
