"""Temporary GDSII files for the core's drawings (no KLayout here: the stages that ask for
one run without it). output.copy_drawing puts their shapes into a layout: KLayout reads the
file and copies its shapes in C++, several times faster than inserting them one by one from
Python (11-14 us a shape), which on a full layer would take minutes. The gauge columns' file
(gauges.columns_file) is made, mapped and removed here too, and the layer's spilled arrays
(polygons.Polygons.spill) are mapped here."""
import mmap
import os
import tempfile


def temporary(prefix="linf_opc-drawing-", suffix=".gds"):
    """A fresh temporary file for the core to write into (its GDSII drawings by default)."""
    fd, path = tempfile.mkstemp(prefix=prefix, suffix=suffix)
    os.close(fd)
    return path


def mapped(path):
    """The file's bytes as a read-only mmap (b"" if empty); the file is removed at once. The pages
    stay the kernel's to drop and read again: a full layer's arrays are hundreds of MB."""
    try:
        return mapped_file(open(path, "rb"))
    finally:
        remove(path)


def mapped_file(f):
    """An open file's bytes as a read-only mmap (b"" if empty); the file is closed (the map keeps
    what it needs of it)."""
    with f:
        f.flush()
        return mmap.mmap(f.fileno(), 0, access=mmap.ACCESS_READ) if os.fstat(f.fileno()).st_size else b""


def remove(path):
    try:
        os.remove(path)
    except OSError:
        pass


def drawn_by(call, draw):
    """call(path): path a fresh temporary file when `draw`, else "" (nothing to draw). The file
    is removed if the call fails; else it is the caller's. Returns (result, path or None)."""
    path = temporary() if draw else None
    try:
        return call(path or ""), path
    except BaseException:
        if path:
            remove(path)
        raise
