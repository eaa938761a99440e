# The fault matrix's editor rows (docs/testing.md, "Fault matrix"), run by run_gui.sh in
# editor mode under Xvfb:
#   run_gui.sh BUILD samples/metal.oas 1/0 SHOT.png -e script=gui_faults.py
# Each hostile input is written into a temporary folder, opened in a view of its own and given
# to a menu action, as a person would. A refused input gives one message (captured, closed),
# leaves the layout as it was (every layer's shapes) and the undo history intact (the person's
# own last edit, made just before, is still what Undo takes back). An accepted one gives its
# result and no message. -rd input is unused but for run_gui.sh's contract.
import json
import os
import sys
import tempfile
import time

import pya

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from gui_harness import Gui  # noqa: E402

g = globals()
gui = Gui(g, watch_ms=300, capture_all=True)
app, mw, failures, timers = gui.app, gui.mw, gui.failures, gui.timers
say, expect, finish, later = gui.say, gui.expect, gui.finish, gui.later
expected_dialog, captured, capture_titles = gui.expected_dialog, gui.captured, gui.capture_titles
work = tempfile.mkdtemp(prefix="linf_gui_faults_")
L, D = 1, 0


# --- the hostile layouts -------------------------------------------------------------------

def write(name, fill, top="TOP"):
    ly = pya.Layout()
    ly.dbu = 0.001
    cell = ly.create_cell(top)
    li = ly.layer(L, D)
    fill(ly, cell, li)
    path = os.path.join(work, name + ".oas")
    ly.write(path)
    return path


def wires(cell, li, x0=0, y0=0, n=6):
    for i in range(n):
        cell.shapes(li).insert(pya.Box(x0 + i * 60, y0, x0 + i * 60 + 30, y0 + 400))


def empty_layer(ly, cell, li):
    pass


def texts_only(ly, cell, li):
    for i in range(3):
        cell.shapes(li).insert(pya.Text("label%d" % i, pya.Trans(i * 100, 0)))


def beyond_range(ly, cell, li):
    wires(cell, li)
    cell.shapes(li).insert(pya.Box(2 ** 30 - 200, 0, 2 ** 30, 100))  # reaches +2^30: outside the range


def huge_coordinates(ly, cell, li):
    wires(cell, li)
    m = 2 ** 30 - 1
    cell.shapes(li).insert(pya.Box(m - 800, m - 800, m, m))
    cell.shapes(li).insert(pya.Box(-m, -m, -m + 800, -m + 800))


def bow_tie(ly, cell, li):
    wires(cell, li, 1000, 0)
    cell.shapes(li).insert(pya.Polygon([pya.Point(0, 0), pya.Point(400, 400), pya.Point(400, 0), pya.Point(0, 400)],
                                       True))
    # A figure-8 touching itself at a vertex.
    cell.shapes(li).insert(pya.Polygon([pya.Point(0, 600), pya.Point(200, 600), pya.Point(200, 800),
                                        pya.Point(400, 800), pya.Point(400, 1000), pya.Point(200, 1000),
                                        pya.Point(200, 800), pya.Point(0, 800)], True))


def ordinary(ly, cell, li):
    for j in range(4):
        wires(cell, li, 0, j * 500, 10)


# --- one case ------------------------------------------------------------------------------

def settle(seconds=1.0):
    end = time.monotonic() + seconds
    while time.monotonic() < end:
        app.process_events()
        time.sleep(0.02)


def snapshot(ly, cell):
    """Each layer holding shapes, with their number and box."""
    return sorted((ly.get_info(i).to_s(), cell.shapes(i).size(), cell.bbox_per_layer(i).to_s())
                  for i in ly.layer_indexes() if cell.shapes(i).size())


