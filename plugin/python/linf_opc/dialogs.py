"""Dialogs, built with KLayout's Qt bindings."""
import json
import os

import pya

from . import cluster
from .flow_summary import flow_results
from .litho import PRESETS
from .selection import MODE_NAMES

TITLE = "L\u221e Voronoi OPC"

# The dialog on screen, if any: lets a scripted session (the GUI test) fill it in.
current = None


def _marker_row(dialog, layers, text=""):
    """An editable list of layers with a File... button; returns (row widget, combo box)."""
    row = pya.QWidget(dialog)
    line = pya.QHBoxLayout(row)
    line.setContentsMargins(0, 0, 0, 0)
    combo = pya.QComboBox(row)
    combo.editable = True
    combo.minimumContentsLength = 30
    for name in layers:
        combo.addItem(name)
    # Never a layer by default: the first in the list is often the working layer itself.
    combo.currentIndex = -1
    combo.setEditText(text)
    combo.lineEdit.placeholderText = "a marker layer L/D, a .csv or a .lyrdb file"
    browse = pya.QPushButton("File...", row)

    def pick():
        path = pya.QFileDialog.getOpenFileName(dialog, "Marker file", "", "Markers (*.csv *.lyrdb *.rdb);;All (*)")
        if path:
            combo.setEditText(path)
    browse.clicked = pick
    row._pick = pick  # keep the handler alive with the row
    line.addWidget(combo)
    line.addWidget(browse)
    return row, combo


def _mode_box(dialog, mode="A"):
    box = pya.QComboBox(dialog)
    for m in ("A", "B", "C"):
        box.addItem("%s: %s" % (m, MODE_NAMES[m]))
    box.currentIndex = "ABC".find(mode) if mode in ("A", "B", "C") else 0
    return box


def _buttons(dialog, form, ok=None):
    buttons = pya.QDialogButtonBox(dialog)
    buttons.addButton(pya.QDialogButtonBox.Ok)
    buttons.addButton(pya.QDialogButtonBox.Cancel)
    buttons.accepted = ok or dialog.accept
    buttons.rejected = dialog.reject
    form.addRow(buttons)


class SelectDialog(pya.QDialog):
    """Marker source, window sizes, coverage mode and pitch for "Select patterns..."."""

    def __init__(self, parent, layers, title):
        super().__init__(parent)
        self.windowTitle = title
        form = pya.QFormLayout(self)
        row, self.markers = _marker_row(self, layers)
        form.addRow("Markers (layer L/D, .csv, .lyrdb)", row)
        self.sizes = pya.QLineEdit("5,6,7,8", self)
        form.addRow("Window sizes (pitches)", self.sizes)
        self.mode = _mode_box(self)
        form.addRow("Coverage mode", self.mode)
        self.pitch = pya.QLineEdit("", self)
        self.pitch.placeholderText = "estimated from the layer"
        form.addRow("Pitch (um)", self.pitch)
        _buttons(self, form)

    def values(self):
        """{"markers", "sizes", "mode", "pitch"} as the batch command's arguments take them."""
        return {"markers": self.markers.currentText.strip(), "sizes": self.sizes.text.strip(),
                "mode": "ABC"[self.mode.currentIndex], "pitch": self.pitch.text.strip()}


def ask_selection(layers, title):
    """Shows the dialog; returns its values, or None if cancelled."""
    global current
    d = SelectDialog(pya.Application.instance().main_window(), layers, title)
    current = d
    try:
        return d.values() if d.exec_() else None
    finally:
        current = None
        d._destroy()


def _settings_path():
    return os.path.join(pya.Application.instance().application_data_path(), "linf_opc_flow.json")


def load_settings():
    """The flow dialog's last values (kept in KLayout's home folder), or {}."""
    try:
        with open(_settings_path()) as f:
            v = json.load(f)
        return v if isinstance(v, dict) else {}
    except (OSError, ValueError):
        return {}


def save_settings(values):
    try:
        with open(_settings_path(), "w") as f:
            json.dump(values, f, indent=1, sort_keys=True)
    except OSError:
        pass  # settings are a convenience: never fail the flow for them


def _ask(parent, question):
    """Yes or no, No the default."""
    answer = pya.QMessageBox.question(parent, TITLE, question, pya.QMessageBox.Yes | pya.QMessageBox.No,
                                      pya.QMessageBox.No)
    return answer == pya.QMessageBox.Yes


