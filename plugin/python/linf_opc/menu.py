"""Editor glue: the Tools menu entries and what they do to the current view.

Everything here is about the editor (current layer, transactions, progress, messages); the
work itself is the same stage functions the batch macro calls.
"""
import os

import pya

from . import arguments
from . import bar as progress_bar
from . import contexts
from . import core
from . import diagram as diagram_stage
from . import diagram_output
from . import dialogs
from . import farthest as farthest_stage
from . import flow
from . import gauge_output
from . import gauges as gauge_stage
from . import layer_style
from . import layout as layer_io
from . import contour_output
from . import markers as marker_io
from . import selection as selection_stage
from . import selection_output
from . import worker
from .inputs import Input
from .progress import count

MENU = "tools_menu.linf_opc"
TITLE = "L\u221e Voronoi OPC"


def _warn(text):
    pya.MessageBox.warning(TITLE, text, pya.MessageBox.Ok)


def _sentence(text):
    """A batch message ("no marker source given") as the editor says it: a sentence."""
    text = text.strip()
    if not text:
        return text
    text = text[0].upper() + text[1:]
    return text if text.endswith((".", "?", "!")) else text + "."


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
        shapes = sum(1 for _ in cv.cell.begin_shapes_rec(index).each())
        if shapes:  # a result layer of this plugin (zero-width paths), texts, or zero-area shapes
            _warn("Layer %s holds no area in cell %s: its %d shapes are lines of no width, texts or shapes of no "
                  "area (a result layer of this plugin is drawn so). Select a drawing layer."
                  % (info.to_s(), cv.cell.name, shapes))
        else:
            _warn("Layer %s has no shapes in cell %s. Select a drawing layer, or the cell that holds it."
                  % (info.to_s(), cv.cell.name))
        raise _Stop()
    return mw, view, cv, info, polygons


def _show_report(view, name, write):
    """The report database that write(path) writes as a file, loaded at once into the marker
    browser as `name`.lyrdb (KLayout names a loaded database after its file), in place of the
    one a previous run left there: filled item by item through KLayout's API it froze the
    editor for half a minute on a large layer."""
    import shutil
    import tempfile
    folder = tempfile.mkdtemp(prefix="linf_opc_rdb_")
    try:
        path = os.path.join(folder, name + ".lyrdb")
        write(path)
        rdb = pya.ReportDatabase(name)
        rdb.load(path)
    finally:
        shutil.rmtree(folder, ignore_errors=True)
    return _add_report(view, rdb)


def _add_report(view, rdb):
    """Adds a loaded report database to the view and shows it, in place of one of the same
    name (KLayout names a loaded database after its file) a previous run left there."""
    for i in reversed(range(view.num_rdbs())):
        if view.rdb(i).name() == rdb.name():
            view.remove_rdb(i)
    index = view.add_rdb(rdb)
    view.show_rdb(index, view.active_cellview_index())
    return index


def _undoable(view, ly, title, draw, working):
    """Runs draw() and puts the new layers into the layer list (layer_style: the group of the
    working layer (layer, datatype)) in one undo step; viewer mode keeps no undo history for
    shapes."""
    undoable = ly.is_editable()
    if undoable:
        view.transaction(title)
    try:
        result = draw()
        layer_style.show(view, ly, *working)
    finally:
        if undoable:
            view.commit()
    return result


def _run(title, action):
    """The editor survives anything the flow does: the core runs in a watched worker process
    (while it works, the editor stays responsive and the progress bar's cancel button stops it),
    and every failure becomes a message. action(bar) names its stages with bar.start(stage)."""
    bar = progress_bar.Bar(title)
    failures = os.path.join(pya.Application.instance().application_data_path(), "linf_opc_failures")
    runner = worker.Runner(bar.waiting, failures)
    try:
        with core.running_with(runner):
            action(bar)
    except _Stop:
        pass
    except arguments.UsageError as e:
        _warn(_sentence(str(e)))
    except diagram_stage.core.DiagramError as e:
        pya.MessageBox.critical(TITLE, "The diagram failed its independent check; nothing was drawn:\n%s" % e,
                                pya.MessageBox.Ok)
    except worker.Cancelled:
        pya.Application.instance().main_window().message("%s cancelled" % title, 5000)
    except worker.WorkerError as e:
        pya.MessageBox.critical(TITLE, "%s: %s" % (title, e), pya.MessageBox.Ok)
    except ValueError as e:  # input the core refuses (a coordinate beyond +-2^30, a bad marker file, ...)
        _warn("%s cannot run on this input: %s. Your layout was not changed." % (title, str(e).strip().rstrip(".")))
    except Exception as e:
        if "cancel" in str(e).lower():  # the progress bar's cancel button raises in set()
            pya.Application.instance().main_window().message("%s cancelled" % title, 5000)
        else:
            pya.MessageBox.critical(TITLE, "%s failed: %s" % (title, e), pya.MessageBox.Ok)
    finally:
        bar.close()


