# GUI test on a real layer (ICCAD 2016 testcase 3, 9,779 polygons), run by run_gui.sh inside
# KLayout under Xvfb with a temporary KLAYOUT_HOME that holds the installed package:
#   run_gui.sh BUILD testcase3.oas 1000/0 SHOT.png -e script=gui_testcase3.py markers=test3.csv
# Through the menu, as a person would: the diagram (drawn within the layer's box, so that zoom
# fit shows the layout), the gauges (the drawn representatives, the marker browser's formatted
# values, the stages named in the progress bar) and the flow (its dialog and results dialog).
# During each action a QTimer ticks every 50 ms; the largest gap between two ticks is the
# longest freeze of the editor's event loop: printed, and asserted below FREEZE_LIMIT seconds
# for the diagram and gauge actions. Screenshots kept: the view at a 2 x 2 um zoom (labels
# hidden as they start, then shown), the flow dialog, the results dialog.
import os
import re
import sys
import tempfile
import time

import pya

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from gui_harness import Gui, group_children, select_layer  # noqa: E402

g = globals()
gui = Gui(g)
app, mw, failures, timers = gui.app, gui.mw, gui.failures, gui.timers
say, expect, finish, later = gui.say, gui.expect, gui.finish, gui.later
expected_dialog, captured, capture_titles = gui.expected_dialog, gui.captured, gui.capture_titles
L, D = [int(v) for v in g["layer"].split("/")]
FREEZE_LIMIT = 2.0
MOST = 1000  # the representatives the gauge action draws at most (gauge_output.EDITOR_MAX)
base = os.path.splitext(g["shot"])[0]


class Freeze:
    """The longest gap between two ticks of a 50 ms timer while `run()` runs: how long the
    editor's event loop did not turn (the person could not click, scroll or cancel)."""

    def __init__(self):
        self.timer = pya.QTimer()
        self.timer.interval = 50
        self.timer.timeout = self._tick

    def _tick(self):
        import linf_opc.bar as bar
        now = time.monotonic()
        stage = bar.Bar.last[-1] if bar.Bar.last else "-"
        if now - self.last > self.longest:
            self.longest = now - self.last
            self.where = "from '%s' to '%s'" % (self.stage, stage) if stage != self.stage else "in '%s'" % stage
        self.last, self.stage = now, stage

    def measure(self, run):
        self.longest, self.last, self.stage, self.where = 0.0, time.monotonic(), "-", ""
        t0 = self.last
        self.timer.start()
        try:
            run()
        finally:
            self._tick()  # the gap up to the action's end
            self.timer.stop()
        return self.longest, time.monotonic() - t0


freeze = Freeze()
state = {}


def select(view, ly, datatype=D):
    return select_layer(view, ly, L, datatype)


def load():
    gui.load(g["input"], voronoi_step)


def voronoi_step():
    """The diagram: drawn, but within the layer's box; zoom fit shows the layout."""
    try:
        view = mw.current_view()
        cv = view.active_cellview()
        ly, cell = cv.layout(), cv.cell
        expect(select(view, ly), "layer %d/%d selected" % (L, D))
        layer_box = cell.bbox_per_layer(ly.find_layer(L, D))
        seconds, took = freeze.measure(lambda: mw.menu().action("tools_menu.linf_opc.voronoi").trigger())
        say("longest event-loop freeze during 'Voronoi diagram of current layer': %.2f s %s (action %.1f s)"
            % (seconds, freeze.where, took))
        expect(seconds < FREEZE_LIMIT, "the diagram action never freezes the editor %g s (%.2f s)"
               % (FREEZE_LIMIT, seconds))
        counts = {}
        inside = True
        for i in range(4):
            li = ly.find_layer(L, 200 + i)
            counts[200 + i] = cell.shapes(li).size() if li is not None else 0
            if li is not None and counts[200 + i]:
                inside = inside and layer_box.contains(cell.bbox_per_layer(li).p1) and \
                    layer_box.contains(cell.bbox_per_layer(li).p2)
        say("diagram pieces drawn per datatype: %s; layer box %s, cell box %s" % (counts, layer_box, cell.bbox()))
        expect(all(counts[d] > 0 for d in (200, 201, 203)), "the diagram is drawn")
        expect(inside and cell.bbox() == layer_box, "every piece ends within the layer's box: rays cut")
        view.max_hier_levels = 99
        view.zoom_fit()
        vb = view.box()
        lb = layer_box.to_dtype(ly.dbu)
        expect(vb.contains(lb.p1) and vb.contains(lb.p2) and vb.width() < 1.6 * max(lb.width(), lb.height()),
               "zoom fit shows the layout (%s for the layer's %s), not rays" % (vb, lb))
        groups, children = group_children(view, L, D)
        expect(groups == 1 and [c[3] for c in children if c[0] == 203] == [False],
               "one group node; adjacent hidden")
        if ly.is_editable():
            mw.cm_undo()
        state.update(view=view, ly=ly, cell=cell)
        later(500, gauges_step)
        return
    except Exception as e:
        expect(False, "exception: %s" % e)
    finish()


