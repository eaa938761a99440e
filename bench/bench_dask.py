# The diagram's tiles on a Dask cluster against one local thread, on the scale benchmark's
# generated wires (bench/flow_one.py's generator, here without KLayout), with what a cost model
# needs: per-tile times on the workers, the submitting host's own share per tile, the bytes
# moved, the scheduler's overhead per task, and each worker's peak memory.
#   python3 bench/bench_dask.py [--wires 100000] [--workers 2] [--tile -1] [--overhead-tasks 2000] [--builder sweep]
#                               [--flow] [--host-threads 1]
#                               [--litho euv [--rounds 3]]   (the gauge stage, then the printability)
# --flow: the gauge stage as the flow runs it (no voronoi.csv or gauges.csv: the runs compare the
# gauge columns); --host-threads: the submitting host's own threads in the cluster's run (the
# stages after the tiles), the workers and the local run keep one.
# Starts a dask-scheduler and --workers dask-workers (--nthreads 1) on 127.0.0.1 and stops them.
# Both runs build the gauges (diagram + gauges, as cmd=gauges without its writers) with one
# thread on the submitting host; the cluster's run must give the same voronoi.csv and gauges.csv
# bytes. Prints a JSON line, a Markdown table and each run's stages (the core's progress).
import array
import json
import os
import platform
import random
import signal
import socket
import subprocess
import sys
import tempfile
import time

repo = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(repo, "build"))
sys.path.insert(0, os.path.join(repo, "plugin", "python"))
import linf_opc_core as core  # noqa: E402

args = sys.argv[1:]


def opt(name, default):
    return args[args.index(name) + 1] if name in args else default


BUILDER = opt("--builder", "sweep")  # the batch's default; "subdivision" as the batch's -rd builder


def wires(n, seed=1):
    """bench/flow_one.py's generated block: horizontal tracks on a 100 DBU pitch, wires 50 DBU
    wide of random length (150-1500) with random gaps (50-600), as the core's flat arrays."""
    rng = random.Random(seed)
    tracks = max(1, int((11.5 * n) ** 0.5))
    length, count = 100 * tracks, 0
    pts, rings = array.array("q"), array.array("q")
    for k in range(tracks):
        x = rng.randrange(0, 400)
        while x < length and count < n:
            w = rng.randrange(150, 1500)
            y = k * 100
            pts.extend((x, y, x + w, y, x + w, y + 50, x, y + 50))
            rings.append(4)
            count += 1
            x += w + rng.randrange(50, 600)
    return (pts, rings), count


def free_port():
    s = socket.socket()
    s.bind(("127.0.0.1", 0))
    p = s.getsockname()[1]
    s.close()
    return p


FLOW = "--flow" in args  # the gauge stage as the flow runs it: no voronoi.csv, no gauges.csv
HOST_THREADS = int(opt("--host-threads", "1"))  # the submitting host's own threads (the workers keep one)


class Stages:
    """The core's progress stages of one run, timed: where the serial part of a cluster's run is."""

    def __init__(self):
        self.marks = []

    def __call__(self, name, done, total):
        if not self.marks or self.marks[-1][0] != name:
            self.marks.append((name, time.perf_counter()))

    def seconds(self, end):
        ends = [t for _, t in self.marks[1:]] + [end]
        out = {}
        for (name, t), e in zip(self.marks, ends):
            out[name] = out.get(name, 0.0) + e - t
        return out


def build(polys, out, tiles=None):
    """The gauge stage with one thread (cluster: the host's HOST_THREADS); the files the runs
    compare: voronoi.csv and gauges.csv, or with --flow the gauge columns (as the flow keeps them)."""
    stages = Stages()
    files = ({"columns": os.path.join(out, "gauges.columns")} if FLOW else
             {"csv": os.path.join(out, "voronoi.csv"), "gauges_csv": os.path.join(out, "gauges.csv")})
    t0 = time.perf_counter()
    r = core.gauges_polygons(polys, True, 2000, 1 if tiles is None else HOST_THREADS, tile=tile, dbu=0.001,
                             tiles=tiles, builder=BUILDER, progress=stages, **files)
    end = time.perf_counter()
    r["stages"] = stages.seconds(end)
    return r, end - t0


