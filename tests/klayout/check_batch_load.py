# The batch reads only the layers a command needs (inputs.load): the working layer and a marker
# layer, with the same shapes as a plain read, and the same errors for layers the file lacks.
#   klayout -b -r tests/klayout/check_batch_load.py -rd work=DIR
import os
import sys

import pya

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from harness import arg, expect, finish  # noqa: E402

from linf_opc import inputs, markers as marker_io  # noqa: E402


def layers(ly):
    """{(L, D): shapes under the top cell, hierarchy flattened}"""
    top = ly.top_cells()[0]
    return {(ly.get_info(i).layer, ly.get_info(i).datatype): pya.Region(top.begin_shapes_rec(i)).count()
            for i in ly.layer_indexes()}


work = arg("work", "/tmp/linf_batch_load")
os.makedirs(work, exist_ok=True)
path = os.path.join(work, "layers.oas")
ly = pya.Layout()
top, sub = ly.create_cell("TOP"), ly.create_cell("SUB")
for k, (l, d) in enumerate([(1, 0), (2, 0), (1, 5), (100, 0)]):
    for i in range(4 + k):
        sub.shapes(ly.layer(l, d)).insert(pya.Box(100 * i, 1000 * k, 100 * i + 50, 1000 * k + 500))
top.shapes(ly.layer(1, 0)).insert(pya.Box(-500, -500, -100, -100))
top.insert(pya.CellInstArray(sub.cell_index(), pya.Trans(pya.Point(0, 0))))
top.insert(pya.CellInstArray(sub.cell_index(), pya.Trans(pya.Point(0, 9000))))
ly.write(path)
plain = pya.Layout()
plain.read(path)
whole = layers(plain)

for markers, want in [("100/0", {(1, 0), (100, 0)}), ("1/0", {(1, 0)}), (os.path.join(work, "hotspots.csv"), {(1, 0)}),
                      (None, {(1, 0)})]:
    got_ly, cell, index, ld = inputs.load({"input": path, "layer": "1/0", "markers": markers})
    got = layers(got_ly)
    expect(set(got) == want, "markers %s: layers read %s, want %s" % (markers, sorted(got), sorted(want)))
    expect(all(got[k] == whole[k] for k in got), "markers %s: the same shapes as a plain read: %s vs %s"
           % (markers, got, whole))
    expect(cell.name == "TOP" and ld == (1, 0) and got_ly.get_info(index).datatype == 0, "the cell and the layer")
# A layer the file does not have: the same message as before, not "empty".
try:
    inputs.load({"input": path, "layer": "5/0"})
    expect(False, "layer 5/0 is not in the file: an error")
except inputs.UsageError as e:
    expect("is not in" in str(e), "layer 5/0: %s" % e)
got_ly, cell, _, _ = inputs.load({"input": path, "layer": "1/0", "markers": "7/0"})
try:
    marker_io.load("7/0", got_ly, cell)
    expect(False, "marker layer 7/0 is not in the file: an error")
except marker_io.MarkerError as e:
    expect("not in the layout" in str(e), "marker layer 7/0: %s" % e)
expect(marker_io.layer_of("100/0") == (100, 0) and marker_io.layer_of("x.csv") is None
       and marker_io.layer_of("a.lyrdb@um") is None and marker_io.layer_of("") is None, "marker_io.layer_of")

finish()
