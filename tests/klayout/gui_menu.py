# GUI test, run by run_gui.sh inside KLayout under Xvfb with a temporary KLAYOUT_HOME that holds
# the installed package:
#   klayout -rr tests/klayout/gui_menu.py -rd input=FILE -rd layer=L/D -rd shot=PNG -rd log=TXT
# Loads the layout, selects the layer, triggers Tools > L-inf Voronoi OPC > Voronoi diagram of
# current layer through the menu, asserts the diagram layers and undo, saves a screenshot.
import json
import os
import sys

import pya

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from gui_harness import Gui, group_children, select_layer  # noqa: E402

g = globals()
gui = Gui(g)
app, mw, failures, timers = gui.app, gui.mw, gui.failures, gui.timers
say, expect, finish, later = gui.say, gui.expect, gui.finish, gui.later
expected_dialog, captured, capture_titles = gui.expected_dialog, gui.captured, gui.capture_titles

L, D = [int(v) for v in g["layer"].split("/")]
g.setdefault("markers", "100/0")


def load():
    gui.load(g["input"], run_test)


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
        layer_box = cell.bbox_per_layer(ly.find_layer(L, D))
        boxes = [cell.bbox_per_layer(ly.find_layer(L, 200 + i)) for i in range(4)]
        expect(all(layer_box.contains(b.p1) and layer_box.contains(b.p2) for b in boxes),
               "the diagram ends at the layer's box %s (rays cut): %s" % (layer_box, [b.to_s() for b in boxes]))
        shown = set()
        it = view.begin_layers()
        while not it.at_end():
            shown.add(it.current().layer_index())
            it.next()
        expect(ly.find_layer(L, 200) in shown and ly.find_layer(L, 203) in shown, "diagram layers in the layer list")
        check_group(view, "the diagram")
        view.max_hier_levels = 99
        view.zoom_fit()
        state.update(view=view, ly=ly, cell=cell, action=action, counts=counts)
        later(1000, second_step)
        return
    except Exception as e:  # any error fails the test, never hangs it
        expect(False, "exception: %s" % e)
    finish()


def check_group(view, when):
    """The plugin's layers: one group node "L∞ OPC (L/D)", each kind its own colour with a
    hollow fill, adjacent hidden."""
    groups, children = group_children(view, L, D)
    say("%s: group %d, children %s" % (when, groups, children))
    colours = [c[1] for c in children]
    expect(groups == 1 and len(children) >= 4 and len(set(colours)) == len(colours)
           and all(c[2] == 1 for c in children), "%s: one group node, a colour a layer, hollow fills" % when)
    expect([c[3] for c in children if c[0] in (203, 215)] == [False] * len([c for c in children if c[0] in (203, 215)])
           and all(c[3] for c in children if c[0] not in (203, 215)),
           "%s: adjacent (and gauge labels) hidden, the rest shown" % when)


state = {}


