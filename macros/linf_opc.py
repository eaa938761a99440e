# Batch entry point of the L-inf Voronoi OPC flow (see README, "Batch"):
#   klayout -b -r macros/linf_opc.py -rd cmd=voronoi|gauges|select|split|flow -rd input=FILE -rd layer=L/D
#           [-rd cell=NAME] -rd out=DIR ...   (arguments per command: plugin/python/linf_opc/batch.py)
# Run from a checkout it uses the checkout's sources and build; otherwise the installed package.
import os
import sys

_repo = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
if os.path.isdir(os.path.join(_repo, "plugin", "python", "linf_opc")):
    sys.path.insert(0, os.path.join(_repo, "build"))
    sys.path.insert(0, os.path.join(_repo, "plugin", "python"))

from linf_opc import batch  # noqa: E402

_args = {k: globals().get(k) for k in ("cmd", "input", "layer", "cell", "out", "window", "markers", "sizes", "modes",
                                     "mode", "size", "pitch", "halves", "max_norm", "split", "fraction", "seed",
                                     "threshold", "bin", "box", "tile", "rdb_max")}
sys.exit(batch.main(_args))
