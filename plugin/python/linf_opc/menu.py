"""Editor glue: the Tools menu entries and what they do to the current view.

Everything here is about the editor (current layer, transactions, progress, messages); the
work itself is the same stage functions the batch macro calls.
"""
import os

import pya

from . import batch
from . import core
from . import diagram as diagram_stage
from . import dialogs
from . import farthest as farthest_stage
from . import gauge_output
from . import gauges as gauge_stage
from . import layout as layer_io
from . import markers as marker_io
from . import output
from . import selection as selection_stage
from . import selection_output
from . import worker

MENU = "tools_menu.linf_opc"
TITLE = "L\u221e Voronoi OPC"


def _warn(text):
    pya.MessageBox.warning(TITLE, text, pya.MessageBox.Ok)


def current_layer(view):
    """(cellview, layer index, LayerInfo) of the layer selected in the layer list, or None."""
    it = view.current_layer
    if it.is_null():
        return None
    props = it.current()
    if props.has_children() or props.layer_index() < 0:
        return None
    cv = view.cellview(props.cellview())
    if not cv.is_valid():
        return None
    return cv, props.layer_index(), cv.layout().get_info(props.layer_index())


class _Stop(Exception):
    """Raised after the person has been told why the action cannot go on."""


def _open_view():
    """(main window, view) with a layout open, or _Stop after a message."""
    mw = pya.Application.instance().main_window()
    view = mw.current_view()
    if view is None or not view.active_cellview().is_valid():
        _warn("Open a layout first.")
        raise _Stop()
    return mw, view


def _layer_polygons():
    """(main window, view, cellview, layer info, polygons) of the current layer, or _Stop
    after a message: no layout, no layer selected, empty layer."""
    mw, view = _open_view()
    sel = current_layer(view)
    if sel is None:
        _warn("Select a drawing layer in the layer list first.")
        raise _Stop()
    cv, index, info = sel
    polygons = layer_io.polygons_of(layer_io.region_of(cv.cell, index))
    if not polygons:
        _warn("Layer %s has no shapes in cell %s." % (info.to_s(), cv.cell.name))
        raise _Stop()
    return mw, view, cv, info, polygons


def _undoable(view, ly, title, draw):
    """Runs draw() and adds the new layers to the layer list in one undo step; viewer mode
    keeps no undo history for shapes."""
    undoable = ly.is_editable()
    if undoable:
        view.transaction(title)
    try:
        result = draw()
        view.add_missing_layers()
    finally:
        if undoable:
            view.commit()
    return result


def _runner():
    """The core runs in a watched worker process; while it works, the editor stays responsive
    and the progress bar's cancel button stops it."""
    app = pya.Application.instance()
    busy = pya.AbsoluteProgress("computing")
    busy.format = "%.0f s"
    busy.unit = 1

    def wait(elapsed):
        busy.set(int(elapsed), True)  # raises when the person cancels
        app.process_events()
    failures = os.path.join(app.application_data_path(), "linf_opc_failures")
    runner = worker.Runner(wait, failures)
    runner.progress = busy
    return runner


def _run(title, action, steps=3):
    """The editor survives anything the flow does: the core runs in a worker process, and
    every failure becomes a message."""
    progress = pya.RelativeProgress(title, steps)
    runner = _runner()
    try:
        with core.running_with(runner):
            action(progress)
    except _Stop:
        pass
    except batch.UsageError as e:
        _warn(str(e))
    except diagram_stage.core.DiagramError as e:
        pya.MessageBox.critical(TITLE, "The diagram failed its independent check; nothing was drawn:\n%s" % e,
                                pya.MessageBox.Ok)
    except worker.Cancelled:
        pya.Application.instance().main_window().message("%s cancelled" % title, 5000)
    except worker.WorkerError as e:
        pya.MessageBox.critical(TITLE, "%s: %s" % (title, e), pya.MessageBox.Ok)
    except Exception as e:
        if "cancel" in str(e).lower():  # the progress bar's cancel button raises in inc()
            pya.Application.instance().main_window().message("%s cancelled" % title, 5000)
        else:
            pya.MessageBox.critical(TITLE, "%s failed: %s" % (title, e), pya.MessageBox.Ok)
    finally:
        runner.progress._destroy()
        progress._destroy()