def _whole(text, least):
    try:
        return int(text) >= least
    except ValueError:
        return False


def flow_problems(values, layout_um):
    """The flow dialog's values as the editor judges them before a run: (errors, questions).
    errors: sentences saying what cannot work and what to do; questions: what may be a slip,
    to confirm. layout_um: the layout's larger side (0: unknown)."""
    errors, questions = [], []
    markers, layer = values.get("markers", ""), values.get("layer", "")
    if not markers:
        errors.append("Choose a marker source: a marker layer (L/D), a .csv file or a .lyrdb file.")
    elif markers == layer:
        questions.append("The markers are the working layer %s itself: every shape becomes a marker, and the "
                         "run covers them all. Use the working layer as markers?" % layer)
    sizes = values.get("sizes", "").split(",")
    if not all(_whole(k.strip(), 1) for k in sizes):
        errors.append("Window sizes are whole numbers of pitches separated by commas, such as 5,6,7,8.")
    pitch = values.get("pitch", "")
    if pitch:
        try:
            p = float(pitch)
        except ValueError:
            p = -1.0
        if not p > 0:
            errors.append("The pitch is a positive number of micrometres; leave it blank to estimate it from the "
                          "layer.")
        elif layout_um > 0 and p > layout_um:
            errors.append("A pitch of %g \u00b5m is larger than the layout (%.4g \u00b5m): every window would "
                          "hold the whole layout. Leave it blank to estimate it from the layer." % (p, layout_um))
    split = values.get("split", "plan")
    if split == "plan":
        if not _whole(values.get("budget", ""), 1):
            errors.append("The calibration budget is a whole number of gauges, at least 1.")
        if values.get("verify") and not _whole(values["verify"], 0):
            errors.append("The verification size is a whole number of gauges, 0 or more; blank: the budget.")
    elif split == "stratified":
        try:
            ok = 0 < float(values.get("fraction", "")) < 1
        except ValueError:
            ok = False
        if not ok:
            errors.append("The verification fraction lies strictly between 0 and 1, such as 0.3.")
        if not _whole(values.get("seed", ""), 0):
            errors.append("The seed is a whole number, 0 or more.")
    else:
        try:
            float(values.get("threshold", ""))
        except ValueError:
            errors.append("The threshold is a normalised score, such as 0.1.")
    scheduler = values.get("scheduler", "")
    if scheduler:
        try:
            cluster.parse_address(scheduler)
        except cluster.ClusterError:
            errors.append("The Dask scheduler is an address such as tcp://farm-head:8786; leave it blank to build "
                          "on this computer.")
    out = values.get("out", "")
    if not out:
        errors.append("Choose an output folder.")
    elif os.path.isdir(out):
        held = [f for f in os.listdir(out) if not f.startswith(".")]
        if held:
            questions.append("The folder %s already holds %d files; the flow's files there will be replaced. "
                             "Write into it?" % (out, len(held)))
    return errors, questions


# The split modes in the dialog's order (the batch's -rd split=), the plan first: the default.
SPLIT_MODES = ("plan", "stratified", "threshold")
SPLIT_LABELS = ("budgeted gauge plan", "stratified hold-out", "score threshold")


# The model that scores the gauges (-rd litho): none keeps the geometric score.
LITHO_LABELS = {"": "none: the geometric score", "duv193": "duv193: ArF immersion, 193 nm",
                "euv": "euv: 13.5 nm, NA 0.33", "iccad13": "iccad13: the ICCAD 2013 contest's kernels"}


# The diagram's construction (-rd builder): the same files either way.
BUILDER_LABELS = {"subdivision": "subdivision: every layer",
                  "sweep": "sweep line: Manhattan layers, faster (others: the subdivision)"}
# The independent check (-rd check): the same files either way.
CHECK_LABELS = {"sample": "sampled: one piece in 16 searched for a closer site", "full": "full: every piece searched"}


