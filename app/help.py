"""The user guide shown inside the application (Help ▸ User Guide, F1): no desktop launcher or browser needed.

The guide is docs/user-guide.md, rendered by Qt's own Markdown support in a text browser; its pictures
(docs/img/*.png) resolve relative to the guide. One window per main window, raised when asked again.
"""

from __future__ import annotations

from pathlib import Path

from PySide6 import QtCore, QtGui, QtWidgets

GUIDE = Path(__file__).resolve().parent.parent / "docs" / "user-guide.md"


class HelpWindow(QtWidgets.QDialog):
    """A non-modal window with the user guide and a search field."""

    def __init__(self, parent: QtWidgets.QWidget | None = None, guide: Path = GUIDE) -> None:
        super().__init__(parent)
        self.setObjectName("helpWindow")
        self.setWindowTitle("MR Modeler — User Guide")
        self.setModal(False)
        lay = QtWidgets.QVBoxLayout(self)
        row = QtWidgets.QHBoxLayout()
        self.find = QtWidgets.QLineEdit(self)
        self.find.setObjectName("helpFind")
        self.find.setPlaceholderText("Find in the guide (Enter: next)")
        self.find.setClearButtonEnabled(True)
        self.find.returnPressed.connect(self.find_next)
        row.addWidget(self.find)
        lay.addLayout(row)
        self.browser = QtWidgets.QTextBrowser(self)
        self.browser.setObjectName("helpBrowser")
        self.browser.setOpenExternalLinks(True)
        lay.addWidget(self.browser, 1)
        if guide.is_file():
            self.browser.setSearchPaths([str(guide.parent)])
            self.browser.document().setBaseUrl(QtCore.QUrl.fromLocalFile(str(guide.parent) + "/"))
            self.browser.setMarkdown(guide.read_text(encoding="utf-8"))
        else:
            self.browser.setPlainText(
                "The user guide (docs/user-guide.md) is not part of this installation; "
                "it is in the project's source repository."
            )
        self._sizes: dict[str, QtCore.QSize] = {}  # each picture's own size, read from its file's header
        self.browser.viewport().installEventFilter(self)
        self.resize(820, 760)
        self.fit_images()

    def eventFilter(self, obj: QtCore.QObject, ev: QtCore.QEvent) -> bool:
        if obj is self.browser.viewport() and ev.type() == QtCore.QEvent.Type.Resize:
            # After the resize: fitting changes the text's layout, which may show or hide a scroll bar.
            QtCore.QTimer.singleShot(0, self.fit_images)
        return super().eventFilter(obj, ev)

    def _picture_size(self, name: str) -> QtCore.QSize | None:
        if name not in self._sizes:
            doc = self.browser.document()
            path = doc.baseUrl().resolved(QtCore.QUrl(name)).toLocalFile()
            size = QtGui.QImageReader(path).size()
            self._sizes[name] = size
        size = self._sizes[name]
        return size if size.isValid() and size.width() > 0 else None

    def fit_images(self) -> None:
        """Show every picture at its own size, or scaled down to the width of the text when wider."""
        doc = self.browser.document()
        room = self.browser.viewport().width() - 2 * doc.documentMargin() - 2
        if room <= 0:
            return
        found: list[tuple[int, int, QtGui.QTextImageFormat]] = []
        block = doc.begin()
        while block.isValid():
            it = block.begin()
            while not it.atEnd():
                frag = it.fragment()
                if frag.isValid() and frag.charFormat().isImageFormat():
                    found.append((frag.position(), frag.length(), frag.charFormat().toImageFormat()))
                it += 1
            block = block.next()
        cursor = QtGui.QTextCursor(doc)
        for pos, length, fmt in found:
            size = self._picture_size(fmt.name())
            if size is None:
                continue
            width = min(float(size.width()), room)
            if abs(fmt.width() - width) < 0.5:
                continue
            fmt.setWidth(width)
            fmt.setHeight(size.height() * width / size.width())
            cursor.setPosition(pos)
            cursor.setPosition(pos + length, QtGui.QTextCursor.MoveMode.KeepAnchor)
            cursor.setCharFormat(fmt)

    def find_next(self) -> bool:
        """Select the next occurrence of the search text (wrapping around); False when there is none."""
        text = self.find.text()
        if not text:
            return False
        if self.browser.find(text):
            return True
        self.browser.moveCursor(QtGui.QTextCursor.MoveOperation.Start)
        return bool(self.browser.find(text))