def voronoi_of_current_layer():
    def action(progress):
        mw, view, cv, info, polygons = _layer_polygons()
        progress.inc()
        diagram = diagram_stage.compute(polygons, dbu=cv.layout().dbu, with_pieces=False, draw_layer=info.layer)
        progress.inc()
        ly = cv.layout()
        _undoable(view, ly, "L\u221e Voronoi diagram of %s" % info.to_s(),
                  lambda: output.add_layers(ly, cv.cell, diagram, info.layer, info.datatype))
        progress.inc()
        c = diagram.counts()
        mw.message("L\u221e Voronoi: %d pieces (internal %d, external %d, notch %d, adjacent %d), checked, %.2f s"
                   % (diagram.n_pieces, c["internal"], c["external"], c["notch"], c["adjacent"],
                      diagram.seconds["total"]), 10000)
    _run("L\u221e Voronoi diagram", action)


def gauges_of_current_layer():
    def action(progress):
        mw, view, cv, info, polygons = _layer_polygons()
        progress.inc()
        result = gauge_stage.compute(polygons)
        progress.inc()
        ly = cv.layout()
        _undoable(view, ly, "Gauges on %s" % info.to_s(),
                  lambda: gauge_output.add_layer(ly, cv.cell, result.gauges, info.layer, info.datatype))
        index = view.create_rdb("gauges %s" % info.to_s())
        gauge_output.report(result.gauges, ly.dbu, cv.cell.name, cv.filename(), view.rdb(index))
        view.show_rdb(index, view.active_cellview_index())
        progress.inc()
        c = result.counts()
        best = result.gauges[0] if result.gauges else None
        cap = gauge_output.REPORT_MAX_PER_TYPE
        mw.message("Gauges: %d (internal %d, external %d, sandwich %d, comb %d, T %d)%s%s, %.2f s"
                   % (len(result.gauges), c["internal"], c["external"], c["sandwich"], c["comb"], c["T"],
                      "; most critical: %s %.4g um" % (best.type, best.cd * ly.dbu) if best else "",
                      "; the marker browser holds the %d most critical of each type" % cap
                      if max(c.values()) > cap else "", result.seconds["total"]), 10000)
    _run("Gauges", action)


def select_patterns():
    def action(progress):
        mw, view, cv, info, polygons = _layer_polygons()
        ly = cv.layout()
        layers = ["%d/%d" % (i.layer, i.datatype) for i in (ly.get_info(k) for k in ly.layer_indexes())
                  if not (i.layer == info.layer and i.datatype == info.datatype) and i.datatype < 200]
        values = dialogs.ask_selection(layers, "Select patterns on %s" % info.to_s())
        if values is None:
            return
        try:
            sizes, modes, mode, size, pitch, _ = batch.select_args(dict(values, modes="A,B,C"), ly.dbu)
            markers = marker_io.load(values["markers"], ly, cv.cell)
        except (batch.UsageError, marker_io.MarkerError) as e:
            _warn(str(e))
            raise _Stop()
        if not markers.boxes:
            _warn("No markers in %s." % markers.source)
            raise _Stop()
        progress.inc()
        result = gauge_stage.compute(polygons)
        if pitch is None:
            pitch = selection_stage.pitch_of(result.gauges)
        if not pitch or pitch <= 0:
            _warn("Cannot estimate the pitch of %s: give it in the dialog." % info.to_s())
            raise _Stop()
        st = selection_stage.study(result.gauges, markers.boxes, pitch, sizes, modes)
        chosen = st.best(mode)
        progress.inc()
        _undoable(view, ly, "Pattern windows on %s" % info.to_s(),
                  lambda: selection_output.add_layer(ly, cv.cell, chosen, info.layer, info.datatype))
        index = view.create_rdb("patterns %s" % info.to_s())
        selection_output.report(st, result.gauges, ly.dbu, cv.cell.name, view.rdb(index), markers)
        view.show_rdb(index, view.active_cellview_index())
        progress.inc()
        row = chosen.row(ly.dbu)
        mw.message("Patterns: mode %s %s (pitch %.4g um): %d windows cover %d of %d markers (P_d %.2f%%)"
                   % (chosen.mode, row["W_s"], pitch * ly.dbu, len(chosen.windows), chosen.covered,
                      len(markers.boxes), row["P_d"]), 10000)
    _run("Select patterns", action)


