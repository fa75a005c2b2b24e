"""The Segments dock: the (a, b, μ, ω) of the selected object's digital straight segments, and a preimage.

The preimage of the chosen segment is drawn in its line-parameter space (u, w), the chosen (median) line
marked. A 3D object's digital plane segments are listed instead, (a, b, c, μ, ω) and their surfels, without a
preimage plot.

Rows follow the analytical representation: per component its outer chain, then its holes; within a chain
the segments in order. Selecting a row selects the segment in the analytical view, and the reverse.
"""

from __future__ import annotations

import bisect
from typing import Any

import numpy as np
import pyqtgraph as pg
from PySide6 import QtCore, QtGui, QtWidgets

from mrm.document import Changes
from mrm.views.items import PathItem, rings_path
from mrm.views.scene import Scene

_ROOT = QtCore.QModelIndex()  # the invalid index: the model's root
COLUMNS = ("chain", "#", "first", "last", "a", "b", "μ", "ω", "points")


_ROLES = frozenset(
    (
        QtCore.Qt.ItemDataRole.DisplayRole,
        QtCore.Qt.ItemDataRole.TextAlignmentRole,
        QtCore.Qt.ItemDataRole.ToolTipRole,
    )
)


class _Columns(QtCore.QAbstractTableModel):
    """A table model whose columns are the names in :attr:`columns`."""

    columns: tuple[str, ...] = ()

    def columnCount(self, parent: QtCore.QModelIndex | QtCore.QPersistentModelIndex = _ROOT) -> int:
        return 0 if parent.isValid() else len(self.columns)

    def headerData(self, section: int, orientation: QtCore.Qt.Orientation, role: int = 0) -> object:
        if role == QtCore.Qt.ItemDataRole.DisplayRole and orientation == QtCore.Qt.Orientation.Horizontal:
            return self.columns[section]
        return None


class SegmentModel(_Columns):
    """Lazy rows over an analytical representation (thousands of segments stay cheap)."""

    columns = COLUMNS

    def __init__(self, parent: QtCore.QObject | None = None) -> None:
        super().__init__(parent)
        self.ana: Any = None
        self._offsets = np.zeros(1, dtype=np.int64)
        self._starts: list[int] = [0]

    def set_analytical(self, ana: Any) -> None:
        if ana is self.ana:
            return
        self.beginResetModel()
        self.ana = ana
        lengths = [len(c) for c in ana.chains] if ana is not None else []
        self._offsets = np.concatenate([[0], np.cumsum(lengths)]).astype(np.int64)
        self._starts = self._offsets.tolist()  # bisect on a list: a row is found in a microsecond
        self.endResetModel()

    def locate(self, row: int) -> tuple[int, int]:
        ci = bisect.bisect_right(self._starts, row) - 1
        return ci, row - self._starts[ci]

    def row_of(self, ci: int, k: int) -> int:
        return int(self._offsets[ci]) + k

    def rowCount(self, parent: QtCore.QModelIndex | QtCore.QPersistentModelIndex = _ROOT) -> int:
        return 0 if parent.isValid() else int(self._offsets[-1])

    def data(self, index: QtCore.QModelIndex | QtCore.QPersistentModelIndex, role: int = 0) -> object:
        # The view asks about ten roles per cell at every paint: the ones never answered cost nothing.
        if role not in _ROLES or not index.isValid() or self.ana is None:
            return None
        ci, k = self.locate(index.row())
        chain = self.ana.chains[ci]
        row = chain.table[k]
        c = index.column()
        if role == QtCore.Qt.ItemDataRole.DisplayRole:
            if c == 0:
                return f"{'hole' if chain.hole else 'outer'} {chain.component}"
            if c == 1:
                return k
            if c == 8:
                return int(row[1] - row[0] + 1)
            return int(row[c - 2])
        if role == QtCore.Qt.ItemDataRole.TextAlignmentRole and c > 0:
            return int(QtCore.Qt.AlignmentFlag.AlignRight | QtCore.Qt.AlignmentFlag.AlignVCenter)
        if role == QtCore.Qt.ItemDataRole.ToolTipRole:
            a, b, mu, om = (int(v) for v in row[2:6])
            return f"{_n(mu)} ≤ {linear(a, -b)} < {_n(mu + om)}  (pointels (i, j); direction ({b}, {a}))"
        return None


