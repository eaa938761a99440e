# The batch in plain Python (`python3 macros/linf_opc.py -rd ...`, on KLayout's standalone
# modules: plugin/python/linf_opc/standalone.py) gives the files `klayout -b` gives.
#   klayout -b -r tests/klayout/check_standalone.py -rd input=FILE -rd layer=L/D -rd markers=SPEC
#           [-rd cell=NAME] -rd work=DIR
# - voronoi, gauges, flow (with the markers, the plan's split) and farthest: the same files, byte
#   for byte (JSON files without their timings; report.html not compared: it states them), the
#   flow also under the `python3` on PATH (the README's command);
# - a report's layout picture (klayout.lay, loaded on first use) is the same PNG as KLayout's;
# - --help prints the commands' usage;
# - a name the commands do not read, a word that is not `-rd name=value`, a memory limit too small
#   for KLayout's libraries, and a Python without KLayout's modules each give exit 2, one line
#   `linf_opc: error: ...`, and nothing written.
import os
import re
import shutil
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from harness import BATCH, arg, expect, finish, ok, repo, same_files  # noqa: E402

from linf_opc import picture  # noqa: E402

work = arg("work", "/tmp/linf_standalone_check")
MACRO = os.path.join(repo, "macros", "linf_opc.py")
PYTHON = "/usr/bin/python3"  # the Python KLayout embeds (Debian's 3.11), for which the module is built


def run(launcher, out, *settings):
    """launcher: "klayout" (klayout -b -r), "python" (PYTHON) or "path" (BATCH: the python3 on PATH,
    as the README writes it: here perhaps another interpreter, pyenv's, which the macro leaves for
    KLayout's own Python)."""
    shutil.rmtree(out, ignore_errors=True)
    layer = ["input=" + arg("input"), "layer=" + arg("layer"), "out=" + out, "quiet=1"] + \
        (["cell=" + arg("cell")] if arg("cell", None) else [])
    start = {"klayout": ["klayout", "-b", "-r", MACRO], "python": [PYTHON, MACRO], "path": BATCH}[launcher]
    return subprocess.run(start + [a for s in layer + list(settings) for a in ("-rd", s)], capture_output=True,
                          text=True, timeout=900)


def limited():
    """The address space of a machine far too small: KLayout's libraries do not fit."""
    import resource
    resource.setrlimit(resource.RLIMIT_AS, (60 << 20, 60 << 20))


def one_error_line(r, what, words, out):
    lines = r.stderr.strip().splitlines()
    expect(r.returncode == 2, "%s: exit %d, not 2" % (what, r.returncode))
    expect(len(lines) == 1 and lines[0].startswith("linf_opc: error: ") and all(w in lines[0] for w in words),
           "%s: one line naming %s, got %r" % (what, words, r.stderr.strip()))
    expect(not os.path.exists(out) or not os.listdir(out), "%s: nothing written into %s" % (what, out))


shutil.rmtree(work, ignore_errors=True)
os.makedirs(work)
commands = [("voronoi", "python"), ("gauges", "python"), ("flow", "python", "markers=" + arg("markers")),
            ("flow", "path", "markers=" + arg("markers")), ("farthest", "python")]
references = {}  # cmd: klayout -b's run, into work/CMD_klayout
for cmd, launcher, *settings in commands:
    ref, got = os.path.join(work, cmd + "_klayout"), os.path.join(work, cmd + "_" + launcher)
    what = "%s in plain Python (%s)" % (cmd, PYTHON if launcher == "python" else "python3 on PATH: %s"
                                        % shutil.which("python3"))
    if cmd not in references:
        references[cmd] = run("klayout", ref, "cmd=" + cmd, *settings)
    a = references[cmd]
    b = run(launcher, got, "cmd=" + cmd, *settings)
    if ok(a, cmd + " under klayout -b") and ok(b, what):
        line_a, line_b = (re.sub(r"\b[0-9.]+ s\b", "_ s", r.stdout) for r in (a, b))  # its run time
        expect(line_a.replace(ref, got) == line_b, "%s: the same summary line (%r against %r)"
               % (what, a.stdout.strip(), b.stdout.strip()))
        same_files(ref, got, what)

# The picture: KLayout's layout view, drawn in this process and by the standalone modules.
shape = ([(0, 0), (1000, 0), (1000, 100), (700, 100), (700, 400), (0, 400)], [])
args = (0.001, [(0, 0, 50, 50)], [(10, 10, 500, 90)])
want = picture.picture([shape], *args)
script = ("import sys; sys.path[:0] = [%r, %r]\n"
          "from linf_opc import standalone; standalone.start()\n"
          "from linf_opc import picture\n"
          "sys.stdout.buffer.write(picture.picture([%r], *%r))\n"
          % (os.path.join(repo, "plugin", "python"), os.path.join(repo, "build"), shape, args))
script_path = os.path.join(work, "picture.py")  # a file: the start may run the process again, with its argv
with open(script_path, "w") as f:
    f.write(script)
r = subprocess.run([PYTHON, script_path], capture_output=True, timeout=300)
expect(r.returncode == 0 and r.stdout[:8] == b"\x89PNG\r\n\x1a\n", "the picture in plain Python: exit %d, %r"
       % (r.returncode, r.stderr.decode(errors="replace")[-400:]))
expect(r.stdout == want, "the picture in plain Python is KLayout's (%d bytes against %d)" % (len(r.stdout), len(want)))
expect(not r.stderr.strip(), "the picture in plain Python prints nothing on stderr: %r" % r.stderr[-400:])

r = subprocess.run([PYTHON, MACRO, "--help"], capture_output=True, text=True, timeout=300)
expect(r.returncode == 0 and "python3 macros/linf_opc.py -rd cmd=COMMAND" in r.stdout and "farthest" in r.stdout,
       "--help prints the commands' usage, exit 0 (exit %d, %r)" % (r.returncode, r.stdout[:200]))

# What the plain-Python batch refuses.
out = os.path.join(work, "refused")
one_error_line(run("python", out, "cmd=flow", "budgt=10"), "a misspelt name", ["unknown argument -rd budgt"], out)
r = subprocess.run([PYTHON, MACRO, "cmd=flow", "-rd", "out=" + out], capture_output=True, text=True, timeout=300)
one_error_line(r, "a bare name=value", ["unexpected argument 'cmd=flow'", "-rd name=value"], out)
r = subprocess.run([PYTHON, MACRO, "-rd", "cmd=flow", "-rd", "input=" + arg("input"), "-rd", "layer=" + arg("layer"),
                    "-rd", "out=" + out], capture_output=True, text=True, timeout=300, preexec_fn=limited)
one_error_line(r, "a 60 MB memory limit", ["out of memory while starting"], out)
plain = subprocess.run([PYTHON, "-c", "import klayout.db"], capture_output=True, env={"PATH": "/nonexistent"})
if expect(plain.returncode != 0, "this machine's Python has no klayout module of its own (the next case needs it)"):
    r = subprocess.run([PYTHON, MACRO, "-rd", "cmd=flow", "-rd", "out=" + out], capture_output=True, text=True,
                       timeout=300, env={"PATH": "/nonexistent"})
    one_error_line(r, "no KLayout on PATH", ["KLayout's Python modules", "apt-get install klayout"], out)

finish("the batch in plain Python gives klayout -b's files")
