# GUI test, run by run_gui.sh inside KLayout under Xvfb with a temporary KLAYOUT_HOME that holds
# the installed package:
#   klayout -rr tests/klayout/gui_menu.py -rd input=FILE -rd layer=L/D -rd shot=PNG -rd log=TXT
# Loads the layout, selects the layer, triggers Tools > L-inf Voronoi OPC > Voronoi diagram of
# current layer through the menu, asserts the diagram layers and undo, saves a screenshot.
import os

import pya

g = globals()
app = pya.Application.instance()
mw = app.main_window()
failures = []
# In GUI mode print() goes to KLayout's console, so the test writes its own log.
log = open(g.get("log") or "/dev/stderr", "w")


def say(text):
    log.write(text + "\n")
    log.flush()


def expect(cond, what):
    say(("ok:   " if cond else "FAIL: ") + what)
    if not cond:
        failures.append(what)


def finish():
    say("gui test %s" % ("FAILED" if failures else "passed"))
    app.exit(1 if failures else 0)


expected_dialog = []  # titles of dialogs a step opens on purpose (a step fills them in)
captured = []         # message boxes a step expects: their texts, then closed
capture_titles = []


def dialog_texts(w):
    texts, todo = [], list(w.children())
    while todo:
        c = todo.pop()
        todo.extend(c.children())
        if "Label" in type(c).__name__ and c.text:
            texts.append(c.text)
    return texts


def close_modal():
    """A modal dialog during the test is a failure, never a hang (unless a step expects it)."""
    w = pya.QApplication.activeModalWidget()
    if w is None or any(w.windowTitle.startswith(t) for t in expected_dialog):
        return
    if any(w.windowTitle.startswith(t) for t in capture_titles):
        captured.append(" / ".join(dialog_texts(w)))
        w.close()
        return
    expect(False, "a modal dialog came up: %s: %s" % (w.windowTitle, " / ".join(dialog_texts(w))))
    w.close()


watchdog = pya.QTimer()
watchdog.interval = 1000
watchdog.timeout = close_modal
watchdog.start()

L, D = [int(v) for v in g["layer"].split("/")]
g.setdefault("markers", "100/0")


def load():
    """Once the event loop is up: load the layout; the layer list fills in from the loop."""
    try:
        mw.load_layout(g["input"], 0)
    except Exception as e:
        expect(False, "exception: %s" % e)
        finish()
        return
    later(1500, run_test)


def run_test():
    try:
        view = mw.current_view()
        ly = view.active_cellview().layout()
        # Select the layer in the layer list, as the user does.
        select(view, ly)
        expect(not view.current_layer.is_null() and view.current_layer.current().layer_index() == ly.find_layer(L, D),
               "layer %d/%d selected" % (L, D))
        action = mw.menu().action("tools_menu.linf_opc.voronoi")
        expect(action is not None and mw.menu().is_valid("tools_menu.linf_opc.voronoi"), "menu entry registered")
        action.trigger()
        cell = view.active_cellview().cell
        counts = {}
        for i, kind in enumerate(["internal", "external", "notch", "adjacent"]):
            li = ly.find_layer(L, 200 + i)
            counts[kind] = cell.shapes(li).size() if li is not None else 0
        say("diagram shapes per kind: %s" % counts)
        expect(all(counts[k] > 0 for k in ("internal", "external", "adjacent")), "diagram layers filled")
        shown = set()
        it = view.begin_layers()
        while not it.at_end():
            shown.add(it.current().layer_index())
            it.next()
        expect(ly.find_layer(L, 200) in shown and ly.find_layer(L, 203) in shown, "diagram layers in the layer list")
        view.max_hier_levels = 99
        view.zoom_fit()
        state.update(view=view, ly=ly, cell=cell, action=action, counts=counts)
        later(1000, second_step)
        return
    except Exception as e:  # any error fails the test, never hangs it
        expect(False, "exception: %s" % e)
    finish()


timers = []


