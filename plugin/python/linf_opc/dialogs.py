"""Dialogs, built with KLayout's Qt bindings."""
import pya

from .selection import MODE_NAMES

# The dialog on screen, if any: lets a scripted session (the GUI test) fill it in.
current = None


class SelectDialog(pya.QDialog):
    """Marker source, window sizes, coverage mode and pitch for "Select patterns..."."""

    def __init__(self, parent, layers, title):
        super().__init__(parent)
        self.windowTitle = title
        form = pya.QFormLayout(self)
        row = pya.QWidget(self)
        line = pya.QHBoxLayout(row)
        line.setContentsMargins(0, 0, 0, 0)
        self.markers = pya.QComboBox(row)
        self.markers.editable = True
        self.markers.minimumContentsLength = 30
        for name in layers:
            self.markers.addItem(name)
        browse = pya.QPushButton("File...", row)
        browse.clicked = self._browse
        line.addWidget(self.markers)
        line.addWidget(browse)
        form.addRow("Markers (layer L/D, .csv, .lyrdb)", row)
        self.sizes = pya.QLineEdit("5,6,7,8", self)
        form.addRow("Window sizes (pitches)", self.sizes)
        self.mode = pya.QComboBox(self)
        for m in ("A", "B", "C"):
            self.mode.addItem("%s: %s" % (m, MODE_NAMES[m]))
        form.addRow("Coverage mode", self.mode)
        self.pitch = pya.QLineEdit("", self)
        self.pitch.placeholderText = "estimated from the layer"
        form.addRow("Pitch (um)", self.pitch)
        buttons = pya.QDialogButtonBox(self)
        buttons.addButton(pya.QDialogButtonBox.Ok)
        buttons.addButton(pya.QDialogButtonBox.Cancel)
        buttons.accepted = self.accept
        buttons.rejected = self.reject
        form.addRow(buttons)

    def _browse(self):
        path = pya.QFileDialog.getOpenFileName(self, "Marker file", "", "Markers (*.csv *.lyrdb *.rdb);;All (*)")
        if path:
            self.markers.setEditText(path)

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
