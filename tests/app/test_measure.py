"""The measure tool (two clicked points) and the exact Hausdorff distance between two chosen objects."""

from __future__ import annotations

import math
from fractions import Fraction

from PySide6 import QtCore
from shapely.geometry import Polygon

from mrm.document.commands import AddObject, RenameObject, SetSource
from tests.app.helpers import click, colour_at, press_key, zoom_to

Qt = QtCore.Qt
F = Fraction


# ---------------------------------------------------------------------------------------------- reference
def _seg_d2(p: tuple[F, F], a: tuple[F, F], b: tuple[F, F]) -> F:
    """Squared distance from p to segment ab, in rationals."""
    ex, ey = b[0] - a[0], b[1] - a[1]
    t = ((p[0] - a[0]) * ex + (p[1] - a[1]) * ey) / (ex * ex + ey * ey)
    t = min(F(1), max(F(0), t))
    dx, dy = p[0] - (a[0] + t * ex), p[1] - (a[1] + t * ey)
    return dx * dx + dy * dy


def _inside_convex(p: tuple[F, F], ring: list[tuple[F, F]]) -> bool:
    signs = set()
    for a, b in zip(ring, ring[1:] + ring[:1], strict=True):
        c = (b[0] - a[0]) * (p[1] - a[1]) - (b[1] - a[1]) * (p[0] - a[0])
        if c != 0:
            signs.add(c > 0)
    return len(signs) <= 1


def directed_convex_d2(a: list[tuple[int, int]], b: list[tuple[int, int]]) -> F:
    """h(A, B)² for convex polygons by definition: d(·, B) is convex, so its maximum over A is at a vertex."""
    ra = [(F(x), F(y)) for x, y in a]
    rb = [(F(x), F(y)) for x, y in b]
    best = F(0)
    for p in ra:
        if _inside_convex(p, rb):
            continue
        d2 = min(_seg_d2(p, u, v) for u, v in zip(rb, rb[1:] + rb[:1], strict=True))
        best = max(best, d2)
    return best


def _frac(q: F) -> str:
    return str(q.numerator) if q.denominator == 1 else f"{q.numerator}/{q.denominator}"


# ---------------------------------------------------------------------------------------------- tests
def test_measure_tool_gives_the_distance_between_two_clicked_points(make_window, qtbot):
    win = make_window()
    zoom_to(win, -2, -2, 12, 12)
    view = win.views.discrete
    press_key(qtbot, view, Qt.Key.Key_M)
    assert win.tools.tool.name == "measure"
    assert win.registry["tool.measure"].isChecked()
    shift = Qt.KeyboardModifier.ShiftModifier  # snap to pixel centres: exact points
    click(qtbot, view, 1.2, 0.9, modifiers=shift)
    click(qtbot, view, 3.8, 5.1, modifiers=shift)
    m = win.tools.tool.result
    assert (m.a, m.b) == ((1.0, 1.0), (4.0, 5.0))
    assert m.squared == 25
    assert win.measure.points_label.text().startswith("distance 5 ")
    assert "distance 5 " in win.status.currentMessage()
    # Pixel corners, an irrational length: shown exactly as a square root.
    ctrl = Qt.KeyboardModifier.ControlModifier
    click(qtbot, view, 0.2, 0.2, modifiers=ctrl)
    click(qtbot, view, 1.2, 1.2, modifiers=ctrl)
    assert win.tools.tool.result.squared == 2
    assert win.measure.points_label.text().startswith("distance √2 ≈ 1.41421")


def test_hausdorff_between_two_selected_objects_is_exact(make_window, qtbot):
    a = [(0, 0), (6, 0), (0, 3)]
    b = [(2, 1), (9, 2), (3, 7)]
    win = make_window()
    oa = win.doc.make_object(Polygon(a), name="A")
    ob = win.doc.make_object(Polygon(b), name="B")
    win.doc.push(AddObject(oa))
    win.doc.push(AddObject(ob))
    win.doc.set_selection([oa.id, ob.id])
    win.views.discrete.plane.setFocus()
    qtbot.keyClick(
        win.views.discrete.plane,
        Qt.Key.Key_M,
        Qt.KeyboardModifier.ControlModifier | Qt.KeyboardModifier.ShiftModifier,
    )
    qtbot.waitUntil(lambda: win.measure.result is not None, timeout=30_000)
    hab, hba = directed_convex_d2(a, b), directed_convex_d2(b, a)
    assert hab != hba  # a case where the two directions differ
    full = max(hab, hba)
    text = win.measure.result_label.text()
    assert "H(A, B) = " in text
    assert f"(d² = {_frac(full)})" in text.split("<br>")[0]
    assert "h(A, B) = " in text and f"d² = {_frac(hab)}" in text and f"d² = {_frac(hba)}" in text
    assert win.measure.result.full.squared == full
    value = win.measure.result.full.value
    assert abs(value - math.sqrt(full)) <= math.ulp(value)
    assert repr(value) in text


def test_hausdorff_from_the_panel_with_a_hole(make_window, qtbot):
    """A filled square and the same square with a hole of radius 1: H = 1, reached inside the hole."""
    outer = [(0, 0), (10, 0), (10, 10), (0, 10)]
    hole = [(4, 4), (6, 4), (6, 6), (4, 6)]
    win = make_window()
    full = win.doc.make_object(Polygon(outer), name="full")
    holed = win.doc.make_object(Polygon(outer, [hole]), name="holed")
    win.doc.push(AddObject(full))
    win.doc.push(AddObject(holed))
    win.measure_dock.show()
    win.measure_dock.raise_()
    panel = win.measure
    panel.a_combo.setCurrentIndex(panel.a_combo.findText("full"))
    panel.b_combo.setCurrentIndex(panel.b_combo.findText("holed"))
    qtbot.mouseClick(panel.compute_button, Qt.MouseButton.LeftButton)
    qtbot.waitUntil(lambda: panel.result is not None, timeout=30_000)
    # The farthest point of "full" from "holed" is the hole's centre (5, 5), 1 from its sides.
    assert panel.result.ab.squared == 1 and panel.result.ba.squared == 0
    assert panel.result.ab.witness == (5.0, 5.0)
    assert "H(full, holed) = 1 = 1.0" in panel.result_label.text()
    # Where it is reached is marked in every view.
    assert win.tools.marks == [(5.0, 5.0, "H = 1")]
    zoom_to(win, -1, -1, 11, 11)

    def off_mark() -> int:  # how far the colour drawn at (5, 5) is from the mark's (antialiased lines)
        c = colour_at(win.views.euclidean, 5, 5)
        return abs(c.red() - 0xC2) + abs(c.green() - 0x18) + abs(c.blue() - 0x5B)

    assert off_mark() < 120
    win.doc.push(RenameObject(holed.id, "holed 2"))  # a new name: the distance still holds
    assert win.tools.marks == [(5.0, 5.0, "H = 1")]
    # It no longer holds once a shape changes: the mark goes.
    win.doc.push(SetSource(holed.id, Polygon(outer)))
    assert win.tools.marks == []
    assert off_mark() > 150
