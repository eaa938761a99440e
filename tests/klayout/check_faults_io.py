# The fault matrix's rows for files, markers and the environment (docs/testing.md, "Fault
# matrix"): each hostile input or fault through the batch macro gives a correct result (exit 0,
# outputs checked) or exit 2 with one line `linf_opc: error: ...`, nothing written and the
# earlier outputs in the folder intact; never a traceback, never another exit code.
#   klayout -b -r tests/klayout/check_faults_io.py -rd case=NAME -rd work=DIR
# One case a run (one ctest each, tests/faults_io.cmake); CASES lists them.
import csv
import gzip
import json
import os
import random
import shutil
import signal
import subprocess
import sys
import tempfile
import time

import pya

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import harness  # noqa: E402
from harness import arg, expect, finish, repo  # noqa: E402

harness.report_ok = True
MACRO = os.path.join(repo, "macros", "linf_opc.py")
SAMPLE = os.path.join(repo, "samples", "metal.oas")
case = arg("case")
work = os.path.abspath(arg("work"))
shutil.rmtree(work, ignore_errors=True)
os.makedirs(work)
skip_reason = None


def command(*args, script=MACRO):
    return ["klayout", "-b", "-r", script] + [x for a in args for x in ("-rd", a)]


def run(*args, prefix=(), env=None, script=MACRO):
    """(exit code, stdout, stderr, seconds) of the macro with -rd args."""
    t0 = time.perf_counter()
    r = subprocess.run(list(prefix) + command(*args, script=script), capture_output=True, text=True, env=env)
    return r.returncode, r.stdout, r.stderr, time.perf_counter() - t0


def snapshot(folder):
    """Every entry of the folder (hidden ones too) with its bytes; None for a missing folder."""
    if not os.path.isdir(folder):
        return None
    out = {}
    for name in sorted(os.listdir(folder)):
        p = os.path.join(folder, name)
        out[name] = open(p, "rb").read() if os.path.isfile(p) else "<dir>"
    return out


def earlier_outputs(folder):
    """A real earlier run's files in `folder` (cmd=voronoi on the sample); their snapshot."""
    code, out, err, _ = run("cmd=voronoi", "input=" + SAMPLE, "layer=1/0", "out=" + folder, "quiet=1")
    expect(code == 0 and os.path.isfile(os.path.join(folder, "voronoi.csv")),
           "an earlier run's outputs in %s (exit %d)" % (folder, code))
    return snapshot(folder)


def no_stack(code, out, err, what):
    text = out + err
    expect(code in (0, 2, 3), "%s: exit code %d is one of 0, 2, 3" % (what, code))
    expect("Traceback" not in text and "ERROR:" not in text and "Backtrace" not in text,
           "%s: no traceback or KLayout ERROR (%s)" % (what, text.strip()[-200:]))


def clean_failure(code, out, err, what, folder, before, message):
    """Exit 2, exactly one error line (matching `message`), no stack; the folder as before."""
    no_stack(code, out, err, what)
    errors = [line for line in err.splitlines() if line.startswith("linf_opc: error: ")]
    others = [line for line in err.splitlines() if line and not line.startswith("linf_opc: ")]
    expect(code == 2, "%s: exit 2 (got %d)" % (what, code))
    expect(len(errors) == 1 and message in errors[0] and not others and not out.strip(),
           "%s: one line 'linf_opc: error: ...%s...' (%s)" % (what, message, err.strip()[-300:]))
    expect(snapshot(folder) == before, "%s: the output folder as it was (earlier files intact, nothing "
           "partial, no staging folder or lock left): %s" % (what, sorted(snapshot(folder) or [])))
    return errors[0] if errors else ""


def sample_layout():
    ly = pya.Layout()
    ly.read(SAMPLE)
    return ly


def voronoi_rows(folder):
    return open(os.path.join(folder, "voronoi.csv"), "rb").read()


