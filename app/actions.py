"""Every command of the window as a QAction with an id, a default shortcut and a status tip.

The registry is the single place that knows shortcuts: menus, toolbars and the preferences dialog all take
actions from it, and a user's overrides (stored in the preferences) replace the defaults by action id.
"""

from __future__ import annotations

from collections.abc import Callable, Iterable
from dataclasses import dataclass

from PySide6 import QtGui, QtWidgets

Std = QtGui.QKeySequence.StandardKey


@dataclass(frozen=True)
class ActionSpec:
    """How to build one action."""

    id: str
    text: str
    shortcut: str | Std | None = None
    tip: str = ""
    checkable: bool = False
    group: str | None = None  # exclusive group (tools)
    icon: str | None = None  # freedesktop theme icon name


#: The window's commands, in menu order. Ids are stable: they key the shortcut overrides.
SPECS: tuple[ActionSpec, ...] = (
    # File
    ActionSpec("file.new", "&New", Std.New, "Start a new, empty project", icon="document-new"),
    ActionSpec("file.open", "&Open…", Std.Open, "Open a project (.mrm)", icon="document-open"),
    ActionSpec("file.save", "&Save", Std.Save, "Save the project", icon="document-save"),
    ActionSpec(
        "file.save_as", "Save &As…", Std.SaveAs, "Save the project under a new name", icon="document-save-as"
    ),
    ActionSpec(
        "file.import",
        "&Import…",
        "Ctrl+I",
        "Import an image, GeoJSON, WKT, voxel or mesh file as new objects",
    ),
    ActionSpec(
        "file.export",
        "&Export Selection…",
        "Ctrl+E",
        "Export the selected object (PNG, SVG, GeoJSON, WKT; a 3D one as OBJ, PLY, OFF, STL or voxels)",
    ),
    ActionSpec("file.screenshot", "Save Window &Picture…", "Ctrl+Shift+P", "Save a picture of the window"),
    ActionSpec("file.preferences", "Pre&ferences…", Std.Preferences, "Models, colours, brush, shortcuts"),
    ActionSpec("file.quit", "&Quit", Std.Quit, "Quit MR Modeler", icon="application-exit"),
    # Edit
    ActionSpec("edit.undo", "&Undo", Std.Undo, "Undo the last edit", icon="edit-undo"),
    ActionSpec("edit.redo", "&Redo", Std.Redo, "Redo the last undone edit", icon="edit-redo"),
    ActionSpec(
        "edit.cut",
        "Cu&t",
        Std.Cut,
        "Copy the selected objects to the clipboard and delete them (one undo step)",
        icon="edit-cut",
    ),
    ActionSpec(
        "edit.copy", "&Copy", Std.Copy, "Copy the selected objects to the clipboard", icon="edit-copy"
    ),
    ActionSpec(
        "edit.paste",
        "&Paste",
        Std.Paste,
        "Paste objects from the clipboard (MR Modeler objects, GeoJSON or WKT text) in place",
        icon="edit-paste",
    ),
    ActionSpec(
        "edit.select_all", "Select &All", Std.SelectAll, "Select every object", icon="edit-select-all"
    ),
    ActionSpec("edit.delete", "&Delete Object", "Del", "Delete the selected object", icon="edit-delete"),
    ActionSpec("edit.duplicate", "D&uplicate Object", "Ctrl+D", "Copy the selected object"),
    ActionSpec(
        "edit.split_labels",
        "Split into O&bjects",
        "",
        "Replace the selected label map by one pixel object per label",
    ),
    ActionSpec("edit.rename", "Re&name Object…", "F2", "Rename the selected object"),
    ActionSpec(
        "edit.transform_3d",
        "&Transform 3D Object…",
        "Ctrl+T",
        "Move, scale and rotate the selected polyhedron by numbers",
    ),
    ActionSpec(
        "edit.compact_limit",
        "Compact R &Limit…",
        "Ctrl+Alt+L",
        "The most triangles of a voxel object's safety net that its R simplifies into a compact polyhedron",
    ),
    ActionSpec("edit.colour", "Object Co&lour…", "Ctrl+Shift+L", "Choose the colour of the selected object"),
    ActionSpec(
        "edit.properties",
        "Object P&roperties",
        "Ctrl+Shift+O",
        "Name, colour, opacity and vertex coordinates of the selected object",
    ),
    ActionSpec("edit.select_next", "Select &Next Object", "Ctrl+]", "Select the next object in the list"),
    ActionSpec(
        "edit.select_previous", "Select &Previous Object", "Ctrl+[", "Select the previous object in the list"
    ),
    # Tools (exclusive)
    ActionSpec("tool.select", "&Select", "S", "Click an object to select it; drag to pan", True, "tools"),
    ActionSpec(
        "tool.polygon",
        "Draw &Polygon",
        "P",
        "Click vertices; click the first one or press Enter to close. Alt: draw a hole. "
        "Shift: snap to pixel centres, Ctrl: to pixel corners",
        True,
        "tools",
    ),
    ActionSpec(
        "tool.vertex",
        "Edit &Vertices",
        "V",
        "Drag a vertex; click an edge to insert one; right-click or Delete removes one. "
        "Shift: snap to centres, Ctrl: to corners",
        True,
        "tools",
    ),
    ActionSpec(
        "tool.paint",
        "P&aint Pixels",
        "B",
        "Paint pixels with the brush ([ and ] change its size)",
        True,
        "tools",
    ),
    ActionSpec(
        "tool.erase",
        "&Erase Pixels",
        "E",
        "Erase pixels with the brush ([ and ] change its size)",
        True,
        "tools",
    ),
    ActionSpec("tool.fill_hole", "&Fill Hole", "F", "Click inside a hole to fill it", True, "tools"),
    ActionSpec(
        "tool.delete_component", "Delete &Component", "X", "Click a component to delete it", True, "tools"
    ),
    ActionSpec(
        "tool.measure",
        "&Measure",
        "M",
        "Click two points to measure their distance (Shift: snap to pixel centres, Ctrl: to corners)",
        True,
        "tools",
    ),
    ActionSpec("tool.brush_larger", "Larger Brush", "]", "Increase the brush size"),
    ActionSpec("tool.brush_smaller", "Smaller Brush", "[", "Decrease the brush size"),
    # View
    ActionSpec("view.fit", "&Fit All", "Home", "Zoom to show every visible object", icon="zoom-fit-best"),
    ActionSpec("view.fit_selection", "Zoom to &Selection", "Shift+Home", "Zoom to the selected objects"),
    ActionSpec(
        "view.fit_differences",
        "Zoom to &Differences",
        "Ctrl+Shift+D",
        "Zoom to the pixels where the selected result differs from its direct computation",
    ),
    ActionSpec("view.zoom_in", "Zoom &In", Std.ZoomIn, "Zoom in", icon="zoom-in"),
    ActionSpec("view.zoom_out", "Zoom &Out", Std.ZoomOut, "Zoom out", icon="zoom-out"),
    ActionSpec("view.actual", "&One Pixel per Pixel", "Ctrl+0", "One plane unit per screen pixel"),
    ActionSpec(
        "view.grid_layout", "&Grid (2×2)", "Ctrl+Shift+G", "Show the four views side by side", True, "layout"
    ),
    ActionSpec("view.tabs_layout", "&Tabs", "Ctrl+Shift+T", "Show the views as tabs", True, "layout"),
    ActionSpec("view.discrete", "&Discrete View", "Ctrl+1", "Show or focus the discrete (pixel) view"),
    ActionSpec("view.region", "&Region View", "Ctrl+2", "Show or focus the region view"),
    ActionSpec("view.analytical", "&Analytical View", "Ctrl+3", "Show or focus the analytical view"),
    ActionSpec("view.euclidean", "&Euclidean View", "Ctrl+4", "Show or focus the Euclidean view"),
    ActionSpec(
        "view.three_d", "&3D Views", "F3", "Show the four views of the 3D objects (voxels, polyhedra)", True
    ),
    ActionSpec("view.pixel_grid", "Pixel &Grid", "G", "Draw the pixel grid when zoomed in", True),
    ActionSpec(
        "view.snap",
        "S&nap to Objects",
        "Shift+S",
        "Drawn and dragged points snap to the vertices and edges of objects (hold Alt to place one freely)",
        True,
    ),
    # Operations / inspector
    ActionSpec("ops.panel", "&Operations", "Ctrl+R", "Show the operations panel"),
    ActionSpec("ops.apply", "&Apply Operation", "Ctrl+Return", "Apply the operation of the panel"),
    ActionSpec("ops.cancel", "&Cancel Running Task", "Esc", "Cancel the operation that is running"),
    ActionSpec(
        "ops.pick_centre",
        "Pick &Centre in View",
        "Ctrl+Shift+C",
        "Click in a view to set the operation's rotation or scaling centre",
    ),
    ActionSpec(
        "measure.hausdorff",
        "&Hausdorff Distance",
        "Ctrl+Shift+M",
        "Exact Hausdorff distance between two objects (the two selected, or those of the Measure panel)",
    ),
    ActionSpec("inspect.errors", "&Error Inspector", "Ctrl+Shift+I", "Provenance, bound and measured error"),
    # Help
    ActionSpec("help.guide", "&User Guide", Std.HelpContents, "Open the user guide"),
    ActionSpec("help.about", "&About MR Modeler", None, "Version and credits"),
)


