"""The batch commands behind macros/linf_opc.py: which arguments each takes, which function
(runs.py) runs it, and main().

  python3 macros/linf_opc.py -rd cmd=COMMAND -rd input=FILE -rd layer=L/D [-rd cell=NAME] -rd out=DIR
           [-rd tile=UM|0|auto]  (the diagram builder's tiles; the same pieces for any size)
           [-rd builder=sweep|subdivision]  (sweep, the default: the sweep-line builder, on any layer; the
           subdivision builder, several times slower; the same pieces)
           [-rd check=sample|full]  (the independent check: sampled search for closer sites, or on every piece)
           [-rd scheduler=tcp://HOST:PORT]  (voronoi, gauges, select, split, flow: the tiles built on that
           Dask cluster's workers; the same files)
           [-rd quiet=0|1]  (1: no progress lines on stderr)
  voronoi  the diagram: voronoi.csv, voronoi.oas, summary.json
  gauges   [-rd window=X1,Y1,X2,Y2] (um: the per-pattern mode) [-rd rdb_max=100000] (gauges.lyrdb holds the
           most critical rdb_max of each type, 0 all): gauges.csv, gauges.lyrdb, gauges.oas, summary.json
  select   -rd markers=SPEC [-rd sizes=5,6,7,8] [-rd modes=A,B,C] [-rd mode=A] [-rd size=K] [-rd pitch=UM]
           [-rd max_norm=1] [-rd halves=0|1] (1: Table 5.9's experiment) [-rd pattern_classes=area|edge|off]
           [-rd class_area=0.05] [-rd class_edge=UM] (windows alike are one class): windows.csv,
           pattern_classes.csv, windows.lyrdb, windows.oas, stats.json, report.html
  split    the select arguments and [-rd split=plan|threshold|stratified] [-rd budget=1000] [-rd verify=BUDGET]
           [-rd context_radius=UM] (plan; default half the window) [-rd fraction=0.3] [-rd seed=1] (stratified)
           [-rd threshold=0.1] [-rd bin=0.025]: the select outputs, calibration.oas, verification.oas,
           calibration_gauges.csv, verification_gauges.csv, split.json (windows.lyrdb items tagged)
  flow     voronoi -> gauges -> select -> split in one run, the diagram built once: the split and select
           outputs (flow.lyrdb instead of windows.lyrdb, with the rdb_max=100 most critical gauges of each
           type), summary.json; on request [-rd all_gauges=1] gauges.csv, gauges.lyrdb, gauges.oas and
           [-rd diagram=1] voronoi.csv, voronoi.oas
  gauges, select, split, flow: [-rd litho=duv193|euv|iccad13|DIR] the gauges scored and ranked by printability on
           that lithography model (gauges.csv gains geo_score, printed_cd, pv_band, fails); with [-rd opc=1]
           the layer is read after an emulated model-based OPC, not as drawn
  farthest [-rd box=X1,Y1,X2,Y2] (um: shapes meeting the box): farthest.csv, farthest.oas, summary.json
"""
import sys

from . import cluster
from . import core
from . import runs
from .arguments import UsageError
from .staging import Staging

_LAYER = ("input", "layer", "cell", "out", "markers", "quiet")  # a marker layer is read with the layer
_SELECT = ("sizes", "modes", "mode", "size", "pitch", "max_norm", "halves", "pattern_classes", "class_area",
           "class_edge")
# The diagram's construction: its tiles' size, a Dask cluster to build them on, the builder, the check.
_TILES = ("tile", "scheduler", "builder", "check")
_SPLIT = ("split", "budget", "verify", "context_radius", "fraction", "seed", "threshold", "bin")

# name: (the function that runs it, the arguments it reads)
COMMANDS = {
    "farthest": (runs.cmd_farthest, _LAYER + ("box",)),
    "voronoi": (runs.cmd_voronoi, _LAYER + _TILES),
    "gauges": (runs.cmd_gauges, _LAYER + _TILES + ("window", "rdb_max", "litho", "opc")),
    "select": (runs.cmd_select, _LAYER + _TILES + ("litho", "opc") + _SELECT),
    "split": (runs.cmd_split, _LAYER + _TILES + ("litho", "opc") + _SELECT + _SPLIT),
    "flow": (runs.cmd_flow, _LAYER + _TILES + ("rdb_max", "all_gauges", "diagram", "litho", "opc") + _SELECT + _SPLIT),
}

# Every argument name, for the macro to collect (a command ignores those it does not read).
ARGUMENTS = ("cmd",) + tuple(dict.fromkeys(a for _, names in COMMANDS.values() for a in names))


def main(args):
    """Runs one command; returns the process exit code (0 ok, 2 usage/input, 3 core failure)."""
    cmd = args.get("cmd")
    try:
        if cmd not in COMMANDS:
            raise UsageError("unknown or missing -rd cmd=%s; one of: %s" % (cmd, ", ".join(sorted(COMMANDS))))
        run, names = COMMANDS[cmd]
        address = cluster.parse_address(args.get("scheduler")) if "scheduler" in names else None
        if address is None:
            line = run(args)
        else:
            with cluster.tiles_on(address):  # connected before anything is read or written
                line = run(args)
        Staging.finish_all(True)
        print(line)
        return 0
    except (UsageError, ValueError, cluster.ClusterError) as e:
        Staging.finish_all(False)
        sys.stderr.write("linf_opc: error: %s\n" % e)
        return 2
    except core.DiagramError as e:
        Staging.finish_all(False)
        sys.stderr.write("linf_opc: the diagram failed its independent check, nothing written: %s\n" % e)
        return 3
    except BaseException:
        Staging.finish_all(False)
        raise