#: The columns of a 3D object's plane segments.
PLANE_COLUMNS = ("surface", "#", "a", "b", "c", "μ", "ω", "surfels")


class PlaneSegmentModel(_Columns):
    """Lazy rows over a 3D analytical representation: a segment's plane is chosen when its row is drawn."""

    columns = PLANE_COLUMNS

    def __init__(self, parent: QtCore.QObject | None = None) -> None:
        super().__init__(parent)
        self.ana: Any = None

    def set_analytical(self, ana: Any) -> None:
        if ana is self.ana:
            return
        self.beginResetModel()
        self.ana = ana
        self.endResetModel()

    def rowCount(self, parent: QtCore.QModelIndex | QtCore.QPersistentModelIndex = _ROOT) -> int:
        return 0 if parent.isValid() or self.ana is None else len(self.ana)

    def data(self, index: QtCore.QModelIndex | QtCore.QPersistentModelIndex, role: int = 0) -> object:
        if role not in _ROLES or not index.isValid() or self.ana is None:
            return None
        k, c = index.row(), index.column()
        if role == QtCore.Qt.ItemDataRole.TextAlignmentRole:
            return int(QtCore.Qt.AlignmentFlag.AlignRight | QtCore.Qt.AlignmentFlag.AlignVCenter)
        seg = self.ana.segmentation
        if c == 0:
            return int(self.ana.surface_of[k]) if role == QtCore.Qt.ItemDataRole.DisplayRole else None
        if c == 1:
            return k if role == QtCore.Qt.ItemDataRole.DisplayRole else None
        if c == 7:
            n = int(seg.member_ptr[k + 1] - seg.member_ptr[k])
            return n if role == QtCore.Qt.ItemDataRole.DisplayRole else None
        plane = seg.segment(k).plane  # recognized once, then kept by the segmentation
        if role == QtCore.Qt.ItemDataRole.ToolTipRole:
            a, b, cc, mu = plane.a, plane.b, plane.c, plane.mu
            return (
                f"{_n(mu)} ≤ {_n(a)}·x + {_n(b)}·y + {_n(cc)}·z < {_n(mu + plane.omega)} over the segment's "
                "voxels; the voxels outside are beyond it"
            )
        return (plane.a, plane.b, plane.c, plane.mu, plane.omega)[c - 2]


def _n(v: object) -> str:
    return str(v).replace("-", "−")


def linear(a: object, b: object, x: str = "i", y: str = "j") -> str:
    """``a·x + b·y`` written as a person would: ``4·i − 3·j``, never ``4·i − -3·j``; zero terms dropped."""
    from fractions import Fraction

    terms = []
    for coef, var in ((Fraction(str(a)), x), (Fraction(str(b)), y)):
        if coef == 0:
            continue
        mag = abs(coef)
        body = var if mag == 1 else f"{_n(mag)}·{var}"
        if not terms:
            terms.append(("−" if coef < 0 else "") + body)
        else:
            terms.append(("− " if coef < 0 else "+ ") + body)
    return " ".join(terms) or "0"


def to_local(frame: tuple[int, int], u: Any, w: Any, i0: int, j0: int) -> tuple[Any, Any]:
    """(u, w) of a line in coordinates relative to the pointel (i0, j0), exactly.

    u·x′ − (1 − u)·y′ = w with x′ = σx·x, y′ = σy·y keeps u and gets w − u·σx·i0 + (1 − u)·σy·j0.
    """
    sx, sy = frame
    return u, w - u * sx * i0 + (1 - u) * sy * j0


