"""Dialogs, built with KLayout's Qt bindings."""
import json
import os

import pya

from .selection import MODE_NAMES

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
    if text:
        combo.setEditText(text)
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


def _buttons(dialog, form):
    buttons = pya.QDialogButtonBox(dialog)
    buttons.addButton(pya.QDialogButtonBox.Ok)
    buttons.addButton(pya.QDialogButtonBox.Cancel)
    buttons.accepted = dialog.accept
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


class FlowDialog(pya.QDialog):
    """The whole flow: layer, markers, window sizes, coverage mode, split mode and ratio, output folder."""

    def __init__(self, parent, layers, current_layer, settings, title):
        super().__init__(parent)
        self.windowTitle = title
        form = pya.QFormLayout(self)
        self.layer = pya.QComboBox(self)
        for name in layers:
            self.layer.addItem(name)
        self._select(self.layer, current_layer or settings.get("layer", ""))
        form.addRow("Layer", self.layer)
        row, self.markers = _marker_row(self, layers, settings.get("markers", ""))
        form.addRow("Markers (layer L/D, .csv, .lyrdb)", row)
        self.sizes = pya.QLineEdit(settings.get("sizes", "5,6,7,8"), self)
        form.addRow("Window sizes (pitches)", self.sizes)
        self.mode = _mode_box(self, settings.get("mode", "A"))
        form.addRow("Coverage mode", self.mode)
        self.split = pya.QComboBox(self)
        self.split.addItem("stratified hold-out")
        self.split.addItem("score threshold")
        self.split.currentIndex = 1 if settings.get("split") == "threshold" else 0
        form.addRow("Split", self.split)
        self.fraction = pya.QLineEdit(settings.get("fraction", "0.3"), self)
        form.addRow("Verification fraction (stratified)", self.fraction)
        self.threshold = pya.QLineEdit(settings.get("threshold", "0.1"), self)
        form.addRow("Normalised score threshold", self.threshold)
        self.seed = pya.QLineEdit(settings.get("seed", "1"), self)
        form.addRow("Seed", self.seed)
        row = pya.QWidget(self)
        line = pya.QHBoxLayout(row)
        line.setContentsMargins(0, 0, 0, 0)
        self.out = pya.QLineEdit(settings.get("out", os.path.join(os.path.expanduser("~"), "linf_opc_flow")), row)
        pick = pya.QPushButton("Browse...", row)
        pick.clicked = self._browse_out
        line.addWidget(self.out)
        line.addWidget(pick)
        form.addRow("Output folder", row)
        _buttons(self, form)

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
                "sizes": self.sizes.text.strip(), "mode": "ABC"[self.mode.currentIndex],
                "split": "threshold" if self.split.currentIndex == 1 else "stratified",
                "fraction": self.fraction.text.strip(), "threshold": self.threshold.text.strip(),
                "seed": self.seed.text.strip(), "out": self.out.text.strip()}


def ask_flow(layers, current_layer, title):
    """Shows the flow dialog with the last settings; returns its values (and remembers them),
    or None if cancelled."""
    global current
    d = FlowDialog(pya.Application.instance().main_window(), layers, current_layer, load_settings(), title)
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