#: Keys for standard actions the platform leaves without a binding (Linux has none for Preferences).
_FALLBACK = {
    Std.Preferences: "Ctrl+,",
    Std.Quit: "Ctrl+Q",
    Std.HelpContents: "F1",
    Std.SaveAs: "Ctrl+Shift+S",
    Std.Redo: "Ctrl+Shift+Z",
}


#: Keys a standard action always has, whatever the platform binds (the user guide promises them): redo is
#: both Ctrl+Y and Ctrl+Shift+Z, help is F1 even where the desktop has no help key binding.
_ALWAYS = {
    Std.Redo: ("Ctrl+Y", "Ctrl+Shift+Z"),
    Std.HelpContents: ("F1",),
}


def _key_sequence(spec: ActionSpec, overrides: dict[str, str]) -> list[QtGui.QKeySequence]:
    if spec.id in overrides:
        text = overrides[spec.id]
        return [QtGui.QKeySequence(text)] if text else []
    if spec.shortcut is None:
        return []
    if isinstance(spec.shortcut, str):
        return [QtGui.QKeySequence(spec.shortcut)]
    seqs = list(QtGui.QKeySequence.keyBindings(spec.shortcut))
    if not seqs and spec.shortcut in _FALLBACK:
        seqs = [QtGui.QKeySequence(_FALLBACK[spec.shortcut])]
    for text in _ALWAYS.get(spec.shortcut, ()):
        k = QtGui.QKeySequence(text)
        if k not in seqs:
            seqs.append(k)
    return seqs