class FlowDialog(pya.QDialog):
    """The whole flow: layer, markers, window sizes, coverage mode, split mode and its numbers
    (plan budget and verification size, fraction, threshold, seed), output folder, lithography
    model, Dask scheduler, diagram builder, check."""

    def __init__(self, parent, layers, current_layer, settings, title, default_out="", layout_um=0.0):
        super().__init__(parent)
        self.windowTitle = title
        self.layout_um = layout_um
        form = pya.QFormLayout(self)
        self.layer = pya.QComboBox(self)
        for name in layers:
            self.layer.addItem(name)
        self._select(self.layer, current_layer or settings.get("layer", ""))
        form.addRow("Layer", self.layer)
        markers = settings.get("markers", "")
        row, self.markers = _marker_row(self, layers, "" if markers == self.layer.currentText else markers)
        form.addRow("Markers (layer L/D, .csv, .lyrdb)", row)
        self.sizes = pya.QLineEdit(settings.get("sizes", "5,6,7,8"), self)
        form.addRow("Window sizes (pitches)", self.sizes)
        self.pitch = pya.QLineEdit(settings.get("pitch", ""), self)
        self.pitch.placeholderText = "estimated from the layer"
        form.addRow("Pitch (\u00b5m)", self.pitch)
        self.mode = _mode_box(self, settings.get("mode", "A"))
        form.addRow("Coverage mode", self.mode)
        self.split = pya.QComboBox(self)
        for label in SPLIT_LABELS:
            self.split.addItem(label)
        self.split.currentIndex = SPLIT_MODES.index(settings.get("split")) if settings.get("split") in SPLIT_MODES else 0
        form.addRow("Split", self.split)
        self.budget = pya.QLineEdit(settings.get("budget", "1000"), self)
        form.addRow("Calibration gauges (plan)", self.budget)
        self.verify = pya.QLineEdit(settings.get("verify", ""), self)
        self.verify.placeholderText = "the budget"
        form.addRow("Verification gauges (plan)", self.verify)
        self.fraction = pya.QLineEdit(settings.get("fraction", "0.3"), self)
        form.addRow("Verification fraction (stratified)", self.fraction)
        self.threshold = pya.QLineEdit(settings.get("threshold", "0.1"), self)
        form.addRow("Normalised score threshold (threshold)", self.threshold)
        self.seed = pya.QLineEdit(settings.get("seed", "1"), self)
        form.addRow("Seed (stratified)", self.seed)
        row = pya.QWidget(self)
        line = pya.QHBoxLayout(row)
        line.setContentsMargins(0, 0, 0, 0)
        out = settings.get("out") or default_out or os.path.join(os.path.expanduser("~"), "linf_opc_flow")
        self.out = pya.QLineEdit(out, row)
        pick = pya.QPushButton("Browse...", row)
        pick.clicked = self._browse_out
        line.addWidget(self.out)
        line.addWidget(pick)
        form.addRow("Output folder", row)
        self.litho = pya.QComboBox(self)
        for name in ("",) + PRESETS:
            self.litho.addItem(LITHO_LABELS.get(name, name))
        self.litho.currentIndex = (("",) + PRESETS).index(settings.get("litho", "")) if settings.get("litho", "") in \
            PRESETS else 0
        form.addRow("Lithography model", self.litho)
        self.opc = pya.QCheckBox("read the layer after an emulated model-based OPC (slower)", self)
        self.opc.checked = settings.get("opc") == "1"
        form.addRow("OPC", self.opc)
        self.litho.currentIndexChanged = self._litho_changed
        self._litho_changed(self.litho.currentIndex)
        self.scheduler = pya.QLineEdit(settings.get("scheduler", ""), self)
        self.scheduler.placeholderText = "tcp://HOST:PORT; blank: this computer"
        form.addRow("Dask scheduler (optional)", self.scheduler)
        self.builder = pya.QComboBox(self)
        for label in BUILDER_LABELS.values():
            self.builder.addItem(label)
        self.builder.currentIndex = 0 if settings.get("builder") == "subdivision" else 1
        form.addRow("Diagram builder", self.builder)
        self.check = pya.QComboBox(self)
        for label in CHECK_LABELS.values():
            self.check.addItem(label)
        self.check.currentIndex = 1 if settings.get("check") == "full" else 0
        form.addRow("Independent check", self.check)
        _buttons(self, form, self._ok)
        self.split.currentIndexChanged = self._split_changed
        self._split_changed(self.split.currentIndex)
        self.confirm = _ask  # how a question is put (the GUI test answers it itself)

    def _split_changed(self, index):
        """Only the chosen split's fields can be edited."""
        mode = SPLIT_MODES[index] if 0 <= index < len(SPLIT_MODES) else "plan"
        for field, modes in ((self.budget, ("plan",)), (self.verify, ("plan",)), (self.fraction, ("stratified",)),
                             (self.seed, ("stratified",)), (self.threshold, ("threshold",))):
            field.enabled = mode in modes

    def _litho_changed(self, index):
        """The OPC is the model's: without one there is nothing to correct for."""
        self.opc.enabled = index > 0

    def _ok(self):
        """OK: a sentence for what cannot work, a question for what may be a slip."""
        errors, questions = flow_problems(self.values(), self.layout_um)
        if errors:
            pya.QMessageBox.warning(self, self.windowTitle, errors[0])
            return
        for q in questions:
            if not self.confirm(self, q):
                return
        self.accept()

    @staticmethod
    def _select(combo, text):
        i = combo.findText(text)
        if i >= 0:
            combo.currentIndex = i

    def _browse_out(self):
        path = pya.QFileDialog.getExistingDirectory(self, "Output folder", self.out.text)
        if path:
            self.out.text = path

    def values(self):
        """The batch flow's arguments (strings), plus the layer."""
        return {"layer": self.layer.currentText, "markers": self.markers.currentText.strip(),
                "sizes": self.sizes.text.strip(), "pitch": self.pitch.text.strip(), "mode": "ABC"[self.mode.currentIndex],
                "split": SPLIT_MODES[self.split.currentIndex], "budget": self.budget.text.strip(),
                "verify": self.verify.text.strip(),
                "fraction": self.fraction.text.strip(), "threshold": self.threshold.text.strip(),
                "seed": self.seed.text.strip(), "out": self.out.text.strip(),
                "scheduler": self.scheduler.text.strip(), "litho": (("",) + PRESETS)[max(0, self.litho.currentIndex)],
                "opc": "1" if self.opc.checked and self.litho.currentIndex > 0 else "0",
                "builder": list(BUILDER_LABELS)[max(0, self.builder.currentIndex)],
                "check": list(CHECK_LABELS)[max(0, self.check.currentIndex)]}


