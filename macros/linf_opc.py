# Batch entry point of the L-inf Voronoi OPC flow (README, "Batch commands"):
#   python3 macros/linf_opc.py -rd cmd=voronoi|gauges|select|split|flow|farthest -rd input=FILE -rd layer=L/D
#           [-rd cell=NAME] -rd out=DIR ...   (arguments per command: plugin/python/linf_opc/commands.py)
# or the same arguments after `klayout -b -r macros/linf_opc.py`: the same files. In plain Python it
# runs on KLayout's standalone modules (plugin/python/linf_opc/standalone.py) and starts about 1.8 s sooner.
# Run from a checkout it uses the checkout's sources and build; otherwise the installed package.
import os
import sys

_repo = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
if os.path.isdir(os.path.join(_repo, "plugin", "python", "linf_opc")):
    sys.path.insert(0, os.path.join(_repo, "build"))
    sys.path.insert(0, os.path.join(_repo, "plugin", "python"))


def _starting_out_of_memory(e):
    """A memory limit that leaves no room even for the package shows as a MemoryError, as a shared
    object the loader could not map (ImportError), or as CPython's SystemError from an allocation
    that failed inside an import."""
    if isinstance(e, (MemoryError, SystemError)):
        return True
    text = str(e)
    return isinstance(e, ImportError) and ("failed to map segment" in text or "Cannot allocate memory" in text)


_OUT_OF_MEMORY = ("linf_opc: error: out of memory while starting: the process's memory limit (ulimit -v, "
                  "RLIMIT_AS) is too small; nothing written\n")
_in_klayout = "pya" in sys.modules  # KLayout's own Python has it before any script runs
try:
    _reserve = bytearray(1 << 20)  # given back before the handler runs: handling needs memory too
    if not _in_klayout:
        from linf_opc import standalone  # noqa: E402
        try:
            standalone.start()
        except standalone.StartError as e:
            sys.stderr.write("linf_opc: error: %s\n" % e)
            sys.exit(2)
    from linf_opc import commands, faults  # noqa: E402
except Exception as e:  # noqa: BLE001
    _reserve = None
    if not _starting_out_of_memory(e):
        raise
    sys.stderr.write(_OUT_OF_MEMORY)
    sys.exit(2)
_reserve = None

if _in_klayout:  # the -rd arguments are the script's global variables
    _args = {k: globals().get(k) for k in commands.ARGUMENTS}
elif sys.argv[1:] in (["-h"], ["--help"]):
    sys.stdout.write("usage:\n" + commands.__doc__.split("\n\n", 1)[1])  # the docstring past its opening
    sys.exit(0)
else:
    try:
        _args = standalone.parse(sys.argv[1:], commands.ARGUMENTS)
    except standalone.StartError as e:
        sys.stderr.write("linf_opc: error: %s\n" % e)
        sys.exit(2)
# faults.run: a full disk, a read-only folder or a memory limit give one line and exit 2, not a stack.
sys.exit(faults.run(commands.main, _args))
