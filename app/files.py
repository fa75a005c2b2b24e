"""Files: New, Open, Save, Save As, recent files, import, export, drag-and-drop, autosave and recovery.

The window keeps one :class:`~mrm.document.Document` for its whole life; opening a project resets it
with the file's content, so every view stays subscribed. Nothing is touched until a file has been read and
validated completely: a corrupt or hostile file leaves the open document exactly as it was and says why.
"""

from __future__ import annotations

import itertools
import os
from collections.abc import Callable, Iterable
from pathlib import Path
from typing import TYPE_CHECKING, Any

from PySide6 import QtCore, QtWidgets

from mrm.core.errors import MRMError
from mrm.document import Document, Settings
from mrm.document.commands import AddObject

if TYPE_CHECKING:
    from mrm.app.main_window import MainWindow

PROJECT_EXT = ".mrm"
IMAGE_EXTS = (".png", ".pbm", ".pgm", ".npz", ".tif", ".tiff")
VECTOR_EXTS = (".geojson", ".json", ".wkt")
#: 3D files (meshes and volumes; an .npz or .tif is a volume when it holds a 3-D array).
SOLID_EXTS = (".obj", ".ply", ".off", ".stl", ".nii", ".gz")
EXPORT_FILTERS = {
    ".png": "PNG image — pixels (*.png)",
    ".svg": "SVG picture — polygons (*.svg)",
    ".geojson": "GeoJSON — polygons (*.geojson)",
    ".wkt": "WKT — polygons (*.wkt)",
    ".npz": "NumPy mask — pixels (*.npz)",
    ".pbm": "PBM bitmap — pixels (*.pbm)",
    ".tif": "GeoTIFF — pixels, georeferenced (*.tif)",
}
#: What a 3D object exports as: its polyhedron (R(A) of voxels, exactly as the Euclidean 3D view shows it) or
#: its voxels (D(P) of a polyhedron). A label volume exports as its labels only.
EXPORT_FILTERS_3D = {
    ".obj": "Wavefront OBJ — polyhedron, one polygon per face (*.obj)",
    ".off": "OFF — polyhedron, one polygon per face (*.off)",
    ".ply": "PLY — polyhedron, triangles (*.ply)",
    ".stl": "STL — polyhedron, rounded to float32 (*.stl)",
    ".npz": "NumPy volume — voxels (*.npz)",
    ".tif": "Multi-page TIFF — voxels (*.tif)",
    ".nii.gz": "NIfTI — voxels (*.nii.gz)",
}
_VOLUME_EXTENSIONS = (".npz", ".tif", ".nii.gz")


def _extension_3d(p: Path) -> str:
    """The export extension of ``p`` (``.nii.gz`` is one), lower case."""
    name = p.name.lower()
    return ".nii.gz" if name.endswith(".nii.gz") else p.suffix.lower()


def describe_error(e: BaseException) -> str:
    """A one-line message for a user error (file problems included), never a traceback."""
    if isinstance(e, FileNotFoundError):
        return f"{e.filename}: no such file"
    if isinstance(e, IsADirectoryError):
        return f"{e.filename}: is a folder, not a file"
    if isinstance(e, PermissionError):
        return f"{e.filename}: permission denied"
    if isinstance(e, OSError):
        return f"{getattr(e, 'filename', '') or ''}: {e.strerror or e}".lstrip(": ")
    return str(e)


#: Projects bigger than this (bytes, or pixels + vertices for a document) are read and written on a worker.
BIG_FILE = 4_000_000


def document_weight(doc: Any) -> int:
    """A cheap size estimate of a document's file: points of grid sources plus coordinates of polygons."""
    import shapely

    from mrm.core.grids import GridSet, LabelGrid
    from mrm.geometry.polyhedra import Polyhedron

    total = 0
    for o in doc.objects:
        src = o.source
        if isinstance(src, GridSet):
            total += src.mask.size // 4
        elif isinstance(src, LabelGrid):
            total += src.labels.size  # zlib of int32 labels: about a byte a point or less
        elif isinstance(src, Polyhedron):  # three coordinates a vertex
            total += 60 * int(src.n_vertices)
        else:
            total += 40 * int(shapely.get_num_coordinates(src))
    return total


def is_bundled(path: str | os.PathLike[str]) -> bool:
    """True for a path inside the application's own resources (the bundled examples)."""
    from mrm.app.gui import RESOURCES

    try:
        return Path(path).resolve().is_relative_to(RESOURCES.resolve())
    except OSError:
        return False