def later(ms, f):
    t = pya.QTimer()
    t.singleShot = True
    t.interval = ms
    t.timeout = f
    t.start()
    timers.append(t)


state = {}


def select(view, ly):
    """Selects the input layer in the layer list, as the user does by clicking it."""
    target = ly.find_layer(L, D)
    it = view.begin_layers()
    while not it.at_end():
        if it.current().layer_index() == target:
            view.current_layer = it
            return True
        it.next()
    return False


def second_step():
    """Editor mode: one undo removes the whole diagram (the action is a transaction).
    Viewer mode: running again replaces the diagram instead of adding a second copy."""
    try:
        view, ly, cell = state["view"], state["ly"], state["cell"]
        view.save_image(g["shot"], 1200, 800)
        # An empty view (grid only) encodes to about 9 KB; the drawn diagram to more.
        expect(os.path.getsize(g["shot"]) > 12000, "screenshot %s (%d bytes)" % (g["shot"], os.path.getsize(g["shot"])))
        if ly.is_editable():
            mw.cm_undo()
            li = ly.find_layer(L, 200)
            expect(li is None or cell.shapes(li).size() == 0, "undo removes the diagram")
        else:
            select(view, ly)
            state["action"].trigger()
            n = cell.shapes(ly.find_layer(L, 203)).size()
            expect(n == state["counts"]["adjacent"], "a second run replaces the diagram (%d adjacent)" % n)
        later(500, gauges_step)
        return
    except Exception as e:
        expect(False, "exception: %s" % e)
    finish()


def gauges_step():
    """Suggest gauges: the gauge layer with lines and rank texts, a report database with one
    category per gauge type shown in the marker browser; editor mode: one undo removes them."""
    try:
        view, ly, cell = state["view"], state["ly"], state["cell"]
        select(view, ly)
        action = mw.menu().action("tools_menu.linf_opc.gauges")
        expect(mw.menu().is_valid("tools_menu.linf_opc.gauges"), "gauges menu entry registered")
        rdbs = view.num_rdbs()
        action.trigger()
        li = ly.find_layer(L, 210)
        n = cell.shapes(li).size() if li is not None else 0
        expect(n > 0 and n % 2 == 0, "gauge layer filled: %d shapes (a line and a text per gauge)" % n)
        expect(view.num_rdbs() == rdbs + 1, "a report database was added to the view")
        rdb = view.rdb(view.num_rdbs() - 1)
        cats = {c.name(): c.num_items() for c in rdb.each_category()}
        say("marker browser categories: %s" % cats)
        expect(set(cats) == {"internal", "external", "sandwich", "comb", "T"} and sum(cats.values()) == n // 2,
               "one category per gauge type, one item per gauge")
        view.zoom_box(cell.dbbox_per_layer(ly.find_layer(L, D)))
        later(1000, gauges_shot)
        return
    except Exception as e:
        expect(False, "exception: %s" % e)
    finish()


def gauges_shot():
    try:
        view, ly, cell = state["view"], state["ly"], state["cell"]
        base, ext = os.path.splitext(g["shot"])
        shot = base + "_gauges" + ext
        view.save_image(shot, 1200, 800)
        expect(os.path.getsize(shot) > 12000, "screenshot %s (%d bytes)" % (shot, os.path.getsize(shot)))
        if ly.is_editable():
            mw.cm_undo()
            li = ly.find_layer(L, 210)
            expect(li is None or cell.shapes(li).size() == 0, "undo removes the gauges")
        later(500, select_step)
        return
    except Exception as e:
        expect(False, "exception: %s" % e)
    finish()


def fill_select_dialog():
    """Inside the dialog's event loop: the markers layer, two sizes, mode A; then OK."""
    import linf_opc.dialogs as dialogs
    d = dialogs.current
    expect(d is not None, "the Select patterns dialog is open")
    if d is None:
        return
    expect(d.markers.findText(g["markers"]) >= 0, "the marker layer %s is offered" % g["markers"])
    d.markers.setEditText(g["markers"])
    d.sizes.text = "5,6"
    d.mode.currentIndex = 0
    state["dialog_shot"] = d.grab().save(os.path.splitext(g["shot"])[0] + "_select_dialog.png")
    d.accept()


