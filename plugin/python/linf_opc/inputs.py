"""The layer a command works on: read from the batch's arguments (load, Input.from_args) or
taken from the editor's open layout (Input), with the staging folder its files go to."""
import os
import time

import pya

from . import glp
from . import layout as layer_io
from . import markers as marker_io
from . import polygons as polygons_io
from .arguments import UsageError, parse_builder, parse_check, parse_tile
from .staging import Staging


def load(args):
    """Reads input/cell/layer; returns (layout, cell, layer index, (L, D))."""
    path = args.get("input")
    if not path:
        raise UsageError("missing -rd input=FILE")
    if os.path.isdir(path):
        raise UsageError("the input %s is a folder, not a layout file" % path)
    if not os.path.isfile(path):
        raise UsageError("input file not found: %s" % path)
    try:
        open(path, "rb").close()  # KLayout's own message would be "Unable to open file ... (errno=13)"
    except OSError as e:
        raise UsageError("cannot read the input file %s: %s" % (path, e.strerror))
    layer, datatype = layer_io.parse_layer(args.get("layer") or "")
    try:
        ly = layer_io.read_layout(path, only_layers([(layer, datatype), marker_io.layer_of(args.get("markers"))]))
    except glp.GlpError as e:
        raise UsageError("cannot read %s" % e)
    except RuntimeError as e:
        raise UsageError("cannot read %s: %s" % (path, str(e).splitlines()[0]))
    for i in list(ly.layer_indexes()):  # a layer the map made that the file does not have
        if all(c.shapes(i).is_empty() for c in ly.each_cell()):
            ly.delete_layer(i)
    name = args.get("cell")
    if name:
        cell = ly.cell(name)
        if cell is None:
            raise UsageError("no cell named %r in %s" % (name, path))
    else:
        tops = ly.top_cells()
        if len(tops) != 1:
            raise UsageError("%s has %d top cells; choose one with -rd cell=NAME" % (path, len(tops)))
        cell = tops[0]
    index = ly.find_layer(layer, datatype)
    if index is None:
        raise UsageError("layer %d/%d is not in %s" % (layer, datatype, path))
    return ly, cell, index, (layer, datatype)


def only_layers(layers):
    """Reading options for the given (L, D) layers only (None entries ignored): a design file
    holds dozens of layers, and a command needs its layer and perhaps a marker layer."""
    opt = pya.LoadLayoutOptions()
    lm = pya.LayerMap()
    for i, ld in enumerate(x for x in layers if x is not None):
        lm.map(pya.LayerInfo(*ld), i)
    opt.layer_map = lm
    opt.create_other_layers = False
    return opt


class Input:
    """The layer to work on: layout, cell, layer, its region and polygons (as drawn: the core
    merges them), where its files go (out: a Staging; dir: the output folder). The batch builds
    it from its arguments (from_args), the editor from the current view."""
    def __init__(self, ly, cell, index, path, out, tile=-1, builder="sweep", check="sample"):
        self.ly, self.cell, self.index = ly, cell, index
        self.tile = tile  # the builder's tile side in DBU, 0 one tile, -1 automatic
        self.builder = builder  # "sweep" or "subdivision" (arguments.parse_builder)
        self.check = check  # "sample" or "full" (arguments.parse_check)
        info = ly.get_info(index)
        self.layer, self.datatype = info.layer, info.datatype
        self.path = os.path.abspath(path) if path else ""
        self.out = Staging(out)  # the output folder locked at once: a second run there is refused early
        self.dir = self.out.final  # where the files end up (named in messages)
        try:
            t0 = time.perf_counter()
            self.region = layer_io.region_of(self.cell, self.index)
            self.polygons = layer_io.polygons_of(self.region, polygons_io.SPILL_SHAPES)
            if not self.polygons:
                raise UsageError("layer %d/%d is empty in cell %s" % (self.layer, self.datatype, self.cell.name))
            self.t_read = time.perf_counter() - t0
        except BaseException:
            self.out.abort()  # the editor has no finish_all: its folder must not stay locked
            raise
        self.dbu = self.ly.dbu
        self.name = "%d/%d" % (self.layer, self.datatype)

    @classmethod
    def from_args(cls, args):
        ly, cell, index, _ = load(args)
        if not args.get("out"):
            raise UsageError("missing -rd out=DIR")
        return cls(ly, cell, index, args["input"], args["out"], parse_tile(args.get("tile"), ly.dbu),
                   parse_builder(args.get("builder")), parse_check(args.get("check")))

    def file(self, name):
        return self.out.file(name)