def gauges_step():
    """Suggest gauges: freeze below the limit; the representatives drawn (at most MOST), the
    marker browser holding the same with formatted values, the stages named."""
    try:
        import linf_opc.bar as bar
        import linf_opc.menu as menu
        from linf_opc import gauge_output
        view, ly, cell = state["view"], state["ly"], state["cell"]
        select(view, ly)
        seconds, took = freeze.measure(lambda: mw.menu().action("tools_menu.linf_opc.gauges").trigger())
        say("longest event-loop freeze during 'Suggest gauges on current layer': %.2f s %s (action %.1f s)"
            % (seconds, freeze.where, took))
        expect(seconds < FREEZE_LIMIT, "the gauge action never freezes the editor %g s (%.2f s)"
               % (FREEZE_LIMIT, seconds))
        say("progress bar stages: %s" % bar.Bar.last)
        expect(bar.Bar.last == ["reading the layer", "diagram and gauges (core)", "pitch and contexts (core)",
                                "drawing", "marker browser"], "the progress bar names each stage")
        say("the core's steps in the bar: %s" % bar.Bar.last_steps)
        expect(bar.Bar.last_steps[-1:] == ["placing the gauges"] and len(bar.Bar.last_steps) >= 2,
               "the bar names the core's own steps inside its call")
        total, groups, drawn = menu.gauges_of_current_layer.last
        lines = {dt: cell.shapes(ly.find_layer(L, dt)).size() if ly.find_layer(L, dt) is not None else 0
                 for dt in range(210, 215)}
        n = sum(lines.values())
        say("gauges %d in %d contexts; drawn per type %s" % (total, groups, lines))
        expect(0 < n == drawn == min(MOST, groups) <= MOST, "the representatives drawn, at most %d: %d" % (MOST, n))
        # Labels at their own size never overlap (checked pairwise here, not by the plugin's grid).
        boxes = [gauge_output.label_box(t.x, t.y, t.string, t.size)
                 for t in (s.text for s in cell.shapes(ly.find_layer(L, 215)).each())]
        boxes.sort()
        overlaps = sum(1 for k, a in enumerate(boxes) for b in boxes[k + 1:]
                       if b[0] < a[2] and a[1] < b[3] and b[1] < a[3])
        say("labels %d of %d drawn gauges, size %s DBU, overlapping pairs %d"
            % (len(boxes), n, boxes and round(boxes[0][3] - boxes[0][1]), overlaps))
        expect(0 < len(boxes) <= n and overlaps == 0 and all(b[3] > b[1] for b in boxes),
               "labels sized and never overprinting one another")
        rdb = view.rdb(view.num_rdbs() - 1)
        items = list(rdb.each_item())
        expect(len(items) == n, "the marker browser holds the drawn gauges: %d items" % len(items))
        forms = {"rank": r"^\d+$", "cd": r"^\d+(\.\d+)? nm$", "score": r"^\d+(\.\d+)? nm$",
                 "count": r"^\d{1,3}(,\d{3})* \([\d.e+-]+% of the layer's gauges\)$"}
        bad, example, ranks = [], None, []
        for item in items:
            values = {rdb.tag_name(v.tag_id): v.string() for v in item.each_value() if v.tag_id and v.is_string()}
            if set(values) != set(forms) or not all(re.match(forms[k], values[k]) for k in forms):
                bad.append(values)
            else:
                ranks.append(int(values["rank"]))
            example = example or values
        say("a marker browser item: %s" % example)
        expect(not bad, "every item reads rank as an integer, cd and score in nm, the count: %s" % bad[:2])
        expect(ranks == sorted(ranks) and len(set(ranks)) == len(ranks), "the items in rank order, one a drawn gauge")
        # The view at a 2 x 2 um zoom around the most critical gauge.
        edge = next(v.edge() for v in items[0].each_value() if v.is_edge())  # rank 1, in um
        c = edge.bbox().center()
        view.zoom_box(pya.DBox(c.x - 1, c.y - 1, c.x + 1, c.y + 1))
        state.update(items=len(items))
        later(1000, zoom_shots)
        return
    except Exception as e:
        expect(False, "exception: %s" % e)
    finish()


