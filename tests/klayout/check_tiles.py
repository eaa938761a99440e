# The flow cut into tiles gives the flow in one piece: for several tile sizes, the batch macro's
# cmd=flow writes the same voronoi.csv, gauges.csv (both on request: diagram=1, all_gauges=1),
# windows.csv and split lists, byte for byte; and so does the sweep-line builder (builder=sweep).
#   klayout -b -r tests/klayout/check_tiles.py -rd input=FILE -rd layer=L/D -rd markers=SPEC [-rd cell=NAME]
#           -rd work=DIR [-rd parts=1.5,3,20] [-rd swept=1|0]
# Tile sizes are the layer's extent divided by each of `parts`; summary.json must show that the
# builder did cut the layer into more than one tile, and how many sites its largest tile held.
# swept: whether the sweep takes the layer (1, the default: a Manhattan layer) or the
# subdivision builds it in its place (0: slanted edges).
import filecmp
import json
import os
import subprocess
import sys

import pya

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from harness import BATCH, arg, expect, finish, repo  # noqa: E402

work = arg("work", "/tmp/linf_tiles_check")
FILES = ["voronoi.csv", "gauges.csv", "windows.csv", "calibration_gauges.csv", "verification_gauges.csv"]


def flow(tile, out, builder="subdivision"):
    args = ["-rd", "cmd=flow", "-rd", "input=" + arg("input"), "-rd", "layer=" + arg("layer"), "-rd",
            "markers=" + arg("markers"), "-rd", "out=" + out, "-rd", "tile=" + tile,
            "-rd", "all_gauges=1", "-rd", "diagram=1", "-rd", "builder=" + builder]
    if arg("cell", None):
        args += ["-rd", "cell=" + arg("cell")]
    r = subprocess.run(BATCH + args,
                       capture_output=True, text=True)
    print("tile=%s: %s" % (tile, r.stdout.strip() or r.stderr.strip()))
    expect(r.returncode == 0, "flow with tile=%s exits %d" % (tile, r.returncode))
    with open(os.path.join(out, "summary.json")) as f:
        return json.load(f)["voronoi"]


ly = pya.Layout()
ly.read(arg("input"))
top = ly.cell(arg("cell")) if arg("cell", None) else ly.top_cells()[0]
L, D = (int(v) for v in arg("layer").split("/"))
box = top.dbbox_per_layer(ly.find_layer(L, D))
extent = max(box.width(), box.height())

ref = flow("0", os.path.join(work, "whole"))
expect(ref["tiles"]["tiles"] == 1, "tile=0 builds one tile")
for parts in (float(v) for v in arg("parts", "1.5,3,20").split(",")):
    tile = "%.4f" % (extent / parts)
    out = os.path.join(work, "tile_%g" % parts)
    s = flow(tile, out)
    t = s["tiles"]
    print("  %d tiles of %d tasks, largest tile %d of %d sites" % (t["tiles"], t["tasks"], t["largest_tile_sites"],
                                                                  s["sites"]))
    expect(t["tiles"] > 1, "tile=%s um cuts the layer into tiles" % tile)
    for name in FILES:
        same = filecmp.cmp(os.path.join(work, "whole", name), os.path.join(out, name), shallow=False)
        expect(same, "%s with tile=%s um differs from the untiled run" % (name, tile))

out = os.path.join(work, "sweep")
s = flow("0", out, "sweep")
wanted = "sweep" if arg("swept", "1") == "1" else "subdivision"
expect(s["builder"] == wanted, "asked for the sweep, the %s built it, not the %s" % (wanted, s["builder"]))
for name in FILES:
    same = filecmp.cmp(os.path.join(work, "whole", name), os.path.join(out, name), shallow=False)
    expect(same, "%s with builder=sweep differs from the subdivision's" % name)

finish("on %s %s" % (os.path.basename(arg("input")), arg("layer")))
