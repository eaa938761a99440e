# The scale benchmark (issue 7's table): per input, polygons, segments, the time per stage
# (load, diagram, gauges, selection, split), how the builder tiled it and the peak memory, each
# input in its own process; in the same run, the ratios against CGAL's raw L-inf construction
# of the same polygons (its own process, with a deadline: it can hang or crash) and against
# KLayout's width + space checks (metrics Square) on the same layer.
#   python3 bench/bench_flow.py [--generated 10000,100000,1000000] [--shared] [--threads]
#                               [--tile DBU] [--deadline SECONDS] [--no-reach] [--match TEXT]
# --match keeps the inputs whose name contains TEXT (--shared --match glp: the ten contest clips).
# --threads adds the diagram with one thread against two (inputs up to 20,000 polygons).
# KLayout's checks run at the gauges' own reach (see flow_one.py; docs/benchmarks.md,
# "Comparing with KLayout's checks") and at 2 x the narrowest width; --no-reach leaves the first out.
import json
import os
import subprocess
import sys
import tempfile

repo = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
data = os.path.join(repo, "..", "shared", "data")
args = sys.argv[1:]


def opt(name, default):
    return args[args.index(name) + 1] if name in args else default


sizes = [int(v) for v in opt("--generated", "10000,100000").split(",") if v]
tile = opt("--tile", "-1")
deadline = float(opt("--deadline", "1800"))
inputs = [("generated:%d" % n, "1/0", None, None) for n in sizes]
if "--shared" in args:
    ic = os.path.join(data, "iccad16")
    inputs += [(os.path.join(ic, "testcase%d.oas" % k), "1000/0", None, os.path.join(ic, "test%d.csv" % k))
               for k in (1, 2, 3)]
    inputs += [(os.path.join(data, "openilt", "gcd_45nm.gds"), "11/0", None, None),
               (os.path.join(data, "ihp", "sg13g2_stdcell.gds"), "8/0", "sg13g2_dfrbp_1", None),
               (os.path.join(data, "freepdk45", "sram_8_128_freepdk45.gds"), "11/0", None, None)]
    inputs += [(os.path.join(data, "openilt", "M1_test%d.glp" % k), "1/0", None, None) for k in range(1, 11)]
if "--match" in args:
    inputs = [i for i in inputs if opt("--match", "") in os.path.basename(i[0])]


def one(inp, layer, cell, markers, threads, drc, polygons_json=None):
    cmd = ["klayout", "-b", "-r", os.path.join(repo, "bench", "flow_one.py"), "-rd", "input=" + inp, "-rd",
           "layer=" + layer, "-rd", "threads=%d" % threads, "-rd", "drc=%d" % drc, "-rd", "tile=" + tile]
    if drc and "--no-reach" not in args:
        cmd += ["-rd", "reach=1"]
    if cell:
        cmd += ["-rd", "cell=" + cell]
    if markers:
        cmd += ["-rd", "markers=" + markers]
    if polygons_json:
        cmd += ["-rd", "polygons_json=" + polygons_json]
    r = subprocess.run(cmd, capture_output=True, text=True)
    for line in r.stdout.splitlines():
        if line.startswith("RESULT "):
            return json.loads(line[7:])
    raise RuntimeError(r.stdout + r.stderr)


def cgal(polygons_json):
    """CGAL's construction alone in seconds, or a note why there is none."""
    try:
        r = subprocess.run(["/usr/bin/python3", os.path.join(repo, "bench", "cgal_baseline.py"), polygons_json, "0"],
                           capture_output=True, text=True, timeout=deadline)
    except subprocess.TimeoutExpired:
        return None, "no result after %.0f s" % deadline
    if r.returncode != 0:
        return None, "crashed (exit %d)" % r.returncode
    return float(r.stdout.split()[-1]), ""


reach = "--no-reach" not in args
print("| input | polygons | segments | load | diagram | gauges | selection | split | tiles (largest, sites) | "
      "peak MB: RSS / anonymous (RSS after load) | CGAL construction | diagram / CGAL | width+space | flow / (width+space) |%s%s"
      % (" width+space at the gauges' reach (t width, space) | flow / that |" if reach else "",
         " diagram 1 thread / 2 threads |" if "--threads" in args else ""))
print("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|%s%s"
      % ("---|---|" if reach else "", "---|" if "--threads" in args else ""))
for inp, layer, cell, markers in inputs:
    with tempfile.TemporaryDirectory() as tmp:
        pj = os.path.join(tmp, "polygons.json")
        two = one(inp, layer, cell, markers, 2, 1, pj)
        t_cgal, why = cgal(pj)
    s = two["seconds"]
    flow = s["load"] + s["diagram_and_gauges"] + s["selection"] + s["split"]
    tl = two["tiles"]
    row = ("| %s | %d | %d | %.2f s | %.2f s | %.2f s | %.2f s | %.2f s | %d (%d of %d) | %s | %s | %s | %.2f s | %.1f |"
           % (two["input"] + (" " + cell if cell else ""), two["polygons"], two["segments"], s["load"], s["diagram"],
              s["gauges"], s["selection"], s["split"], tl["tiles"], tl["largest_tile_sites"], two["sites"],
              "%.0f / %.0f (load %.0f)" % (two["peak_rss_mb"], two["peak_anon_mb"], two["peak_mb_after"]["load"]), "%.2f s" % t_cgal if t_cgal else why, "%.1f" % (s["diagram"] / t_cgal) if t_cgal else "-",
              s["klayout_width_space"], flow / s["klayout_width_space"]))
    if reach:
        row += " %.2f s (%d, %d DBU) | %.2f |" % (s["klayout_width_space_reach"], two["reach_dbu"][0], two["reach_dbu"][1],
                                                 flow / s["klayout_width_space_reach"])
    if "--threads" in args:
        if two["polygons"] <= 20000:
            single = one(inp, layer, cell, markers, 1, 0)
            row += " %.2f s / %.2f s = %.2fx |" % (single["seconds"]["diagram"], s["diagram"],
                                                   single["seconds"]["diagram"] / s["diagram"])
        else:
            row += " - |"
    print(row)
    sys.stdout.flush()
