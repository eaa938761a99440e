"""GLP, the text layout format of the ICCAD 2013 mask-optimisation contest clips (OpenILT's
M1_test*.glp), which KLayout does not read:

    EQUIV  1  1000  MICRON  +X,+Y      1 database unit = 1/1000 um
    CNAME Temp_Top
    LEVEL M1                           layers, in this order: M1 -> 1/0 (named M1), the next 2/0, ...
    CELL Temp_Top PRIME
       RECT N M1  80  492  452  88     lower left x, y, width, height
       PGON N M1  216 80  304 80 ...   the vertices
    ENDMSG

read() gives a KLayout layout with one cell, so that the batch and the benchmarks take a GLP
clip as any other layout file. Anything else in the file is an error naming its line: a shape
silently dropped would be a wrong diagram.
"""
import pya

HEADER = ("BEGIN", "CNAME", "ENDMSG")


class GlpError(Exception):
    pass


def is_glp(path):
    return path.lower().endswith(".glp")


def read(path):
    ly = pya.Layout()
    cell, layers = None, {}

    def layer(name):
        if name not in layers:
            layers[name] = ly.layer(pya.LayerInfo(len(layers) + 1, 0, name))
        return layers[name]

    with open(path, encoding="ascii", errors="replace") as f:
        for n, line in enumerate(f, 1):
            words = line.split("/*")[0].split()
            if not words or words[0] in HEADER:
                continue
            key = words[0]
            try:
                if key == "EQUIV":
                    ly.dbu = float(words[1]) / float(words[2])
                    if words[3] != "MICRON":
                        raise ValueError("units %s, not MICRON" % words[3])
                elif key == "LEVEL":
                    layer(words[1])
                elif key == "CELL":
                    if cell is not None:
                        raise ValueError("a second CELL: one cell a clip is read")
                    cell = ly.create_cell(words[1])
                elif key in ("RECT", "PGON"):
                    if cell is None:
                        raise ValueError("a shape before CELL")
                    v = [int(w) for w in words[3:]]
                    if key == "RECT":
                        if len(v) != 4 or v[2] <= 0 or v[3] <= 0:
                            raise ValueError("RECT takes x y width height")
                        shape = pya.Box(v[0], v[1], v[0] + v[2], v[1] + v[3])
                    else:
                        if len(v) < 6 or len(v) % 2:
                            raise ValueError("PGON takes at least three x y vertices")
                        shape = pya.Polygon([pya.Point(v[i], v[i + 1]) for i in range(0, len(v), 2)])
                    cell.shapes(layer(words[2])).insert(shape)
                else:
                    raise ValueError("unknown statement %s" % key)
            except (ValueError, IndexError) as e:
                raise GlpError("%s line %d: %s" % (path, n, e))
    if cell is None:
        raise GlpError("%s: no CELL" % path)
    return ly