def cpu_seconds():
    """This process's user + system CPU time (on a worker or the scheduler through client.run)."""
    import resource
    u = resource.getrusage(resource.RUSAGE_SELF)
    return u.ru_utime + u.ru_stime


def same(a, b, name):
    with open(os.path.join(a, name), "rb") as f, open(os.path.join(b, name), "rb") as g:
        return f.read() == g.read()


class Measured:
    """cluster.Tiles with the submitting host's share timed: next (planning a tile, gathering
    its halo, encoding), done (decoding, the spill; classifying and the stretches' readings
    where the tasks do not), the bytes."""

    def __init__(self, tiles):
        self.tiles = tiles
        self.next_s = self.done_s = 0.0
        self.sent = self.received = self.jobs = 0
        self.largest_job = 0

    def __call__(self, next_job, done):
        def timed_next():
            t = time.perf_counter()
            job = next_job()
            self.next_s += time.perf_counter() - t
            if job is not None:
                self.sent += len(job)
                self.jobs += 1
                self.largest_job = max(self.largest_job, len(job))
            return job

        def timed_done(result):
            t = time.perf_counter()
            self.received += len(result)
            done(result)
            self.done_s += time.perf_counter() - t

        t0 = time.perf_counter()
        self.tiles(timed_next, timed_done)
        self.phase_s = time.perf_counter() - t0


def noop(x):
    return x


# Cost model assumptions (stated in docs/benchmarks.md): a farm's network moves 1 GB/s to and from
# the submitting host (10 GbE, shared by every task), 0.5 ms latency a message; every term
# scales linearly with the layer's sites (tiles of 2^15 own sites: their count grows with the
# layer, their size does not); the scheduler handles tasks one after the other.
BANDWIDTH = 1e9
LATENCY = 0.5e-3
TARGET = 5e7


def project(r, tiles):
    """Wall time of the gauges stage for TARGET wires on W single-thread workers: the tile phase
    is bounded by the slowest of the workers' share, the submitting host's per-tile work, the
    scheduler's per-task overhead and the network; then the host's serial rest."""
    k = TARGET / r["wires"]
    n_tiles = tiles * k
    compute = r["tile_compute_sum_s"] * k
    host = (r["host_next_s"] + r["host_done_s"]) * k
    sched = n_tiles * r["overhead_per_task_batch_ms"] / 1000
    net = (r["bytes_sent"] + r["bytes_received"]) * k / BANDWIDTH + n_tiles * 2 * LATENCY
    serial = r["host_after_tiles_s"] * k
    out = {"tiles": round(n_tiles), "host_serial_s": serial, "host_per_tile_total_s": host,
           "scheduler_total_s": sched, "network_total_s": net}
    for w in (64, 256):
        phase = max(compute / w + r["tile_compute_max_s"], host, sched, net)
        out["workers_%d_s" % w] = phase + serial
    out["one_thread_s"] = r["local_seconds"] * k
    return out


LITHO = opt("--litho", "")  # the printability reading instead of the gauge stage
ROUNDS = int(opt("--rounds", "3"))  # with --litho: cluster runs, each between two local ones
if LITHO:  # the package's litho reading needs pya: KLayout's standalone modules, as the batch
    from linf_opc import standalone
    standalone.start()  # may run this process again, once


