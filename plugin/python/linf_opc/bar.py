"""The editor's progress bar: one bar an action, naming the stage that runs ("Gauges: diagram
and gauges (core)") and the core's own step inside it ("building the diagram"), with the
percentage the core reports (core) or else the seconds a core call has run (the worker's wait),
or the percentage of a Python loop that reports how far it is (progress.Progress.fraction). It is the
progress.Progress the stages are given, so the flow's stages name themselves as in the batch.
Its cancel button raises from set(); the worker turns that into Cancelled."""
import time

import pya

from . import progress
from .progress import Progress

BREATH = 0.05  # seconds: how often a long Python loop lets the event loop turn (progress.breathe)


class Bar(Progress):
    last = []  # the stages of the last action, in order: what the GUI test reads
    last_steps = []  # the core's steps told in the last action, in order

    def __init__(self, title):
        super().__init__(quiet=True)
        self.title = title
        self.app = pya.Application.instance()
        self.bar = pya.AbsoluteProgress(title)
        self.bar.unit = 1
        self.stages = []
        Bar.last = self.stages
        self.steps = Bar.last_steps = []
        self._format, self._value = None, 0
        self._core = None  # the core's step (stage, done, total) while a core call runs
        self._breath = time.monotonic()
        progress._breath = self.breathe

    def start(self, stage, what=""):
        super().start(stage, what)
        self.stages.append(stage)
        self._core = None
        self.bar.desc = "%s: %s" % (self.title, stage)
        self._show("%.0f s", 0)

    def core(self, step, done, total):
        """The core's own step inside a core call (from the worker's progress file): named after
        the stage, with its percentage where the core counts parts."""
        if self._core is None or self._core[0] != step:
            self.bar.desc = "%s: %s: %s" % (self.title, self.stage, step)
            self.steps.append(step)
        self._core = (step, done, total)

    def fraction(self, done, total):
        if total:
            self._show("%.0f%%", 100 * done // total)

    def waiting(self, elapsed):
        """The worker's wait callback, about ten times a second while the core works."""
        if self._core and self._core[2]:
            self._show("%.0f%%", 100 * self._core[1] // self._core[2])
        else:
            self._show("%.0f s", int(elapsed))
        self.app.process_events()

    def breathe(self, done=None, total=None):
        """progress.breathe in the editor: every BREATH seconds the event loop turns and, with
        a total, the stage's percentage is shown. Cancel raises here too: the loops that call
        it run before an action's undo step opens (the flow's into its staging folder)."""
        now = time.monotonic()
        if now - self._breath >= BREATH:
            self._breath = now
            if total:
                self.fraction(done, total)
            else:
                self.bar.set(self._value, True)
            self.app.process_events()

    def _show(self, form, value):
        if form != self._format:
            self.bar.format = self._format = form
        self._value = value
        self.bar.set(value, True)  # raises when the person cancels

    def close(self):
        if progress._breath == self.breathe:
            progress._breath = None
        self.bar._destroy()
