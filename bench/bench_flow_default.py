# The default `cmd=flow` against the flow with every file on request, as people run them, the
# variants alternately in one run (so that a busy machine slows all alike), N runs each; best and
# median wall time, CPU time, bytes written, and the ratios.
#   python3 bench/bench_flow_default.py FILE L/D MARKERS [--runs 3] [--litho PRESET [--opc]] [-- k=v ...]  (k=v: more -rd arguments)
# e.g. python3 bench/bench_flow_default.py ../shared/data/iccad16/testcase3.oas 1000/0 ../shared/data/iccad16/test3.csv
# "full" is the flow as it was before the defaults changed: every file (all_gauges=1, diagram=1),
# the two-layouts experiment (halves=1), every gauge up to 100,000 a type in the report
# databases (rdb_max=100000), the subdivision builder (builder=subdivision) and every piece
# searched by the independent check (check=full), each the old default. Each runs under both
# launchers: `python3 macros/linf_opc.py` (KLayout's standalone modules, the README's command) and
# `klayout -b -r macros/linf_opc.py` (the only one before); "full under klayout -b" is the flow as
# people ran it then. Threads: the batch's own, one builder thread per core
# (std::thread::hardware_concurrency), the same for every variant. KLayout's own start (`klayout
# -b`, an empty script) is timed in the same rounds.
# With --litho PRESET the variants are instead the default flow without and with printability
# scoring (-rd litho=PRESET), under each launcher, and the ratios printed are that flow's time over
# the default's on the same launcher (the printability issue's goal: at most 2x). --opc adds the
# flow with printability read after the emulated OPC (-rd opc=1) under python3, its ratios against
# the default and against printability without it.
import os
import resource
import statistics
import subprocess
import sys
import tempfile
import time

repo = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
FULL = ["all_gauges=1", "diagram=1", "halves=1", "rdb_max=100000", "builder=subdivision", "check=full"]
# name: (launcher, switches)
VARIANTS = {
    "default": ("python3", []),
    "default, klayout -b": ("klayout", []),
    "full": ("python3", FULL),
    "full, klayout -b": ("klayout", FULL),
}
LAUNCHERS = {"python3": [sys.executable], "klayout": ["klayout", "-b", "-r"]}


def cpu():
    r = resource.getrusage(resource.RUSAGE_CHILDREN)
    return r.ru_utime + r.ru_stime


def run_once(path, layer, markers, launcher, extra, more):
    with tempfile.TemporaryDirectory() as out:
        cmd = LAUNCHERS[launcher] + [os.path.join(repo, "macros", "linf_opc.py"), "-rd", "cmd=flow",
               "-rd", "input=" + path, "-rd", "layer=" + layer, "-rd", "markers=" + markers, "-rd", "out=" + out,
               "-rd", "quiet=1"] + [x for e in extra + more for x in ("-rd", e)]
        c0, t0 = cpu(), time.perf_counter()
        p = subprocess.run(cmd, capture_output=True, text=True)
        wall, used = time.perf_counter() - t0, cpu() - c0
        if p.returncode != 0:
            sys.exit("flow failed:\n%s%s" % (p.stdout, p.stderr))
        size = sum(os.path.getsize(os.path.join(out, f)) for f in os.listdir(out))
        return wall, used, size, len(os.listdir(out))


def klayout_start():
    """KLayout's own start and exit (`klayout -b` with an empty script): in the klayout -b
    variants' times, none of it ours to shorten."""
    with tempfile.NamedTemporaryFile("w", suffix=".py") as f:
        c0, t0 = cpu(), time.perf_counter()
        subprocess.run(["klayout", "-b", "-r", f.name], capture_output=True)
        return time.perf_counter() - t0, cpu() - c0


def main(argv):
    more = argv[argv.index("--") + 1:] if "--" in argv else []
    argv = argv[:argv.index("--")] if "--" in argv else argv
    runs = 3
    if "--litho" in argv:
        preset = argv[argv.index("--litho") + 1]
        del argv[argv.index("--litho"):argv.index("--litho") + 2]
        VARIANTS.clear()
        VARIANTS.update({"default": ("python3", []), "litho": ("python3", ["litho=" + preset]),
                         "default, klayout -b": ("klayout", []), "litho, klayout -b": ("klayout", ["litho=" + preset])})
    if "--opc" in argv:
        del argv[argv.index("--opc")]
        if "litho" not in VARIANTS:
            sys.exit("--opc needs --litho PRESET")
        VARIANTS["litho, opc"] = ("python3", VARIANTS["litho"][1] + ["opc=1"])
    if "--runs" in argv:
        runs = int(argv[argv.index("--runs") + 1])
        del argv[argv.index("--runs"):argv.index("--runs") + 2]
    if len(argv) != 3:
        sys.exit("usage: python3 bench/bench_flow_default.py FILE L/D MARKERS [--runs 3] [--litho PRESET [--opc]] "
                 "[-- k=v ...]")
    path, layer, markers = argv
    got = {v: [] for v in VARIANTS}
    start = []
    for i in range(runs):
        start.append(klayout_start())
        for v, (launcher, extra) in VARIANTS.items():
            got[v].append(run_once(path, layer, markers, launcher, extra, more))
            wall, used, size, n = got[v][-1]
            print("run %d %-19s wall %7.2f s, cpu %7.2f s, %d files, %.1f MB" % (i + 1, v, wall, used, n, size / 1e6),
                  flush=True)
    print("flow on %s %s, %d runs each, alternately; threads: the batch's default, one a core (%d here), both"
          % (os.path.basename(path), layer, runs, os.cpu_count()))
    best = {}
    for v in VARIANTS:
        walls = [g[0] for g in got[v]]
        cpus = [g[1] for g in got[v]]
        best[v] = (min(walls), statistics.median(walls), min(cpus), statistics.median(cpus))
        print("%-19s %s: wall best %.2f s, median %.2f s; cpu best %.2f s, median %.2f s; %d files, %.1f MB"
              % (v, " ".join("-rd " + e for e in VARIANTS[v][1]) or "(no switch)", *best[v], got[v][0][3],
                 got[v][0][2] / 1e6))
    pairs = [("litho", "default"), ("litho, klayout -b", "default, klayout -b")] if "litho" in best else \
        [("full, klayout -b", "default"), ("full", "default"), ("full, klayout -b", "default, klayout -b")]
    if "litho, opc" in best:
        pairs += [("litho, opc", "default"), ("litho, opc", "litho")]
    for slow, fast in pairs:
        f, d = best[slow], best[fast]
        print("%s / %s: wall best %.2fx, median %.2fx; cpu best %.2fx, median %.2fx"
              % (slow, fast, f[0] / d[0], f[1] / d[1], f[2] / d[2], f[3] / d[3]))
    k = min(w for w, _ in start), statistics.median(w for w, _ in start)
    print("KLayout's own start (klayout -b, an empty script): wall best %.2f s, median %.2f s" % k)


if __name__ == "__main__":
    main(sys.argv[1:])