def user_documents() -> str:
    """The user's documents folder (XDG ``Documents``) when it exists, else the home folder."""
    docs = QtCore.QStandardPaths.writableLocation(QtCore.QStandardPaths.StandardLocation.DocumentsLocation)
    return docs if docs and Path(docs).is_dir() else str(Path.home())


def ask_paths(
    parent: QtWidgets.QWidget,
    name: str,
    title: str,
    start: str,
    filters: str,
    *,
    save: bool = False,
    many: bool = False,
) -> tuple[list[str], str]:
    """Ask for files with a file dialog; the chosen paths ([] when cancelled) and the chosen filter.

    The dialog is an object named ``name`` (``openDialog``, ``saveDialog``, ``importDialog``…), so a test
    or an accessibility tool finds it as the active modal widget and answers it as a user does. ``start``
    is a folder, or a file whose folder is shown with its name proposed.
    """
    dlg = QtWidgets.QFileDialog(parent, title, start, filters)
    dlg.setObjectName(name)
    F = QtWidgets.QFileDialog.FileMode
    if save:
        dlg.setAcceptMode(QtWidgets.QFileDialog.AcceptMode.AcceptSave)
        dlg.setFileMode(F.AnyFile)
    else:
        dlg.setFileMode(F.ExistingFiles if many else F.ExistingFile)
    try:
        if dlg.exec() != QtWidgets.QDialog.DialogCode.Accepted:
            return [], ""
        return dlg.selectedFiles(), dlg.selectedNameFilter()
    finally:
        dlg.deleteLater()


