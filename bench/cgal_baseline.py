# Times CGAL's construction on polygons stored as JSON; run in its own process by
# bench_diagram.py because CGAL can hang or crash on real layouts.
#   python3 bench/cgal_baseline.py POLYGONS.json SEED   -> prints seconds
import json
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "build"))
import linf_opc_cgal  # noqa: E402  (built with the tests or -DLINF_BENCH=ON; not shipped)

polygons = [(outer, holes) for outer, holes in json.load(open(sys.argv[1]))]
print(linf_opc_cgal.cgal_construction_seconds(polygons, int(sys.argv[2])))
