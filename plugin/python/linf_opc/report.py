"""A self-contained HTML report of a selection study: the thesis's tables, SVG plots of
coverage, useful gauges and runtime against window size (Figures 5.17-5.19), the gauge plan's
cd-against-space plot and most repeated contexts, and a picture of the layout with the chosen
windows. No network resources."""
import base64
import html

from .progress import breathe

# The layout picture is drawn as SVG up to this many polygon points, markers and windows; a
# larger layer comes as a PNG rendered by the caller (an SVG of five million wires is a quarter
# of a gigabyte that no browser opens).
SVG_PICTURE_MAX = 200000


def _point_count(polygons):
    flat = getattr(polygons, "flat", None)
    if flat is not None:
        return len(flat()[0]) // 2
    return sum(len(outer) + sum(len(h) for h in holes) for outer, holes in polygons)


def _rings(polygons):
    """Every ring, outer or hole, as (xs, ys): slices of a Polygons' flat arrays (no tuple a
    point), or the lists' coordinates."""
    flat = getattr(polygons, "flat", None)
    if flat is None:
        for outer, holes in polygons:
            for ring in [outer] + list(holes):
                yield [p[0] for p in ring], [p[1] for p in ring]
        return
    points, counts = flat()
    at = 0
    for c in counts:
        n = abs(c)
        yield points[2 * at:2 * (at + n):2], points[2 * at + 1:2 * (at + n):2]
        at += n


def svg_picture_fits(polygons, run, markers):
    return len(markers) + len(run.windows) + _point_count(polygons) <= SVG_PICTURE_MAX

COLOURS = {"A": "#1f77b4", "B": "#d62728", "C": "#2ca02c"}


def _table(head, rows):
    out = ["<table><tr>" + "".join("<th>%s</th>" % html.escape(str(h)) for h in head) + "</tr>"]
    for r in rows:
        out.append("<tr>" + "".join("<td>%s</td>" % html.escape(_fmt(v)) for v in r) + "</tr>")
    return "\n".join(out) + "</table>"


def _fmt(v):
    if isinstance(v, float):
        return "%.4g" % v
    if isinstance(v, list) and len(v) == 2:
        return "[%.3g - %.3g]" % tuple(v)
    if v is None:
        return "-"
    return str(v)


def _plot(title, ylabel, series, sizes):
    """A line plot: series {mode: [y per size]}."""
    w, h, l, b = 420, 260, 60, 40
    ys = [y for v in series.values() for y in v if y is not None]
    lo, hi = (min(ys), max(ys)) if ys else (0, 1)
    if hi == lo:
        hi = lo + 1
    x = lambda i: l + (w - l - 20) * (i / max(1, len(sizes) - 1))
    y = lambda v: h - b - (h - b - 20) * ((v - lo) / (hi - lo))
    out = ['<svg xmlns="http://www.w3.org/2000/svg" width="%d" height="%d" class="plot">' % (w, h),
           '<text x="%d" y="14" font-weight="bold">%s</text>' % (l, html.escape(title)),
           '<line x1="%d" y1="%d" x2="%d" y2="%d" stroke="black"/>' % (l, h - b, w - 10, h - b),
           '<line x1="%d" y1="20" x2="%d" y2="%d" stroke="black"/>' % (l, l, h - b),
           '<text x="4" y="%d" font-size="11">%s</text>' % (h / 2, html.escape(ylabel))]
    for i, k in enumerate(sizes):
        out.append('<text x="%.0f" y="%d" font-size="11" text-anchor="middle">%dx%d</text>' % (x(i), h - b + 16, k, k))
    for v in (lo, hi):
        out.append('<text x="%d" y="%.0f" font-size="10" text-anchor="end">%.4g</text>' % (l - 4, y(v) + 4, v))
    for j, (mode, vals) in enumerate(sorted(series.items())):
        pts = " ".join("%.1f,%.1f" % (x(i), y(v)) for i, v in enumerate(vals) if v is not None)
        c = COLOURS.get(mode, "black")
        out.append('<polyline fill="none" stroke="%s" stroke-width="2" points="%s"/>' % (c, pts))
        out.append('<text x="%d" y="%d" fill="%s" font-size="11">mode %s</text>' % (w - 70, 30 + 14 * j, c, mode))
    out.append("</svg>")
    return "\n".join(out)


