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
        self.resize(820, 760)

    def find_next(self) -> bool:
        """Select the next occurrence of the search text (wrapping around); False when there is none."""
        text = self.find.text()
        if not text:
            return False
        if self.browser.find(text):
            return True
        self.browser.moveCursor(QtGui.QTextCursor.MoveOperation.Start)
        return bool(self.browser.find(text))
