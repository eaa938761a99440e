# Timing of the farthest-site diagram on random segments (not a timed test):
#   python3 bench/bench_farthest.py [N ...]        (default 100000 1000000)
# Segments in a 10^6 square, any angle, crossing; prints the time, the faces and the root.
import os
import random
import sys
import time

sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "build"))
import linf_opc_core as core  # noqa: E402

for n in [int(v) for v in sys.argv[1:]] or [100000, 1000000]:
    rng = random.Random(n)
    sites = [[(rng.randrange(10 ** 6), rng.randrange(10 ** 6)), (rng.randrange(10 ** 6), rng.randrange(10 ** 6))]
             for _ in range(n)]
    t0 = time.perf_counter()
    r = core.farthest_voronoi(sites)
    t = time.perf_counter() - t0
    print("%8d segments: %.2f s (%.2f us per segment), %d faces, %d vertices, half-side %.1f"
          % (n, t, 1e6 * t / n, len(r["faces"]), len(r["vertices"]), r["root"][4]))
