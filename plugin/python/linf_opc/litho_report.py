"""The report's printability pictures: for the most critical contexts, the drawn layer with the
gauge's measurement line beside the printed contours (nominal, and the process window's two
corners) with the same line, each an inline SVG of the window's valid centre (half the model's
period, where the simulation is read).

in:  the re-ranked gauge table (its .litho), the layer's region (pya.Region, DBU), the model and
     the threshold the gauges were read with (result.litho_model, result.litho_summary), the rows
     to draw
out: an HTML fragment for report.html
"""
import html
from array import array

import pya

from . import core
from .litho import DOSE, FAILS
from .polygons import core_input

GRID = 128   # image samples across the model's period
PICTURES = 8  # contexts drawn
SIDE = 260   # px of one panel


def region_of(points, rings, scale=1):
    """The core's flat arrays as a Region, their coordinates divided by `scale` and rounded (1:
    exact, in their own units)."""
    out, at, poly = pya.Region(), 0, None
    for c in rings:
        n = abs(c)
        ring = [pya.Point(round(points[2 * k] / scale), round(points[2 * k + 1] / scale)) for k in range(at, at + n)]
        at += n
        if c > 0:
            if poly is not None:
                out.insert(poly)
            poly = pya.Polygon(ring, True)
        elif poly is not None:
            poly.insert_hole(ring, True)
    if poly is not None:
        out.insert(poly)
    return out


def contours_of(values, m, lo, hi, level):
    """Marching squares on the grid cells [lo, hi) x [lo, hi) (core.litho_contours): segments
    (x1, y1, x2, y2) in grid units where the image crosses `level`."""
    flat = array("d")
    flat.frombytes(core.litho_contours(values, m, lo, hi, level))
    return [tuple(flat[k:k + 4]) for k in range(0, len(flat), 4)]


def _panel(title, draw):
    return ('<svg xmlns="http://www.w3.org/2000/svg" width="%d" height="%d" class="litho">'
            '<rect width="%d" height="%d" fill="white" stroke="#999"/>%s'
            '<text x="4" y="%d" font-size="11">%s</text></svg>'
            % (SIDE, SIDE + 16, SIDE, SIDE, draw, SIDE + 12, html.escape(title)))