def open_case(path):
    """A new view of `path`, its layer 1/0 current, and a person's edit (a box on 99/0, one undo
    step) made last: (view, layout, cell, the edit's shape count)."""
    mw.load_layout(path, 1)
    settle()  # the layer list fills in, and the load's own bookkeeping ends, from the event loop
    view = mw.current_view()
    cv = view.active_cellview()
    ly, cell = cv.layout(), cv.cell
    li = ly.layer(99, 0)
    view.add_missing_layers()  # a change of the layer list is an undo step of its own: made before
    settle()
    view.transaction("a person's edit")
    cell.shapes(li).insert(pya.Box(0, 0, 10, 10))
    view.commit()
    target = ly.find_layer(L, D)
    it = view.begin_layers()
    while not it.at_end():
        if it.current().layer_index() == target:
            view.current_layer = it
            break
        it.next()
    return view, ly, cell


def refused(name, fill, action, wanted, top="TOP"):
    """The action on layout `fill` gives one message holding every text of `wanted`; the layout
    is unchanged; Undo then takes back the person's edit."""
    path = write(name, fill, top)
    view, ly, cell = open_case(path)
    before = snapshot(ly, cell)
    del captured[:]
    mw.menu().action("tools_menu.linf_opc." + action).trigger()
    say("%s: messages %s" % (name, captured))
    expect(len(captured) == 1 and all(w in captured[0] for w in wanted),
           "%s: one message saying %s" % (name, " / ".join(wanted)))
    expect(snapshot(ly, cell) == before, "%s: the layout unchanged" % name)
    mw.cm_undo()
    expect(edit_undone(ly, cell), "%s: undo intact (it takes back the person's edit)" % name)
    return view, ly, cell


def edit_undone(ly, cell):
    li = ly.find_layer(99, 0)
    return li is None or cell.shapes(li).size() == 0


def accepted(name, fill, action):
    """The action on layout `fill` draws its result without a message; one Undo removes it."""
    path = write(name, fill)
    view, ly, cell = open_case(path)
    before = snapshot(ly, cell)
    del captured[:]
    mw.menu().action("tools_menu.linf_opc." + action).trigger()
    say("%s: messages %s" % (name, captured))
    drawn = {ly.get_info(i).to_s(): cell.shapes(i).size() for i in ly.layer_indexes()
             if ly.get_info(i).datatype >= 200 and cell.shapes(i).size()}
    expect(not captured and drawn, "%s: a result, no message (%s)" % (name, drawn))
    box = cell.bbox()
    expect(max(abs(box.left), abs(box.bottom), abs(box.right), abs(box.top)) < 2 ** 31,
           "%s: everything drawn holds in 32 bits (%s)" % (name, box))
    layer_box = cell.bbox_per_layer(ly.find_layer(L, D))
    results = [cell.bbox_per_layer(i) for i in ly.layer_indexes() if 200 <= ly.get_info(i).datatype < 216]
    expect(all(layer_box.contains(b.p1) and layer_box.contains(b.p2) for b in results if not b.empty()),
           "%s: the result within the layer's box %s" % (name, layer_box))
    mw.cm_undo()
    expect(snapshot(ly, cell) == before, "%s: one undo removes the result" % name)
    return view, ly, cell


