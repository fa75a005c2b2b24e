"""The header of a representation view, plane or 3D: its title, what it shows, and its state on the right.

Both texts elide (``…``, the whole text in the tool tip) rather than being cut: the four views share the
window evenly, and a header with tool buttons (the 3D discrete view's Slice, Paint, Erase) leaves them little
room; a cut text read as nonsense ("voxe voxels").
"""

from __future__ import annotations

from PySide6 import QtGui, QtWidgets

from mrm.views.elided_label import ElidedLabel

__all__ = ["ERROR_COLOUR", "ViewHeader"]

#: The colour of a failure said in a header.
ERROR_COLOUR = "#c0392b"


class ViewHeader(QtWidgets.QWidget):
    """Title (bold), subtitle and status line of a view; tool buttons go to :attr:`layout_` after them."""

    def __init__(self, title: str, subtitle: str, parent: QtWidgets.QWidget | None = None) -> None:
        super().__init__(parent)
        self.setObjectName("viewHeader")
        hl = QtWidgets.QHBoxLayout(self)
        hl.setContentsMargins(8, 3, 6, 3)
        hl.setSpacing(6)
        self.title_label = QtWidgets.QLabel(f"<b>{title}</b>", self)
        self.subtitle_label = ElidedLabel(self)
        self.subtitle_label.setObjectName("viewSubtitle")
        self.subtitle_label.setText(subtitle)
        self.status_label = ElidedLabel(self, right=True)
        self.status_label.setObjectName("viewStatus")
        for lab in (self.subtitle_label, self.status_label):
            # never allowed to widen the view: the four views share the space evenly
            lab.setSizePolicy(QtWidgets.QSizePolicy.Policy.Ignored, QtWidgets.QSizePolicy.Policy.Preferred)
        hl.addWidget(self.title_label)
        hl.addWidget(self.subtitle_label, 2)
        hl.addWidget(self.status_label, 3)
        self.layout_ = hl

    def show_status(self, text: str, tip: str = "", *, error: bool = False) -> None:
        """Say ``text`` on the right (red for a failure); ``tip``: a tool tip beyond the elided text."""
        self.status_label.set_colour(ERROR_COLOUR if error else None)
        self.status_label.set_tip(tip if tip != text else "")
        self.status_label.setText(text)

    def restyle(self, palette: QtGui.QPalette) -> None:
        """Draw the subtitle and the status in the palette's placeholder colour (after a theme change)."""
        mid = palette.color(QtGui.QPalette.ColorRole.PlaceholderText).name()
        self.subtitle_label.setStyleSheet(f"color: {mid};")
        self.status_label.setStyleSheet(f"color: {mid};")