def layer_counts(path):
    """{(layer, datatype): shapes} of a layout file; {} (and a failed expectation) if KLayout cannot read it."""
    ly = pya.Layout()
    try:
        ly.read(path)
    except RuntimeError as e:
        expect(False, "KLayout reads %s (%s)" % (path, str(e).splitlines()[0]))
        return {}
    return {(ly.get_info(i).layer, ly.get_info(i).datatype): sum(c.shapes(i).size() for c in ly.each_cell())
            for i in ly.layer_indexes()}


def grid_layout(path, nx, ny, layer=1):
    """nx x ny copies of a wide and a narrow wire: a layer heavy enough to take a while."""
    ly = pya.Layout()
    ly.dbu = 0.001
    top = ly.create_cell("TOP")
    unit = ly.create_cell("W")
    li = ly.layer(layer, 0)
    unit.shapes(li).insert(pya.Box(0, 0, 100, 300))
    unit.shapes(li).insert(pya.Box(200, 0, 260, 140))
    top.insert(pya.CellInstArray(unit.cell_index(), pya.Trans(), pya.Vector(400, 0), pya.Vector(0, 500), nx, ny))
    ly.write(path)
    return path


def bad_layout_file(name, data):
    """A broken layout file: the input row's check on it, with earlier outputs in the folder."""
    path = os.path.join(work, name)
    with open(path, "wb") as f:
        f.write(data)
    folder = os.path.join(work, "out")
    before = earlier_outputs(folder)
    code, out, err, _ = run("cmd=flow", "input=" + path, "layer=1/0", "markers=100/0", "out=" + folder)
    return code, out, err, folder, before


# ---- Files ----------------------------------------------------------------------------------------

