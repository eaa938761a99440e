"""What every GUI test script shares (scripts run inside KLayout by run_gui.sh under Xvfb): its
own log (in GUI mode print() goes to KLayout's console), expect() and finish(), one-shot timers,
and a watchdog that closes modal dialogs so that none can hang a test.

    gui = Gui(globals())                  # -rd log=FILE: the log, else stderr
    gui.expected_dialog.append("Run OPC") # dialogs a step opens on purpose and fills in itself
    gui.capture_titles.append("L∞")       # message boxes a step expects: texts kept, closed
    gui.later(500, step); ...; gui.finish()

A modal dialog that is neither expected nor captured is a failure (or, with capture_all, is
captured too), and is closed.
"""
import pya


def dialog_texts(w):
    """The texts of a dialog's labels."""
    texts, todo = [], list(w.children())
    while todo:
        c = todo.pop()
        todo.extend(c.children())
        if "Label" in type(c).__name__ and c.text:
            texts.append(c.text)
    return texts


class Gui:
    def __init__(self, g, watch_ms=1000, capture_all=False):
        self.app = pya.Application.instance()
        self.mw = self.app.main_window()
        self.failures = []
        self.log = open(g.get("log") or "/dev/stderr", "w")
        self.expected_dialog = []
        self.captured = []
        self.capture_titles = []
        self.capture_all = capture_all
        self.timers = []
        self.waits = {}  # tries so far of each wait_for_dialog caller
        self.watchdog = pya.QTimer()
        self.watchdog.interval = watch_ms
        self.watchdog.timeout = self.close_modal
        self.watchdog.start()

    def say(self, text):
        self.log.write(text + "\n")
        self.log.flush()

    def expect(self, cond, what):
        self.say(("ok:   " if cond else "FAIL: ") + what)
        if not cond:
            self.failures.append(what)

    def finish(self):
        self.say("gui test %s" % ("FAILED" if self.failures else "passed"))
        self.app.exit(1 if self.failures else 0)

    def later(self, ms, f):
        t = pya.QTimer()
        t.singleShot = True
        t.interval = ms
        t.timeout = f
        t.start()
        self.timers.append(t)

    def wait_for_dialog(self, class_name, again, every, most):
        """The plugin's dialog on screen (dialogs.current) if it is a `class_name`; else None, and
        `again` runs once more after `every` ms, at most `most` times (the action is still busy)."""
        import linf_opc.dialogs as dialogs
        d = dialogs.current
        if d is not None and type(d).__name__ == class_name:
            return d
        self.waits[again] = self.waits.get(again, 0) + 1
        if self.waits[again] < most:
            self.later(every, again)
        return None

    def load(self, path, then, ms=1500):
        """Loads the layout once the event loop is up; `then` runs when the layer list has filled
        in from the loop. A layout that does not load ends the test."""
        try:
            self.mw.load_layout(path, 0)
        except Exception as e:
            self.expect(False, "exception: %s" % e)
            self.finish()
            return
        self.later(ms, then)

    def close_modal(self):
        w = pya.QApplication.activeModalWidget()
        if w is None or any(w.windowTitle.startswith(t) for t in self.expected_dialog):
            return
        if self.capture_all or any(w.windowTitle.startswith(t) for t in self.capture_titles):
            self.captured.append(" / ".join(dialog_texts(w)))
        else:
            self.expect(False, "a modal dialog came up: %s: %s" % (w.windowTitle, " / ".join(dialog_texts(w))))
        w.close()


def group_children(view, layer, datatype):
    """How many group nodes "L∞ OPC (L/D)" the layer list has, and their children as
    [(datatype, fill colour, dither pattern, visible)]."""
    groups, children = 0, []
    it = view.begin_layers()
    while not it.at_end():
        if it.current().name == "L\u221e OPC (%d/%d)" % (layer, datatype):
            groups += 1
            child = it.dup()
            child.down_first_child()
            while not child.at_end():
                c = child.current()
                children.append((c.source_datatype, c.fill_color, c.dither_pattern, c.visible))
                child.next_sibling(1)
        it.next_sibling(1)
    return groups, children


def select_layer(view, ly, layer, datatype):
    """Selects layer/datatype in the layer list, as the user does by clicking it."""
    target = ly.find_layer(layer, datatype)
    it = view.begin_layers()
    while not it.at_end():
        if it.current().layer_index() == target:
            view.current_layer = it
            return True
        it.next()
    return False
