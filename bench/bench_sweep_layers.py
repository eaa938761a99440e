# The sweep-line builder on real layers against Boost.Polygon's construction and the
# subdivision, one thread each, the same merged edges:
#   klayout -b -r bench/bench_sweep_layers.py [-rd runs=N] [-rd tiles=1] [-rd check=1]
# tiles=1: the sweep in automatic tiles on 1 and 2 threads against its whole-layer sweep.
# check=1: the independent checker, sampled (the default) and full, against the builds.
# Reads each layer with KLayout, writes its polygons to a temporary file and runs
# build/bench_sweep on them (docs/benchmarks.md). Layers: the SRAM's 11/0 and ICCAD16
# testcase 3's 1000/0 from ../shared/data; missing files are reported, not skipped silently.
import os
import subprocess
import sys
import tempfile

repo = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(repo, "plugin", "python"))

import pya  # noqa: E402

from linf_opc import layout  # noqa: E402

data = os.path.join(repo, "..", "shared", "data")
LAYERS = [
    ("SRAM 11/0", os.path.join(data, "freepdk45", "sram_8_128_freepdk45.gds"), "11/0"),
    ("ICCAD16 testcase 3, 1000/0", os.path.join(data, "iccad16", "testcase3.oas"), "1000/0"),
]
runs = str(max(1, int(globals().get("runs") or 3)))
mode = ["tiles"] if globals().get("tiles") == "1" else ["check"] if globals().get("check") == "1" else []
args = [os.path.join(repo, "build", "bench_sweep")] + mode + [runs]
with tempfile.TemporaryDirectory() as tmp:
    for k, (name, path, layer) in enumerate(LAYERS):
        if not os.path.exists(path):
            print("MISSING %s: %s" % (name, path))
            continue
        ly = pya.Layout()
        ly.read(path)
        cell = ly.top_cells()[0]
        L, D = layout.parse_layer(layer)
        out = os.path.join(tmp, "layer%d.txt" % k)
        with open(out, "w") as f:
            for outer, holes in layout.polygons_of(layout.region_of(cell, ly.find_layer(L, D))):
                f.write("o " + " ".join("%d %d" % p for p in outer) + "\n")
                for h in holes:
                    f.write("h " + " ".join("%d %d" % p for p in h) + "\n")
        args += [name, out]
    if mode == ["check"]:
        args += ["generated wires, 10^5", "wires:100000", "generated wires, 10^6", "wires:1000000"]
    sys.stdout.write(subprocess.run(args, capture_output=True, text=True).stdout)