def _picture(polygons, run, markers, size=700):
    xs, ys = [b[0] for b in markers] + [b[2] for b in markers], [b[1] for b in markers] + [b[3] for b in markers]
    for rx, ry in _rings(polygons):
        if len(rx):
            xs += (min(rx), max(rx))
            ys += (min(ry), max(ry))
    if not xs:
        return ""
    x0, x1, y0, y1 = min(xs), max(xs), min(ys), max(ys)
    s = size / max(x1 - x0, y1 - y0, 1)
    X = lambda v: (v - x0) * s
    Y = lambda v: (y1 - v) * s
    d = []
    rings = len(polygons.flat()[1]) if hasattr(polygons, "flat") else sum(1 + len(h) for _, h in polygons)
    for k, (rx, ry) in enumerate(_rings(polygons)):
        breathe(k, rings)
        d.append("M" + " L".join("%.1f %.1f" % ((px - x0) * s, (y1 - py) * s) for px, py in zip(rx, ry)) + "Z")
    out = ['<svg xmlns="http://www.w3.org/2000/svg" width="%.0f" height="%.0f" class="layout">'
           % ((x1 - x0) * s + 2, (y1 - y0) * s + 2),
           '<path fill="#bbbbbb" fill-rule="evenodd" d="%s"/>' % " ".join(d)]
    for b in markers:
        out.append('<rect x="%.1f" y="%.1f" width="%.1f" height="%.1f" fill="none" stroke="#d62728"/>'
                   % (X(b[0]) - 1, Y(b[3]) - 1, max(2, (b[2] - b[0]) * s), max(2, (b[3] - b[1]) * s)))
    for x1_, y1_, x2_, y2_, gi, ms in run.windows:
        out.append('<rect x="%.1f" y="%.1f" width="%.1f" height="%.1f" fill="none" stroke="#1f77b4"/>'
                   % (X(x1_), Y(y2_), (x2_ - x1_) * s, (y2_ - y1_) * s))
    out.append("</svg>")
    return "\n".join(out)


PLAN_COLOURS = (("layer", "#bbbbbb", 3), ("calibration", "#1f77b4", 5), ("verification", "#d62728", 4))