def select_step():
    """Select patterns...: the dialog, then the windows layer and the patterns in the marker browser."""
    try:
        view, ly, cell = state["view"], state["ly"], state["cell"]
        select(view, ly)
        expect(mw.menu().is_valid("tools_menu.linf_opc.select"), "select menu entry registered")
        expected_dialog.append("Select patterns")
        later(700, fill_select_dialog)
        rdbs = view.num_rdbs()
        mw.menu().action("tools_menu.linf_opc.select").trigger()
        expected_dialog.pop()
        li = ly.find_layer(L, 220)
        n = cell.shapes(li).size() if li is not None else 0
        expect(n > 0, "windows layer filled: %d windows" % n)
        expect(view.num_rdbs() == rdbs + 1, "a patterns report database was added")
        rdb = view.rdb(view.num_rdbs() - 1)
        names = set()
        for item in rdb.each_item():
            names.add(rdb.category_by_id(item.category_id()).name())
        say("patterns categories: %s" % sorted(names))
        expect({"A 5x5", "A 6x6", "C 6x6", "markers"} <= names, "one category per size and mode, and the markers")
        expect(state.get("dialog_shot") is True, "dialog screenshot saved")
        if ly.is_editable():
            mw.cm_undo()
            li = ly.find_layer(L, 220)
            expect(li is None or cell.shapes(li).size() == 0, "undo removes the windows")
        later(500, flow_step)
        return
    except Exception as e:
        expect(False, "exception: %s" % e)
    finish()


def fill_flow_dialog():
    import linf_opc.dialogs as dialogs
    d = dialogs.current
    expect(d is not None, "the flow dialog is open")
    if d is None:
        return
    d.layer.currentIndex = d.layer.findText(g["layer"])
    d.markers.setEditText(g["markers"])
    d.sizes.text = "5,6"
    d.split.currentIndex = 0
    d.fraction.text = "0.3"
    d.out.text = state["flow_out"]
    state["flow_shot"] = d.grab().save(os.path.splitext(g["shot"])[0] + "_flow_dialog.png")
    d.accept()


def check_remembered():
    """The dialog opens again with the values of the last run; cancelling it does nothing."""
    import linf_opc.dialogs as dialogs
    d = dialogs.current
    expect(d is not None and d.markers.currentText == g["markers"] and d.sizes.text == "5,6"
           and d.out.text == state["flow_out"], "the flow dialog remembers its settings")
    if d is not None:
        d.reject()


def flow_step():
    """Run OPC pattern flow...: the dialog, every output file, the windows, the marker browser;
    then the dialog again with the remembered settings."""
    try:
        import tempfile
        view, ly, cell = state["view"], state["ly"], state["cell"]
        state["flow_out"] = tempfile.mkdtemp(prefix="linf_flow_")
        expect(mw.menu().is_valid("tools_menu.linf_opc.flow"), "flow menu entry registered")
        expected_dialog.append("Run OPC pattern flow")
        later(700, fill_flow_dialog)
        rdbs = view.num_rdbs()
        mw.menu().action("tools_menu.linf_opc.flow").trigger()
        files = sorted(os.listdir(state["flow_out"]))
        say("flow outputs: %s" % files)
        expect({"voronoi.csv", "gauges.csv", "windows.csv", "report.html", "calibration.oas", "verification.oas",
                "split.json", "flow.lyrdb"} <= set(files), "the flow wrote every stage's files")
        li = ly.find_layer(L, 220)
        expect(li is not None and cell.shapes(li).size() > 0, "the flow drew the windows")
        expect(view.num_rdbs() == rdbs + 1, "the flow's report database is in the marker browser")
        expect(state.get("flow_shot") is True, "flow dialog screenshot saved")
        later(700, check_remembered)
        mw.menu().action("tools_menu.linf_opc.flow").trigger()
        expected_dialog.pop()
        expect(view.num_rdbs() == rdbs + 1, "cancelling the dialog runs nothing")
        later(500, farthest_step)
        return
    except Exception as e:
        expect(False, "exception: %s" % e)
    finish()