def zoom_shots():
    try:
        view = state["view"]
        shot = base + "_zoom2um.png"
        view.save_image(shot, 1000, 1000)
        expect(os.path.getsize(shot) > 12000, "screenshot %s (%d bytes)" % (shot, os.path.getsize(shot)))
        it = view.begin_layers()  # the labels, hidden at first, shown for the second picture
        while not it.at_end():
            if it.current().source_datatype == 215:
                p = it.current().dup()
                p.visible = True
                view.set_layer_properties(it, p)
            it.next()
        shot = base + "_zoom2um_labels.png"
        later(500, lambda: labels_shot(shot))
        return
    except Exception as e:
        expect(False, "exception: %s" % e)
    finish()


def labels_shot(shot):
    try:
        state["view"].save_image(shot, 700, 700)
        expect(os.path.getsize(shot) > 12000, "screenshot %s (%d bytes)" % (shot, os.path.getsize(shot)))
        later(300, flow_step)
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
    d.out.text = state["flow_out"]
    d.sizes.text = "5,7"
    expect(d.grab().save(base + "_flow_dialog.png"), "flow dialog screenshot saved")
    d._ok()


def check_results():
    d = gui.wait_for_dialog("ResultsDialog", check_results, 250, 1200)
    if d is None:
        return
    text = d.text()
    say("results dialog:\n" + text)
    expect("Markers covered" in text and "Calibration" in text and "Verification" in text
           and state["flow_out"] in text, "the results dialog: markers covered, the sets, the folder")
    expect(d.grab().save(base + "_results_dialog.png"), "results dialog screenshot saved")
    d.reject()


def flow_step():
    try:
        import linf_opc.bar as bar
        state["flow_out"] = tempfile.mkdtemp(prefix="linf_flow_tc3_")
        expected_dialog.extend(["Run OPC pattern flow", "OPC pattern flow: results"])
        later(700, fill_flow_dialog)
        later(1500, check_results)
        seconds, took = freeze.measure(lambda: mw.menu().action("tools_menu.linf_opc.flow").trigger())
        say("longest event-loop freeze during 'Run OPC pattern flow': %.2f s %s (action %.1f s)"
            % (seconds, freeze.where, took))
        expect(seconds < FREEZE_LIMIT, "the flow never freezes the editor %g s (%.2f s)" % (FREEZE_LIMIT, seconds))
        say("progress bar stages: %s" % bar.Bar.last)
        expect(bar.Bar.last[:3] == ["reading the layer", "diagram and gauges", "selection"]
               and "split" in bar.Bar.last, "the flow's stages named in the progress bar")
        view = state["view"]
        rdb = view.rdb(view.num_rdbs() - 1)
        plan = [{rdb.tag_name(v.tag_id): v.string() for v in it.each_value() if v.tag_id and v.is_string()}
                for it in rdb.each_item() if rdb.category_by_id(it.category_id()).name() == "split"]
        say("a plan item in the marker browser: %s" % (plan[0] if plan else None))
        expect(len(plan) == 2000 and all(re.match(r"^\d+(\.\d+)? nm$", d.get("cd", "")) and
                                         re.match(r"^\d{1,3}(,\d{3})*$", d.get("count", "")) for d in plan),
               "the plan's %d items in the marker browser read cd in nm and the count of their context" % len(plan))
        files = os.listdir(state["flow_out"])
        expect("report.html" in files and "calibration.oas" in files, "the flow wrote its files: %s" % sorted(files))
        expect(os.path.exists(base + "_results_dialog.png"), "the results dialog came up")
    except Exception as e:
        expect(False, "exception: %s" % e)
    finish()


later(500, load)
