"""What the flow's results dialog says, read from the files the flow wrote (summary.json,
split.json, stats.json): rows (label, text) a person reads."""
import json
import os


def flow_results(folder):
    """What the results dialog says about the flow's files in `folder`: [(label, text)]."""
    def load(name):
        try:
            with open(os.path.join(folder, name)) as f:
                return json.load(f)
        except (OSError, ValueError):
            return {}
    summary, split, stats = load("summary.json"), load("split.json"), load("stats.json")
    rows = []
    sel = summary.get("select", {})
    chosen = sel.get("chosen", {})
    coverage = [r for r in stats.get("coverage", []) if r.get("mode") == chosen.get("mode")
                and r.get("W_s") == "%sx%s" % (chosen.get("size"), chosen.get("size"))]
    if coverage:
        rows.append(("Markers covered", "%d of %d by %d windows (mode %s, %s pitches of %.4g \u00b5m)"
                     % (coverage[0]["M_c"], sel.get("markers", 0), chosen.get("windows", 0), chosen.get("mode"),
                        coverage[0]["W_s"], sel.get("pitch_um", 0))))
    classes = stats.get("pattern_classes")
    if classes:
        rows.append(("Pattern classes", "%d windows form %d classes of alike clips (pattern_classes.csv)"
                     % (classes["windows"], classes["classes"])))
    sets = split.get("sets", {})
    for name in ("calibration", "verification"):
        n = split.get("counts", {}).get(name)
        if n is None:
            continue
        text = "%d gauges (%s.oas, %s_gauges.csv)" % (n, name, name)
        if name in sets and "contexts" in sets[name]:
            text += "; %d contexts, %.1f%% of the layer's gauges" % (sets[name]["contexts"],
                                                                     100 * sets[name].get("share_of_gauges", 0))
        rows.append((name.capitalize(), text))
    layer = split.get("layer", {})
    if layer:
        rows.append(("Layer", "%d gauges in %d contexts" % (layer.get("gauges", 0), layer.get("contexts", 0))))
    lit = summary.get("gauges", {}).get("litho")
    if lit:
        fails = lit.get("fails", {})
        opc = lit.get("opc")
        after = (", after an emulated OPC (%d fragments, edge placement error %.2g nm rms)"
                 % (opc["fragments"], opc["rms_epe_nm"][-1]) if opc else "")
        rows.append(("Lithography", "%s, threshold %.4g%s: %d pinch, %d bridge among %d gauges simulated "
                     "(printed contours of the plan's windows on layer L/216)"
                     % (lit.get("model"), lit.get("threshold", 0), after, fails.get("pinch", 0), fails.get("bridge", 0),
                        lit.get("simulated", 0))))
    rows.append(("Output folder", os.path.abspath(folder)))
    return rows
