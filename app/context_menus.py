"""Right-click menus of the views and of the object list.

The menus are made of the window's registered actions (:mod:`mrm.app.actions`), so each item shows the
same text and keyboard shortcut as in the main menus, plus a few items that act *where* the click was:
fill the hole or delete the component under the cursor (the model's ``FillHole`` / ``DeleteComponent``
commands, as the F and X tools push them), and set the operation's centre there.

A right click on an object selects it first (unless it is already part of the selection), as in QGIS and
Inkscape. Menus open with ``popup`` (never a nested event loop); the open one is ``window.context_menu``.
"""

from __future__ import annotations

import logging
from typing import Any

from PySide6 import QtCore, QtWidgets

from mrm.core.errors import MRMError
from mrm.views import geometry_edit as ge

log = logging.getLogger(__name__)

#: The object items of both menus (None = separator).
OBJECT_ITEMS: tuple[str | None, ...] = (
    "edit.rename",
    "edit.colour",
    "edit.properties",
    None,
    "edit.cut",
    "edit.copy",
    "edit.paste",
    "edit.duplicate",
    "edit.delete",
    "edit.split_labels",
    None,
    "view.fit_selection",
    "view.fit_differences",
    "measure.hausdorff",
)


class ContextMenus(QtCore.QObject):
    """Builds and opens the context menus of ``window`` (a :class:`~mrm.app.main_window.MainWindow`)."""

    def __init__(self, window: Any) -> None:
        super().__init__(window)
        self.win = window
        lst = window.object_list.view
        lst.setContextMenuPolicy(QtCore.Qt.ContextMenuPolicy.CustomContextMenu)
        lst.customContextMenuRequested.connect(self.open_list_menu)
        window.tools.contextMenuRequested.connect(self.open_view_menu)

    # ------------------------------------------------------------------ building
    def _menu(self, name: str) -> QtWidgets.QMenu:
        old = getattr(self.win, "context_menu", None)
        if old is not None:
            old.close()
            old.deleteLater()
        m = QtWidgets.QMenu(self.win)
        m.setObjectName(name)
        m.setAttribute(QtCore.Qt.WidgetAttribute.WA_DeleteOnClose, False)
        self.win.context_menu = m
        return m

    def _add_object_items(self, m: QtWidgets.QMenu) -> None:
        self.win.update_action_states()
        for aid in OBJECT_ITEMS:
            if aid is None:
                m.addSeparator()
            elif aid != "edit.split_labels" or self.win.registry[aid].isEnabled():  # label maps only
                m.addAction(self.win.registry[aid])

    def _here(self, m: QtWidgets.QMenu, text: str, name: str, slot: Any, enabled: bool, tip: str) -> None:
        act = m.addAction(text)
        act.setObjectName(name)
        act.setEnabled(enabled)
        act.setStatusTip(tip)
        act.setToolTip(tip)
        act.triggered.connect(lambda _c=False: slot())

    # ------------------------------------------------------------------ views
    def open_view_menu(self, view: Any, x: float, y: float, global_pos: QtCore.QPoint) -> QtWidgets.QMenu:
        """The menu of a right click at plane point (x, y) in ``view``."""
        win = self.win
        doc = win.doc
        tool = win.tools.tool
        obj = tool.object_at(x, y) if tool is not None else None
        if obj is not None and obj.id not in doc.selection:
            doc.set_selection([obj.id])
        m = self._menu("viewContextMenu")
        self._add_object_items(m)
        m.addSeparator()
        px = ge.pixel_at(x, y)
        hole_owner = self.hole_owner(px)
        self._here(
            m,
            "Fill This &Hole",
            "ctx.fill_hole",
            lambda: self.fill_hole(px),
            hole_owner is not None,
            f"Fill the hole under the cursor, pixel {px} (the Fill Hole tool, F, does this by click)",
        )
        self._here(
            m,
            "Delete This C&omponent",
            "ctx.delete_component",
            lambda: self.delete_component(px),
            obj is not None,
            f"Delete the component under the cursor, pixel {px} (the Delete Component tool, X)",
        )
        has_centre = win.operations.centre_control() is not None
        self._here(
            m,
            "Set Operation &Centre Here",
            "ctx.set_centre",
            lambda: win.operations.set_centre(x, y),
            has_centre,
            "Use this point as the rotation or scaling centre of the Operations panel",
        )
        m.addSeparator()
        m.addAction(win.registry["view.fit"])
        m.popup(global_pos)
        return m

    def hole_owner(self, px: tuple[int, int]) -> int | None:
        """An object that may have a hole at pixel ``px`` (None: none).

        It has holes, and ``px`` is inside its box but not one of its pixels. Cheap: the region is already
        derived; the Fill Hole command decides.
        """
        doc, scene = self.win.doc, self.win.scene
        for obj in [scene.primary(), *reversed(doc.plane_objects)]:
            if obj is None or not obj.style.visible or obj.kind == "labels":  # its "region" is its cells
                continue
            entry = scene.entry(obj.id)
            ps = obj.source if obj.kind == "discrete" else entry.peek("discrete")
            region = entry.peek("region")
            b = ps.bbox if ps is not None else None
            if b is None or region is None or region.n_holes == 0 or px in ps:
                continue
            if b[0] < px[0] < b[2] and b[1] < px[1] < b[3]:
                return int(obj.id)
        return None

    def fill_hole(self, px: tuple[int, int]) -> None:
        """What the Fill Hole tool does on a click at ``px`` (the model's ``FillHole``)."""
        self.win.tools.tools["fill_hole"].click(px)

    def delete_component(self, px: tuple[int, int]) -> None:
        """What the Delete Component tool does on a click at ``px`` (the model's ``DeleteComponent``)."""
        self.win.tools.tools["delete_component"].click(px)

    def _push(self, cmd: Any) -> bool:
        try:
            self.win.doc.push(cmd)
        except MRMError as e:
            self.win.show_message(str(e), 5000, error=True)
            return False
        return True

    # ------------------------------------------------------------------ object list
    def open_list_menu(self, pos: QtCore.QPoint) -> QtWidgets.QMenu:
        """The menu of a right click at ``pos`` (viewport coordinates) in the object list."""
        lst = self.win.object_list
        idx = lst.view.indexAt(pos)
        if idx.isValid():
            obj_id = lst.model.ids()[idx.row()]
            if obj_id not in self.win.doc.selection:
                self.win.doc.set_selection([obj_id])
        m = self._menu("listContextMenu")
        self._add_object_items(m)
        m.addSeparator()
        for text, name, slot in (
            ("Raise", "ctx.raise", lst.raise_selected),
            ("Lower", "ctx.lower", lst.lower_selected),
        ):
            self._here(m, text, name, slot, bool(self.win.doc.selection), f"{text} the selected objects")
        sel = [i for i in self.win.doc.selection if i in self.win.doc]
        vis = bool(sel) and all(self.win.doc.get(i).style.visible for i in sel)
        self._here(
            m,
            "Hide" if vis else "Show",
            "ctx.visibility",
            lambda: self.win.set_visible_selection(not vis),
            bool(self.win.doc.selection),
            "Show or hide the selected objects",
        )
        m.popup(lst.view.viewport().mapToGlobal(pos))
        return m