class SegmentTable(QtWidgets.QWidget):
    """Table of the selected object's segments + the chosen segment's preimage."""

    def __init__(self, scene: Scene, parent: QtWidgets.QWidget | None = None) -> None:
        super().__init__(parent)
        self.setObjectName("segmentTable")
        self.scene = scene
        self.obj_id = -1
        self.caption = QtWidgets.QLabel("", self)
        self.caption.setWordWrap(True)
        self.model = SegmentModel(self)
        self.table = QtWidgets.QTableView(self)
        self.table.setObjectName("segmentView")
        self.table.setModel(self.model)
        self.table.setSelectionBehavior(QtWidgets.QAbstractItemView.SelectionBehavior.SelectRows)
        self.table.setSelectionMode(QtWidgets.QAbstractItemView.SelectionMode.SingleSelection)
        self.table.verticalHeader().hide()
        self.table.verticalHeader().setDefaultSectionSize(self.fontMetrics().height() + 4)
        # Fixed column widths: resizing to contents would read every row (tens of thousands on big objects).
        hdr = self.table.horizontalHeader()
        hdr.setSectionResizeMode(QtWidgets.QHeaderView.ResizeMode.Interactive)
        fm = self.fontMetrics()
        widths = ("outer 00", "000", "0000", "0000", "−00", "−00", "−0000", "000", "000")
        for c, sample in enumerate(widths):
            hdr.resizeSection(c, fm.horizontalAdvance(sample) + 10)
        self.table.setAlternatingRowColors(True)
        self.table.selectionModel().currentRowChanged.connect(self._row_changed)
        # A 3D object's plane segments: a table of their own (no preimage plot, no row ↔ view selection yet).
        self.planes = PlaneSegmentModel(self)
        self.plane_table = QtWidgets.QTableView(self)
        self.plane_table.setObjectName("planeSegmentView")
        self.plane_table.setModel(self.planes)
        self.plane_table.setSelectionBehavior(QtWidgets.QAbstractItemView.SelectionBehavior.SelectRows)
        self.plane_table.verticalHeader().hide()
        self.plane_table.verticalHeader().setDefaultSectionSize(self.fontMetrics().height() + 4)
        self.plane_table.setAlternatingRowColors(True)
        phdr = self.plane_table.horizontalHeader()
        phdr.setSectionResizeMode(QtWidgets.QHeaderView.ResizeMode.Interactive)
        for c, sample in enumerate(("0000", "00000", "−000", "−000", "−000", "−000000", "0000", "000000")):
            wide = max(fm.horizontalAdvance(sample), fm.horizontalAdvance(PLANE_COLUMNS[c]))
            phdr.resizeSection(c, wide + 14)
        self.plane_table.setVisible(False)
        self.plane_table.selectionModel().currentRowChanged.connect(self._plane_row_changed)
        self.solid_id = -1  # the 3D object whose plane segments are listed
        self.plot = pg.PlotWidget(self)
        self.plot.setObjectName("preimagePlot")
        self.plot.setMenuEnabled(False)
        self.plot.hideButtons()
        self.plot.setMinimumHeight(140)
        for side in ("left", "bottom"):
            self.plot.getAxis(side).enableAutoSIPrefix(False)
        self._style_plot()
        self.plot.setLabel("bottom", "u (0 horizontal … 1 vertical)")
        self.plot.setLabel("left", "w (offset from the first pointel)")
        self.preimage_item = PathItem()
        self.median_item = pg.ScatterPlotItem(size=9, symbol="o")
        self.plot.addItem(self.preimage_item)
        self.plot.addItem(self.median_item)
        self.plot_caption = QtWidgets.QLabel("", self)
        self.plot_caption.setObjectName("preimageCaption")
        self.plot_caption.setWordWrap(True)
        lay = QtWidgets.QVBoxLayout(self)
        lay.setContentsMargins(4, 4, 4, 4)
        lay.addWidget(self.caption)
        lay.addWidget(self.table, 3)
        lay.addWidget(self.plane_table, 3)
        lay.addWidget(self.plot_caption)
        lay.addWidget(self.plot, 2)
        self._syncing = False
        self._timer = QtCore.QTimer(self)
        self._timer.setSingleShot(True)
        self._timer.setInterval(0)
        self._timer.timeout.connect(self.refresh)
        scene.documentChanged.connect(self._on_changes)
        scene.derivedReady.connect(lambda _i: self._timer.start())
        scene.previewChanged.connect(lambda _i: self._timer.start())
        scene.segmentSelected.connect(self._segment_selected)
        self.refresh()

    def _style_plot(self) -> None:
        pal = self.palette()
        self.plot.setBackground(pal.color(QtGui.QPalette.ColorRole.Base))
        text = pal.color(QtGui.QPalette.ColorRole.Text)
        for side in ("left", "bottom"):
            ax = self.plot.getAxis(side)
            ax.setPen(pg.mkPen(text))
            ax.setTextPen(pg.mkPen(text))

    def changeEvent(self, ev: QtCore.QEvent) -> None:
        if ev.type() in (QtCore.QEvent.Type.PaletteChange, QtCore.QEvent.Type.ApplicationPaletteChange):
            self._style_plot()
        super().changeEvent(ev)

    def _on_changes(self, _ch: Changes) -> None:
        self._timer.start()

    def refresh(self) -> None:
        obj = self.scene.primary()
        solid = self.scene.selected()
        three_d = obj is None and solid is not None
        for w in (self.table, self.plot, self.plot_caption):
            w.setVisible(not three_d)
        self.plane_table.setVisible(three_d)
        if not three_d:
            self.solid_id = -1
        if three_d:
            assert solid is not None
            self._show_planes(solid)
            return
        self.planes.set_analytical(None)
        if obj is None:
            self.obj_id = -1
            self.model.set_analytical(None)
            self.caption.setText("Select an object to list the digital straight segments of its boundaries.")
            self._show_preimage(None, -1)
            return
        self.obj_id = obj.id
        if obj.kind == "labels":  # no segments of its own (ADR 0033): not even asked for
            from mrm.views.label_maps import NO_SEGMENTS_NOTE

            self.model.set_analytical(None)
            self.caption.setText(f"<b>{obj.name}</b>: {NO_SEGMENTS_NOTE}")
            self._show_preimage(None, -1)
            return
        ana = self.scene.get(obj.id, "analytical")
        if ana is None:
            err = self.scene.error(obj.id, "analytical")
            self.caption.setText(f"{obj.name}: {err}" if err else f"{obj.name}: computing…")
            self.model.set_analytical(None)
            return
        self.model.set_analytical(ana)
        holes = sum(1 for c in ana.chains if c.hole)
        self.caption.setText(
            f"<b>{obj.name}</b>: {ana.n_segments} segments on {len(ana.chains)} boundary chains "
            f"({holes} hole{'s' if holes != 1 else ''}), {ana.mode} segmentation. "
            "μ ≤ a·i − b·j &lt; μ + ω over the pointels (i, j)."
        )
        self._segment_selected(*self.scene.segment)

    def _plane_row_changed(self, cur: QtCore.QModelIndex, _prev: QtCore.QModelIndex) -> None:
        # A row chosen: the analytical 3D view shows that segment's surfels.
        if cur.isValid() and self.solid_id >= 0:
            self.scene.select_plane_segment(self.solid_id, cur.row())

    def _show_planes(self, obj: Any) -> None:
        """List a 3D object's digital plane segments (computed on a worker; listed when ready)."""
        self.solid_id = obj.id
        self.obj_id = -1
        self.model.set_analytical(None)
        self._show_preimage(None, -1)
        ana = self.scene.get(obj.id, "analytical")
        self.planes.set_analytical(ana)
        if ana is None:
            err = self.scene.error(obj.id, "analytical")
            self.caption.setText(f"<b>{obj.name}</b>: {err}" if err else f"<b>{obj.name}</b>: computing…")
            return
        surfaces = int(np.unique(ana.surface_of).size)
        self.caption.setText(
            f"<b>{obj.name}</b>: {len(ana):,} digital plane segments on {surfaces:,} "
            f"surface{'s' if surfaces != 1 else ''}, μ ≤ a·x + b·y + c·z &lt; μ + ω over each segment's "
            "voxels; drawn in the analytical 3D view (F3)."
        )

    def _row_changed(self, cur: QtCore.QModelIndex, _prev: QtCore.QModelIndex) -> None:
        if self._syncing or not cur.isValid() or self.obj_id < 0:
            return
        ci, k = self.model.locate(cur.row())
        self.scene.select_segment(self.obj_id, ci, k)

    def _segment_selected(self, obj_id: int, ci: int, k: int) -> None:
        if obj_id != self.obj_id or self.model.ana is None or ci < 0:
            self._show_preimage(None, -1)
            return
        self._syncing = True
        try:
            row = self.model.row_of(ci, k)
            idx = self.model.index(row, 0)
            self.table.selectionModel().setCurrentIndex(
                idx,
                QtCore.QItemSelectionModel.SelectionFlag.ClearAndSelect
                | QtCore.QItemSelectionModel.SelectionFlag.Rows,
            )
            self.table.scrollTo(idx)
        finally:
            self._syncing = False
        self._show_preimage(self.model.ana.chains[ci], k)

    def _show_preimage(self, chain: Any, k: int) -> None:
        self.plot.setVisible(chain is not None)
        if chain is None:
            self.preimage_item.setPath(QtGui.QPainterPath())
            self.median_item.setData([], [])
            self.plot_caption.setText("Preimage of the selected segment (pick a row).")
            return
        seg = chain.segments[k]
        pre = chain.preimage(k)
        # Drawn in the segment's local frame (origin at its first pointel): far from the origin the global
        # offsets w are huge and the polygon would be a sliver.
        pts = chain.points()
        i0, j0 = (int(v) for v in pts[seg.first % len(pts)])
        local = [to_local(pre.frame, u, w, i0, j0) for u, w in pre.vertices]
        vs = np.array([(float(u), float(w)) for u, w in local]).reshape(-1, 2)
        fill = QtGui.QColor("#9467bd")
        fill.setAlpha(90)
        self.preimage_item.setPath(rings_path([vs]) if len(vs) else QtGui.QPainterPath())
        self.preimage_item.set_style(fill, QtGui.QColor("#9467bd"), 2.0)
        text = (
            f"Segment {k}: (a, b, μ, ω) = ({seg.a}, {seg.b}, {seg.mu}, {seg.omega}), "
            f"pointels {seg.first}–{seg.last}. Preimage in the segment's frame {pre.frame}, origin at its "
            f"first pointel ({_n(i0)}, {_n(j0)}): {len(pre.vertices)} vertices."
        )
        if seg.a or seg.b:
            from mrm.geometry.dss.preimage import median_parameters

            u, w = to_local(pre.frame, *median_parameters(seg), i0, j0)
            self.median_item.setData(
                [float(u)], [float(w)], brush=pg.mkBrush("#000000"), pen=pg.mkPen("#ffffff")
            )
            a, b, c = chain.line(k)
            text += f" Chosen line: {linear(a, -b)} = {_n(c)} (the median line, inside the open preimage)."
        else:
            self.median_item.setData([], [])
        self.plot_caption.setText(text)
        if len(vs):
            lo, hi = vs.min(axis=0), vs.max(axis=0)
            span = np.maximum(hi - lo, 1e-3)
            self.plot.setRange(
                xRange=(lo[0] - 0.15 * span[0], hi[0] + 0.15 * span[0]),
                yRange=(lo[1] - 0.15 * span[1], hi[1] + 0.15 * span[1]),
                padding=0,
            )
