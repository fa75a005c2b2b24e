"""Cut, copy and paste of objects through the system clipboard (Ctrl+X, Ctrl+C, Ctrl+V).

A copy puts two things on the clipboard:

* :data:`MIME`: the copied objects as a small project file (the ``.mrm`` format,
  :func:`mrm.io.project.dumps`). Pixels stay pixels, polygons keep every coordinate bit for bit, names,
  styles and provenance come along.
* plain text: the objects' Euclidean representations as a GeoJSON FeatureCollection (a ``name`` property
  per feature, coordinates written with ``repr``), which other programs — QGIS, a text editor — can read.

A paste reads the MIME data when it is there, else the text as GeoJSON or WKT. Both go through the
importer (:func:`mrm.io.imports.objects_from_file`), so a pasted payload is checked exactly as an opened
file is (limits, hostile content). The pasted objects get fresh ids and unique names and are added in one
undo step, selected, at the place they were copied from. A cut is a copy followed, once the data is on the
clipboard, by the deletion of the objects in one undo step ("Cut").
"""

from __future__ import annotations

import json
import logging
import os
import tempfile
from collections.abc import Sequence
from typing import Any

from PySide6 import QtCore, QtGui

from mrm.core.errors import MRMError
from mrm.document import DocObject, Document
from mrm.document.commands import ApplyResults, RemoveObjects

log = logging.getLogger(__name__)

#: The clipboard format of MR Modeler objects: the bytes of a project file holding just them.
MIME = "application/x-mrm-objects"

#: The name of a pasted shape that has none (WKT, or GeoJSON without a ``name``), by kind; made unique as
#: every pasted name is (``Pasted polygon (2)``).
PASTED_NAMES = {"euclidean": "Pasted polygon", "discrete": "Pasted pixels", "labels": "Pasted label map"}


def selection_part(doc: Document, ids: Sequence[int]) -> Document:
    """A document holding just the objects ``ids`` of ``doc`` (in drawing order), as a copy puts them.

    Cheap (the objects are immutable values, shared): the GUI thread makes it, a worker encodes it.
    """
    part = Document(doc.settings)
    for o in doc.objects:
        if o.id in ids:
            part.insert_object(o, None)
    return part


def geojson_text(named: Sequence[tuple[str, Any]]) -> str:
    """A GeoJSON FeatureCollection of (name, polygonal geometry); coordinates exactly as stored."""
    from shapely.geometry import mapping

    features = [
        {"type": "Feature", "properties": {"name": name}, "geometry": mapping(g)}
        for name, g in named
        if g is not None
    ]
    return json.dumps({"type": "FeatureCollection", "features": features}, allow_nan=False)


def mime_data(payload: bytes, text: str) -> QtCore.QMimeData:
    """The clipboard data of a copy: the project bytes under :data:`MIME`, the text as plain text."""
    md = QtCore.QMimeData()
    md.setData(MIME, QtCore.QByteArray(payload))
    md.setText(text)
    return md


def _suffix_of_text(text: str) -> str:
    return ".geojson" if text.lstrip().startswith("{") else ".wkt"


def mime_payload(md: QtCore.QMimeData) -> tuple[bytes, str]:
    """The bytes to read from clipboard data and their file suffix: :data:`MIME`, else GeoJSON/WKT text.

    Raises
    ------
    MRMError
        Nothing usable on the clipboard.
    """
    from mrm.core.errors import FileFormatError

    if md.hasFormat(MIME):
        return bytes(md.data(MIME).data()), ".mrm"
    if md.hasText() and md.text().strip():
        return md.text().encode("utf-8"), _suffix_of_text(md.text())
    raise FileFormatError("the clipboard holds no objects, GeoJSON or WKT")


def objects_from_payload(doc: Document, data: bytes, suffix: str) -> list[DocObject]:
    """New objects for ``doc`` read from clipboard bytes (:func:`mime_payload`), checked as a file is.

    Any thread: the document only gives fresh ids.
    """
    from mrm.core.errors import FileFormatError
    from mrm.io.imports import objects_from_file

    fd, path = tempfile.mkstemp(prefix="mrm-paste-", suffix=suffix)
    try:
        with os.fdopen(fd, "wb") as fh:
            fh.write(data)
        objs = objects_from_file(doc, path)
    finally:
        os.unlink(path)
    if not objs:
        raise FileFormatError("the clipboard holds no shapes")
    # A shape without a name of its own is named after the file it came from: here a temporary one.
    stem = os.path.splitext(os.path.basename(path))[0]
    return [o.with_(name=PASTED_NAMES[o.kind]) if o.name.startswith(stem) else o for o in objs]