def run_cases():
    try:
        refused("empty_top_cell", empty_layer, "gauges", ["Select a drawing layer"])
        refused("texts_only", texts_only, "voronoi", ["holds no area", "Select a drawing layer"])
        refused("beyond_range", beyond_range, "voronoi", ["2^30", "not changed"])
        refused("beyond_range_gauges", beyond_range, "gauges", ["2^30", "not changed"])
        view, ly, cell = accepted("huge_coordinates", huge_coordinates, "voronoi")
        accepted("bow_tie", bow_tie, "voronoi")
        accepted("bow_tie_gauges", bow_tie, "gauges")
        # A truncated layout file: KLayout refuses to open it (its own error); no view is added.
        with open(write("whole", ordinary), "rb") as f:
            data = f.read()
        cut = os.path.join(work, "truncated.oas")
        with open(cut, "wb") as f:
            f.write(data[:len(data) // 2])
        views = mw.views()
        try:
            mw.load_layout(cut, 1)
            expect(False, "truncated: KLayout opened a truncated file")
        except Exception as e:
            say("truncated: %s" % str(e).splitlines()[0])
            expect(mw.views() == views, "truncated: KLayout refuses it, no view added")
        later(300, markers_cases)
        return
    except Exception as e:
        expect(False, "exception: %s" % e)
    finish()


def flow_case(name, markers, after):
    """The flow on the ordinary layer with `markers` (a file): fills its dialog, runs it."""
    import linf_opc.dialogs as dialogs
    path = write(name, ordinary)
    view, ly, cell = open_case(path)
    out = os.path.join(work, name + "_out")
    os.makedirs(out)
    with open(os.path.join(out, "earlier.txt"), "w") as f:
        f.write("an earlier run's file\n")

    def fill():
        d = dialogs.current
        if d is None:
            later(200, fill)
            return
        d.layer.currentIndex = d.layer.findText("%d/%d" % (L, D))
        d.markers.setEditText(markers)
        d.out.text = out
        d.sizes.text = "5"
        d.pitch.text = "0.06"
        d.budget.text = "5"
        d.confirm = lambda parent, q: True  # the folder holds a file: yes, write into it
        d._ok()

    def close_results():
        d = dialogs.current
        if d is not None and isinstance(d, dialogs.ResultsDialog):
            state["results"] = d.text()
            d.reject()
        elif state.get("running"):
            later(300, close_results)
    state.update(results=None, running=True)
    before = snapshot(ly, cell)
    del captured[:]
    expected_dialog[:] = ["Run OPC pattern flow", "OPC pattern flow: results"]
    later(500, fill)
    later(800, close_results)
    mw.menu().action("tools_menu.linf_opc.flow").trigger()
    state["running"] = False
    expected_dialog[:] = []
    after(name, view, ly, cell, out, before)


state = {}


def markers_cases():
    try:
        # NaN, inf and empty rows are skipped and counted: the flow runs.
        nan = os.path.join(work, "nan_markers.csv")
        with open(nan, "w") as f:
            f.write("x,y\n100,200\nnan,5\ninf,7\n\n,\n400,1200\n-inf,1e999\n")

        def nan_after(name, view, ly, cell, out, before):
            say("%s: messages %s; results %r" % (name, captured, state["results"]))
            expect(not captured and state["results"] and "Markers covered" in state["results"],
                   "%s: the flow runs, its results shown, no message" % name)
            try:
                with open(os.path.join(out, "stats.json")) as f:
                    skipped = json.load(f)["marker_source"].get("skipped_rows")
            except (OSError, ValueError, KeyError) as e:
                skipped = str(e)
            expect(skipped == 5, "%s: the 5 bad rows skipped and counted (%s)" % (name, skipped))
            mw.cm_undo()
            expect(snapshot(ly, cell) == before, "%s: one undo removes the windows" % name)
        flow_case("nan_markers", nan, nan_after)

        # A folder given as the marker file: refused, nothing written, the earlier file kept.
        def folder_after(name, view, ly, cell, out, before):
            say("%s: messages %s" % (name, captured))
            expect(len(captured) == 1 and "folder" in captured[0] and state["results"] is None,
                   "%s: one message, no results" % name)
            expect(sorted(os.listdir(out)) == ["earlier.txt"], "%s: nothing written, the earlier file kept: %s"
                   % (name, sorted(os.listdir(out))))
            expect(snapshot(ly, cell) == before, "%s: the layout unchanged" % name)
            mw.cm_undo()
            expect(edit_undone(ly, cell), "%s: undo intact (it takes back the person's edit)" % name)
        flow_case("markers_folder", work, folder_after)
    except Exception as e:
        expect(False, "exception: %s" % e)
    finish()


later(500, run_cases)
