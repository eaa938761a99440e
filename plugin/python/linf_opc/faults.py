"""What the machine can do to a batch run that no argument caused: a full disk, a folder that
turned read-only, a memory limit. commands.main answers the user's own errors (exit 2) and a
diagram failing its check (exit 3); it removes the staging folder on any exception and lets the
others through. They arrive here and become one line `linf_opc: error: ...` with exit 2, never a
stack: by then nothing of the run is left in the output folder, and earlier files are intact."""
import errno
import os
import re
import sys

from .staging import PARTIAL_PREFIX

# The core's and KLayout's messages for a file that could not be written or a failed allocation
# (the core raises std::runtime_error, which reaches Python as RuntimeError).
_IO_OR_MEMORY = re.compile(r"cannot write|error writing|write error|cannot create a temporary file|disk full|"
                           r"no space left|errno=28|errno=30|read-only file system|cannot read the diagram's "
                           r"temporary file|bad_alloc|out of memory|cannot allocate|resource temporarily unavailable",
                           re.IGNORECASE)
# Of those, the ones that mean memory: an allocation, or a thread the limit left no room for
# (std::system_error EAGAIN: "Resource temporarily unavailable").
_MEMORY = re.compile(r"bad_alloc|out of memory|cannot allocate|resource temporarily unavailable", re.IGNORECASE)

EXIT = 2
OUT_OF_MEMORY = ("out of memory: the process's memory limit (ulimit -v, RLIMIT_AS) or the machine is too small "
                 "for this input; nothing written")


def _final(text):
    """A path in the staging folder named as where the file was going (the staging folder is gone)."""
    return re.sub(re.escape(os.sep + PARTIAL_PREFIX) + r"[^" + re.escape(os.sep) + r"]*", "", text)


def message(e, out=None):
    """The one line for an environment fault, or None for an exception that is a program error
    (left to show its stack). `out`: the run's output folder, named where the error names no file."""
    if isinstance(e, MemoryError):
        return OUT_OF_MEMORY
    if isinstance(e, OSError):
        what = e.strerror or str(e)
        where = " %s" % _final(str(e.filename)) if e.filename else (" into %s" % out if out else "")
        if e.errno in (errno.ENOSPC, errno.EDQUOT):
            return "no space left on the device while writing%s; nothing written" % where
        if e.errno == errno.ENOMEM:
            return "out of memory while writing%s; nothing written" % where
        if e.errno in (errno.EROFS, errno.EACCES, errno.EPERM):
            return "cannot write%s: %s; nothing written" % (where, what)
        return "%s%s; nothing written" % (what, " (%s)" % e.filename if e.filename else "")
    if isinstance(e, RuntimeError):
        first = (str(e).splitlines() or [""])[0].strip()
        if _IO_OR_MEMORY.search(first):
            if _MEMORY.search(first):
                return OUT_OF_MEMORY
            first = _final(first)
            m = re.match(r"(?:error writing|cannot write) (.*)$", first)
            if m:  # the core's writers say no more than this: the device was full, or the file not writable
                return "cannot write %s (the disk is full or the folder not writable); nothing written" % m.group(1)
            return "%s; nothing written" % first
    return None


def run(main, args):
    """main(args) -> exit code, with environment faults turned into one line and exit 2."""
    try:
        return main(args)
    except (MemoryError, OSError, RuntimeError) as e:
        line = message(e, os.path.abspath(args["out"]) if args.get("out") else None)
        if line is None:
            raise
        try:
            sys.stderr.write("linf_opc: error: %s\n" % line)
            sys.stderr.flush()
        except (OSError, MemoryError):
            pass
        return EXIT