def section(table, region, polygons, dbu_um, model, threshold, rows, mask=None):
    """The pictures of `rows` (table rows, most critical first). `mask`: the layer imaged instead
    of `polygons` (after the OPC: (flat arrays, scale), litho.opc_mask)."""
    if not rows:
        return ""
    lit = table.litho
    dbu_nm = dbu_um * 1000.0
    P = model.kernels.period
    m = GRID
    lo, hi = m // 4, 3 * m // 4 + 1  # the valid centre: half the period around the point
    cx, cy = table.centres()
    xs, ys = [cx[i] for i in rows], [cy[i] for i in rows]
    flat, S = mask if mask is not None else (core_input(polygons), 1)
    corrected = region_of(*flat) if mask is not None else None  # in DBU / S, exactly
    xs, ys = [x * S for x in xs], [y * S for y in ys]
    focus = core.litho_window_images(flat, dbu_nm / S, xs, ys, model.kernels, m, blur=model.blur_nm)
    blurred = (core.litho_window_images(flat, dbu_nm / S, xs, ys, model.defocus, m, blur=model.blur_nm)
               if model.defocus is not None
               else focus)
    view = (hi - 1 - lo)  # grid units across the view
    s = SIDE / view
    parts = ["<h2>Printability of the most critical contexts (%s)</h2>" % html.escape(model.name),
             "<p>Left: the drawn layer and the gauge's measurement line; right: the printed contour at nominal "
             "dose and focus (solid) and at the process window's corners (dashed: dose %.2f defocused, inner; "
             "dose %.2f in focus, outer), threshold %.4g%s. Each panel is the window's centre, %.4g nm across, "
             "where the simulation is read.</p>"
             % (1 - DOSE, 1 + DOSE, threshold, ", resist blur %g nm" % model.blur_nm if model.blur_nm else "", P / 2)
             + ("<p>The images are of the layer after an emulated model-based OPC (orange on the left), the "
                "panels' grey the drawn layer: the contour should follow it.</p>" if mask is not None else "")]
    for k, i in enumerate(rows):
        g = table[i]
        # Grid (i, j) lies at the window's corner + (i, j) P / m nm; the corner is the point minus P / 2.
        x0 = g.cx * dbu_nm - P / 2 + lo * P / m
        y0 = g.cy * dbu_nm - P / 2 + lo * P / m
        X = lambda x_nm: (x_nm - x0) / (P / m) * s  # noqa: E731
        Y = lambda y_nm: SIDE - (y_nm - y0) / (P / m) * s  # noqa: E731
        box = pya.Box(int((x0) / dbu_nm) - 1, int(y0 / dbu_nm) - 1, int((x0 + view * P / m) / dbu_nm) + 1,
                      int((y0 + view * P / m) / dbu_nm) + 1)

        def path(layer, scale):  # the layer (in DBU / scale) inside the view, as SVG path data
            d = []
            clip = pya.Box(box.left * scale, box.bottom * scale, box.right * scale, box.top * scale)
            for poly in (layer & pya.Region(clip)).each():
                for ring in [list(poly.each_point_hull())] + [list(poly.each_point_hole(h)) for h in range(poly.holes())]:
                    d.append("M" + " L".join("%.1f %.1f" % (X(p.x * dbu_nm / scale), Y(p.y * dbu_nm / scale))
                                             for p in ring) + "Z")
            return " ".join(d)
        d = path(region, 1)
        drawn = '<path fill="#bbbbbb" fill-rule="evenodd" d="%s"/>' % d
        if corrected is not None:  # the OPC's mask over the drawn layer, as an outline
            drawn += '<path fill="none" stroke="#ff7f0e" stroke-width="1" d="%s"/>' % path(corrected, S)
        line = ('<line x1="%.1f" y1="%.1f" x2="%.1f" y2="%.1f" stroke="#d62728" stroke-width="2"/>'
                % (X(g.x1 * dbu_nm), Y(g.y1 * dbu_nm), X(g.x2 * dbu_nm), Y(g.y2 * dbu_nm)))
        outline = '<path fill="none" stroke="#888" stroke-width="0.6" d="%s"/>' % d
        printed = []
        for values, level, style in ((array("d", blurred[k]), threshold / (1 - DOSE) ** 2, ' stroke-dasharray="3,2"'),
                                     (array("d", focus[k]), threshold / (1 + DOSE) ** 2, ' stroke-dasharray="3,2"'),
                                     (array("d", focus[k]), threshold, "")):
            segs = contours_of(values, m, lo, hi, level)
            printed.append('<path fill="none" stroke="#1f77b4" stroke-width="1.4"%s d="%s"/>' % (style, " ".join(
                "M%.1f %.1f L%.1f %.1f" % ((a - lo) * s, SIDE - (b - lo) * s, (c - lo) * s, SIDE - (e - lo) * s)
                for a, b, c, e in segs)))
        pcd = lit.printed_cd[i]
        about = "#%d %s cd %.4g nm, printed %s, pv band %s, %s" % (
            g.rank, g.type, g.cd * dbu_nm, "-" if pcd != pcd else "%.4g nm" % pcd,
            "-" if lit.pv_band[i] != lit.pv_band[i] else "%.4g nm" % lit.pv_band[i], FAILS[lit.fails[i]])
        parts.append('<div class="litho-pair">%s%s<br/><small>%s</small></div>' % (
            _panel("drawn" if corrected is None else "drawn (grey), after the OPC (orange)", drawn + line),
            _panel("printed", outline + "".join(printed) + line), html.escape(about)))
    return "\n".join(parts)


def rows_to_draw(table, plan=None, most=PICTURES):
    """The most critical contexts: the plan's representatives in rank order, else the table's first
    rows."""
    if plan is not None:
        return list(plan.contexts.representatives[:most])
    return list(range(min(most, len(table))))

