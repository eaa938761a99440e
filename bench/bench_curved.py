# Speed of the diagram on curved shapes (disks and rings drawn with many vertices, as round
# pads, bends and curvilinear masks are), against CGAL's raw construction of the same sites in
# the same run:
#   python3 bench/bench_curved.py [--threads N]
# Needs only the compiled module in build/ (no KLayout). "ours" = merge + build + check, one
# thread unless told; CGAL runs in its own process with a deadline (it can hang or crash).
import argparse
import json
import math
import os
import subprocess
import sys
import tempfile
import time

repo = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(repo, "build"))
import linf_opc_core as core  # noqa: E402


def regular(n, r, cx=0, cy=0):
    return [(cx + int(round(r * math.cos(2 * math.pi * k / n))), cy + int(round(r * math.sin(2 * math.pi * k / n))))
            for k in range(n)]


def cgal_seconds(polygons, deadline):
    with tempfile.TemporaryDirectory() as tmp:
        data = os.path.join(tmp, "polygons.json")
        with open(data, "w") as f:
            json.dump(polygons, f)
        try:
            run = subprocess.run([sys.executable, os.path.join(repo, "bench", "cgal_baseline.py"), data, "1"],
                                 capture_output=True, text=True, timeout=deadline)
        except subprocess.TimeoutExpired:
            return None
        return float(run.stdout.split()[-1]) if run.returncode == 0 else None


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--threads", type=int, default=1)
    ap.add_argument("--deadline", type=float, default=600)
    args = ap.parse_args()
    inputs = [
        ("disk, 256 vertices, r = 1,000 DBU", [(regular(256, 1000), [])]),
        ("disk, 1,024 vertices, r = 10^6 DBU", [(regular(1024, 10 ** 6), [])]),
        ("disk, 2,048 vertices, r = 50,000 DBU (vertices on the grid: near-collinear runs)",
         [(regular(2048, 50000), [])]),
        ("disk, 4,096 vertices, r = 10^7 DBU", [(regular(4096, 10 ** 7), [])]),
        ("ring, 1,024 + 512 vertices", [(regular(1024, 10 ** 6), [list(reversed(regular(512, 4 * 10 ** 5, 120000, -70000)))])]),
        ("25 disks of 256 vertices", [(regular(256, 1000 + 37 * k, 3000 * (k % 5), 3000 * (k // 5)), []) for k in range(25)]),
    ]
    print("| input | sites | pieces | ours (merge + build + check) | CGAL construction | ratio |")
    print("|---|---|---|---|---|---|")
    for name, polygons in inputs:
        t = time.perf_counter()
        r = core.voronoi_polygons(polygons, check=True, pieces=False, threads=args.threads)
        ours = time.perf_counter() - t
        if not r["check"]["ok"]:
            sys.exit("%s: the check failed" % name)
        cgal = cgal_seconds(polygons, args.deadline)
        ratio = "%.0f" % (ours / cgal) if cgal else "-"
        print("| %s | %d | %d | %.2f s | %s | %s |" % (name, r["sites"], r["pieces"], ours,
                                                   "%.3f s" % cgal if cgal else "no result", ratio), flush=True)


if __name__ == "__main__":
    main()
