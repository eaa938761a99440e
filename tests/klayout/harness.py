"""What every KLayout check script shares: the repository, the module's search path, the
script's -rd arguments, expectations, and the exit status ctest reads.

A check script is run as `klayout -b -r tests/klayout/check_X.py -rd name=value ...` and starts
    import os
    import sys
    sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
    from harness import arg, expect, finish, repo  # noqa: E402
Importing the harness puts the repository's build/ (the compiled module) and plugin/python (the
package) first on sys.path, so `from linf_opc import ...` follows it.

Exit status: 1 if any expectation failed; else 77, which ctest reports as skipped
(SKIP_RETURN_CODE), where an input the check needs is missing; else 0.
"""
import json
import os
import sys

repo = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
sys.path.insert(0, os.path.join(repo, "build"))
sys.path.insert(0, os.path.join(repo, "plugin", "python"))

# The batch command as the README writes it: plain Python on KLayout's standalone modules (the
# macro runs itself under KLayout's own Python). klayout -b -r gives the same files
# (check_standalone) and starts 1.8 s later; check_faults_io keeps it for its memory limits.
BATCH = ["python3", os.path.join(repo, "macros", "linf_opc.py")]

SKIP = 77
failures = []
# Print every expectation met as well ("ok:   what"), for scripts whose checks are a list to read.
report_ok = False

_required = object()


def arg(name, default=_required):
    """The value of `-rd name=value`; `default` where it is missing or empty. Without a default
    the argument is required: its absence stops the script with a usage message (exit 2)."""
    value = vars(sys.modules["__main__"]).get(name)
    if value:
        return value
    if default is _required:
        print("%s: missing -rd %s=..." % (_script(), name))
        sys.exit(2)
    return default


def batch(out, cmd, *settings, ok=True):
    """Runs the batch command `cmd` (BATCH, quiet) on the script's
    -rd input, layer and, if given, cell, writing into `out` (emptied first), with `settings` as
    further "name=value" -rd arguments; the completed process. ok: a non-zero exit prints its
    output and ends the script (exit 1)."""
    import shutil
    import subprocess
    shutil.rmtree(out, ignore_errors=True)
    settings = ["cmd=" + cmd, "input=" + arg("input"), "layer=" + arg("layer"), "out=" + out, "quiet=1"] + \
        (["cell=" + arg("cell")] if arg("cell", None) else []) + list(settings)
    r = subprocess.run(BATCH +
                       [a for s in settings for a in ("-rd", s)], capture_output=True, text=True)
    if ok and r.returncode != 0:
        print(r.stdout, r.stderr)
        print("FAIL: %s %s exited with %d" % (cmd, " ".join(settings), r.returncode))
        sys.exit(1)
    return r

TIMINGS = ("seconds", "elapsed", "time", "date")  # JSON keys that differ from run to run


def untimed(v, ignore=()):
    """A JSON value without its timings (keys naming TIMINGS) and the keys in `ignore`."""
    if isinstance(v, dict):
        # In stats.json's coverage rows (they have W_s), T is the selection's run time (the
        # thesis's T); elsewhere T is the gauge type and stays.
        return {k: untimed(x, ignore) for k, x in v.items()
                if not (k == "T" and "W_s" in v) and not any(t in k.lower() for t in TIMINGS) and k not in ignore}
    if isinstance(v, list):
        return [untimed(x, ignore) for x in v]
    return v


def same_files(ref, got, what, ignore=()):
    """Expects the folders `ref` and `got` to hold the same files with the same bytes: JSON files
    compared without their timings (untimed) and the keys in `ignore`, report.html not compared
    (it states its run's timings)."""
    names = sorted(os.listdir(ref))
    expect(names == sorted(os.listdir(got)), "%s: the same files (%s against %s)"
           % (what, names, sorted(os.listdir(got))))
    compared = 0
    for name in names:
        a, b = os.path.join(ref, name), os.path.join(got, name)
        if not os.path.isfile(b):
            continue
        if name.endswith(".json"):
            with open(a) as f, open(b) as g:
                same = untimed(json.load(f), ignore) == untimed(json.load(g), ignore)
        elif name.endswith(".html"):  # the report states its run's timings
            same = True
        else:
            with open(a, "rb") as f, open(b, "rb") as g:
                same = f.read() == g.read()
        compared += 1
        expect(same, "%s: %s differs from the reference run's" % (what, name))
    expect(compared >= 3, "%s: %d files compared" % (what, compared))


def ok(r, what):
    """Expects the completed process `r` to have exited 0; the end of its output where not."""
    return expect(r.returncode == 0, "%s exits %d: %s" % (what, r.returncode, (r.stderr or r.stdout).strip()[-400:]))


def expect(cond, what):
    """Records a failed expectation (the script goes on, to report them all) and prints it."""
    if not cond:
        failures.append(what)
        print("FAIL: " + what)
    elif report_ok:
        print("ok:   " + what)
    return cond


def finish(summary="", missing=None):
    """Prints the outcome and exits: 1 on failures; 77 with "SKIPPED: <missing> missing" where
    `missing` names an input the check needs and did not find; else 0."""
    tail = (": " + summary) if summary else ""
    if failures:
        print("%s FAILED, %d failed expectation(s)%s" % (_script(), len(failures), tail))
        sys.exit(1)
    if missing:
        print("%s%s" % (_script(), tail))
        print("SKIPPED: %s missing" % missing)
        sys.exit(SKIP)
    print("%s passed%s" % (_script(), tail))
    sys.exit(0)


def _script():
    main = sys.modules["__main__"]
    return os.path.splitext(os.path.basename(getattr(main, "__file__", "") or "check"))[0]