def select(view, ly, datatype=D):
    """Selects the input layer (or L/datatype) in the layer list, as the user does by clicking it."""
    return select_layer(view, ly, L, datatype)


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
            check_group(view, "a second run")
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
        import re
        import linf_opc.menu as menu
        total, groups, drawn = menu.gauges_of_current_layer.last
        lines = {dt: cell.shapes(ly.find_layer(L, dt)).size() if ly.find_layer(L, dt) is not None else 0
                 for dt in range(210, 215)}
        li = ly.find_layer(L, 215)
        labels = [s.text_string for s in cell.shapes(li).each()] if li is not None else []
        n = sum(lines.values())
        say("gauges %d in %d contexts; drawn per type %s; labels e.g. %s" % (total, groups, lines, labels[:3]))
        # A label is left out where it would overprint a more critical one (gauge_output._free).
        expect(0 < n == drawn == min(1000, groups) and 0 < len(labels) <= n and all(v > 0 for v in lines.values()),
               "the representatives drawn, each type on its layer, at most a label each: %d of %d gauges, %d labels"
               % (n, total, len(labels)))
        form = re.compile(r"^(W|S|SW|C|T) [\d.e+]+ nm \u00d7([\d,]+)$")
        counts = [form.match(t) for t in labels]
        expect(all(counts), "labels read 'W 16 nm \u00d72,400': %s" % [t for t, m in zip(labels, counts) if not m][:3])
        if groups <= 1000 and all(counts):
            expect(0 < sum(int(m.group(2).replace(",", "")) for m in counts) <= total,
                   "the labels' counts add up to at most the layer's %d gauges" % total)
        expect(view.num_rdbs() == rdbs + 1, "a report database was added to the view")
        rdb = view.rdb(view.num_rdbs() - 1)
        cats = {c.name(): c.num_items() for c in rdb.each_category()}
        say("marker browser categories: %s" % cats)
        expect(set(cats) == {"internal", "external", "sandwich", "comb", "T"} and sum(cats.values()) == drawn,
               "one category per gauge type, one item per drawn gauge")
        tags = {}
        for item in rdb.each_item():
            for v in item.each_value():
                if v.tag_id:
                    tags.setdefault(rdb.tag_name(v.tag_id), []).append(v.string() if v.is_string() else v.to_s())
        say("marker browser values, e.g. %s" % {k: v[:2] for k, v in tags.items()})
        forms = {"rank": r"^\d+$", "cd": r"^\d+(\.\d+)? nm$", "score": r"^\d+(\.\d+)? nm$",
                 "count": r"^\d{1,3}(,\d{3})* \([\d.e+-]+% of the layer's gauges\)$"}
        expect(set(tags) == set(forms) and all(len(tags[k]) == drawn and all(re.match(forms[k], t) for t in tags[k])
                                               for k in forms),
               "each item reads rank as an integer, cd and score in nm, the count of its context")
        expect(sum(int(t.split()[0].replace(",", "")) for t in tags.get("count", [])) == total or groups > 1000,
               "the items' counts add up to the layer's %d gauges" % total)
        import linf_opc.bar as bar
        expect(bar.Bar.last == ["reading the layer", "diagram and gauges (core)", "pitch and contexts (core)",
                                "drawing", "marker browser"], "the progress bar names the stages: %s" % bar.Bar.last)
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
        check_group(view, "with the gauges")
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
        # A rerun replaces its report database instead of adding another (once the layer list
        # shows the regrouped layers).
        import time
        end = time.monotonic() + 0.7
        while time.monotonic() < end:
            app.process_events()
        expect(select(view, ly), "layer selected again for the rerun")
        state.pop("dialog_shot", None)
        later(700, fill_select_dialog)
        mw.menu().action("tools_menu.linf_opc.select").trigger()
        expected_dialog.pop()
        names = [view.rdb(i).name() for i in range(view.num_rdbs())]
        expect(names.count("patterns %d/%d" % (L, D)) == 1 and state.get("dialog_shot") is True,
               "a rerun replaces the patterns database: %s" % names)
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
            mw.cm_undo()  # the rerun's step: the first run's windows are back
            li = ly.find_layer(L, 220)
            expect(li is not None and cell.shapes(li).size() == n, "undo of the rerun gives the first run's windows")
            mw.cm_undo()
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
    expect(d.markers.currentText == "", "the markers are not the working layer by default (%r)" % d.markers.currentText)
    # Only the chosen split's fields can be edited.
    d.split.currentIndex = 1  # stratified
    expect(d.fraction.enabled and d.seed.enabled and not d.budget.enabled and not d.threshold.enabled,
           "stratified: its fraction and seed only")
    d.split.currentIndex = 0  # the budgeted gauge plan
    expect(d.budget.enabled and d.verify.enabled and not d.fraction.enabled and not d.threshold.enabled,
           "plan: its budget and verification size only")
    # Refusals, in sentences, and a question for what may be a slip (answered No: the dialog stays).
    v = dict(d.values(), markers=g["markers"], pitch="100000", budget="0", out="")
    errors, _ = dialogs.flow_problems(v, d.layout_um)
    expect(any("larger than the layout" in e for e in errors) and any("budget" in e for e in errors)
           and any("output folder" in e for e in errors), "refused: a pitch above the layout, budget 0, no folder "
           "(%s)" % errors)
    # The Dask scheduler: blank (this computer) by default; an address that is not tcp://HOST:PORT refused.
    expect(d.values().get("scheduler") == "", "the Dask scheduler field is blank by default")
    errors, _ = dialogs.flow_problems(dict(v, scheduler="farm-head:8786"), d.layout_um)
    expect(any("Dask scheduler" in e for e in errors), "refused: a scheduler without tcp:// (%s)" % errors)
    errors, _ = dialogs.flow_problems(dict(v, scheduler="tcp://farm-head:8786"), d.layout_um)
    expect(not any("Dask scheduler" in e for e in errors), "accepted: tcp://farm-head:8786 (%s)" % errors)
    asked = []
    d.confirm = lambda parent, q: asked.append(q) and False
    d.markers.setEditText(g["layer"])
    d.out.text = state["flow_out"]
    d._ok()
    expect(len(asked) == 1 and "working layer" in asked[0] and d.visible, "the working layer as markers: asked, "
           "and No keeps the dialog open (%s)" % asked)
    d.markers.setEditText(g["markers"])
    d.sizes.text = "5,6"
    d.budget.text = "50"
    d.verify.text = "20"
    d.fraction.text = "0.3"
    expect(d.values()["litho"] == "", "no lithography model by default")
    expect(not d.opc.enabled and d.values()["opc"] == "0", "no OPC without a model, and none by default")
    d.litho.currentIndex = d.litho.findText(dialogs.LITHO_LABELS["euv"])
    expect(d.values()["litho"] == "euv", "the lithography model chosen: %r" % d.values()["litho"])
    expect(d.opc.enabled, "the OPC can be chosen once a model is")
    d.opc.checked = True
    expect(d.values()["opc"] == "1", "the OPC chosen: %r" % d.values()["opc"])
    expect(d.values()["builder"] == "sweep", "the sweep line builds the diagram by default")
    d.builder.currentIndex = d.builder.findText(dialogs.BUILDER_LABELS["subdivision"])
    expect(d.values()["builder"] == "subdivision", "the subdivision chosen: %r" % d.values()["builder"])
    d.builder.currentIndex = d.builder.findText(dialogs.BUILDER_LABELS["sweep"])
    expect(d.values()["builder"] == "sweep", "the sweep line chosen: %r" % d.values()["builder"])
    expect(d.values()["check"] == "sample", "the sampled check by default")
    d.check.currentIndex = d.check.findText(dialogs.CHECK_LABELS["full"])
    expect(d.values()["check"] == "full", "the full check chosen: %r" % d.values()["check"])
    state["flow_shot"] = d.grab().save(os.path.splitext(g["shot"])[0] + "_flow_dialog.png")
    d._ok()
    expect(not asked[1:], "valid values into an empty folder: no question")
    later(1000, check_results)