def add_pasted(doc: Document, objs: list[DocObject]) -> list[int]:
    """Add pasted objects to ``doc`` in one undo step ("Paste"), with unique names; their ids."""
    from mrm.views.operation_panel import unique_name

    taken = {o.name for o in doc.objects}
    named = []
    for o in objs:
        name = unique_name(o.name, taken)
        taken.add(name)
        named.append(o.with_(name=name))
    doc.push(ApplyResults("Paste" if len(named) == 1 else f"Paste {len(named)} objects", add=named))
    return [o.id for o in named]


class ClipboardController(QtCore.QObject):
    """The window's Cut, Copy and Paste actions on the system clipboard."""

    def __init__(self, window: Any) -> None:
        super().__init__(window)
        self.win = window

    def copy(self) -> bool:
        """Copy the selected objects to the clipboard (Ctrl+C); False when nothing is selected."""
        return self._copy(cut=False)

    def cut(self) -> bool:
        """Cut (Ctrl+X): copy the selected objects, then delete them in one undo step.

        They are deleted once they are on the clipboard: a copy that fails deletes nothing, and an object
        edited while the copy was being encoded stays (what is on the clipboard is its earlier state).
        """
        return self._copy(cut=True)

    def _copy(self, *, cut: bool) -> bool:
        doc = self.win.doc
        ids = [i for i in doc.selection if i in doc]
        verb = "cut" if cut else "copy"
        if not ids:
            self.win.show_message(f"select the objects to {verb}", 3000)
            return False
        # Immutable values are read here; the encoding (megabytes for a big pixel object) runs on a worker.
        part = selection_part(doc, ids)
        copied = part.objects
        # As GeoJSON text, the shapes: a label map (its subdivision, ADR 0033) is copied as an object only.
        named = [(o.name, self.win.scene.get(o.id, "euclidean")) for o in copied if o.kind != "labels"]
        n = len(ids)

        def work(_progress: Any) -> tuple[bytes, str]:
            from mrm.io.project import dumps

            return dumps(part), geojson_text(named)

        def done(result: tuple[bytes, str]) -> None:
            QtGui.QGuiApplication.clipboard().setMimeData(mime_data(*result))
            if not cut:
                self.win.show_message(f"copied {n} object{'s' if n != 1 else ''}", 3000)
                return
            same = [o.id for o in copied if o.id in doc and doc.get(o.id) is o]
            if same:
                with doc.history.macro("Cut" if len(same) == 1 else f"Cut {len(same)} objects"):
                    doc.push(RemoveObjects(same))
            kept = n - len(same)
            self.win.show_message(
                f"cut {len(same)} object{'s' if len(same) != 1 else ''}"
                + (f"; {kept} changed or removed meanwhile, left as they are" if kept else ""),
                4000,
            )

        def failed(exc: BaseException) -> None:
            if not isinstance(exc, MRMError):
                raise exc
            self.win.show_message(f"{verb}: {exc}" + ("; nothing deleted" if cut else ""), 6000, error=True)

        self.win.runner.submit("copy", work, on_result=done, on_error=failed, label="Copying")
        return True

    def paste(self) -> bool:
        """Paste: the clipboard's objects are read on a worker, then added in one undo step.

        A big object's project data is megabytes to parse. False when the clipboard holds nothing usable.
        """
        md = QtGui.QGuiApplication.clipboard().mimeData()
        if md is None:
            return False
        doc = self.win.doc
        try:
            payload = mime_payload(md)  # the bytes are copied here: the clipboard may change meanwhile
        except MRMError as e:
            self.win.show_message(f"paste: {e}", 6000, error=True)
            return False

        def done(objs: list[DocObject]) -> None:
            try:
                ids = add_pasted(doc, objs)
            except MRMError as e:
                failed(e)
                return
            n = len(ids)
            self.win.show_message(f"pasted {n} object{'s' if n != 1 else ''}", 3000)

        def failed(exc: BaseException) -> None:
            if not isinstance(exc, MRMError):
                raise exc
            self.win.show_message(f"paste: {exc}", 6000, error=True)

        self.win.runner.submit(
            "paste",
            lambda _p: objects_from_payload(doc, *payload),
            on_result=done,
            on_error=failed,
            label="Pasting",
            show_progress=True,
        )
        return True
