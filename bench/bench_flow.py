# The scale benchmark (issue 7's table, without tiling yet): per input, polygons, segments, the
# time per stage (load, diagram, gauges, selection, split) and peak memory, each input in its
# own process; in the same run, KLayout's width + space checks and (optional) CGAL's raw
# construction, and the diagram with one and two threads.
#   python3 bench/bench_flow.py [--generated 10000,100000] [--shared] [--cgal]
import json
import os
import subprocess
import sys

repo = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
data = os.path.join(repo, "..", "shared", "data")
args = sys.argv[1:]
sizes = [int(v) for v in (args[args.index("--generated") + 1] if "--generated" in args else "10000,100000").split(",")]
inputs = [("generated:%d" % n, "1/0", None, None) for n in sizes]
if "--shared" in args:
    inputs += [(os.path.join(data, "iccad16", "testcase3.oas"), "1000/0", None, os.path.join(data, "iccad16", "test3.csv")),
               (os.path.join(data, "openilt", "gcd_45nm.gds"), "11/0", None, None),
               (os.path.join(data, "freepdk45", "sram_8_128_freepdk45.gds"), "11/0", None, None)]


def one(inp, layer, cell, markers, threads, drc):
    cmd = ["klayout", "-b", "-r", os.path.join(repo, "bench", "flow_one.py"), "-rd", "input=" + inp, "-rd",
           "layer=" + layer, "-rd", "threads=%d" % threads, "-rd", "drc=%d" % drc]
    if cell:
        cmd += ["-rd", "cell=" + cell]
    if markers:
        cmd += ["-rd", "markers=" + markers]
    r = subprocess.run(cmd, capture_output=True, text=True)
    for line in r.stdout.splitlines():
        if line.startswith("RESULT "):
            return json.loads(line[7:])
    raise RuntimeError(r.stdout + r.stderr)


print("| input | polygons | segments | load | diagram | gauges | selection | split | peak MB | "
      "width+space | flow / (width+space) | diagram 1 thread / 2 threads |")
print("|---|---|---|---|---|---|---|---|---|---|---|---|")
for inp, layer, cell, markers in inputs:
    two = one(inp, layer, cell, markers, 2, 1)
    single = one(inp, layer, cell, markers, 1, 0)
    s = two["seconds"]
    flow = s["load"] + s["diagram_and_gauges"] + s["selection"] + s["split"]
    print("| %s | %d | %d | %.2f s | %.2f s | %.2f s | %.2f s | %.2f s | %.0f | %.2f s | %.2f | %.2f s / %.2f s = %.2fx |"
          % (two["input"], two["polygons"], two["segments"], s["load"], s["diagram"], s["gauges"], s["selection"],
             s["split"], two["peak_rss_mb"], s["klayout_width_space"], flow / s["klayout_width_space"],
             single["seconds"]["diagram"], s["diagram"], single["seconds"]["diagram"] / s["diagram"]))
    sys.stdout.flush()
