# Draws samples/metal.oas: a metal-like layer 1/0 and a marker layer 100/0 (dbu 1 nm).
#   klayout -b -r scripts/make_sample.py -rd out=samples/metal.oas
# Contents, left to right: a bus of wires of several widths and spaces; line-ends facing a
# line; a comb against a bus line; T-junctions; jogs; 45-degree bends. Markers sit on the
# places a lithographer would flag: the tightest line-end gap, the comb fingers, a T, a jog.
import pya

ly = pya.Layout()
ly.dbu = 0.001
top = ly.create_cell("SAMPLE")
metal = top.shapes(ly.layer(1, 0))
marker = top.shapes(ly.layer(100, 0))


def box(x1, y1, x2, y2):
    metal.insert(pya.Box(x1, y1, x2, y2))


def poly(pts):
    metal.insert(pya.Polygon([pya.Point(x, y) for x, y in pts]))


def mark(x, y, s=40):
    marker.insert(pya.Box(x - s // 2, y - s // 2, x + s // 2, y + s // 2))


# 1. Bus: widths 50..120 nm, spaces 50..100 nm, 3 um long.
y = 0
for w, s in [(50, 50), (60, 60), (80, 50), (120, 70), (50, 100), (70, 60)]:
    box(0, y, 3000, y + w)
    y += w + s
mark(1500, 80)

# 2. Line-ends facing a vertical line, gaps 40..100 nm.
box(3400, 0, 3460, 900)
for i, gap in enumerate([40, 60, 80, 100]):
    yy = 60 + 200 * i
    box(3460 + gap, yy, 4300, yy + 60)
mark(3480, 80)

# 3. Comb: fingers from a spine, interleaved with a bus line's fingers.
box(4600, 0, 6400, 80)
box(4600, 900, 6400, 980)
for i in range(9):
    x = 4700 + 200 * i
    if i % 2 == 0:
        box(x, 80, x + 60, 780)
    else:
        box(x, 200, x + 60, 900)
mark(5000, 800)

# 4. T-junctions: stems meeting a horizontal line; one with a neighbour close by.
box(6800, 600, 8400, 680)
for x in (7000, 7600, 8100):
    box(x, 0, x + 70, 600)
box(7170, 0, 7230, 500)
mark(7100, 600)

# 5. Jogs: wires stepping sideways by half their width.
for i in range(3):
    x = 8800 + 300 * i
    poly([(x, 0), (x + 80, 0), (x + 80, 400), (x + 120, 400), (x + 120, 900),
          (x + 40, 900), (x + 40, 480), (x, 480)])
mark(8880, 440)

# 6. 45-degree bends: two parallel wires turning diagonally, and a lone one.
for off in (0, 160):
    poly([(9900 + off, 0), (9980 + off, 0), (9980 + off, 300), (10380 + off, 700), (10380 + off, 1000),
          (10300 + off, 1000), (10300 + off, 733), (9900 + off, 333)])
poly([(11000, 0), (11300, 0), (11600, 300), (11600, 380), (11300, 80), (11000, 80)])
mark(10200, 480)

ly.write(globals().get("out") or "samples/metal.oas")
