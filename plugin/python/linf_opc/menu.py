"""Editor glue: the Tools menu entries and what they do to the current view.

Everything here is about the editor (current layer, transactions, progress, messages); the
work itself is the same stage functions the batch macro calls.
"""
import pya

from . import diagram as diagram_stage
from . import layout as layer_io
from . import output

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


def voronoi_of_current_layer():
    mw = pya.Application.instance().main_window()
    view = mw.current_view()
    if view is None:
        _warn("Open a layout first.")
        return
    sel = current_layer(view)
    if sel is None:
        _warn("Select a drawing layer in the layer list first.")
        return
    cv, index, info = sel
    ly, cell = cv.layout(), cv.cell
    progress = pya.RelativeProgress("L\u221e Voronoi diagram of %s" % info.to_s(), 3)
    try:
        polygons = layer_io.polygons_of(layer_io.region_of(cell, index))
        progress.inc()
        if not polygons:
            _warn("Layer %s has no shapes in cell %s." % (info.to_s(), cell.name))
            return
        try:
            diagram = diagram_stage.compute(polygons)
        except diagram_stage.core.DiagramError as e:
            pya.MessageBox.critical(TITLE, "The diagram failed its independent check and was not drawn:\n%s" % e,
                                    pya.MessageBox.Ok)
            return
        progress.inc()
        # Shapes and layer list in one undo step; viewer mode keeps no undo history for shapes.
        undoable = ly.is_editable()
        if undoable:
            view.transaction("L\u221e Voronoi diagram of %s" % info.to_s())
        try:
            output.add_layers(ly, cell, diagram, info.layer, info.datatype)
            view.add_missing_layers()
        finally:
            if undoable:
                view.commit()
        progress.inc()
        c = diagram.counts()
        mw.message("L\u221e Voronoi: %d pieces (internal %d, external %d, notch %d, adjacent %d), checked, %.2f s"
                   % (len(diagram.pieces), c["internal"], c["external"], c["notch"], c["adjacent"],
                      diagram.seconds["total"]), 10000)
    except Exception as e:  # the editor must survive anything the flow does
        pya.MessageBox.critical(TITLE, "L\u221e Voronoi failed: %s" % e, pya.MessageBox.Ok)
    finally:
        progress._destroy()


def register():
    menu = pya.Application.instance().main_window().menu()
    if menu.is_valid(MENU):
        return
    menu.insert_menu("tools_menu.end", "linf_opc", TITLE)
    action = pya.Action()
    action.title = "Voronoi diagram of current layer"
    action.on_triggered(voronoi_of_current_layer)
    menu.insert_item(MENU + ".end", "voronoi", action)
    register.actions = [action]  # keep the action alive