def run_flow():
    """Run OPC pattern flow...: the dialog, then diagram -> gauges -> selection -> split written
    to the chosen folder, the windows drawn (one undo step) and the results in the marker browser."""
    def action(progress):
        mw, view = _open_view()
        cv = view.active_cellview()
        ly = cv.layout()
        layers = ["%d/%d" % (i.layer, i.datatype) for i in (ly.get_info(k) for k in ly.layer_indexes())
                  if i.datatype < 200]
        sel = current_layer(view)
        here = "%d/%d" % (sel[2].layer, sel[2].datatype) if sel else None
        values = dialogs.ask_flow(layers, here, "Run OPC pattern flow on %s" % cv.cell.name)
        if values is None:
            raise _Stop()
        if not values["out"]:
            _warn("Choose an output folder.")
            raise _Stop()
        l, d = layer_io.parse_layer(values["layer"])
        index = ly.find_layer(l, d)
        if index is None:
            _warn("Layer %s is not in the layout." % values["layer"])
            raise _Stop()
        inp = batch.Input(ly, cv.cell, index, cv.filename(), values["out"])
        args = dict(values, modes="A,B,C", halves="0")

        def step(stage):
            progress.format = stage
            progress.inc()
        try:
            line, rdb_name, chosen = batch.flow(inp, args, step)
            inp.out.commit()
        finally:
            inp.out.abort()  # no-op after a commit; a failed run leaves no partial files
        rdb = pya.ReportDatabase("flow")
        rdb.load(os.path.join(inp.dir, rdb_name))
        _undoable(view, ly, "OPC pattern flow on %s" % values["layer"],
                  lambda: selection_output.add_layer(ly, cv.cell, chosen, l, d))
        index = view.add_rdb(rdb)
        view.show_rdb(index, view.active_cellview_index())
        mw.message(line, 20000)
        run_flow.last = line
    _run("OPC pattern flow", action, steps=4)


def farthest_of_selection():
    """Farthest Voronoi of selection: the selected shapes, or the current layer's shapes in the
    visible area; the diagram on L/240, the smallest touching square on L/241 (one undo step)."""
    def action(progress):
        mw, view = _open_view()
        cv = view.active_cellview()
        ly = cv.layout()
        shapes, layers = [], set()
        for obj in view.each_object_selected():
            if not obj.is_cell_inst() and obj.cv_index == view.active_cellview_index():
                shapes.append((obj.shape, obj.trans()))
                layers.add(obj.layer)
        if shapes:
            sites = farthest_stage.sites_of_shapes(shapes)
            info = ly.get_info(sorted(layers)[0])
            what = "%d selected shapes" % len(sites)
        else:
            sel = current_layer(view)
            if sel is None:
                _warn("Select shapes, or a layer in the layer list (its shapes in the visible area are used).")
                raise _Stop()
            _, index, info = sel
            box = view.box().transformed(pya.CplxTrans(ly.dbu).inverted())
            sites = farthest_stage.sites_of_layer(cv.cell, index, box)
            what = "%d shapes of %s in view" % (len(sites), info.to_s())
        if not sites:
            _warn("No shapes to work on.")
            raise _Stop()
        progress.inc()
        result = farthest_stage.compute(sites)
        progress.inc()
        clip = farthest_stage.clip_for(sites)
        _undoable(view, ly, "Farthest Voronoi of %s" % what,
                  lambda: farthest_stage.add_layers(ly, cv.cell, result, clip, info.layer))
        progress.inc()
        mw.message("Farthest Voronoi of %s: %d faces; smallest touching square %.6g um (half-side %.6g um)"
                   % (what, len(result.faces), 2 * result.half_side * ly.dbu, result.half_side * ly.dbu), 20000)
        farthest_of_selection.last = result
    _run("Farthest Voronoi", action)


ENTRIES = [
    ("voronoi", "Voronoi diagram of current layer", voronoi_of_current_layer),
    ("gauges", "Suggest gauges on current layer", gauges_of_current_layer),
    ("select", "Select patterns...", select_patterns),
    ("flow", "Run OPC pattern flow...", run_flow),
    ("farthest", "Farthest Voronoi of selection", farthest_of_selection),
]


def register():
    menu = pya.Application.instance().main_window().menu()
    if menu.is_valid(MENU):
        return
    menu.insert_menu("tools_menu.end", "linf_opc", TITLE)
    register.actions = []  # keep the actions alive
    for name, title, handler in ENTRIES:
        action = pya.Action()
        action.title = title
        action.on_triggered(handler)
        menu.insert_item(MENU + ".end", name, action)
        register.actions.append(action)
