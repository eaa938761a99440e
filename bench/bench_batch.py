# The batch command as a person runs it: the whole `cmd=flow` (or another command) with its
# outputs (the default ones; more with -- all_gauges=1 diagram=1 halves=1), its wall time and peak
# memory, against the computation inside the same run (diagram and gauges, from its
# summary.json): how much the outputs add. bench_flow_default.py compares the two.
# Threads: both figures come from the same process, with the batch's default (one builder thread
# per core); the line says how many. The command is the README's (python3 macros/linf_opc.py);
# --klayout runs it under klayout -b instead.
#   python3 bench/bench_batch.py FILE L/D [MARKERS] [--cmd flow] [--klayout] [-- k=v ...]   (k=v: more -rd arguments)
# e.g. python3 bench/bench_batch.py ../shared/data/iccad16/testcase3.oas 1000/0 ../shared/data/iccad16/test3.csv
import json
import os
import resource
import subprocess
import sys
import tempfile
import time

repo = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
args = sys.argv[1:]
extra = args[args.index("--") + 1:] if "--" in args else []
args = args[:args.index("--")] if "--" in args else args
cmd = "flow"
if "--cmd" in args:
    cmd = args[args.index("--cmd") + 1]
    del args[args.index("--cmd"):args.index("--cmd") + 2]
launcher = [sys.executable]
if "--klayout" in args:
    args.remove("--klayout")
    launcher = ["klayout", "-b", "-r"]
if len(args) < 2:
    sys.exit("usage: python3 bench/bench_batch.py FILE L/D [MARKERS] [--cmd flow] [--klayout] [-- k=v ...]")
path, layer = args[0], args[1]
with tempfile.TemporaryDirectory() as out:
    run = launcher + [os.path.join(repo, "macros", "linf_opc.py"), "-rd", "cmd=" + cmd,
           "-rd", "input=" + path, "-rd", "layer=" + layer, "-rd", "out=" + out]
    if len(args) > 2:
        run += ["-rd", "markers=" + args[2]]
    for e in extra:
        run += ["-rd", e]
    t0 = time.perf_counter()
    p = subprocess.run(run, capture_output=True, text=True)
    wall = time.perf_counter() - t0
    if p.returncode != 0:
        sys.exit("%s failed:\n%s%s" % (cmd, p.stdout, p.stderr))
    peak = resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss / 1024
    s = json.load(open(os.path.join(out, "summary.json")))
    sec = (s.get("gauges") or s).get("seconds", {})
    compute = sum(sec.get(k, 0) for k in ("merge", "build", "check", "gauges"))
    print(p.stdout.strip())
    threads = os.cpu_count()
    print("%s on %s %s (%s; %d builder threads, both sides): whole command %.2f s, peak %.0f MB; of it the computation "
          "(merge, build, check, gauges) %.2f s: the command takes %.2f x its computation"
          % (cmd, os.path.basename(path), layer, "klayout -b" if launcher[0] == "klayout" else "python3", threads, wall, peak, compute, wall / compute if compute else 0))
