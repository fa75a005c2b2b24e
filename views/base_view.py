"""The frame shared by the four representation views: a header, a :class:`PlaneView`, one layer per object.

A view never mutates the model. It marks objects dirty when the document, a preview or a background
derivation changes them, and redraws once per event-loop turn (a 0 ms single-shot timer), so a burst of
events costs one repaint.
"""

from __future__ import annotations

from typing import Any

import pyqtgraph as pg
from PySide6 import QtCore, QtGui, QtWidgets

from mrm.document import Changes, DocObject
from mrm.document.derive import Rep
from mrm.views.canvas import PlaneView
from mrm.views.scene import CANCELLED, Phantom, Scene
from mrm.views.view_header import ViewHeader


class Layer(pg.ItemGroup):
    """The items drawing one object in one view."""

    def __init__(self, obj_id: int) -> None:
        super().__init__()
        self.obj_id = obj_id
        self.waiting = False  # True while a representation it needs is being computed


class PreparedDrawing:
    """Drawing data made at once when small, on the scene's runner when big (the plane and the 3D views).

    The class using it has ``name``, ``scene`` and ``mark_dirty(obj_id)`` and calls
    :meth:`init_prepared_drawing` in its constructor.
    """

    name: str
    scene: Any

    def init_prepared_drawing(self) -> None:
        self._prepared: dict[tuple[int, str], tuple[Any, Any]] = {}  # (object, what) -> (key, drawing data)
        self._preparing: dict[str, Any] = {}  # worker slot -> the key it prepares

    def mark_dirty(self, obj_id: int) -> None:
        raise NotImplementedError

    def forget_prepared(self, obj_id: int) -> None:
        """Drop the drawing data of an object no longer drawn."""
        for k in [k for k in self._prepared if k[0] == obj_id]:
            del self._prepared[k]

    #: Drawing data for representations up to this many elements (pixels, vertices) is prepared at once on
    #: the GUI thread (well under 50 ms); beyond, on a worker, and the layer waits for it.
    PREPARE_SYNC = 250_000

    def prepared(self, obj_id: int, what: str, key: Any, size: int, compute: Any) -> Any | None:
        """The drawing data ``compute()`` makes for ``key`` (a representation, compared by identity).

        Small ones are computed now; big ones on a worker (the newest request per object wins), and None is
        returned meanwhile: the layer keeps what it shows and the view says "computing…".
        """
        hit = self._prepared.get((obj_id, what))
        if hit is not None and hit[0] is key:
            return hit[1]
        if size <= self.PREPARE_SYNC or getattr(self.scene, "runner", None) is None:
            value = compute()
            self._prepared[(obj_id, what)] = (key, value)
            return value
        slot = f"prepare:{self.name}:{what}:{obj_id}"
        if self._preparing.get(slot) is key and self.scene.runner.is_busy(slot):
            return None
        self._preparing[slot] = key

        def done(value: Any) -> None:
            if self._preparing.get(slot) is key:
                del self._preparing[slot]
            self._prepared[(obj_id, what)] = (key, value)
            self.mark_dirty(obj_id)

        def failed(exc: BaseException) -> None:
            self._preparing.pop(slot, None)
            raise exc

        self.scene.runner.submit(slot, lambda _p: compute(), on_result=done, on_error=failed, drawing=True)
        return None

    def is_preparing(self) -> bool:
        runner = getattr(self.scene, "runner", None)
        if runner is None:
            return False
        # The exact detail of a coarse image, zoomed in (MaskItem.update_detail), is drawing data too.
        return any(runner.is_busy(s) for s in self._preparing) or runner.is_busy_prefix(
            f"detail:{self.name}:"
        )