def voronoi_of_current_layer():
    def action(bar):
        bar.start("reading the layer")
        mw, view, cv, info, polygons = _layer_polygons()
        bar.start("diagram (core)")
        diagram = diagram_stage.compute(polygons, dbu=cv.layout().dbu, with_pieces=False, draw_layer=info.layer,
                                        progress=bar.core)
        bar.start("drawing")
        ly = cv.layout()
        # Drawn within the layer's box: "zoom fit" shows the layout, not rays (voronoi.oas keeps them).
        box = cv.cell.bbox_per_layer(ly.find_layer(info.layer, info.datatype))
        drawn = diagram_output.drawing(diagram, info.layer, box)
        _undoable(view, ly, "L\u221e Voronoi diagram of %s" % info.to_s(),
                  lambda: diagram_output.add_layers(ly, cv.cell, diagram, info.layer, info.datatype, drawn),
                  (info.layer, info.datatype))
        c = diagram.counts()
        mw.message("L\u221e Voronoi: %d pieces (internal %d, external %d, notch %d, adjacent %d), checked, %.2f s"
                   % (diagram.n_pieces, c["internal"], c["external"], c["notch"], c["adjacent"],
                      diagram.seconds["total"]), 10000)
    _run("L\u221e Voronoi diagram", action)


def gauges_of_current_layer():
    def action(bar):
        bar.start("reading the layer")
        mw, view, cv, info, polygons = _layer_polygons()
        bar.start("diagram and gauges (core)")
        result = gauge_stage.compute(polygons, progress=bar.core)
        ly = cv.layout()
        # Drawn for reading: the representatives of the most critical (type, context) groups, the
        # context that of a 7 x 7 window (radius 3.5 pitches); the marker browser holds the same.
        bar.start("pitch and contexts (core)")
        pitch = selection_stage.pitch_of(result.gauges)
        groups = contexts.Contexts(result.gauges, contexts.context_ids(result.gauges, polygons,
                                                                        3.5 * pitch if pitch > 0 else 1000.0))
        bar.start("drawing")
        drawn = _undoable(view, ly, "Gauges on %s" % info.to_s(),
                          lambda: gauge_output.add_representatives(ly, cv.cell, result.gauges, groups, info.layer,
                                                                   info.datatype, label_height=pitch / 2),
                          (info.layer, info.datatype))
        bar.start("marker browser")
        _show_report(view, "gauges %d-%d" % (info.layer, info.datatype), lambda path: gauge_output.write_drawn_report(
            result.gauges, groups, drawn, ly.dbu, cv.cell.name, cv.filename(), path))
        c = {k: count(v) for k, v in result.counts().items()}
        best = result.gauges[0] if result.gauges else None
        mw.message("Gauges: %s (internal %s, external %s, sandwich %s, comb %s, T %s) in %s contexts; the %s most "
                   "critical contexts drawn and in the marker browser%s; %.1f s"
                   % (count(len(result.gauges)), c["internal"], c["external"], c["sandwich"], c["comb"], c["T"],
                      count(len(groups)), count(len(drawn)),
                      "; most critical: %s %.4g nm" % (best.type, best.cd * ly.dbu * 1000) if best else "",
                      result.seconds["total"]), 10000)
        gauges_of_current_layer.last = (len(result.gauges), len(groups), len(drawn))
    _run("Gauges", action)


def select_patterns():
    def action(bar):
        bar.start("reading the layer")
        mw, view, cv, info, polygons = _layer_polygons()
        ly = cv.layout()
        layers = ["%d/%d" % (i.layer, i.datatype) for i in (ly.get_info(k) for k in ly.layer_indexes())
                  if not (i.layer == info.layer and i.datatype == info.datatype) and i.datatype < 200]
        values = dialogs.ask_selection(layers, "Select patterns on %s" % info.to_s())
        if values is None:
            return
        try:
            sizes, modes, mode, size, pitch, _ = arguments.select_args(dict(values, modes="A,B,C"), ly.dbu)
            markers = marker_io.load(values["markers"], ly, cv.cell)
        except (arguments.UsageError, marker_io.MarkerError) as e:
            _warn(str(e))
            raise _Stop()
        if not markers.boxes:
            _warn("No markers in %s." % markers.source)
            raise _Stop()
        bar.start("diagram and gauges (core)")
        result = gauge_stage.compute(polygons, progress=bar.core)
        bar.start("selection (core)")
        if pitch is None:
            pitch = selection_stage.pitch_of(result.gauges)
        if not pitch or pitch <= 0:
            _warn("Cannot estimate the pitch of %s: give it in the dialog." % info.to_s())
            raise _Stop()
        st = selection_stage.study(result.gauges, markers.boxes, pitch, sizes, modes)
        chosen = st.best(mode)
        bar.start("drawing")
        _undoable(view, ly, "Pattern windows on %s" % info.to_s(),
                  lambda: selection_output.add_layer(ly, cv.cell, chosen, info.layer, info.datatype),
                  (info.layer, info.datatype))
        name = "patterns %s" % info.to_s()
        for i in reversed(range(view.num_rdbs())):  # a rerun replaces its report database
            if view.rdb(i).name() == name:
                view.remove_rdb(i)
        index = view.create_rdb(name)
        selection_output.report(st, result.gauges, ly.dbu, cv.cell.name, view.rdb(index), markers)
        view.show_rdb(index, view.active_cellview_index())
        row = chosen.row(ly.dbu)
        mw.message("Patterns: mode %s %s (pitch %.4g um): %d windows cover %d of %d markers (P_d %.2f%%)"
                   % (chosen.mode, row["W_s"], pitch * ly.dbu, len(chosen.windows), chosen.covered,
                      len(markers.boxes), row["P_d"]), 10000)
    _run("Select patterns", action)


