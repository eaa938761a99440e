"""How the plugin's layers look in the editor's layer list: one group node a working layer,
"L∞ OPC (L/D)", holding each result layer with its own colour and a hollow fill, the
`adjacent` pieces and the gauge labels hidden (millions of edge-to-endpoint pieces on a full
layer are not what a person looks for; labels overprint until zoomed in). A second run replaces
the group."""
import pya

from .diagram_output import DATATYPE_BASE, KINDS
from .gauge_output import DATATYPE as GAUGE_DATATYPE
from .selection_output import DATATYPE as WINDOW_DATATYPE

# datatype: (name in the layer list, colour, shown at first)
STYLES = {DATATYPE_BASE + KINDS.index("internal"): ("internal (widths)", 0x1f77b4, True),
          DATATYPE_BASE + KINDS.index("external"): ("external (spaces)", 0xff7f0e, True),
          DATATYPE_BASE + KINDS.index("notch"): ("notch", 0x9467bd, True),
          DATATYPE_BASE + KINDS.index("adjacent"): ("adjacent (edge to its end)", 0x9a9a9a, False),
          GAUGE_DATATYPE: ("gauges internal (W)", 0xd62728, True),
          GAUGE_DATATYPE + 1: ("gauges external (S)", 0x17becf, True),
          GAUGE_DATATYPE + 2: ("gauges sandwich (SW)", 0xbcbd22, True),
          GAUGE_DATATYPE + 3: ("gauges comb (C)", 0xe7298a, True),
          GAUGE_DATATYPE + 4: ("gauges T", 0x7f7f00, True),
          GAUGE_DATATYPE + 5: ("gauge labels", 0x404040, False),
          WINDOW_DATATYPE: ("pattern windows", 0x2ca02c, True),
          216: ("printed contours (nominal)", 0x1f3fb4, True),
          217: ("OPC-corrected layer", 0xff7f0e, True),
          240: ("farthest diagram", 0x8c564b, True),
          241: ("smallest touching square", 0xe377c2, True)}
HOLLOW = 1  # KLayout's dither pattern 1: no fill, the frame only


def group_name(layer, datatype):
    return "L\u221e OPC (%d/%d)" % (layer, datatype)


def show(view, layout, layer, datatype):
    """Puts the plugin's layers of working layer `layer`/`datatype` that exist in `layout` into
    their group node (made anew), styled; any other new layer as KLayout adds it."""
    name = group_name(layer, datatype)
    it = view.begin_layers()
    while not it.at_end():
        if it.current().name == name:
            view.delete_layer(it)
            break
        it.next_sibling(1)
    cv = view.active_cellview_index()
    node = pya.LayerPropertiesNode()
    node.name = name
    for dt, (label, colour, visible) in sorted(STYLES.items()):
        if layout.find_layer(layer, dt) is None:
            continue
        p = pya.LayerPropertiesNode()
        p.source_layer, p.source_datatype, p.source_cellview = layer, dt, cv
        p.name = "%s %d/%d" % (label, layer, dt)
        p.fill_color = p.frame_color = colour
        p.dither_pattern = HOLLOW
        p.width = 3 if GAUGE_DATATYPE <= dt < GAUGE_DATATYPE + 5 else 1  # gauge lines are tens of nm: drawn bold
        p.visible = visible
        node.add_child(p)
    if node.has_children():
        view.insert_layer(view.end_layers(), node)
    view.add_missing_layers()


def group(view, layer, datatype):
    """The group node of working layer layer/datatype in the layer list, or None."""
    name = group_name(layer, datatype)
    it = view.begin_layers()
    while not it.at_end():
        if it.current().name == name:
            return it.current()
        it.next_sibling(1)
    return None
