# Batch entry point of the L-inf Voronoi OPC flow (README, "Batch commands"):
#   klayout -b -r macros/linf_opc.py -rd cmd=voronoi|gauges|select|split|flow|farthest -rd input=FILE -rd layer=L/D
#           [-rd cell=NAME] -rd out=DIR ...   (arguments per command: plugin/python/linf_opc/commands.py)
# Run from a checkout it uses the checkout's sources and build; otherwise the installed package.
import os
import sys

_repo = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
if os.path.isdir(os.path.join(_repo, "plugin", "python", "linf_opc")):
    sys.path.insert(0, os.path.join(_repo, "build"))
    sys.path.insert(0, os.path.join(_repo, "plugin", "python"))

try:
    from linf_opc import commands, faults  # noqa: E402
except MemoryError:  # a memory limit that leaves no room even for the package
    sys.stderr.write("linf_opc: error: out of memory while starting: the process's memory limit (ulimit -v, "
                     "RLIMIT_AS) is too small; nothing written\n")
    sys.exit(2)

# faults.run: a full disk, a read-only folder or a memory limit give one line and exit 2, not a stack.
sys.exit(faults.run(commands.main, {k: globals().get(k) for k in commands.ARGUMENTS}))
