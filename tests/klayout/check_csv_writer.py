# The core's voronoi.csv writer (C++, used by the batch) writes the same bytes as the Python
# writer row by row, on one layout:
#   klayout -b -r tests/klayout/check_csv_writer.py -rd input=FILE -rd layer=L/D -rd work=DIR
import filecmp
import os
import sys

repo = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
sys.path.insert(0, os.path.join(repo, "build"))
sys.path.insert(0, os.path.join(repo, "plugin", "python"))

import pya  # noqa: E402

from linf_opc import diagram, layout, output  # noqa: E402

g = globals()
os.makedirs(g["work"], exist_ok=True)
ly = pya.Layout()
ly.read(g["input"])
L, D = layout.parse_layer(g["layer"])
polygons = layout.polygons_of(layout.region_of(ly.top_cells()[0], ly.find_layer(L, D)))
core_csv, py_csv = os.path.join(g["work"], "core.csv"), os.path.join(g["work"], "python.csv")
d = diagram.compute(polygons, csv_path=core_csv, dbu=ly.dbu)
d.csv_path = None  # make output.write_csv write its own
output.write_csv(d, py_csv, ly.dbu)
same = filecmp.cmp(core_csv, py_csv, shallow=False)
rows = sum(1 for _ in open(core_csv)) - 1
print("csv writer on %s: %d rows (%d pieces), core %.3f s, %s" % (os.path.basename(g["input"]), rows, len(d.pieces),
                                                                   d.seconds["csv"], "identical" if same else "DIFFERENT"))
sys.exit(0 if same and rows == len(d.pieces) and rows > 0 else 1)