class RepresentationView(PreparedDrawing, QtWidgets.QFrame):
    """Base class of the discrete, region, analytical and Euclidean views."""

    #: Short name (object names, tests), title and what the view shows.
    name = "base"
    title = ""
    subtitle = ""
    #: The representation the view draws (used for error and "computing" messages).
    rep: Rep = "discrete"
    #: Whether the view draws previewed results (ghosts); the region and analytical views colour each
    #: component or segment, which would make a ghost look like an object, so they do not.
    shows_ghosts = False
    #: What the marks mean, shown under the plane (rich text, one line that wraps).
    legend = ""

    #: Emitted after each refresh (tests and the screenshot wait for it).
    refreshed = QtCore.Signal()

    def __init__(self, scene: Scene, parent: QtWidgets.QWidget | None = None) -> None:
        super().__init__(parent)
        self.setObjectName(f"repview_{self.name}")
        self.scene = scene
        self.setFrameShape(QtWidgets.QFrame.Shape.StyledPanel)
        lay = QtWidgets.QVBoxLayout(self)
        lay.setContentsMargins(0, 0, 0, 0)
        lay.setSpacing(0)
        self.header = ViewHeader(self.title, self.subtitle, self)
        hl = self.header.layout_
        self.title_label = self.header.title_label
        self.subtitle_label = self.header.subtitle_label
        self.status_label = self.header.status_label
        # After a Cancel in the status bar: compute what was left out (shown only then).
        self.resume_button = QtWidgets.QToolButton(self.header)
        self.resume_button.setObjectName("resumeDerivations")
        self.resume_button.setText("Compute")
        self.resume_button.setToolTip("Compute what was cancelled")
        self.resume_button.setAutoRaise(True)
        self.resume_button.clicked.connect(lambda: self.scene.resume_derivations())
        self.resume_button.hide()
        hl.addWidget(self.resume_button)
        lay.addWidget(self.header)
        self.plane = PlaneView(self.name, self)
        self.plane.runner = getattr(scene, "runner", None)
        lay.addWidget(self.plane, 1)
        self.legend_label = QtWidgets.QLabel(self.legend, self)
        self.legend_label.setObjectName("viewLegend")
        self.legend_label.setWordWrap(True)
        self.legend_label.setTextFormat(QtCore.Qt.TextFormat.RichText)
        self.legend_label.setContentsMargins(8, 1, 6, 2)
        policy = QtWidgets.QSizePolicy.Policy
        self.legend_label.setSizePolicy(policy.Ignored, policy.Fixed)
        self.legend_label.setVisible(bool(self.legend))
        lay.addWidget(self.legend_label)
        self._layers: dict[int, Layer] = {}
        self.init_prepared_drawing()
        self._dirty: set[int] = set()
        self._all_dirty = True
        self._timer = QtCore.QTimer(self)
        self._timer.setSingleShot(True)
        self._timer.setInterval(0)
        self._timer.timeout.connect(self.refresh)
        scene.documentChanged.connect(self._on_changes)
        scene.previewChanged.connect(self.mark_dirty)
        scene.derivedReady.connect(self.mark_dirty)
        scene.phantomsChanged.connect(self.mark_all_dirty)
        self._style_header()
        self.mark_all_dirty()

    # ------------------------------------------------------------------ scheduling
    def _on_changes(self, changes: Changes) -> None:
        if changes.reset or changes.reordered or changes.settings or changes.selection:
            self.mark_all_dirty()
            return
        for i in (*changes.inserted, *changes.removed, *changes.changed):
            self.mark_dirty(i)

    def mark_dirty(self, obj_id: int) -> None:
        self._dirty.add(obj_id)
        self._timer.start()

    def mark_all_dirty(self) -> None:
        self._all_dirty = True
        self._timer.start()

    def is_drawn(self) -> bool:
        """True when nothing is waiting to be drawn or computed."""
        return (
            not self._timer.isActive()
            and not self._all_dirty
            and not self._dirty
            and not any(layer.waiting for layer in self._layers.values())
            and not self.is_preparing()
        )

    def refresh(self) -> None:
        """Bring the layers of dirty objects up to date with the scene."""
        self._timer.stop()
        doc = self.scene.doc
        objects = tuple(o for o in self.scene.objects() if self.shows_ghosts or not isinstance(o, Phantom))
        present = {o.id for o in objects}
        for i in [i for i in self._layers if i not in present]:
            self._remove_layer(i)
        todo = present if self._all_dirty else (self._dirty & present)
        self._all_dirty = False
        self._dirty.clear()
        selected = set(doc.selection)
        order = {obj.id: k for k, obj in enumerate(objects)}
        from mrm.views.label_maps import LabelLayer, draw_labels  # it imports this module

        for obj in objects:
            if obj.id not in todo:
                continue
            layer = self._layers.get(obj.id)
            # A label map object has its own items in every view (ADR 0033).
            labels = obj.kind == "labels"
            if layer is not None and isinstance(layer, LabelLayer) != labels:
                self._remove_layer(obj.id)
                layer = None
            if layer is None:
                layer = self._layers[obj.id] = LabelLayer(obj.id) if labels else self.make_layer(obj.id)
                self.plane.vb.addItem(layer)
            layer.setZValue(order[obj.id] * 2 + (1 if obj.id in selected else 0))
            layer.setVisible(obj.style.visible and not self.hidden_while_editing(obj.id))
            if not obj.style.visible:
                layer.waiting = False
            elif isinstance(layer, LabelLayer):
                layer.waiting = not draw_labels(self, layer, obj, self.rep, obj.id in selected)
            else:
                layer.waiting = not self.update_layer(layer, obj, obj.id in selected)
        self._update_status()
        self.after_refresh()
        self.refreshed.emit()

    def _remove_layer(self, obj_id: int) -> None:
        layer = self._layers.pop(obj_id)
        self.plane.vb.removeItem(layer)
        self.forget_prepared(obj_id)

    def _update_status(self) -> None:
        errors = []
        cancelled = []
        for obj in self.scene.objects():
            if not obj.style.visible or (obj.kind == "labels" and self.rep == "analytical"):
                continue  # (a label map has no segments: label_map_note says so, neutrally)
            if self.scene.is_cancelled(obj.id, self.rep) or self.scene.is_cancelled(obj.id, "discrete"):
                cancelled.append(obj.name)
                continue
            e = self.scene.error(obj.id, self.rep) or self.scene.error(obj.id, "discrete")
            if e:
                errors.append(f"{obj.name}: {e}")
        if cancelled and not errors:
            self.header.show_status(f"{cancelled[0]}: {CANCELLED}", "\n".join(cancelled))
        elif errors:
            self.header.show_status(errors[0], "\n".join(errors), error=True)
        elif any(layer.waiting for layer in self._layers.values()):
            self.header.show_status("computing…")
        elif (note := self.label_map_note()) is not None:
            self.header.show_status(note, note)
        else:
            self.header.show_status("")
        from mrm.views.label_maps import LABEL_LEGEND

        maps = any(o.kind == "labels" and o.style.visible for o in self.scene.doc.plane_objects)
        extra = LABEL_LEGEND.get(self.name) if maps else None
        self.legend_label.setText(f"{self.legend}<br>{extra}" if extra else self.legend)
        self.legend_label.setVisible(bool(self.legend_label.text()))
        self.resume_button.setVisible(bool(cancelled) and not errors)
        # An empty status takes no room: the subtitle ("components, holes, cracks") is then shown whole.
        self.status_label.setVisible(bool(self.status_label.text()))

    def label_map_note(self) -> str | None:
        """What the view says, neutrally, of a selected label map it does not draw (the analytical view)."""
        return None

    def layer(self, obj_id: int) -> Layer | None:
        return self._layers.get(obj_id)

    # ------------------------------------------------------------------ for subclasses
    def make_layer(self, obj_id: int) -> Layer:
        return Layer(obj_id)

    def update_layer(self, layer: Layer, obj: DocObject | Phantom, selected: bool) -> bool:
        """Redraw ``layer`` for ``obj``; return False when a representation is still being computed."""
        raise NotImplementedError

    def hidden_while_editing(self, obj_id: int) -> bool:
        """True when a tool draws the object itself for now (the brush's stroke in progress)."""
        return False

    def after_refresh(self) -> None:
        """Hook run after the layers were updated (e.g. the selected segment's overlay)."""

    def get(self, obj_id: int, rep: Rep) -> Any | None:
        return self.scene.get(obj_id, rep)

    # ------------------------------------------------------------------ appearance
    def _style_header(self) -> None:
        pal = self.palette()
        self.header.restyle(pal)
        if hasattr(self, "legend_label"):
            mid = pal.color(QtGui.QPalette.ColorRole.PlaceholderText).name()
            self.legend_label.setStyleSheet(f"color: {mid}; font-size: 8pt;")

    def changeEvent(self, ev: QtCore.QEvent) -> None:
        if ev.type() in (QtCore.QEvent.Type.PaletteChange, QtCore.QEvent.Type.ApplicationPaletteChange):
            self._style_header()
            self.mark_all_dirty()
        super().changeEvent(ev)

    def is_dark(self) -> bool:
        return self.plane.is_dark()