class ActionRegistry:
    """Owns the window's QActions, keyed by :class:`ActionSpec` id."""

    def __init__(self, parent: QtWidgets.QWidget, overrides: dict[str, str] | None = None) -> None:
        self._parent = parent
        self._actions: dict[str, QtGui.QAction] = {}
        self._specs: dict[str, ActionSpec] = {}
        self._groups: dict[str, QtGui.QActionGroup] = {}
        for spec in SPECS:
            self._add(spec)
        self.apply_shortcuts(overrides or {})

    def _add(self, spec: ActionSpec) -> QtGui.QAction:
        a = QtGui.QAction(spec.text, self._parent)
        a.setObjectName(spec.id)
        # Toolbar buttons show the icon text: short and fixed, so that "Undo Discrete-based simplification
        # Sp_α" never widens the toolbar (the full text is in the menu and the tooltip).
        a.setIconText(spec.text.replace("&", "").replace("…", ""))
        if spec.tip:
            a.setStatusTip(spec.tip)
            a.setToolTip(spec.tip)
        if spec.icon and QtGui.QIcon.hasThemeIcon(spec.icon):
            a.setIcon(QtGui.QIcon.fromTheme(spec.icon))
        a.setCheckable(spec.checkable)
        if spec.group:
            g = self._groups.get(spec.group)
            if g is None:
                g = self._groups[spec.group] = QtGui.QActionGroup(self._parent)
                g.setExclusive(True)
            g.addAction(a)
        # Window-wide shortcuts: they work whichever view or dock has the focus.
        a.setShortcutContext(QtGui.Qt.ShortcutContext.WindowShortcut)
        self._parent.addAction(a)
        self._actions[spec.id] = a
        self._specs[spec.id] = spec
        return a

    def __getitem__(self, action_id: str) -> QtGui.QAction:
        return self._actions[action_id]

    def __contains__(self, action_id: str) -> bool:
        return action_id in self._actions

    def ids(self) -> list[str]:
        return list(self._actions)

    def spec(self, action_id: str) -> ActionSpec:
        return self._specs[action_id]

    def default_shortcut(self, action_id: str) -> str:
        """The default shortcut of an action as portable text ('' for none)."""
        seqs = _key_sequence(self._specs[action_id], {})
        return seqs[0].toString(QtGui.QKeySequence.SequenceFormat.PortableText) if seqs else ""

    def group(self, name: str) -> QtGui.QActionGroup:
        return self._groups[name]

    def connect(self, action_id: str, slot: Callable[..., object]) -> None:
        """Run ``slot`` when the action is triggered (checked state passed for checkable actions)."""
        a = self._actions[action_id]
        if a.isCheckable():
            a.toggled.connect(slot)
        else:
            a.triggered.connect(lambda _checked=False: slot())

    def apply_shortcuts(self, overrides: dict[str, str]) -> None:
        """Install default shortcuts replaced by ``overrides`` (id → portable key text, '' = none)."""
        for aid, a in self._actions.items():
            seqs = _key_sequence(self._specs[aid], overrides)
            a.setShortcuts(seqs)
            tip = self._specs[aid].tip or a.text().replace("&", "")
            if seqs:
                tip = f"{tip} ({seqs[0].toString(QtGui.QKeySequence.SequenceFormat.NativeText)})"
            a.setToolTip(tip)

    def conflicts(self) -> list[tuple[str, str, str]]:
        """Pairs of actions that share a key: (key, id1, id2)."""
        seen: dict[str, str] = {}
        out = []
        for aid, a in self._actions.items():
            for s in a.shortcuts():
                k = s.toString()
                if k in seen:
                    out.append((k, seen[k], aid))
                else:
                    seen[k] = aid
        return out

    def menu(self, menu: QtWidgets.QMenu, ids: Iterable[str | None]) -> None:
        """Fill ``menu`` with the actions (None = separator)."""
        for aid in ids:
            if aid is None:
                menu.addSeparator()
            else:
                menu.addAction(self._actions[aid])