def litho_bench(polys, n, client):
    """--litho NAME: the gauge stage (gauges.compute, as the flow runs it), then the gauges'
    printability (litho.rescore, as -rd litho=NAME reads it) on it, each with one local thread and
    on the workers (the tiles; cluster.Tiles.printability); the same gauges, columns, ranks and
    counts. Prints a JSON line, the two stages' sum, and a row."""
    import copy
    from linf_opc import core as plugin_core, gauges as gauge_stage, litho
    model = litho.model_of({"litho": LITHO})
    # The gauge stage as the flow runs it before the reading, locally and on the cluster: with the
    # reading, the flow's two stages that grow with the layer (the selection and split are small).
    t0 = time.perf_counter()
    base = gauge_stage.compute(polys, tile=-1, dbu=0.001, threads=1)
    t_stage_local = time.perf_counter() - t0
    t0 = time.perf_counter()
    with plugin_core.tiles_with(cluster.Tiles(client)):
        on_cluster = gauge_stage.compute(polys, tile=-1, dbu=0.001, threads=1)
    t_stage_dask = time.perf_counter() - t0
    stage_same = [c.tobytes() for c in base.gauges.columns()] == [c.tobytes() for c in on_cluster.gauges.columns()]
    del on_cluster
    model.kernels, model.defocus  # computed beside the gauge stage; waited for here, not timed

    # The contexts alone (the reading's first step, at half the model's window), with one local
    # thread and in chunks on the workers (cluster.Tiles.contexts); the same ids.
    cx, cy = base.gauges.centres()
    points = array.array("d", bytes(16 * len(cx)))
    points[0::2], points[1::2] = array.array("d", cx), array.array("d", cy)
    radius = model.kernels.period / 2
    t0 = time.perf_counter()
    ids_local = core.gauge_contexts(polys, points, radius, 1)
    t_ctx_local = time.perf_counter() - t0
    with get_task_stream(client) as ts:
        t0 = time.perf_counter()
        ids_dask = cluster.Tiles(client).contexts(polys, points, radius)
        t_ctx_dask = time.perf_counter() - t0
    ctx_spans = [(s["stop"] - s["start"]) for t in ts.data if t["key"].startswith("linf-context")
                 for s in t["startstops"] if s["action"] == "compute"]
    print("contexts of %d points: local %.2f s, cluster %.2f s (%d chunks, %.2f s on the workers; same: %s)"
          % (len(cx), t_ctx_local, t_ctx_dask, len(ctx_spans), sum(ctx_spans), ids_local == ids_dask), file=sys.stderr)
    del points

    def read(tiles=None):
        r = copy.copy(base)
        r.seconds = dict(base.seconds)
        t0 = time.perf_counter()
        if tiles is None:
            litho.rescore(r, polys, 0.001, model, threads=1)
        else:
            with plugin_core.tiles_with(tiles):
                litho.rescore(r, polys, 0.001, model, threads=1)
        return r, time.perf_counter() - t0

    def same(a, b):
        la, lb = a.gauges.litho, b.gauges.litho
        sa = {k: v for k, v in a.litho_summary.items() if k != "seconds"}
        sb = {k: v for k, v in b.litho_summary.items() if k != "seconds"}
        cols = all(getattr(la, k).tobytes() == getattr(lb, k).tobytes()
                   for k in ("geo_score", "printed_cd", "pv_band", "fails"))
        return cols and sa == sb and [c.tobytes() for c in a.gauges.columns()] == [c.tobytes() for c in b.gauges.columns()]

    # Rounds alternating local, cluster, ..., local: on a shared machine the load drifts, and the
    # best and the median of each side are compared.
    locals_, dasks = [], []
    c0 = cpu_seconds()
    r_local, t = read()
    cpu_local = cpu_seconds() - c0
    locals_.append(t)
    for k in range(ROUNDS):
        c0, w0, s0 = cpu_seconds(), client.run(cpu_seconds), client.run_on_scheduler(cpu_seconds)
        with get_task_stream(client) as ts:
            r_dask, t = read(cluster.Tiles(client))
        c1, w1, s1 = cpu_seconds(), client.run(cpu_seconds), client.run_on_scheduler(cpu_seconds)
        dasks.append(t)
        if not same(r_local, r_dask):
            break
        locals_.append(read()[1])
    spans = [(s["stop"] - s["start"]) for t in ts.data if t["key"].startswith("linf-litho")
             for s in t["startstops"] if s["action"] == "compute"]
    t_local, t_dask = min(locals_), min(dasks)
    median = lambda v: sorted(v)[len(v) // 2]  # noqa: E731
    peak = client.run(lambda: __import__("resource").getrusage(__import__("resource").RUSAGE_SELF).ru_maxrss)
    s = r_local.litho_summary
    result = {"wires": n, "gauges": len(base.gauges), "model": LITHO, "simulated": s["simulated"],
              "simulations": s["simulations"], "images": s["images"], "chunks": len(spans),
              "local_seconds": t_local, "dask_seconds": t_dask, "speedup": t_local / t_dask,
              "local_runs_seconds": locals_, "dask_runs_seconds": dasks,
              "speedup_median": median(locals_) / median(dasks),
              "same": same(r_local, r_dask), "chunk_compute_sum_s": sum(spans),
              "chunk_compute_max_s": max(spans) if spans else 0,
              "cpu_local_s": cpu_local, "cpu_host_s": c1 - c0, "cpu_workers_s": sorted(w1[k] - w0[k] for k in w1),
              "cpu_scheduler_s": s1 - s0, "worker_peak_rss_mb": sorted(v / 1024 for v in peak.values()),
              "contexts_local_seconds": t_ctx_local, "contexts_dask_seconds": t_ctx_dask,
              "contexts_chunks": len(ctx_spans), "contexts_compute_sum_s": sum(ctx_spans),
              "contexts_same": ids_local == ids_dask,
              "stage_local_seconds": t_stage_local, "stage_dask_seconds": t_stage_dask, "stage_same": stage_same,
              "flow_speedup": (t_stage_local + t_local) / (t_stage_dask + t_dask),
              "date": time.strftime("%Y-%m-%d %H:%M UTC", time.gmtime())}
    print(json.dumps(result))
    print("gauge stage, then the printability: local %.1f + %.1f s, cluster %.1f + %.1f s (same gauges: %s): %.2f×"
          % (t_stage_local, t_local, t_stage_dask, t_dask, "yes" if stage_same else "NO", result["flow_speedup"]))
    print("| wires | gauges | simulations / line images | chunks | local, 1 thread: best / median | 2 workers x 1 thread: "
          "best / median | speed-up: best / median | "
          "same | chunks on the workers: sum / max | CPU: local / host / workers / scheduler | worker peak RSS |")
    print("|---|---|---|---|---|---|---|---|---|---|---|")
    print("| %d | %d | %d / %d | %d | %.1f / %.1f s | %.1f / %.1f s | %.2f× / %.2f× | %s | %.1f / %.2f s | "
          "%.1f / %.1f / %s / %.1f s | %s MB |"
          % (n, len(base.gauges), s["simulations"], s["images"], len(spans), t_local, median(locals_), t_dask,
             median(dasks), t_local / t_dask, result["speedup_median"],
             "yes" if result["same"] else "NO", sum(spans), result["chunk_compute_max_s"], cpu_local,
             result["cpu_host_s"], " + ".join("%.1f" % v for v in result["cpu_workers_s"]), result["cpu_scheduler_s"],
             ", ".join("%.0f" % v for v in result["worker_peak_rss_mb"])))


n_wires = int(opt("--wires", "100000"))
n_workers = int(opt("--workers", "2"))
tile = float(opt("--tile", "-1"))
n_overhead = int(opt("--overhead-tasks", "2000"))
work = tempfile.mkdtemp(prefix="linf_bench_dask_")
procs = []
try:
    import distributed
    from distributed import get_task_stream
    from linf_opc import cluster

    polys, n = wires(n_wires)
    local_dir, dask_dir = os.path.join(work, "local"), os.path.join(work, "dask")
    os.makedirs(local_dir)
    os.makedirs(dask_dir)
    c0 = cpu_seconds()
    r_local, t_local = build(polys, local_dir)
    cpu_local = cpu_seconds() - c0
    print("local, one thread: %.2f s (diagram build %.2f s)" % (t_local, r_local["diagram"]["seconds"]["build"]),
          file=sys.stderr)

    port = free_port()
    address = "tcp://127.0.0.1:%d" % port
    log = open(os.path.join(work, "cluster.log"), "w")
    procs.append(subprocess.Popen(["dask-scheduler", "--host", "127.0.0.1", "--port", str(port), "--no-dashboard"],
                                  stdout=log, stderr=log, start_new_session=True))
    env = dict(os.environ, PYTHONPATH=os.path.join(repo, "build"))
    for k in range(n_workers):
        procs.append(subprocess.Popen(["dask-worker", address, "--nthreads", "1", "--nworkers", "1", "--no-dashboard",
                                       "--memory-limit", "0", "--local-directory", os.path.join(work, "w%d" % k)],
                                      stdout=log, stderr=log, env=env, start_new_session=True))
    client = distributed.Client(address, timeout=60, set_as_default=False)  # retries while it starts
    client.wait_for_workers(n_workers, timeout=120)

    # Scheduler overhead: trivial tasks, submitted all at once and one after the other.
    t0 = time.perf_counter()
    client.gather(client.map(noop, range(n_overhead), pure=False))
    per_task_batch = (time.perf_counter() - t0) / n_overhead
    t0 = time.perf_counter()
    for i in range(200):
        client.submit(noop, i, pure=False).result()
    round_trip = (time.perf_counter() - t0) / 200

    if LITHO:
        litho_bench(polys, n, client)
        raise SystemExit(0)
    tiles = Measured(cluster.Tiles(client))
    # CPU time of every process of the cluster's run: on two shared cores the wall times above
    # include waiting for a core, the CPU times do not.
    c0, w0, s0 = cpu_seconds(), client.run(cpu_seconds), client.run_on_scheduler(cpu_seconds)
    with get_task_stream(client) as ts:
        r_dask, t_dask = build(polys, dask_dir, tiles)
    c1, w1, s1 = cpu_seconds(), client.run(cpu_seconds), client.run_on_scheduler(cpu_seconds)
    spans = [(s["stop"] - s["start"]) for t in ts.data if t["key"].startswith("linf-tile")
             for s in t["startstops"] if s["action"] == "compute"]
    peak = client.run(lambda: __import__("resource").getrusage(__import__("resource").RUSAGE_SELF).ru_maxrss)
    client.close()
    # The local run again, after: on a shared machine the load drifts; the faster of the two
    # counts (the speed-up is the smaller for it).
    _, t_local_after = build(polys, local_dir)
    t_local_first, t_local = t_local, min(t_local, t_local_after)

    d_local, d_dask = r_local["diagram"], r_dask["diagram"]
    result = {
        "wires": n, "sites": d_local["sites"], "workers": n_workers, "builder": d_dask["builder"],
        "tiles": d_dask["tiles"], "jobs": tiles.jobs,
        "local_seconds": t_local, "local_runs_seconds": [t_local_first, t_local_after], "dask_seconds": t_dask, "speedup": t_local / t_dask,
        "local_build_seconds": d_local["seconds"]["build"], "dask_build_seconds": d_dask["seconds"]["build"],
        "as_flow": FLOW, "host_threads": HOST_THREADS,
        "same_files": all(same(local_dir, dask_dir, f) for f in (["gauges.columns"] if FLOW else
                                                                  ["voronoi.csv", "gauges.csv"])),
        "local_stages_s": r_local["stages"], "dask_stages_s": r_dask["stages"],
        "tile_compute_sum_s": sum(spans), "tile_compute_max_s": max(spans) if spans else 0,
        "tile_compute_mean_s": sum(spans) / len(spans) if spans else 0,
        "host_next_s": tiles.next_s, "host_done_s": tiles.done_s, "tile_phase_s": tiles.phase_s,
        "host_after_tiles_s": t_dask - tiles.phase_s,
        "bytes_sent": tiles.sent, "bytes_received": tiles.received, "largest_job_bytes": tiles.largest_job,
        "overhead_per_task_batch_ms": 1000 * per_task_batch, "round_trip_ms": 1000 * round_trip,
        "worker_peak_rss_mb": sorted(v / 1024 for v in peak.values()),
        "cpu_local_s": cpu_local, "cpu_host_s": c1 - c0, "cpu_workers_s": sorted(w1[k] - w0[k] for k in w1),
        "cpu_scheduler_s": s1 - s0,
        "machine": "%s, %d cores, Python %s" % (platform.processor() or platform.machine(), os.cpu_count(),
                                                  platform.python_version()),
        "date": time.strftime("%Y-%m-%d %H:%M UTC", time.gmtime()),
    }
    result["projection"] = project(result, d_dask["tiles"]["tiles"])
    print(json.dumps(result))
    print("builder: local %s, cluster %s" % (r_local["diagram"]["builder"], d_dask["builder"]))
    print(("| wires | sites | tiles | local, 1 thread | %d workers x 1 thread + host %d thread%s | speed-up | same files | "
           % (n_workers, HOST_THREADS, "" if HOST_THREADS == 1 else "s")) +
          "tile compute sum / mean / max | host per tile (plan+gather / decode+spill) | host after tiles | "
          "sent / received | task overhead (batch / round trip) | worker peak RSS |")
    print("|---|---|---|---|---|---|---|---|---|---|---|---|---|")
    print("| %d | %d | %d | %.1f s | %.1f s | %.2f× | %s | %.1f / %.3f / %.3f s | %.1f / %.1f ms | %.1f s | "
          "%.1f / %.1f MB | %.2f / %.2f ms | %s MB |"
          % (n, d_local["sites"], d_dask["tiles"]["tiles"], t_local, t_dask, t_local / t_dask,
             "yes" if result["same_files"] else "NO",
             result["tile_compute_sum_s"], result["tile_compute_mean_s"], result["tile_compute_max_s"],
             1000 * tiles.next_s / max(1, tiles.jobs), 1000 * tiles.done_s / max(1, tiles.jobs),
             result["host_after_tiles_s"], tiles.sent / 1e6, tiles.received / 1e6,
             result["overhead_per_task_batch_ms"], result["round_trip_ms"],
             ", ".join("%.0f" % v for v in result["worker_peak_rss_mb"])))
    print("CPU time: local run %.2f s; cluster run: host %.2f s, workers %s s, scheduler %.2f s"
          % (cpu_local, result["cpu_host_s"], " + ".join("%.2f" % v for v in result["cpu_workers_s"]),
             result["cpu_scheduler_s"]))
    print("| stage (the core's progress) | local, 1 thread | cluster, host %d thread%s |"
          % (HOST_THREADS, "" if HOST_THREADS == 1 else "s"))
    print("|---|---|---|")
    for name in list(dict.fromkeys(list(r_dask["stages"]) + list(r_local["stages"]))):
        print("| %s | %s | %s |" % (name, *("%.1f s" % st[name] if name in st else "-"
                                            for st in (r_local["stages"], r_dask["stages"]))))
    pr = result["projection"]
    print("projection to %.0e wires (%d tiles): one thread %.0f s; 64 workers %.0f s; 256 workers %.0f s; host serial "
          "%.0f s, host per-tile work %.0f s, scheduler %.0f s, network %.0f s"
          % (TARGET, pr["tiles"], pr["one_thread_s"], pr["workers_64_s"], pr["workers_256_s"], pr["host_serial_s"],
             pr["host_per_tile_total_s"], pr["scheduler_total_s"], pr["network_total_s"]))
finally:
    for p in procs:
        if p.poll() is None:
            os.killpg(p.pid, signal.SIGTERM)
    for p in procs:
        try:
            p.wait(10)
        except subprocess.TimeoutExpired:
            os.killpg(p.pid, signal.SIGKILL)
    import shutil
    shutil.rmtree(work, ignore_errors=True)