class FileController(QtCore.QObject):
    """The window's file commands; dialogs are shown only when no path is given."""

    documentOpened = QtCore.Signal(str)  # path ('' for a new document)
    saved = QtCore.Signal(str)

    def __init__(self, window: MainWindow, autosave_dir: str | os.PathLike[str] | None = None) -> None:
        super().__init__(window)
        self.win = window
        self.doc: Document = window.doc
        self.prefs = window.prefs
        self._chosen: dict[int, Any] = {}  # answers of the image import dialog, by file index
        # Each import is a task of its own slot (an export's is its path): a second one must not cancel
        # the first.
        self._tasks = itertools.count()
        self.image_dialog: Any = None  # the open "how should this image become objects" dialog
        #: The bundled example the untitled document was opened from (its name is in the title).
        self.example: Path | None = None
        from mrm.io.autosave import Autosaver

        seconds = self.prefs.autosave_seconds
        self.autosave_dir = Path(autosave_dir) if autosave_dir is not None else None
        self.autosaver = Autosaver(
            self.doc,
            interval=float(seconds or 60),
            every_edits=50,
            directory=self.autosave_dir,
            on_error=self._autosave_failed,  # shown, and retried by the autosaver (never fatal)
        )
        self._timer = QtCore.QTimer(self)
        self._timer.setInterval(2000)
        self._timer.timeout.connect(self.autosave_tick)
        if seconds > 0:
            self._timer.start()

    # ------------------------------------------------------------------ helpers
    def _error(self, title: str, text: str) -> None:
        self.win.show_error(title, text)

    def maybe_save(self) -> bool:
        """Ask what to do with unsaved changes; False means the user cancelled."""
        if not self.doc.is_modified:
            return True
        name = self.document_name()
        box = QtWidgets.QMessageBox(self.win)
        box.setObjectName("unsavedDialog")
        box.setIcon(QtWidgets.QMessageBox.Icon.Warning)
        box.setWindowTitle("Unsaved changes")
        box.setText(f"Save the changes to {name}?")
        box.setInformativeText("Your changes will be lost if you don't save them.")
        SB = QtWidgets.QMessageBox.StandardButton
        box.setStandardButtons(SB.Save | SB.Discard | SB.Cancel)
        box.setDefaultButton(SB.Save)
        answer = box.exec()
        if answer == SB.Save:
            return self.save()
        if answer == SB.Discard:
            self.autosaver.discard()
            return True
        return False

    def document_name(self) -> str:
        """The document's name for people: its file's, or Untitled (with the example it was copied from)."""
        if self.doc.path is not None:
            return self.doc.path.name
        if self.example is not None:
            return f"Untitled (copy of the example {self.example.name})"
        return "Untitled"

    def _reset(
        self, doc: Document, path: Path | None, *, clean: bool = True, example: Path | None = None
    ) -> None:
        self.win.tools.cancel()
        self.doc.reset(doc.objects, doc.settings, doc.selection, clean=clean)
        self.doc.path = path
        self.example = example
        self.autosaver.discard()
        self.autosaver.edits = 0 if clean else 1
        self.win.update_title()
        self.documentOpened.emit(str(path) if path else "")
        QtCore.QTimer.singleShot(0, self.win.fit_all)

    def _directory(self) -> str:
        d = self.prefs.last_directory
        return d if Path(d).is_dir() and not is_bundled(d) else user_documents()

    def _save_start(self, name: str) -> str:
        """Where a save dialog starts: beside the project, or in the user's documents for an example.

        A bundled example lives inside the installation: the user's work does not belong there.
        """
        p = self.doc.path
        if p is not None and not is_bundled(p):
            return str(p)
        source = p if p is not None else self.example
        stem = Path(source).stem if source is not None else name
        return str(Path(self._directory()) / f"{stem}.mrm")

    # ------------------------------------------------------------------ new / open
    def new(self) -> bool:
        if not self.maybe_save():
            return False
        self._reset(Document(Settings(model=self.prefs.default_model)), None)
        return True

    def open(self, path: str | os.PathLike[str] | None = None, *, ask: bool = True) -> bool:
        """Open a project (a dialog when ``path`` is None); False when nothing was opened.

        A bundled example opens as an untitled copy: Save asks where to write it, so the installed file
        is never overwritten (the title names the example it was copied from).
        """
        if ask and not self.maybe_save():
            return False
        if path is None:
            files, _ = ask_paths(
                self.win, "openDialog", "Open project", self._directory(),
                "MR Modeler projects (*.mrm);;All files (*)",
            )  # fmt: skip
            if not files:
                return False
            path = files[0]
        p = Path(path)
        if p.suffix.lower() != PROJECT_EXT and p.suffix.lower() in IMAGE_EXTS + VECTOR_EXTS + SOLID_EXTS:
            return self.import_files([p])
        from mrm.io.autosave import find_recoveries
        from mrm.io.project import read_project

        example = is_bundled(p)
        try:
            recs = [] if example else find_recoveries(p)
        except OSError:
            recs = []
        # Every window that crashed on this project left its own autosave: each is offered in turn.
        if self._offer_each(recs):
            return True

        def opened(project: Any) -> None:
            if example:
                # Listed in File ▸ Open Example, not among the recent files (it is not the user's file).
                self._reset(project.to_document(p), None, example=p)
                return
            self._reset(project.to_document(p), p.resolve())
            self.prefs.add_recent_file(p)
            self.prefs.last_directory = str(p.resolve().parent)
            self.win.update_recent_menu()

        def failed(e: BaseException) -> None:
            if not isinstance(e, MRMError | OSError | ValueError):
                raise e
            self._error("Cannot open the project", describe_error(e))

        try:
            big = p.stat().st_size > BIG_FILE
        except OSError:
            big = False
        if big:
            # Reading and checking a big project takes seconds: on a worker, with progress and Cancel.
            # In a worker process: parsing tens of megabytes of JSON holds the GIL (ADR 0025).
            from mrm.app import process_jobs

            runner = self.win.runner
            self.win.runner.submit(
                "file", lambda prog: runner.call(process_jobs.read_project, (str(p),), prog),
                on_result=opened, on_error=failed, label=f"Opening {p.name}", show_progress=True,
            )  # fmt: skip
            return True
        try:
            project = read_project(p)
        except (MRMError, OSError, ValueError) as e:
            failed(e)
            return False
        opened(project)
        return True

    def _offer_each(self, recs: list[Any]) -> bool:
        """Offer the autosaves one after the other until one is recovered (the others stay for later)."""
        return any(self.offer_recovery(rec, (k, len(recs))) for k, rec in enumerate(recs, start=1))

    def offer_recovery(self, rec: Any, position: tuple[int, int] = (1, 1)) -> bool:
        """Ask whether to restore an autosave; True if it was restored.

        ``position`` is (k, n) when n autosaves are offered in turn.
        """
        if rec.project is not None:
            what = rec.project.name
        elif getattr(rec, "recorded", None) is not None:
            # Only shown: the recovered document stays untitled, so Save asks where to write it.
            what = f"an unsaved document (its record names {rec.recorded})"
        else:
            what = "an untitled document"
        when = rec.saved_at.replace("T", " ").replace("+00:00", " UTC") if rec.saved_at else "an unknown time"
        box = QtWidgets.QMessageBox(self.win)
        box.setObjectName("recoveryDialog")
        box.setIcon(QtWidgets.QMessageBox.Icon.Question)
        box.setWindowTitle("Recover unsaved work?")
        count = f" (autosave {position[0]} of {position[1]})" if position[1] > 1 else ""
        box.setText(
            f"MR Modeler was not closed properly. An autosave of {what} from {when} was found{count}."
        )
        box.setInformativeText("Recover it? Discarding deletes the autosave.")
        recover = box.addButton("Recover", QtWidgets.QMessageBox.ButtonRole.AcceptRole)
        discard = box.addButton("Discard", QtWidgets.QMessageBox.ButtonRole.DestructiveRole)
        box.addButton("Later", QtWidgets.QMessageBox.ButtonRole.RejectRole)
        box.setDefaultButton(recover)
        box.exec()
        clicked = box.clickedButton()
        if clicked is discard:
            rec.discard()
            return False
        if clicked is not recover:
            return False
        try:
            doc = rec.restore()
        except (MRMError, OSError, ValueError) as e:
            self._error("Cannot recover the autosave", describe_error(e))
            return False
        path = rec.project
        self._reset(doc, path, clean=False)
        rec.discard()
        self.autosaver.write_now()  # the recovered edits are safe again until saved
        if path is not None:
            self.prefs.add_recent_file(path)
            self.win.update_recent_menu()
        return True

    def check_orphans(self) -> bool:
        """On start-up: offer the autosave of an untitled document left by a crashed session."""
        from mrm.io.autosave import find_orphans

        try:
            found = find_orphans(self.autosave_dir)
        except OSError:
            return False
        return self._offer_each(found)

    # ------------------------------------------------------------------ save
    def save(self) -> bool:
        if self.doc.path is None:
            return self.save_as()
        return self._write(Path(self.doc.path))

    def save_as(self, path: str | os.PathLike[str] | None = None) -> bool:
        if path is None:
            start = self._save_start("untitled")
            files, _ = ask_paths(
                self.win, "saveDialog", "Save project", start, "MR Modeler projects (*.mrm)", save=True
            )
            if not files:
                return False
            path = files[0]
        p = Path(path)
        if p.suffix.lower() != PROJECT_EXT:
            p = p.with_name(p.name + PROJECT_EXT)
        return self._write(p)

    def _write(self, p: Path) -> bool:
        from mrm.io.project import save_project

        old_side = self.autosaver.path
        if document_weight(self.doc) > BIG_FILE:
            return self._write_on_worker(p, old_side)
        try:
            save_project(self.doc, p)
        except (MRMError, OSError, ValueError) as e:
            self._error("Cannot save the project", describe_error(e))
            return False
        self._written(p, old_side)
        return True

    def _write_on_worker(self, p: Path, old_side: Path) -> bool:
        """Serialise and write a big project on a worker (the objects are immutable: a snapshot is free)."""
        from types import SimpleNamespace

        from mrm.app import process_jobs

        doc = self.doc
        snap = SimpleNamespace(settings=doc.settings, selection=doc.selection, objects=doc.objects)
        revision = doc.revision

        def work(progress: Any) -> None:
            # In a worker process: encoding tens of megabytes holds the GIL (ADR 0025).
            self.win.runner.call(process_jobs.write_project, (str(p), snap), progress)

        def done(_r: object) -> None:
            if doc.revision == revision:
                doc.history.set_clean()
            self._written(p, old_side)

        def failed(e: BaseException) -> None:
            if not isinstance(e, MRMError | OSError | ValueError):
                raise e
            self._error("Cannot save the project", describe_error(e))

        self.win.runner.submit(
            "file", work, on_result=done, on_error=failed, label=f"Saving {p.name}", show_progress=True
        )
        return True

    def _written(self, p: Path, old_side: Path) -> None:
        self.autosaver.discard()
        if old_side.exists() and old_side != self.autosaver.path:
            old_side.unlink(missing_ok=True)
        self.autosaver.edits = 0
        self.doc.path = p.resolve()
        self.example = None
        self.prefs.add_recent_file(p)
        self.prefs.last_directory = str(p.resolve().parent)
        self.win.update_recent_menu()
        self.win.update_title()
        self.win.show_message(f"Saved {p.name}", 3000)
        self.saved.emit(str(p))

    def autosave_tick(self) -> None:
        # Autosaver.tick reports its failures through _autosave_failed and never raises; the guard keeps
        # a timer slot from ever propagating an exception into Qt's event loop.
        try:
            a = self.autosaver
            if self.win.runner.is_busy("autosave"):
                return
            if self.doc.is_modified and a.due() and document_weight(self.doc) > BIG_FILE:
                self._autosave_on_worker()
                return
            a.tick()
        except Exception as e:
            self._autosave_failed(f"Autosave failed, will retry: {describe_error(e)}")

    def _autosave_on_worker(self) -> None:
        """Serialise a big document's autosave on a worker: at 10⁸ pixels it takes seconds."""
        a = self.autosaver
        target, write = a.prepare_write()
        edits = a.edits

        def failed(e: BaseException) -> None:
            a.write_failed(e)

        self.win.runner.submit(
            "autosave", lambda _p: write(), on_result=lambda _r: a.written(target, edits), on_error=failed
        )

    def _autosave_failed(self, message: str) -> None:
        self.win.show_message(message, 10000, error=True)

    # ------------------------------------------------------------------ import / export
    def import_dialog(self) -> bool:
        """File ▸ Import… (Ctrl+I): choose images or geometry files and import them as new objects."""
        files, _ = ask_paths(
            self.win,
            "importDialog",
            "Import",
            self._directory(),
            "Images, geometry and 3D (*.png *.pbm *.pgm *.npz *.tif *.tiff *.geojson *.json *.wkt"
            " *.obj *.ply *.off *.stl *.nii *.nii.gz);;"
            "Images — pixels (*.png *.pbm *.pgm *.npz *.tif *.tiff);;"
            "Geometry — polygons (*.geojson *.json *.wkt);;"
            "3D — meshes and voxel volumes (*.obj *.ply *.off *.stl *.nii *.nii.gz *.npz *.tif *.tiff);;"
            "All files (*)",
            many=True,
        )
        return self.import_files([Path(f) for f in files]) if files else False

    def read_objects(self, path: Path, model: str | None = None) -> list[tuple[str, Any]]:
        """The (name, source) pairs a file brings in; raises on a bad file (nothing is added then).

        Touches no widget and no document state (lines and points are discretized under ``model``, the
        document's by default), so the import runs it on a worker thread.
        """
        from mrm.core.limits import clean_name
        from mrm.document import validate_geometry

        model = self.doc.model if model is None else model
        ext = path.suffix.lower()
        from mrm.io.imports import solid_sources

        solid = solid_sources(path)  # a mesh, or a voxel file (an .npz or .tif holding a 3-D array)
        if solid is not None:
            return solid
        if ext in IMAGE_EXTS:
            from mrm.io.pixel_files import read_pixels

            return [(clean_name(path.stem), read_pixels(path))]
        if ext in VECTOR_EXTS:
            from mrm.io.vector_files import read_geometries

            out: list[tuple[str, Any]] = []
            named = read_geometries(path)
            for k, (name, g) in enumerate(named):
                stem = clean_name(path.stem)  # an undecodable file name holds lone surrogates
                label = name or (stem if len(named) == 1 else f"{stem} {k + 1}")
                if g.geom_type in ("Polygon", "MultiPolygon"):
                    out.append((str(label), validate_geometry(g)))
                elif not g.is_empty:
                    # Lines and points cannot be polygon sources; their discretization is a pixel object.
                    from mrm.geometry.discretize import discretize

                    out.append((str(label), discretize(g, model)))
            return out
        from mrm.core.errors import FileFormatError

        raise FileFormatError(
            f"{path.name}: cannot import '{ext or 'no extension'}' files; "
            "use PNG, PBM, PGM, NPZ, TIFF, GeoJSON, WKT, a mesh (OBJ, PLY, OFF, STL) or a volume (NIfTI)"
        )

    def _in_background(
        self, slot: str, fn: Callable[[Any], Any], done: Callable[[Any], bool], error_title: str, label: str
    ) -> bool:
        """Run ``fn(progress)`` on a worker, then ``done(result)`` on the GUI thread.

        Progress and Cancel are in the status bar; a user error is shown under ``error_title``. Returns
        ``done``'s answer when the runner has finished already (the tests' synchronous runner), else True:
        the work has started.
        """
        outcome: list[bool] = []

        def failed(e: BaseException) -> None:
            if not isinstance(e, MRMError | OSError | ValueError):
                raise e
            outcome.append(False)
            self._error(error_title, describe_error(e))

        self.win.runner.submit(
            slot, fn, on_result=lambda r: outcome.append(done(r)), on_error=failed,
            on_cancel=lambda: self.win.show_message(f"{label} cancelled; nothing changed", 4000),
            label=label, show_progress=True,
        )  # fmt: skip
        return outcome[0] if outcome else True

    def import_files(self, paths: Iterable[str | os.PathLike[str]]) -> bool:
        """Import every file as new objects, in one undo step; a bad file is reported and skipped.

        A grey, colour or label image first asks (once, window-modal, without blocking) how to turn it
        into objects; the import then happens when the dialog is accepted, and this returns False. The
        files are looked at and read on workers: with the threaded runner this returns True at once.
        """
        paths = [Path(p) for p in paths]
        from mrm.app.import_dialog import image_values

        todo = [k for k, p in enumerate(paths) if p.suffix.lower() in IMAGE_EXTS and k not in self._chosen]
        if not todo:
            chosen, self._chosen = self._chosen, {}
            return self._import(paths, chosen)

        def look(_progress: Any) -> tuple[int, Any] | None:
            # On a worker: a grey image's values are decoded in full to decide whether to ask (seconds at
            # 10⁸ pixels). The first image that needs an answer, with its values; None if none does.
            from mrm.io.voxel_files import is_volume_file

            for k in todo:
                if is_volume_file(paths[k]):
                    continue  # a 3-D .npz or .tif: voxels, no threshold to ask for here
                try:
                    values = image_values(paths[k])
                except (OSError, ValueError):
                    values = None  # the model's reader reports what is wrong with the file
                if values is not None:
                    return k, values
            return None

        def looked(found: tuple[int, Any] | None) -> bool:
            if found is not None:
                self._ask_image(paths, found[0], *found[1])
                return False
            chosen, self._chosen = self._chosen, {}
            return self._import(paths, chosen)

        return self._in_background(
            f"import {next(self._tasks)}", look, looked, "Cannot import", "Reading images"
        )

    def _ask_image(self, paths: list[Path], k: int, grey: Any, labels_ok: bool, labels_first: bool) -> None:
        from mrm.app.import_dialog import ImageImportDialog

        dlg = ImageImportDialog(paths[k], grey, labels_ok, labels_first, self.win)
        self.image_dialog = dlg

        def done(result: int) -> None:
            self.image_dialog = None
            if result != QtWidgets.QDialog.DialogCode.Accepted:
                self._chosen = {}
                self.win.show_message(f"import of {paths[k].name} cancelled; nothing was added", 4000)
                return
            self._chosen[k] = dlg.reader()  # the choices, read now; the file, on the import's worker
            self.import_files(paths)

        dlg.finished.connect(done)
        dlg.setWindowModality(QtCore.Qt.WindowModality.WindowModal)
        dlg.open()

    def _import(self, paths: list[Path], chosen: dict[int, Any]) -> bool:
        """Read the files on a worker, then add their objects on the GUI thread as one undo step.

        Decoding a 10⁸-pixel image takes seconds. True when something was added or is being read.
        """
        model = self.doc.model

        def read(progress: Any) -> tuple[list[tuple[str, Any, Any]], list[str]]:
            items: list[tuple[str, Any, Any]] = []
            errors = []
            for k, p in enumerate(paths):
                progress.update(k / len(paths), f"reading {p.name}")
                try:
                    reader = chosen.get(k)
                    pairs = reader() if reader is not None else self.read_objects(p, model)
                    georef = None
                    from mrm.document.objects import source_dimension

                    flat = all(source_dimension(src) == 2 for _name, src in pairs)
                    if flat and p.suffix.lower() in IMAGE_EXTS:  # a GeoTIFF's or world file's place stays
                        from mrm.io.georef import read_georef

                        georef = read_georef(p)
                    items += [(name, src, georef) for name, src in pairs]
                except (MRMError, OSError, ValueError) as e:
                    errors.append(describe_error(e))
            return items, errors

        names = ", ".join(p.name for p in paths)
        return self._in_background(
            f"import {next(self._tasks)}",
            read,
            lambda r: self._add_imported(paths, *r),
            "Cannot import",
            f"Importing {names}",
        )

    def _add_imported(self, paths: list[Path], items: list[tuple[str, Any, Any]], errors: list[str]) -> bool:
        if items:
            objs = []
            for k, (name, src, georef) in enumerate(items):
                objs.append(
                    self.doc.make_object(src, name=name, style=self.win.host.new_style(k), georef=georef)
                )
            try:
                with self.doc.history.macro("Import" if len(objs) > 1 else f"Import {objs[0].name}"):
                    for o in objs:
                        self.doc.push(AddObject(o))
                self.doc.set_selection([objs[-1].id])
            except MRMError as e:
                errors.append(str(e))
            else:
                self._show_dimension_of(objs)
                QtCore.QTimer.singleShot(0, self.win.fit_all)
            first = Path(next(iter(map(Path, paths))))
            self.prefs.last_directory = str(first.resolve().parent)
        if errors:
            self._error("Cannot import", "\n".join(errors))
        return bool(items) and not errors

    def _show_dimension_of(self, objs: list[Any]) -> None:
        """Bring the views the imported objects are drawn in (3D views for voxels and meshes) to the front.

        A voxel file imported into the plane views was drawn nowhere: the window showed empty grids. A mix of
        plane and 3D objects leaves the views as they are.
        """
        dims = {o.dimension for o in objs}
        views = self.win.views
        if len(dims) != 1 or (dim := dims.pop()) == views.dimension:
            return
        views.set_dimension(dim)
        shown, other = ("3D", "plane") if dim == 3 else ("plane", "3D")
        self.win.show_message(f"showing the {shown} views (F3 for the {other} views)", 6000)

    def export_dialog(self) -> bool:
        obj = self.win.scene.selected()
        if obj is None:
            self._error("Nothing to export", "Select the object to export first.")
            return False
        table = EXPORT_FILTERS_3D if obj.dimension == 3 else EXPORT_FILTERS
        first = ".npz" if obj.dimension == 3 and obj.kind == "labels" else next(iter(table))
        filters = ";;".join(table.values())
        start = str(Path(self._directory()) / f"{obj.name}{first}")
        files, flt = ask_paths(self.win, "exportDialog", f"Export {obj.name}", start, filters, save=True)
        if not files:
            return False
        p = Path(files[0])
        if _extension_3d(p) not in table:
            ext = next((e for e, f in table.items() if f == flt), first)
            p = p.with_name(p.name + ext)
        return self.export(obj.id, p)

    def export(self, obj_id: int, path: str | os.PathLike[str]) -> bool:
        """Write an object's pixels (.png/.pbm/.npz) or polygons (.svg/.geojson/.wkt), from the model."""
        p = Path(path)
        ext = p.suffix.lower()
        entry = self.doc.derived(obj_id)
        if self.doc.get(obj_id).dimension == 3:
            return self._export_3d(obj_id, p)
        if self.doc.get(obj_id).kind == "labels":
            return self._export_label_map(obj_id, p)
        obj = self.doc.get(obj_id)
        doc = self.doc

        def write(_progress: Any) -> None:
            # On a worker: encoding 10⁸ pixels, or continuing them first (R), takes seconds. It reads the
            # object's immutable source and its derived entry, and writes atomically.
            if ext == ".tif" or (obj.georef is not None and ext in (".png", ".geojson", ".json", ".wkt")):
                from mrm.io.export import export_object

                export_object(doc, obj_id, p)  # where it lies on the Earth (ADR 0021)
            elif ext in (".png", ".pbm", ".npz"):
                from mrm.io.pixel_files import write_pixels

                write_pixels(entry.get("discrete"), p)
            elif ext == ".svg":
                from mrm.io.vector_files import write_svg

                write_svg(entry.get("euclidean"), p, colour=obj.style.fill[:7], opacity=obj.style.opacity)
            elif ext in (".geojson", ".json"):
                from mrm.io.vector_files import write_geojson

                write_geojson(entry.get("euclidean"), p, {"name": obj.name})
            elif ext == ".wkt":
                from mrm.io.vector_files import write_wkt

                write_wkt(entry.get("euclidean"), p)
            else:
                raise ValueError(f"{p.name}: cannot export '{ext}'; use " + ", ".join(EXPORT_FILTERS))

        def written(_r: Any) -> bool:
            self.prefs.last_directory = str(p.resolve().parent)
            self.win.show_message(f"Exported {p.name}", 3000)
            return True

        return self._in_background(f"export {p}", write, written, "Cannot export", f"Exporting {p.name}")

    def _export_3d(self, obj_id: int, p: Path) -> bool:
        """Write a 3D object on a worker: its polyhedron as a mesh, or its voxels (a label volume: labels)."""
        obj = self.doc.get(obj_id)
        entry = self.doc.derived(obj_id)
        ext = _extension_3d(p)
        if ext not in EXPORT_FILTERS_3D or (obj.kind == "labels" and ext not in _VOLUME_EXTENSIONS):
            kinds = ", ".join(_VOLUME_EXTENSIONS if obj.kind == "labels" else EXPORT_FILTERS_3D)
            more = " (`mrm polygonize` writes its meshes, one per region)" if obj.kind == "labels" else ""
            self._error(
                "Cannot export", f"{obj.name} is a 3D object: it exports as {kinds}{more}, not '{ext}'."
            )
            return False
        warnings: list[str] = []

        def write(progress: Any) -> None:
            # On a worker: R(A) of a big voxel set, or D(P) of a big polyhedron, takes seconds; both are the
            # document's own (the object's derived entry), written atomically.
            if obj.kind == "labels":
                from mrm.io.voxel_files import write_label_volume

                write_label_volume(obj.source, p)
            elif ext in _VOLUME_EXTENSIONS:
                from mrm.io.voxel_files import write_voxels

                progress.update(None, f"{obj.name}: its voxels")
                write_voxels(entry.get("discrete"), p)
            else:
                from mrm.io.mesh_files import write_mesh

                progress.update(None, f"{obj.name}: its polyhedron")
                warning = write_mesh(entry.get("euclidean"), p)
                if warning is not None:
                    warnings.append(warning)
                if entry.r_note is not None:  # the file holds the safety net: say so, and how to get better
                    warnings.append(
                        "the file holds R's safety net, exact but not compact (a higher Compact R Limit, in "
                        "Edit ▸ Discretization Model, gives a compact R, more slowly)"
                        if entry.r_over_limit
                        else "the file holds R's safety net, exact but not compact"
                    )

        def written(_r: Any) -> bool:
            self.prefs.last_directory = str(p.resolve().parent)
            note = "".join(f" — {w}" for w in warnings)
            self.win.show_message(f"Exported {p.name}{note}", 8000 if warnings else 3000)
            return True

        return self._in_background(f"export {p}", write, written, "Cannot export", f"Exporting {p.name}")

    def _export_label_map(self, obj_id: int, p: Path) -> bool:
        """Write a label map: its labels (.png, .npz) or one GeoJSON Feature per region, on a worker.

        The regions are those of ``mrm polygonize`` (label, pixels, polygon; the gauss subdivision), which
        takes seconds on a big map: the window stays live and the status bar says when it is written.
        """
        obj = self.doc.get(obj_id)
        lm = obj.source
        ext = p.suffix.lower()
        if ext in (".png", ".npz"):
            from mrm.io.pixel_files import write_label_map

            def work(_progress: Any) -> None:
                write_label_map(lm, p)
        elif ext in (".geojson", ".json"):
            from mrm.geometry.reconstruct.polygonize import polygonize
            from mrm.io.vector_files import write_regions_geojson

            def work(progress: Any) -> None:
                progress.update(0.0, f"{obj.name}: polygonizing its regions")
                write_regions_geojson(polygonize(lm), p)
        else:
            self._error(
                "Cannot export",
                f"{obj.name} is a label map: it exports as GeoJSON (one feature per region, with its label "
                f"and pixel count) or as a PNG or NPZ label image, not as '{ext}'. Edit ▸ Split into Objects "
                "gives one object per label for the other formats.",
            )
            return False

        def done(_r: Any) -> None:
            self.prefs.last_directory = str(p.resolve().parent)
            self.win.show_message(f"Exported {p.name}", 3000)

        def failed(e: BaseException) -> None:
            if not isinstance(e, MRMError | OSError | ValueError):
                raise e
            self._error("Cannot export", describe_error(e))

        self.win.runner.submit(
            f"export:{obj_id}",
            work,
            on_result=done,
            on_error=failed,
            label=f"Exporting {p.name}",
            show_progress=True,
        )
        return True

    # ------------------------------------------------------------------ drag and drop
    def drop(self, paths: list[Path]) -> None:
        projects = [p for p in paths if p.suffix.lower() == PROJECT_EXT]
        others = [p for p in paths if p.suffix.lower() != PROJECT_EXT]
        if projects:
            self.open(projects[0])
        if others:
            self.import_files(others)

    def close(self, *, discard_autosave: bool) -> None:
        self._timer.stop()
        if discard_autosave:
            self.autosaver.discard()
        self.autosaver.close()
