"""The batch in plain Python: `python3 macros/linf_opc.py -rd cmd=... ...` runs the same commands
as `klayout -b -r macros/linf_opc.py -rd cmd=... ...`, on KLayout's standalone Python modules
(klayout.db, klayout.tl, klayout.rdb) instead of inside the application.

Why: `klayout -b` spends about 1.8 s before the first line of a script (registering every class
of the application, Qt's included, with both its Ruby and its Python); the standalone modules
load in about 0.3 s. The commands read and write through the same classes of the same KLayout
build, so the files are the same, byte for byte.

This module imports nothing of KLayout at its own import (the macro calls it before the package's
modules, which `import pya`). start() finds the modules, puts a `pya` in sys.modules that holds
klayout.tl, klayout.db and klayout.rdb (klayout.lay, the slowest to load, only on the first use
of a name they lack: a report's picture of a large layer); parse() turns the command line into
the arguments commands.main takes."""
import os
import shutil
import sys
import types

# Where a KLayout installation keeps its standalone modules, relative to the `klayout` program:
# Debian's package (/usr/bin/klayout, /usr/lib/klayout/pymod) and a build or Windows install
# (pymod beside the program). `pip install klayout` puts them on Python's own path instead.
_PYMOD_BESIDE = (os.path.join("..", "lib", "klayout", "pymod"), "pymod")
# Set on the one re-execution under KLayout's Python with its library folder (see _find).
_REEXEC = "LINF_OPC_STANDALONE_REEXEC"

# The loader's words for a shared library that a memory limit (ulimit -v) left no room to map.
_MEMORY = "failed to map segment"

NOT_FOUND = ("KLayout's Python modules (klayout.db) were not found: install KLayout (Debian: apt-get install "
             "klayout; elsewhere: pip install klayout), or run the batch as klayout -b -r macros/linf_opc.py ...")


class StartError(Exception):
    """The batch cannot start: a command line it does not take, or no KLayout modules."""


def parse(argv, names):
    """{name: value} from `-rd name=value` pairs, as `klayout -b` takes them. A name the commands
    do not read is an error here (under KLayout it would be an unused variable, silently)."""
    args = {}
    i = 0
    while i < len(argv):
        if argv[i] != "-rd" or i + 1 == len(argv) or "=" not in argv[i + 1]:
            raise StartError("unexpected argument %r: the batch takes -rd name=value pairs, as klayout -b does"
                             % argv[i + (1 if argv[i] == "-rd" and i + 1 < len(argv) else 0)])
        name, _, value = argv[i + 1].partition("=")
        if name not in names:
            raise StartError("unknown argument -rd %s; the arguments are: %s" % (name, ", ".join(sorted(names))))
        args[name] = value
        i += 2
    return args


def _installation():
    """(pymod, python) of the `klayout` program on PATH: the folder that holds its standalone
    `klayout` package, and the Python it was built for (the `python3` beside the program, where
    there is one: Debian's /usr/bin/python3, which KLayout embeds and the compiled module is built
    for; else this one). None if there is no such folder."""
    program = shutil.which("klayout")
    if not program:
        return None
    home = os.path.dirname(os.path.realpath(program))
    for rel in _PYMOD_BESIDE:
        pymod = os.path.normpath(os.path.join(home, rel))
        if os.path.isdir(os.path.join(pymod, "klayout")):
            python = os.path.join(os.path.dirname(program), "python3")
            return pymod, python if os.access(python, os.X_OK) else sys.executable
    return None


def _find():
    """Imports klayout.db, klayout.tl and klayout.rdb: from Python's own path (`pip install
    klayout`), else from the KLayout installation on PATH. That one's shared libraries
    (libklayout_*.so) lie in the folder above its pymod, which the loader only searches if
    LD_LIBRARY_PATH names it when the process starts; and its modules, like KLayout's own Python,
    are built for one Python (another on PATH, as pyenv's, may lack the system's packages, Dask
    among them). So the process runs again, once, under that Python with that folder named."""
    try:
        import klayout.db  # noqa: F401
        return
    except ImportError as e:
        if _MEMORY in str(e):  # found, but a memory limit left no room to load it: the macro says so
            raise
        if os.environ.get(_REEXEC):  # already run again: the installation's modules do not load
            raise StartError(NOT_FOUND)
    found = _installation()
    if found is None:
        raise StartError(NOT_FOUND)
    pymod, python = found
    libs = os.path.dirname(pymod)
    env = dict(os.environ, **{_REEXEC: "1"})
    for var, first in (("LD_LIBRARY_PATH", libs), ("PYTHONPATH", pymod)):
        env[var] = os.pathsep.join([first] + [p for p in env.get(var, "").split(os.pathsep) if p and p != first])
    sys.stdout.flush()
    sys.stderr.flush()
    os.execve(python, [python] + sys.argv, env)


def _pya():
    """A module standing for KLayout's `pya`: the names of klayout.tl, klayout.db and klayout.rdb,
    and klayout.lay's on first use."""
    import klayout.db
    import klayout.rdb
    import klayout.tl
    pya = types.ModuleType("pya", "KLayout's standalone modules, as the batch uses them (linf_opc.standalone)")
    for m in (klayout.tl, klayout.db, klayout.rdb):
        for k, v in vars(m).items():
            if not k.startswith("_"):
                setattr(pya, k, v)

    def more(name):
        if name.startswith("__"):
            raise AttributeError(name)
        # Without an application, Qt warns of menu actions the layout view cannot connect; they
        # mean nothing to a batch run.
        os.environ.setdefault("QT_LOGGING_RULES", "default.warning=false")
        import klayout.lay
        try:
            value = getattr(klayout.lay, name)
        except AttributeError:
            raise AttributeError("module 'pya' has no attribute %r" % name) from None
        setattr(pya, name, value)
        return value
    pya.__getattr__ = more
    return pya


def start():
    """Makes `pya` ready for the package's modules. May run the process again (_find). Raises
    StartError."""
    _find()
    sys.modules["pya"] = _pya()