def _scatter(title, xlabel, ylabel, series):
    """A scatter plot: series [(name, colour, mark size, [(x, y)])], drawn in that order; points
    falling on one pixel are drawn once (a layer has a representative per context)."""
    w, h, l, b = 520, 380, 64, 44
    pts = [p for _, _, _, ps in series for p in ps]
    x0, x1 = (min(p[0] for p in pts), max(p[0] for p in pts)) if pts else (0, 1)
    y0, y1 = (min(p[1] for p in pts), max(p[1] for p in pts)) if pts else (0, 1)
    x1, y1 = (x1 if x1 > x0 else x0 + 1), (y1 if y1 > y0 else y0 + 1)
    X = lambda v: l + (w - l - 20) * (v - x0) / (x1 - x0)
    Y = lambda v: h - b - (h - b - 24) * (v - y0) / (y1 - y0)
    out = ['<svg xmlns="http://www.w3.org/2000/svg" width="%d" height="%d" class="plot">' % (w, h),
           '<text x="%d" y="14" font-weight="bold">%s</text>' % (l, html.escape(title)),
           '<line x1="%d" y1="%d" x2="%d" y2="%d" stroke="black"/>' % (l, h - b, w - 10, h - b),
           '<line x1="%d" y1="20" x2="%d" y2="%d" stroke="black"/>' % (l, l, h - b),
           '<text x="%d" y="%d" font-size="11" text-anchor="middle">%s</text>' % ((l + w) / 2, h - 6, html.escape(xlabel)),
           '<text x="12" y="%d" font-size="11" transform="rotate(-90 12 %d)" text-anchor="middle">%s</text>'
           % (h / 2, h / 2, html.escape(ylabel))]
    for v in (x0, x1):
        out.append('<text x="%.0f" y="%d" font-size="10" text-anchor="middle">%.4g</text>' % (X(v), h - b + 14, v))
    for v in (y0, y1):
        out.append('<text x="%d" y="%.0f" font-size="10" text-anchor="end">%.4g</text>' % (l - 4, Y(v) + 4, v))
    for j, (name, colour, size, ps) in enumerate(series):
        seen = sorted(set((round(X(x)), round(Y(y))) for x, y in ps))
        out.append('<g fill="%s">%s</g>' % (colour, "".join(
            '<rect x="%d" y="%d" width="%d" height="%d"/>' % (px - size // 2, py - size // 2, size, size)
            for px, py in seen)))
        out.append('<text x="%d" y="%d" fill="%s" font-size="11">%s (%d)</text>'
                   % (w - 150, 30 + 14 * j, colour, html.escape(name), len(ps)))
    out.append("</svg>")
    return "\n".join(out)


def plan_section(plan, dbu):
    """The plan's part of the report: cd against neighbouring space of the layer's contexts and
    of the two sets, and the most repeated contexts."""
    s = plan.summary(dbu)
    points = plan.points(dbu)
    p = s["parameters"]
    parts = ["<h2>Gauge plan</h2>",
             "<p>%d gauges in %d contexts (type and the layer within %.4g &micro;m of the gauge, up to the square's "
             "symmetries); calibration %d gauges (%d contexts, %.1f%% of all gauges), verification %d (%d contexts, "
             "%.1f%%); budget %d, verify %d.</p>"
             % (s["layer"]["gauges"], s["layer"]["contexts"], p["context_radius_um"], s["counts"]["calibration"],
                s["sets"]["calibration"]["contexts"], 100 * s["sets"]["calibration"]["share_of_gauges"],
                s["counts"]["verification"], s["sets"]["verification"]["contexts"],
                100 * s["sets"]["verification"]["share_of_gauges"], p["budget"], p["verify"]),
             _scatter("cd against neighbouring space (um)", "cd (um)",
                      "space: least cd of the other kind within the radius (um)",
                      [(name, colour, size, points[name]) for name, colour, size in PLAN_COLOURS]),
             "<p>A width gauge's space is the least external cd within the context radius, an external gauge's "
             "the least internal cd there; %d contexts have none and are not drawn.</p>"
             % s["layer"]["contexts_without_space"],
             "<h2>Most repeated contexts</h2>",
             _table(["context", "type", "cd (um)", "score (um)", "count", "rank", "in"],
                    [[c["context"], c["type"], c["cd_um"], c["score_um"], c["count"], c["rank"],
                      ", ".join(c["in"]) or "-"] for c in s["top_contexts"]])]
    return "\n".join(parts)


def _png_picture(png):
    return '<img class="layout" alt="the layout with the windows" src="data:image/png;base64,%s"/>' % (
        base64.b64encode(png).decode("ascii"))


def write(path, title, stats, study, polygons, dbu, png=None, plan=None, extra=None):
    """png: the layout picture as PNG bytes, for a layer too large for SVG (svg_picture_fits);
    plan: the split's plan.Plan, shown before the picture; extra: an HTML fragment shown before
    the picture too (the printability pictures, litho_report.py)."""
    sizes = sorted(study.heuristic)
    modes = sorted(set(m for m, k in study.runs))
    cov = {m: [study.runs[(m, k)].covered if (m, k) in study.runs else None for k in sizes] for m in modes}
    use = {m: [study.runs[(m, k)].n_used if (m, k) in study.runs else None for k in sizes] for m in modes}
    tim = {m: [study.runs[(m, k)].seconds if (m, k) in study.runs else None for k in sizes] for m in modes}
    chosen = study.runs[(stats["chosen"]["mode"], stats["chosen"]["size"])]
    parts = ["<!DOCTYPE html><html><head><meta charset='utf-8'><title>%s</title>" % html.escape(title),
             "<style>body{font-family:sans-serif;margin:2em}table{border-collapse:collapse;margin:1em 0}"
             "td,th{border:1px solid #999;padding:2px 6px;text-align:right}svg{margin:0.5em}</style></head><body>",
             "<h1>%s</h1>" % html.escape(title),
             "<p>Pitch %.4g &micro;m; %d markers; %d gauges ranked. Windows are k&times;k pitches centred on "
             "gauges in rank order; a window is kept if it covers a marker not yet covered.</p>"
             % (stats["pitch_um"], stats["markers"], stats.get("gauges", 0))]
    pats = stats.get("pattern_classes")
    if pats:
        rule = ("XOR area at most %g%% of the window" % (100 * pats["area_fraction"]) if pats["rule"] == "area"
                else "edges moved by at most %g &micro;m" % pats["edge_um"])
        parts.append("<h2>Pattern classes</h2><p>The %d windows of mode %s %d&times;%d are <b>%d patterns</b>: "
                     "windows whose clips match under a rotation or mirror (%s) are one class, represented by its "
                     "most critical window (<code>pattern_classes.csv</code>; each window's class in "
                     "<code>windows.csv</code>). The largest:</p>"
                     % (pats["windows"], chosen.mode, chosen.size, chosen.size, pats["classes"], rule))
        parts.append(_table(["class", "windows", "markers covered", "representative window"],
                            [[c["class"], c["windows"], c["markers"], c["representative_window"]]
                             for c in pats["largest"]]))
    head = ["mode", "W_s", "side (um)", "M_c", "G_u", "r_u", "G_f", "r_f", "redundant", "P_d (%)", "u_g (%)", "T (s)"]
    for m in modes:
        parts.append("<h2>Coverage, mode %s</h2>" % m)
        parts.append(_table(head, [[r[k] for k in ("mode", "W_s", "side_um", "M_c", "G_u", "r_u", "G_f", "r_f",
                                                   "redundant", "P_d", "u_g", "T")]
                                   for r in stats["coverage"] if r["mode"] == m]))
    parts.append("<h2>Figures</h2>")
    parts.append(_plot("Markers covered (M_c)", "M_c", cov, sizes))
    parts.append(_plot("Useful gauges (G_u)", "G_u", use, sizes))
    parts.append(_plot("Selection time (s)", "T", tim, sizes))
    types = ["internal", "external", "sandwich", "comb", "T"]
    for which in ("used", "failed"):
        parts.append("<h2>Gauge distribution: %s gauges</h2>" % which)
        rows = []
        for key, dist in stats["distribution"].items():
            row = [key]
            for t in types:
                row += [dist[which][t]["n"], dist[which][t]["range"]]
            rows.append(row + [sum(dist[which][t]["n"] for t in types)])
        parts.append(_table(["run"] + [x for t in types for x in ("N_" + t, "r_" + t)] + ["total"], rows))
    parts.append("<h2>Window reduction (heuristic)</h2>")
    parts.append(_table(["W_s", "W_b", "W_a", "R_w (%)", "W_m"],
                        [[k, h["W_b"], h["W_a"], h["R_w"], h["W_m"]] for k, h in stats["heuristic"].items()]))
    key = "%s %dx%d" % (chosen.mode, chosen.size, chosen.size)
    parts.append("<h2>Representative gauges (%s)</h2>" % key)
    parts.append(_table(["R_g", "type", "S_n", "N_g", "S (%)"],
                        [["%s_%d" % (c["type"][0], i + 1), c["type"], c["S_n"], c["N_g"], c["similarity_pct"]]
                         for i, c in enumerate(stats["representatives"][key])]))
    if "similarity" in stats:
        s = stats["similarity"]
        parts.append("<h2>Similarity of the two halves (split at x = %.4g &micro;m)</h2>" % s["x_split_um"])
        parts.append(_table(["type", "S_n", "N_g^1", "N_g^2"], [[c[0], c[1], c[2], c[3]] for c in s["classes"]]))
        parts.append("<p>N_t^1 = %d, N_t^2 = %d, S_12 = %.2f%%</p>" % (s["N_t1"], s["N_t2"], s["S_12"]))
    if plan is not None:
        parts.append(plan_section(plan, dbu))
    if extra:
        parts.append(extra)
    parts.append("<h2>Layout with the windows (%s)</h2>" % key)
    parts.append(_png_picture(png) if png is not None else _picture(polygons, chosen, study.markers))
    parts.append("</body></html>")
    with open(path, "w") as f:
        f.write("\n".join(parts))