def run_flow():
    """Run OPC pattern flow...: the dialog, then diagram -> gauges -> selection -> split written
    to the chosen folder, the windows drawn (one undo step) and the results in the marker browser."""
    def action(bar):
        mw, view = _open_view()
        cv = view.active_cellview()
        ly = cv.layout()
        layers = ["%d/%d" % (i.layer, i.datatype) for i in (ly.get_info(k) for k in ly.layer_indexes())
                  if i.datatype < 200]
        sel = current_layer(view)
        here = "%d/%d" % (sel[2].layer, sel[2].datatype) if sel else None
        path = cv.filename()
        beside = (os.path.join(os.path.dirname(path), os.path.splitext(os.path.basename(path))[0] + "_linf_opc")
                  if path else "")
        box = cv.cell.dbbox()
        values = dialogs.ask_flow(layers, here, "Run OPC pattern flow on %s" % cv.cell.name, beside,
                                  max(box.width(), box.height()))
        if values is None:
            raise _Stop()
        l, d = layer_io.parse_layer(values["layer"])
        index = ly.find_layer(l, d)
        if index is None:
            _warn("Layer %s is not in the layout." % values["layer"])
            raise _Stop()
        bar.start("reading the layer")
        inp = Input(ly, cv.cell, index, cv.filename(), values["out"], builder=values.get("builder", "sweep"),
                    check=values.get("check", "sample"))
        args = dict(values, modes="A,B,C", halves="0")
        try:
            with core.tiles_at(values.get("scheduler") or None):  # blank: this computer
                line, rdb_name, chosen = flow.run(inp, args, bar)  # it names its stages in the bar
            inp.out.commit()
        finally:
            inp.out.abort()  # no-op after a commit; a failed run leaves no partial files
        contours, mask = [], None
        if values.get("litho"):
            bar.start("printed contours (core)")
            contours, mask = contour_output.printed_contours(inp, values, chosen)
        bar.start("drawing")
        rdb = pya.ReportDatabase("flow")
        rdb.load(os.path.join(inp.dir, rdb_name))

        def draw():
            selection_output.add_layer(ly, cv.cell, chosen, l, d)
            contour_output.add_layer(ly, cv.cell, l, d, values.get("litho"), contours)
            contour_output.add_mask_layer(ly, cv.cell, l, d, values.get("litho"), mask)
        _undoable(view, ly, "OPC pattern flow on %s" % values["layer"], draw, (l, d))
        index = _add_report(view, rdb)
        mw.message(line, 20000)
        run_flow.last = line
        run_flow.folder = inp.dir
        run_flow.show_plan = lambda: view.show_rdb(index, view.active_cellview_index())
    run_flow.folder = None
    _run("OPC pattern flow", action)
    if run_flow.folder:  # after the progress bar has gone
        dialogs.show_results(run_flow.folder, "OPC pattern flow: results",
                             lambda path: pya.Application.instance().main_window().load_layout(path, 1),
                             run_flow.show_plan)


def farthest_of_selection():
    """Farthest Voronoi of selection: the selected shapes, or the current layer's shapes in the
    visible area; the diagram on L/240, the smallest touching square on L/241 (one undo step)."""
    def action(bar):
        bar.start("reading the shapes")
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
        bar.start("farthest diagram (core)")
        result = farthest_stage.compute(sites)
        bar.start("drawing")
        clip = farthest_stage.clip_for(sites)
        _undoable(view, ly, "Farthest Voronoi of %s" % what,
                  lambda: farthest_stage.add_layers(ly, cv.cell, result, clip, info.layer),
                  (info.layer, info.datatype))
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
