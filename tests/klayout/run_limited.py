# Runs the batch macro (macros/linf_opc.py, every -rd argument passed on) under an address-space
# limit (RLIMIT_AS) of the process's present size plus -rd limit_mb=N: a memory limit far below
# a run's need that still lets KLayout itself start, whatever KLayout needs on this machine.
#   klayout -b -r tests/klayout/run_limited.py -rd limit_mb=64 -rd cmd=flow -rd input=... -rd out=...
import os as _os
import resource as _resource
import runpy as _runpy
import sys as _sys

_macro = _os.path.join(_os.path.dirname(_os.path.dirname(_os.path.dirname(_os.path.abspath(__file__)))),
                       "macros", "linf_opc.py")
with open("/proc/self/status") as _f:
    _size = next(int(line.split()[1]) * 1024 for line in _f if line.startswith("VmSize:"))
_limit = _size + int(globals().get("limit_mb") or 64) * 1024 * 1024
_resource.setrlimit(_resource.RLIMIT_AS, (_limit, _resource.getrlimit(_resource.RLIMIT_AS)[1]))
_sys.stderr.write("run_limited: RLIMIT_AS %d MB (the process had %d MB)\n" % (_limit >> 20, _size >> 20))
_code = 0
try:
    _runpy.run_path(_macro, init_globals={k: v for k, v in globals().items() if not k.startswith("_")},
                    run_name="__main__")
except SystemExit as _e:  # KLayout takes a SystemExit's code only from the script's own frame
    _code = _e.code
_sys.exit(_code)