def farthest_step():
    """Farthest Voronoi of selection with nothing selected: the current layer in view."""
    try:
        view, ly, cell = state["view"], state["ly"], state["cell"]
        view.clear_selection()
        select(view, ly)
        view.zoom_fit()
        expect(mw.menu().is_valid("tools_menu.linf_opc.farthest"), "farthest menu entry registered")
        mw.menu().action("tools_menu.linf_opc.farthest").trigger()
        le, ls = ly.find_layer(L, 240), ly.find_layer(L, 241)
        ne = cell.shapes(le).size() if le is not None else 0
        ns = cell.shapes(ls).size() if ls is not None else 0
        expect(ne > 0 and ns >= 1, "farthest diagram (%d edges) and the touching square drawn" % ne)
        import linf_opc.menu as menu
        r = getattr(menu.farthest_of_selection, "last", None)
        expect(r is not None and r.half_side > 0, "the smallest touching square has a size")
        # Two selected shapes: the diagram of those two only.
        li = ly.find_layer(L, D)
        picked = []
        for sh in cell.shapes(li).each():
            if len(picked) == 2:
                break
            o = pya.ObjectInstPath()
            o.top = cell.cell_index()
            o.cv_index = 0
            o.layer = li
            o.shape = sh
            picked.append(o)
        view.object_selection = picked
        mw.menu().action("tools_menu.linf_opc.farthest").trigger()
        r = menu.farthest_of_selection.last
        expect(r.n_sites == 2, "the selection's %d shapes are the sites" % r.n_sites)
        view.clear_selection()
        later(300, crash_step)
        return
    except Exception as e:
        expect(False, "exception: %s" % e)
    finish()


def crash_step():
    """The core crashes (the worker is told to die by signal 11): the editor survives, says so
    clearly, keeps the layout unchanged and saves the failing input."""
    try:
        view, ly, cell = state["view"], state["ly"], state["cell"]
        select(view, ly)
        before = cell.shapes(ly.find_layer(L, D)).size()
        li = ly.find_layer(L, 210)
        gauges_before = cell.shapes(li).size() if li is not None else 0
        os.environ["LINF_OPC_WORKER_FAULT"] = "crash"
        capture_titles.append("L")
        try:
            mw.menu().action("tools_menu.linf_opc.gauges").trigger()
        finally:
            del os.environ["LINF_OPC_WORKER_FAULT"]
        say("message after the crash: %s" % captured)
        expect(any("crashed (signal 11" in c and "not changed" in c for c in captured),
               "a clear message after the core crashed")
        failures_dir = os.path.join(pya.Application.instance().application_data_path(), "linf_opc_failures")
        saved = os.listdir(failures_dir) if os.path.isdir(failures_dir) else []
        expect(any(f.endswith("gauges_polygons.pickle") for f in saved), "the failing input is saved: %s" % saved)
        li = ly.find_layer(L, 210)
        expect(cell.shapes(ly.find_layer(L, D)).size() == before and
               (cell.shapes(li).size() if li is not None else 0) == gauges_before, "the layout is unchanged")
        capture_titles.pop()
        # And the next run works again.
        mw.menu().action("tools_menu.linf_opc.gauges").trigger()
        li = ly.find_layer(L, 210)
        expect(li is not None and cell.shapes(li).size() > 0, "the next run works")
        # No layer to work on: a new empty layout. A message, nothing else.
        mw.create_layout(1)
        capture_titles.append("L")
        del captured[:]
        mw.menu().action("tools_menu.linf_opc.gauges").trigger()
        capture_titles.pop()
        say("message without a current layer: %s" % captured)
        expect(any("Select a drawing layer" in c for c in captured), "no current layer: a clear message")
    except Exception as e:
        expect(False, "exception: %s" % e)
    finish()


later(500, load)
