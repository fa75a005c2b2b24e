"""A one-line label that elides what does not fit, the whole text as its tool tip (headers, status bar)."""

from __future__ import annotations

from PySide6 import QtCore, QtGui, QtWidgets

__all__ = ["ElidedLabel"]


class ElidedLabel(QtWidgets.QLabel):
    """A one-line plain-text label that elides what does not fit (``…``), with the whole text as tooltip.

    Its size hint asks for the whole text but never more than ``most`` pixels, and it may shrink to
    ``least``: a long text cannot widen the window. A leading part may be drawn bold (:meth:`set_parts`).
    ``right``: the text is drawn against the right side. :meth:`set_colour` draws it in another colour than
    the palette's (an error in red).
    """

    def __init__(
        self,
        parent: QtWidgets.QWidget | None = None,
        *,
        least: int = 0,
        most: int = 10_000,
        right: bool = False,
    ) -> None:
        super().__init__("", parent)
        self.least, self.most = least, most
        self._lead = ""  # the bold start of the text
        self._colour: QtGui.QColor | None = None
        self._tip = ""  # a tool tip of its own (set_tip), else the whole text when it is elided
        self._align = QtCore.Qt.AlignmentFlag.AlignRight if right else QtCore.Qt.AlignmentFlag.AlignLeft
        self.setTextFormat(QtCore.Qt.TextFormat.PlainText)

    def set_tip(self, tip: str) -> None:
        """A tool tip of the label's own (several errors, an explanation), shown elided or not."""
        self._tip = tip
        self._update_tip()

    def set_colour(self, colour: str | None) -> None:
        """Draw the text in ``colour`` (a name such as ``"#c0392b"``), or in the palette's (None)."""
        self._colour = None if colour is None else QtGui.QColor(colour)
        self.update()

    def setText(self, text: str) -> None:
        self.set_parts("", text)

    def set_parts(self, lead: str, rest: str) -> None:
        """Show ``lead`` in bold, then ``rest``."""
        self._lead = lead
        super().setText(lead + rest)
        self._update_tip()
        self.updateGeometry()

    def _bold(self) -> QtGui.QFontMetrics:
        font = QtGui.QFont(self.font())
        font.setBold(True)
        return QtGui.QFontMetrics(font)

    def _pieces(self) -> tuple[str, str]:
        """The lead and the rest as drawn in the label's width (elided where they do not fit)."""
        width = max(0, self.contentsRect().width())
        rest = self.text()[len(self._lead) :]
        elide = QtCore.Qt.TextElideMode.ElideRight
        if not self._lead:
            return "", self.fontMetrics().elidedText(rest, elide, width)
        bold = self._bold()
        lead = bold.elidedText(self._lead, elide, width)
        if lead != self._lead:
            return lead, ""
        return lead, self.fontMetrics().elidedText(rest, elide, width - bold.horizontalAdvance(lead))

    def displayed_text(self) -> str:
        """What is drawn: the text, elided to the label's width."""
        return "".join(self._pieces())

    def _update_tip(self) -> None:
        self.setToolTip(self._tip or (self.text() if self.displayed_text() != self.text() else ""))

    def sizeHint(self) -> QtCore.QSize:
        rest = self.text()[len(self._lead) :]
        need = self._bold().horizontalAdvance(self._lead) + self.fontMetrics().horizontalAdvance(rest) + 4
        return QtCore.QSize(min(self.most, max(self.least, need)), super().sizeHint().height())

    def minimumSizeHint(self) -> QtCore.QSize:
        return QtCore.QSize(self.least, super().minimumSizeHint().height())

    def resizeEvent(self, ev: QtGui.QResizeEvent) -> None:
        super().resizeEvent(ev)
        self._update_tip()

    def paintEvent(self, _ev: QtGui.QPaintEvent) -> None:
        # Ended on leaving the block, not left to the garbage collector: anything holding this frame (a
        # sampling profiler, a traceback) would keep the painter active into the next paint, which crashed.
        with QtGui.QPainter(self) as p:
            p.setPen(self._colour or self.palette().color(self.foregroundRole()))
            rect = QtCore.QRectF(self.contentsRect())
            lead, rest = self._pieces()
            if self._align == QtCore.Qt.AlignmentFlag.AlignRight:  # the drawn text ends at the right side
                width = self._bold().horizontalAdvance(lead) + self.fontMetrics().horizontalAdvance(rest)
                rect.setLeft(max(rect.left(), rect.right() - width - 1))
            flags = int(QtCore.Qt.AlignmentFlag.AlignLeft | QtCore.Qt.AlignmentFlag.AlignVCenter)
            if lead:
                font = QtGui.QFont(self.font())
                font.setBold(True)
                p.setFont(font)
                p.drawText(rect, flags, lead)
                rect.setLeft(rect.left() + self._bold().horizontalAdvance(lead))
                p.setFont(self.font())
            p.drawText(rect, flags, rest)