def case_truncated_gds():
    gds = os.path.join(work, "metal.gds")
    sample_layout().write(gds)
    data = open(gds, "rb").read()
    for cut in (len(data) // 2, len(data) - 4, 6):
        code, out, err, folder, before = bad_layout_file("cut%d.gds" % cut, data[:cut])
        clean_failure(code, out, err, "GDS cut at byte %d of %d" % (cut, len(data)), folder, before, "cannot read")


def case_truncated_oasis():
    data = open(SAMPLE, "rb").read()
    # OASIS ends in a 256-byte END record, mostly padding, which KLayout does not need: cut the file
    # before it (a file cut inside that padding is read whole, a correct result).
    for cut in (len(data) // 2, len(data) - 257, 14):
        code, out, err, folder, before = bad_layout_file("cut%d.oas" % cut, data[:cut])
        clean_failure(code, out, err, "OASIS cut at byte %d of %d" % (cut, len(data)), folder, before, "cannot read")


def case_wrong_magic():
    gds = os.path.join(work, "metal.gds")
    sample_layout().write(gds)
    oas = open(SAMPLE, "rb").read()
    for name, data in (("magic.oas", b"%SEMI-OASIX" + oas[11:]), ("magic.gds", b"\x00\x06\x99\x02" + open(gds, "rb").read()[4:]),
                       ("text.oas", b"this is not a layout\n" * 40)):
        code, out, err, folder, before = bad_layout_file(name, data)
        clean_failure(code, out, err, "wrong magic number (%s)" % name, folder, before, "cannot read")


def case_gzip_gds():
    """KLayout reads gzip'd GDSII: the same diagram as the plain file, byte for byte."""
    gds = os.path.join(work, "metal.gds")
    sample_layout().write(gds)
    gz = os.path.join(work, "metal.gds.gz")
    with open(gz, "wb") as f:
        f.write(gzip.compress(open(gds, "rb").read()))
    results = {}
    for path in (gds, gz):
        folder = os.path.join(work, os.path.basename(path) + ".out")
        code, out, err, _ = run("cmd=voronoi", "input=" + path, "layer=1/0", "out=" + folder, "quiet=1")
        no_stack(code, out, err, os.path.basename(path))
        expect(code == 0, "%s: exit 0 (%s)" % (os.path.basename(path), err.strip()[-200:]))
        results[path] = voronoi_rows(folder) if code == 0 else None
    expect(results[gz] is not None and results[gz] == results[gds] and results[gz].count(b"\n") > 100,
           "gzip'd GDS: voronoi.csv byte-identical to the plain GDS's (%d rows)" % (results[gds] or b"").count(b"\n"))


def case_layer_above_65535():
    """OASIS holds any layer number; the result layouts must carry the diagram and the gauges on
    the input's own number (the core's drawings are GDSII, 16-bit layers), the same shapes as on
    a small layer number."""
    base = sample_layout()
    src = base.find_layer(1, 0)
    counts = {}
    for number in (7, 40000, 70000, 1000000):
        ly = pya.Layout()
        ly.dbu = base.dbu
        top = ly.create_cell("TOP")
        top.shapes(ly.layer(number, 0)).insert(base.top_cell().shapes(src))
        path = os.path.join(work, "layer%d.oas" % number)
        ly.write(path)
        folder = os.path.join(work, "layer%d" % number)
        code, out, err, _ = run("cmd=flow", "input=" + path, "layer=%d/0" % number, "markers=%d/0" % number,
                                "all_gauges=1", "diagram=1", "out=" + folder, "quiet=1")
        no_stack(code, out, err, "layer %d" % number)
        expect(code == 0, "layer %d/0: exit 0 (%s)" % (number, err.strip()[-200:]))
        if code:
            continue
        counts[number] = {}
        for name in ("voronoi.oas", "gauges.oas", "windows.oas", "calibration.oas"):
            c = layer_counts(os.path.join(folder, name))
            expect(set(layer for layer, _ in c) == {number}, "layer %d: %s holds only layer %d (%s)"
                   % (number, name, number, sorted(c)))
            counts[number][name] = sorted((d, n) for (_, d), n in c.items())
        summary = json.load(open(os.path.join(folder, "summary.json")))
        drawn = summary["voronoi"]["drawn"]
        vor = dict(counts[number]["voronoi.oas"])
        expect(all(vor.get(200 + k, 0) == drawn[kind] for k, kind in enumerate(("internal", "external", "notch",
                                                                               "adjacent"))),
               "layer %d: voronoi.oas holds the drawn pieces of summary.json on %d/200-203 (%s, %s)"
               % (number, number, vor, drawn))
    for number in (40000, 70000, 1000000):
        expect(number in counts and counts.get(number) == counts.get(7),
               "layer %d: every result layout holds the same shapes per datatype as on layer 7" % number)


def case_unreadable_file():
    """Read permission really withheld: the macro runs as `nobody` (root reads anything)."""
    global skip_reason
    if os.geteuid() != 0 or not shutil.which("setpriv"):
        skip_reason = "root and setpriv (to run as nobody)"
        return
    os.chmod(work, 0o755)
    secret = os.path.join(work, "secret.oas")
    shutil.copy(SAMPLE, secret)
    os.chmod(secret, 0o600)  # root's, unreadable by nobody
    readable = os.path.join(work, "readable.oas")
    shutil.copy(SAMPLE, readable)
    os.chmod(readable, 0o644)
    home = tempfile.mkdtemp(prefix="home-", dir=work)
    os.chmod(home, 0o777)
    folder = os.path.join(work, "out")
    before = earlier_outputs(folder)
    os.chmod(folder, 0o777)
    env = dict(os.environ, HOME=home, KLAYOUT_HOME=home, TMPDIR=home)
    as_nobody = ["setpriv", "--reuid=nobody", "--regid=nogroup", "--clear-groups"]
    code, out, err, _ = run("cmd=voronoi", "input=" + readable, "layer=1/0", "out=" + os.path.join(home, "ok"),
                            "quiet=1", prefix=as_nobody, env=env)
    if code != 0 and ("Permission denied" in err or "errno=13" in err or "error while loading" in err):
        skip_reason = "a checkout that nobody can read (%s)" % err.strip()[-120:]
        return
    expect(code == 0, "as nobody, a readable copy runs (exit %d: %s): the refusal below is the permission's"
           % (code, err.strip()[-200:]))
    before = snapshot(folder)
    code, out, err, _ = run("cmd=voronoi", "input=" + secret, "layer=1/0", "out=" + folder, prefix=as_nobody, env=env)
    clean_failure(code, out, err, "unreadable input (mode 600, run as nobody)", folder, before,
                  "cannot read the input file %s: Permission denied" % secret)


def case_directory_input():
    folder = os.path.join(work, "out")
    before = earlier_outputs(folder)
    code, out, err, _ = run("cmd=flow", "input=" + work, "layer=1/0", "markers=100/0", "out=" + folder)
    clean_failure(code, out, err, "a directory as the input", folder, before, "is a folder, not a layout file")
    code, out, err, _ = run("cmd=select", "input=" + SAMPLE, "layer=1/0", "markers=" + work + "/x.csv@um",
                            "out=" + folder)
    clean_failure(code, out, err, "a missing marker file", folder, before, "cannot read marker file")
    os.makedirs(os.path.join(work, "d.csv"), exist_ok=True)
    code, out, err, _ = run("cmd=select", "input=" + SAMPLE, "layer=1/0", "markers=" + os.path.join(work, "d.csv"),
                            "out=" + folder)
    clean_failure(code, out, err, "a directory as the marker file", folder, before, "is a folder, not a file")


def case_missing_file():
    folder = os.path.join(work, "out")
    before = earlier_outputs(folder)
    code, out, err, _ = run("cmd=flow", "input=" + os.path.join(work, "nothing.oas"), "layer=1/0",
                            "markers=100/0", "out=" + folder)
    clean_failure(code, out, err, "a missing input file", folder, before, "input file not found")


# ---- Markers ---------------------------------------------------------------------------------------

def marker_boxes(spec_layer=(100, 0)):
    """The sample's marker boxes on 100/0, in DBU."""
    ly = sample_layout()
    it = ly.top_cell().begin_shapes_rec(ly.find_layer(*spec_layer))
    boxes = []
    while not it.at_end():
        b = it.shape().bbox().transformed(it.trans())
        boxes.append((b.left, b.bottom, b.right, b.top))
        it.next()
    return sorted(set(boxes))


def covered(folder):
    """Markers covered: windows.csv's column adds up to them."""
    return sum(int(r["markers_covered"]) for r in csv.DictReader(open(os.path.join(folder, "windows.csv"))))


def flow_with_markers(spec, *more):
    folder = os.path.join(work, "out")
    code, out, err, seconds = run("cmd=flow", "input=" + SAMPLE, "layer=1/0", "markers=" + spec, "out=" + folder,
                                  "quiet=1", *more)
    stats = json.load(open(os.path.join(folder, "stats.json"))) if code == 0 else {}
    return code, out, err, seconds, folder, stats


def case_markers_nan_inf_empty():
    good = marker_boxes()
    path = os.path.join(work, "markers.csv")
    bad = ["nan,nan,nan,nan", "inf,0,10,10", "0,-inf,10,10", "NaN,1,2,3", "1e999,0,1,1", "", ",,,", "1,2,3",
           "x1,y1,x2,y2", "  ,  ,  ,  ", "1,2,3,nan"]
    with open(path, "w") as f:
        f.write("x1,y1,x2,y2\n")
        for i, b in enumerate(good):
            f.write("%d,%d,%d,%d\n" % b)
            f.write(bad[i % len(bad)] + "\n")
        for row in bad[len(good):]:
            f.write(row + "\n")
    blank = sum(1 for r in bad if r == "")  # csv reads an empty line as a row of no fields: skipped too
    code, out, err, _, folder, stats = flow_with_markers(path)
    no_stack(code, out, err, "NaN, inf and empty marker rows")
    ms = stats.get("marker_source", {})
    expect(code == 0, "NaN, inf and empty rows: exit 0 (%s)" % err.strip()[-200:])
    expect(ms.get("markers") == len(good) and ms.get("skipped_rows") == len(bad),
           "the %d good rows are the markers, the %d bad ones (%d blank) skipped and counted: %s"
           % (len(good), len(bad), blank, ms))
    expect(code == 0 and covered(folder) == len(good), "every good marker covered, as with the marker layer")
    # The good rows are the boxes of the marker layer 100/0: the same windows as with that layer.
    windows = open(os.path.join(folder, "windows.csv"), "rb").read() if code == 0 else None
    code, out, err, _, folder, stats = flow_with_markers("100/0")
    expect(code == 0 and windows == open(os.path.join(folder, "windows.csv"), "rb").read(),
           "windows.csv equals the run with the clean marker layer")


def case_markers_wrong_columns():
    folder = os.path.join(work, "out")
    before = earlier_outputs(folder)
    for name, data, message in (("cols.csv", "a,b,c\n1,2,3\n", "needs columns x,y or x1,y1,x2,y2"),
                                ("empty.csv", "", "is empty"),
                                ("onlybad.csv", "x,y\nnan,1\ninf,2\n\n", "no usable row (3 skipped)"),
                                ("binary.csv", "x,y\n1,2\x00\x01\n", "no usable row (1 skipped)"),
                                ("latin.csv", None, "cannot read marker file")):
        path = os.path.join(work, name)
        with open(path, "wb") as f:
            f.write(data.encode() if data is not None else b"x,y\n\xff\xfe1,2\n")
        code, out, err, _ = run("cmd=flow", "input=" + SAMPLE, "layer=1/0", "markers=" + path, "out=" + folder)
        clean_failure(code, out, err, "marker file %s" % name, folder, before, message)
    # Rows with too few columns are rows that do not parse: skipped and counted.
    path = os.path.join(work, "short.csv")
    with open(path, "w") as f:
        f.write("id,x,y\n1,1500,80\n2,3480\n3\n")
    code, out, err, _ = run("cmd=select", "input=" + SAMPLE, "layer=1/0", "markers=" + path, "quiet=1",
                            "out=" + os.path.join(work, "short"))
    stats = json.load(open(os.path.join(work, "short", "stats.json"))) if code == 0 else {}
    no_stack(code, out, err, "short rows")
    expect(code == 0 and stats["marker_source"]["markers"] == 1 and stats["marker_source"]["skipped_rows"] == 2,
           "rows with too few columns: skipped and counted (%s)" % stats.get("marker_source"))


def case_markers_million_rows():
    """A million rows of point markers (ICCAD-style def,id,category,x,y), the same hotspots many times
    over (as under several process conditions): read, merged, the whole flow; timed."""
    rng = random.Random(35)
    path = os.path.join(work, "million.csv")
    points = set()
    with open(path, "w") as f:
        f.write("def,id,category,x,y\n")
        for i in range(1000000):
            x, y = rng.randrange(0, 11600, 40), rng.randrange(0, 1000, 40)
            points.add((x, y))
            f.write("d,%d,hot,%d,%d\n" % (i, x, y))
    code, out, err, seconds, folder, stats = flow_with_markers(path)
    no_stack(code, out, err, "a million marker rows")
    ms = stats.get("marker_source", {})
    expect(code == 0, "a million rows: exit 0 in %.1f s (%s)" % (seconds, err.strip()[-200:]))
    expect(ms.get("markers") == len(points) and ms.get("duplicates_merged") == 1000000 - len(points)
           and ms.get("skipped_rows") == 0,
           "%d distinct markers, %d repeats merged (%s)" % (len(points), 1000000 - len(points), ms))
    expect(code == 0 and 0 < covered(folder) <= len(points), "windows.csv: markers covered, at most the distinct ones")
    print("timing: a million marker rows, the whole flow on the sample: %.1f s" % seconds)
    expect(seconds < 600, "a million rows within 600 s (%.1f s)" % seconds)


def case_markers_outside_layout():
    inside = marker_boxes()
    far = [(-50000, -50000, -40000, -40000), (900000, 0, 900010, 10), (0, 5000, 10, 5010),
           (10 ** 12, 10 ** 12, 10 ** 12 + 1, 10 ** 12 + 1)]
    for name, boxes in (("some", inside + far), ("all", far)):
        path = os.path.join(work, name + ".csv")
        with open(path, "w") as f:
            f.write("x1,y1,x2,y2\n" + "".join("%d,%d,%d,%d\n" % b for b in boxes))
        code, out, err, _, folder, stats = flow_with_markers(path)
        no_stack(code, out, err, "markers outside the layout (%s)" % name)
        warn = [line for line in err.splitlines() if line.startswith("linf_opc: warning: ")]
        expect(code == 0, "%s markers outside: exit 0 (%s)" % (name, err.strip()[-200:]))
        expect(len(warn) == 1 and "%d of %d markers" % (len(far), len(boxes)) in warn[0]
               and "outside the layout" in warn[0], "one warning line naming %d of %d outside (%s)"
               % (len(far), len(boxes), warn))
        ms = stats.get("marker_source", {})
        expect(ms.get("outside_layout") == len(far) and code == 0 and covered(folder) == len(boxes) - len(far),
               "stats.json: outside_layout %d; the windows cover the %d inside (%s)" % (len(far), len(boxes) - len(far),
                                                                                       ms))
        expect(os.path.isfile(os.path.join(folder, "calibration.oas")), "the flow's outputs are written")


def case_marker_layer_is_working_layer():
    ly = sample_layout()
    it = ly.top_cell().begin_shapes_rec(ly.find_layer(1, 0))
    boxes = set()
    while not it.at_end():
        if not it.shape().is_text():
            b = it.shape().bbox().transformed(it.trans())
            boxes.add((b.left, b.bottom, b.right, b.top))
        it.next()
    code, out, err, _, folder, stats = flow_with_markers("1/0")
    no_stack(code, out, err, "marker layer = working layer")
    warn = [line for line in err.splitlines() if line.startswith("linf_opc: warning: ")]
    expect(code == 0, "marker layer = working layer: exit 0 (%s)" % err.strip()[-200:])
    expect(len(warn) == 1 and "the marker layer 1/0 is the working layer" in warn[0],
           "one warning line: %s" % warn)
    expect(stats.get("marker_source", {}).get("markers") == len(boxes),
           "every shape's box is a marker: %d (%s)" % (len(boxes), stats.get("marker_source")))
    code, out, err, _, folder, stats = flow_with_markers("100/0")
    expect(code == 0 and not [line for line in err.splitlines() if "warning" in line],
           "no warning with another marker layer (%s)" % err.strip()[-200:])


# ---- Environment ----------------------------------------------------------------------------------

def mount_tmpfs(path, options):
    os.makedirs(path, exist_ok=True)
    r = subprocess.run(["mount", "-t", "tmpfs", "-o", options, "tmpfs", path], capture_output=True, text=True)
    return r.returncode == 0


def umount(path):
    subprocess.run(["umount", "-l", path], capture_output=True)


def case_full_disk():
    """A 1 MB tmpfs: an earlier run's files, then the disk filled to several levels and the whole
    flow (every output) written into it: each level ends in a complete result or one line, exit 2,
    the earlier files intact."""
    global skip_reason
    disk = os.path.join(work, "disk")
    if os.geteuid() != 0 or not mount_tmpfs(disk, "size=1m"):
        skip_reason = "a tmpfs mount (root)"
        return
    try:
        folder = os.path.join(disk, "out")
        before = earlier_outputs(folder)
        failures = 0
        free0 = os.statvfs(disk).f_bavail * os.statvfs(disk).f_frsize
        for left in (0, 4096, 16384, 65536, 200000):
            filler = os.path.join(disk, "filler")
            try:
                with open(filler, "wb") as f:
                    f.write(b"\0" * max(0, free0 - left))
            except OSError:
                pass
            code, out, err, _ = run("cmd=flow", "input=" + SAMPLE, "layer=1/0", "markers=100/0", "all_gauges=1",
                                    "diagram=1", "out=" + folder, "quiet=1")
            what = "flow into a full disk (%d bytes left)" % left
            if code == 0:  # it fitted: a complete result
                expect(all(os.path.isfile(os.path.join(folder, n)) for n in ("voronoi.csv", "gauges.csv",
                                                                             "calibration.oas", "flow.lyrdb")),
                       "%s: fitted, every output there" % what)
                shutil.rmtree(folder)
                before = earlier_outputs(folder)
            else:
                failures += 1
                clean_failure(code, out, err, what, folder, before, "")
            os.remove(filler)
        expect(failures >= 3, "the disk was full for most levels (%d)" % failures)
    finally:
        umount(disk)


def case_read_only_folder():
    global skip_reason
    disk = os.path.join(work, "ro")
    if os.geteuid() != 0 or not mount_tmpfs(disk, "size=4m"):
        skip_reason = "a tmpfs mount (root)"
        return
    try:
        folder = os.path.join(disk, "out")
        before = earlier_outputs(folder)
        r = subprocess.run(["mount", "-o", "remount,ro", disk], capture_output=True, text=True)
        expect(r.returncode == 0, "remounted read-only (%s)" % r.stderr.strip())
        code, out, err, _ = run("cmd=flow", "input=" + SAMPLE, "layer=1/0", "markers=100/0", "out=" + folder)
        clean_failure(code, out, err, "a read-only output folder", folder, before, "Read-only file system")
        code, out, err, _ = run("cmd=voronoi", "input=" + SAMPLE, "layer=1/0", "out=" + os.path.join(folder, "new"))
        clean_failure(code, out, err, "a folder to create on a read-only disk", folder, before,
                      "cannot create the output folder")
    finally:
        umount(disk)


def wait_for(cond, seconds, step=0.05):
    end = time.time() + seconds
    while time.time() < end:
        if cond():
            return True
        time.sleep(step)
    return cond()


def partials(folder):
    return [n for n in os.listdir(folder) if n.startswith(".linf_opc-partial-")] if os.path.isdir(folder) else []


def case_sigkill():
    """A run killed (SIGKILL) while it writes leaves its staging folder; the next run into the
    folder removes it, and the stale lock file does not stop it."""
    # 40,000 boxes: a flow needs several hundred MB more than KLayout's start (with 10,000 the
    # need was near +160 MB, and one CI run got through).
    big = grid_layout(os.path.join(work, "grid.oas"), 200, 200)
    folder = os.path.join(work, "out")
    before = earlier_outputs(folder)
    p = subprocess.Popen(command("cmd=flow", "input=" + big, "layer=1/0", "markers=1/0", "all_gauges=1",
                                 "diagram=1", "out=" + folder, "quiet=1"),
                         stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, start_new_session=True)
    def writing():
        try:
            return any(os.listdir(os.path.join(folder, d)) for d in partials(folder))
        except OSError:
            return False
    started = wait_for(writing, 300)
    os.killpg(p.pid, signal.SIGKILL)
    p.wait()
    expect(started and p.returncode == -signal.SIGKILL, "the run was killed while writing into its staging folder")
    left = partials(folder)
    expect(len(left) == 1 and os.path.exists(os.path.join(folder, ".linf_opc.lock")),
           "the killed run left its staging folder and lock file: %s" % sorted(os.listdir(folder)))
    expect({k: v for k, v in snapshot(folder).items() if not k.startswith(".")} == before,
           "the earlier run's files intact after the kill")
    code, out, err, seconds = run("cmd=voronoi", "input=" + SAMPLE, "layer=1/0", "out=" + folder, "quiet=1")
    no_stack(code, out, err, "the next run")
    expect(code == 0 and seconds < 120, "the next run into the folder: exit 0, not blocked by the stale lock (%.1f s)"
           % seconds)
    expect(not partials(folder) and not os.path.exists(os.path.join(folder, ".linf_opc.lock")),
           "the next run removed the stale staging folder and its own lock: %s" % sorted(os.listdir(folder)))
    expect(voronoi_rows(folder) == before["voronoi.csv"], "its own voronoi.csv written")


def case_two_runs():
    """Two runs into one folder: the second refuses at once with one line (exit 2) and writes
    nothing; the first is not disturbed and completes."""
    # 40,000 boxes: a flow needs several hundred MB more than KLayout's start (with 10,000 the
    # need was near +160 MB, and one CI run got through).
    big = grid_layout(os.path.join(work, "grid.oas"), 200, 200)
    folder = os.path.join(work, "out")
    before = earlier_outputs(folder)
    first = subprocess.Popen(command("cmd=flow", "input=" + big, "layer=1/0", "markers=1/0", "out=" + folder,
                                     "quiet=1"), stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    expect(wait_for(lambda: partials(folder), 300), "the first run is writing (its staging folder exists)")
    code, out, err, seconds = run("cmd=voronoi", "input=" + SAMPLE, "layer=1/0", "out=" + folder)
    running = first.poll() is None
    expect(running, "the first run was still running when the second ended")
    while_locked = {k: v for k, v in snapshot(folder).items() if not k.startswith(".")}
    no_stack(code, out, err, "the second run")
    line = [x for x in err.splitlines() if x.startswith("linf_opc: error: ")]
    expect(code == 2 and len(line) == 1 and "another run is writing into the output folder %s (process %d)"
           % (folder, first.pid) in line[0], "the second run refused with one line naming the first's process: %s"
           % err.strip()[-300:])
    expect(seconds < 60, "... at once (%.1f s), without waiting for the first" % seconds)
    expect(while_locked == before, "the second run wrote nothing")
    o, e = first.communicate(timeout=900)
    expect(first.returncode == 0 and "calibration" in o, "the first run completed (exit %d)" % first.returncode)
    expect(os.path.isfile(os.path.join(folder, "split.json")) and not partials(folder)
           and not os.path.exists(os.path.join(folder, ".linf_opc.lock")),
           "its outputs are in place, no staging folder or lock left: %s" % sorted(os.listdir(folder)))


def case_memory_limit():
    """RLIMIT_AS far below the need (the process's size at the start plus a few MB): one line,
    exit 2, the earlier files intact. run_limited.py sets the limit inside KLayout once it has
    started, so the limit bites the run, not KLayout's own start-up."""
    # 40,000 boxes: a flow needs several hundred MB more than KLayout's start (with 10,000 the
    # need was near +160 MB, and one CI run got through).
    big = grid_layout(os.path.join(work, "grid.oas"), 200, 200)
    folder = os.path.join(work, "out")
    before = earlier_outputs(folder)
    for extra in (8, 16, 48, 160):  # 160: inside the builder's threads (it aborted before parallel_for rethrew)
        code, out, err, _ = run("limit_mb=%d" % extra, "cmd=flow", "input=" + big, "layer=1/0", "markers=1/0",
                                "out=" + folder, "quiet=1", script=os.path.join(repo, "tests", "klayout",
                                                                                  "run_limited.py"))
        err = "\n".join(x for x in err.splitlines() if not x.startswith(("run_limited:", "linf_opc: warning:")))
        clean_failure(code, out, err, "RLIMIT_AS of the start-up size + %d MB" % extra, folder, before,
                      "out of memory")


CASES = {name[5:]: f for name, f in sorted(globals().items()) if name.startswith("case_")}

if case not in CASES:
    print("unknown case %r; one of: %s" % (case, ", ".join(CASES)))
    sys.exit(2)
CASES[case]()
finish(case, missing=skip_reason)