def ask_flow(layers, current_layer, title, default_out="", layout_um=0.0):
    """Shows the flow dialog with the last settings; returns its values (and remembers them),
    or None if cancelled. default_out: the output folder when none is remembered."""
    global current
    d = FlowDialog(pya.Application.instance().main_window(), layers, current_layer, load_settings(), title,
                   default_out, layout_um)
    current = d
    try:
        if not d.exec_():
            return None
        v = d.values()
        save_settings(v)
        return v
    finally:
        current = None
        d._destroy()


class ResultsDialog(pya.QDialog):
    """After the flow: its counts, the folder, and buttons to the report and the clips."""

    def __init__(self, parent, folder, title, open_layout, show_plan=None):
        super().__init__(parent)
        self.windowTitle = title
        self.folder = folder
        form = pya.QFormLayout(self)
        self.rows = flow_results(folder)
        for label, text in self.rows:
            value = pya.QLabel(text, self)
            value.textInteractionFlags = pya.Qt.TextSelectableByMouse
            form.addRow(label, value)
        buttons = pya.QDialogButtonBox(self)
        report = buttons.addButton("Open report.html", pya.QDialogButtonBox.ActionRole)
        report.clicked = lambda: pya.QDesktopServices.openUrl(
            pya.QUrl.fromLocalFile(os.path.join(folder, "report.html")))
        clips = buttons.addButton("Show calibration clips", pya.QDialogButtonBox.ActionRole)
        clips.clicked = lambda: (open_layout(os.path.join(folder, "calibration.oas")), self.accept())
        self._keep = (report, clips)
        if show_plan is not None:
            plan = buttons.addButton("Show the plan in the marker browser", pya.QDialogButtonBox.ActionRole)
            plan.clicked = lambda: (self.accept(), show_plan())
            self._keep += (plan,)
        buttons.addButton(pya.QDialogButtonBox.Close)
        buttons.rejected = self.reject
        form.addRow(buttons)

    def text(self):
        return "\n".join("%s: %s" % r for r in self.rows)


def show_results(folder, title, open_layout, show_plan=None):
    """The results dialog (modal) for the flow's files in `folder`; show_plan(): opens the
    marker browser on the flow's report database (its category `split` is the plan)."""
    global current
    d = ResultsDialog(pya.Application.instance().main_window(), folder, title, open_layout, show_plan)
    current = d
    try:
        d.exec_()
    finally:
        current = None
        d._destroy()
