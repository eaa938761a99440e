"""What a run is doing, while it runs: the batch writes one line a stage on stderr with its time
and counts, and during a long stage a percentage every few seconds where Python or the core
knows how far it is (a core call names its own steps: "building the diagram 40%"). stdout keeps the
command's one summary line. The editor passes its progress bar's step instead (on_stage), and
-rd quiet=1 silences the lines."""
import sys
import time

EVERY = 5.0  # seconds between two percentage lines of one stage

# While the editor runs an action: a callable that lets KLayout's event loop turn (bar.Bar).
_breath = None


def breathe(done=None, total=None):
    """Called in long Python loops (once an item): in the editor it lets the event loop turn a
    few times a second, so that a long stage never freezes KLayout, and shows done/total as the
    stage's percentage when given; it raises when the person cancels. In the batch it does
    nothing."""
    if _breath is not None:
        _breath(done, total)


def count(n):
    """A count as people read it: 359,558."""
    return "{:,}".format(n)


class Progress:
    def __init__(self, quiet=False, on_stage=None, stream=None, every=EVERY):
        self.quiet = quiet
        self.on_stage = on_stage
        self.stream = stream
        self.every = every
        self.stage = None
        self._t0 = self._last = time.perf_counter()

    @classmethod
    def of(cls, progress):
        """A Progress as given, an editor's step(stage) callback wrapped (silent), or a silent one."""
        if isinstance(progress, cls):
            return progress
        return cls(quiet=True, on_stage=progress)

    def say(self, text):
        if not self.quiet:
            out = self.stream or sys.stderr
            out.write("linf_opc: %s\n" % text)
            out.flush()

    def start(self, stage, what=""):
        """A stage begins; `what` (e.g. the input's size) is said at once: a stage inside one core
        call is otherwise silent until it ends."""
        self.stage = stage
        self._t0 = self._last = time.perf_counter()
        if self.on_stage:
            self.on_stage(stage)
        if what:
            self.say("%s: %s ..." % (stage, what))

    def done(self, counts=""):
        """The stage ended: its time and counts."""
        self.say("%s %.1f s%s" % (self.stage, time.perf_counter() - self._t0, ": " + counts if counts else ""))

    def core(self, step, done, total):
        """Inside a stage that is one core call: the core's own step ("building the diagram") and,
        where it counts parts, how many of how many; said once `every` seconds have passed since
        the last line. Called from the core's threads (which hold the GIL while it runs)."""
        now = time.perf_counter()
        if now - self._last >= self.every:
            self._last = now
            self.say("%s: %s%s (%.0f s)" % (self.stage, step, " %d%%" % (100 * done // total) if total else "",
                                            now - self._t0))

    def fraction(self, done, total):
        """Inside a stage: its percentage, once `every` seconds have passed since the last line."""
        now = time.perf_counter()
        if total and now - self._last >= self.every:
            self._last = now
            self.say("%s %d%% (%.0f s)" % (self.stage, 100 * done // total, now - self._t0))
