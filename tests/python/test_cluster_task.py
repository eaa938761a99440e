# What a Dask worker runs for a tile (linf_opc/cluster_task.py) keeps large arrays on the heap
# even under the nanny's MALLOC_TRIM_THRESHOLD_=65536, which otherwise pins glibc's mmap
# threshold at 128 KB (every tile's arrays mapped and zeroed afresh).
#   PYTHONPATH=plugin/python:build python3 tests/python/test_cluster_task.py
import os
import subprocess
import sys
import unittest

# Run in a child with the nanny's environment: the thresholds are read at the first malloc.
CHILD = r"""
import ctypes, sys
from linf_opc import cluster_task

libc = ctypes.CDLL("libc.so.6")

class Mallinfo2(ctypes.Structure):
    _fields_ = [(n, ctypes.c_size_t) for n in
                ("arena", "ordblks", "smblks", "hblks", "hblkhd", "usmblks", "fsmblks", "uordblks", "fordblks",
                 "keepcost")]

libc.mallinfo2.restype = Mallinfo2
libc.malloc.restype = ctypes.c_void_p
libc.free.argtypes = [ctypes.c_void_p]

def mapped_by(size):
    # Whether a block of this size comes from its own mapping (hblks counts those).
    before = libc.mallinfo2().hblks
    p = libc.malloc(size)
    after = libc.mallinfo2().hblks
    libc.free(p)
    return after > before

def kept_after_free(size):
    # Whether the heap keeps a freed block's pages for the next one (no trim below the threshold).
    p = libc.malloc(size)
    held = libc.mallinfo2().arena
    libc.free(p)
    return libc.mallinfo2().arena >= held

size = 4 << 20  # a tile's typical array: above 128 KB, below 32 MB
first = mapped_by(size)
cluster_task.reuse_freed_memory()
print(int(first), int(mapped_by(size)), int(mapped_by(64 << 20)), int(kept_after_free(size)))
"""


class WorkerAllocator(unittest.TestCase):
    def run_child(self, **env):
        e = dict(os.environ, **env)
        out = subprocess.run([sys.executable, "-c", CHILD], env=e, capture_output=True, text=True, timeout=60)
        self.assertEqual(out.returncode, 0, out.stderr)
        return [int(v) for v in out.stdout.split()]

    def test_large_arrays_stay_on_the_heap_under_the_nannys_setting(self):
        before, after, huge, kept = self.run_child(MALLOC_TRIM_THRESHOLD_="65536")
        self.assertEqual(before, 1, "the nanny's setting should map a 4 MB block: the premise does not hold")
        self.assertEqual(after, 0, "a 4 MB block is still mapped after reuse_freed_memory")
        self.assertEqual(huge, 1, "blocks above the threshold should still be mapped")
        self.assertEqual(kept, 1, "the heap gave a freed 4 MB block back: the trim threshold is still the nanny's")


if __name__ == "__main__":
    unittest.main()