def check_results():
    """The results dialog after the flow: counts, the folder, the buttons; then closed."""
    d = gui.wait_for_dialog("ResultsDialog", check_results, 500, 300)
    if d is None:
        return
    text = d.text()
    say("results dialog:\n" + text)
    expect("Markers covered" in text and "Calibration" in text and "Verification" in text and "contexts" in text
           and "Pattern classes" in text and state["flow_out"] in text, "the results dialog: sets, markers, "
           "contexts, classes, the folder")
    expect("Lithography: euv, threshold" in text and "after an emulated OPC" in text,
           "the results dialog: the model, its OPC and its fails")
    buttons = [c.text for c in d.findChildren(pya.QPushButton)] if hasattr(d, "findChildren") else []
    state["results_shot"] = d.grab().save(os.path.splitext(g["shot"])[0] + "_results_dialog.png")
    state["results_buttons"] = buttons
    named = {b.text: b for b in d._keep}
    expect(sorted(named) == ["Open report.html", "Show calibration clips", "Show the plan in the marker browser"],
           "the results dialog's buttons: %s" % sorted(named))
    if "Show the plan in the marker browser" in named:
        named["Show the plan in the marker browser"].click()  # closes the dialog, opens the marker browser
    else:
        d.reject()


def check_remembered():
    """The dialog opens again with the values of the last run; cancelling it does nothing."""
    import linf_opc.dialogs as dialogs
    d = dialogs.current
    expect(d is not None and d.markers.currentText == g["markers"] and d.sizes.text == "5,6"
           and d.budget.text == "50" and d.verify.text == "20" and d.split.currentIndex == 0
           and d.out.text == state["flow_out"] and d.values()["litho"] == "euv" and d.values()["builder"] == "sweep"
           and d.values()["check"] == "full" and d.values()["opc"] == "1",
           "the flow dialog remembers its settings")
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
        expected_dialog.append("OPC pattern flow: results")
        later(700, fill_flow_dialog)
        rdbs = view.num_rdbs()
        mw.menu().action("tools_menu.linf_opc.flow").trigger()
        files = sorted(os.listdir(state["flow_out"]))
        say("flow outputs: %s" % files)
        # The editor writes the flow's default files: the plan, the windows and the reports.
        expect(files == sorted(["windows.csv", "pattern_classes.csv", "windows.oas", "stats.json", "report.html",
                                "calibration.oas", "verification.oas", "calibration_gauges.csv",
                                "verification_gauges.csv", "split.json", "flow.lyrdb", "summary.json"]),
               "the flow wrote its default files, no more")
        with open(os.path.join(state["flow_out"], "summary.json")) as f:
            voronoi = json.load(f)["voronoi"]
        built = voronoi["builder"]
        expect(voronoi["check"]["searched_pieces"] == voronoi["pieces"] > 0,
               "check=full chosen: every piece searched (%s)" % voronoi["check"])
        expect(built == "sweep", "the sweep built the sample (axis-parallel and 45-degree edges): %s" % built)
        li = ly.find_layer(L, 220)
        expect(li is not None and cell.shapes(li).size() > 0, "the flow drew the windows")
        # The printed contours (euv) of the windows: edges inside the windows' boxes, in the group.
        ci = ly.find_layer(L, 216)
        edges = list(cell.shapes(ci).each()) if ci is not None else []
        windows = pya.Region(cell.begin_shapes_rec(li)) if li is not None else pya.Region()
        inside = sum(1 for s in edges if s.is_edge() and windows.bbox().contains(s.edge.p1))
        say("printed contours: %d edges, %d inside the windows' box" % (len(edges), inside))
        expect(len(edges) > 0 and inside == len(edges), "the flow drew the printed contours of its windows on L/216")
        # With the OPC chosen: the corrected layer inside the windows on L/217, not the drawn one.
        mi = ly.find_layer(L, 217)
        mask = pya.Region(cell.begin_shapes_rec(mi)) if mi is not None else pya.Region()
        drawn = pya.Region(cell.begin_shapes_rec(ly.find_layer(L, D))) & windows
        say("OPC-corrected layer: %d polygons; XOR with the drawn layer in the windows: %d polygons"
            % (mask.count(), (mask ^ drawn).count()))
        expect(mask.count() > 0 and (mask - windows).is_empty() and not (mask ^ drawn).is_empty(),
               "the flow drew the OPC-corrected layer inside its windows on L/217, moved from the drawn one")
        groups, children = group_children(view, L, D)
        expect(groups == 1 and {216, 217} <= set(c[0] for c in children),
               "the contours and the corrected layer in the layer group: %s" % children)
        expect(view.num_rdbs() == rdbs + 1, "the flow's report database is in the marker browser")
        expect(state.get("flow_shot") is True, "flow dialog screenshot saved")
        expect(state.get("results_shot") is True, "the results dialog came up (screenshot saved)")
        later(700, check_remembered)
        mw.menu().action("tools_menu.linf_opc.flow").trigger()
        expected_dialog.pop()
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
        names = [view.rdb(i).name() for i in range(view.num_rdbs())]
        expect(names.count("gauges %d-%d.lyrdb" % (L, D)) == 1, "a rerun replaces its report database: %s" % names)
        later(500, input_layer_step)  # once the layer list shows the regrouped layers
        return
    except Exception as e:
        expect(False, "exception: %s" % e)
    finish()


def input_layer_step():
    """Messages about the input: a result layer of the plugin, then no layer at all."""
    try:
        view, ly = state["view"], state["ly"]
        # A result layer of the plugin (zero-width paths) as the input: a message that says so.
        if select(view, ly, 200):
            capture_titles.append("L")
            del captured[:]
            mw.menu().action("tools_menu.linf_opc.voronoi").trigger()
            capture_titles.pop()
            say("message on the diagram layer: %s" % captured)
            expect(any("holds no area" in c and "Select a drawing layer" in c for c in captured),
                   "the diagram layer as input: it holds no area, select a drawing layer")
        else:  # the editor's test has undone the diagram
            say("no diagram layer L/200 left to try as input")
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
