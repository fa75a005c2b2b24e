"""The Operations panel: generated from the model's registry, applied as one undo step, read in the inspector.

The issue's scenario: select an object, pick DSS in the panel, type α into its field, click Apply, select the
result and read the paper's bound in the error inspector beside the measured distance (docs/design.md §8: a
chain of DSS steps with ratios s_i is bounded by √2 · Σ_{i=2..k} Π_{j=i..k} s_j; for DSS_5 then DSS_α₂ that is
√2·α₂).
"""

from __future__ import annotations

import math
from fractions import Fraction

import numpy as np
from PySide6 import QtCore

from mrm.core.grids import PixelSet
from mrm.document.commands import AddObject
from mrm.geometry.discretize import discretize
from mrm.geometry.reconstruct import reconstruct
from tests.app.helpers import HANG_MS, task_done, type_into

Qt = QtCore.Qt


def _diamond(r: int = 6) -> PixelSet:
    """A digital octahedron-like diamond, cut to an octagon by a box."""
    yy, xx = np.mgrid[-r : r + 1, -r : r + 1]
    return PixelSet((np.abs(xx) + np.abs(yy) <= r + 2), (-r, -r))


def _dss(ps: PixelSet, alpha: float) -> PixelSet:
    """D(Sc_α(R(A))) about the origin, from the definition (shapely scales the polygon exactly by powers of 2,
    and the exact model reads α as the float it is; used for α = 5 where both agree on this object)."""
    from shapely import affinity

    return discretize(affinity.scale(reconstruct(ps, "standard"), alpha, alpha, origin=(0, 0)), "standard")


def _apply_dss_from_panel(win, qtbot, alpha_text: str) -> int:  # type: ignore[no-untyped-def]
    panel = win.operations
    n = len(win.doc.objects)
    panel.select_operation("dss")
    type_into(qtbot, panel.control("alpha").field, alpha_text)
    assert panel.values()["alpha"] == Fraction(alpha_text)  # the typed decimal, exactly (0.2 is 1/5)
    with task_done(qtbot, win.runner, "operation"):
        qtbot.mouseClick(panel.apply_button, Qt.MouseButton.LeftButton)
    assert len(win.doc.objects) == n + 1
    return int(win.doc.objects[-1].id)


def test_panel_lists_the_registry_with_its_parameter_metadata(make_window):
    win = make_window()
    panel = win.operations
    names = [panel.combo.itemData(i) for i in range(panel.combo.count())]
    for name in ("dss", "discrete_rotation", "simplify", "union", "corefine"):
        assert name in names
    panel.select_operation("dss")
    alpha = panel.control("alpha")
    # α > 0 (exclusive): the range and the unit are shown beside the field, the slider is logarithmic.
    assert alpha.range_label.text() == "× [1e−06, 1e+06]"  # the range the registry declares
    assert alpha.field.suffix().strip() == "×"
    assert alpha.value() == 2.0
    assert panel.control("model").value() == win.doc.model
    panel.select_operation("discrete_rotation")
    assert panel.control("angle").value() == 30.0
    assert panel.control("angle").field.suffix().strip() == "°"
    assert panel.control("center").value() is None  # "no centre": the origin


def test_apply_dss_from_its_panel_and_read_the_bound_in_the_inspector(make_window, qtbot):
    win = make_window()
    doc = win.doc
    a = doc.make_object(_diamond(), name="A")
    doc.push(AddObject(a, select=True))

    first = _apply_dss_from_panel(win, qtbot, "5")
    o1 = doc.get(first)
    assert o1.provenance.operation == "dss" and o1.provenance.inputs == (a.id,)
    assert o1.source == _dss(a.source, 5.0)
    # One undo step removes the result and nothing else.
    doc.undo()
    assert first not in doc and a.id in doc
    doc.redo()
    assert first in doc

    doc.set_selection([first])
    # Live preview (off by default, switched on here): typing α shows the result before Apply, without
    # touching the document.
    panel = win.operations
    assert not panel.live.isChecked()
    qtbot.mouseClick(panel.live, Qt.MouseButton.LeftButton, pos=QtCore.QPoint(8, panel.live.height() // 2))
    assert panel.live.isChecked()
    type_into(qtbot, panel.control("alpha").field, "0.2")
    expected = _dss(o1.source, 0.2)
    qtbot.waitUntil(lambda: [p.source for p in panel.scene.phantoms()] == [expected], timeout=HANG_MS)
    assert len(doc.objects) == 2
    second = _apply_dss_from_panel(win, qtbot, "0.2")
    o2 = doc.get(second)
    assert o2.provenance.inputs == (first,) and o2.provenance.params["alpha"] == 0.2

    doc.set_selection([second])
    insp = win.inspector
    # The inspector refreshes on its own timer: wait for the account of the new object, then its measurement.
    qtbot.waitUntil(
        lambda: (
            insp.account is not None
            and insp.measurement is not None
            and insp.measurement.chain[-1].inputs == (first,)
        ),
        timeout=60_000,
    )
    assert [link.inputs[0] for link in insp.measurement.chain] == [o1.provenance.inputs[0], first]
    # The paper's bound for DSS_5 then DSS_0.2 (Theorem 4): √2 · 0.2, computed here from the formula.
    bound = math.sqrt(2) * 0.2
    assert f"H ≤ {bound:.4g}" in insp.bound_label.text()
    m = insp.measurement
    assert m.measured.value <= bound
    assert m.within_bound is True
    assert "within the bound" in insp.measured_label.text()


def test_cancel_a_long_operation_from_the_panel(make_window, qtbot):
    win = make_window(threaded=True)
    doc = win.doc
    panel = win.operations
    panel.live.setChecked(False)
    big = _diamond(1000)
    a = doc.make_object(big, name="big")
    doc.push(AddObject(a, select=True))
    panel.select_operation("discrete_rotation")
    type_into(qtbot, panel.control("angle").field, "17.3")
    n = len(doc.objects)
    qtbot.mouseClick(panel.apply_button, Qt.MouseButton.LeftButton)
    assert panel.is_running()
    with task_done(qtbot, win.runner, "operation"):
        qtbot.mouseClick(panel.cancel_button, Qt.MouseButton.LeftButton)
    assert not panel.is_running()
    assert "cancelled" in panel.status.text()
    assert len(doc.objects) == n
    assert panel.apply_button.isEnabled()


def test_apply_hands_the_worker_the_r_the_euclidean_view_computed(make_window, qtbot):
    # The Euclidean view shows R(A) of a pixel object; applying DSS to it must not compute R(A) a second
    # time on the worker: the panel hands the worker the R(A) the document holds (plan_operation's held).
    win = make_window()
    doc = win.doc
    a = doc.make_object(_diamond(), name="A")
    doc.push(AddObject(a, select=True))
    qtbot.waitUntil(lambda: doc.derived(a.id).is_ready("euclidean"), timeout=HANG_MS)
    shown = doc.derived(a.id).peek("euclidean")
    runner = win.operations.runner
    calls = []
    real_call = runner.call

    def spy(fn, args, progress):  # type: ignore[no-untyped-def]
        calls.append((fn.__name__, args))
        return real_call(fn, args, progress)

    runner.call = spy
    result = _apply_dss_from_panel(win, qtbot, "5")
    # plan(inputs, operation, params, limit, held, compact_limit): held is R(A) the document holds
    (held,) = [args[4] for name, args in calls if name == "plan"]
    assert [(k, model) for k, model, _g in held] == [(0, doc.model)]
    assert held[0][2].equals_exact(shown, 0.0)
    assert doc.get(result).source == _dss(a.source, 5.0)


def test_dss_and_a_rotation_of_a_voxel_object_from_the_panel_are_the_librarys_and_undo(make_window, qtbot):
    """Issue 30: the panel takes 3D objects for DSS and dR; a centre gets its z, the rotation its axis."""
    import mrm
    from mrm.core.grids import VoxelSet

    win = make_window()
    doc = win.doc
    z, y, x = np.mgrid[-3:4, -3:4, -3:4]
    a = doc.make_object(VoxelSet(np.abs(x) + np.abs(y) + np.abs(z) <= 3, (-3, -3, -3)), name="A")
    doc.push(AddObject(a, select=True))
    panel = win.operations
    panel.select_operation("dss")
    assert panel.inputs[0].currentData() == a.id  # a 3D object is an input of DSS
    centre = panel.control("center")
    assert centre.zs.isVisibleTo(panel) and not centre.pick_button.isVisibleTo(panel)
    first = _apply_dss_from_panel(win, qtbot, "0.8")
    assert doc.get(first).source == mrm.scale(a.source, "0.8")
    assert isinstance(doc.get(first).source, VoxelSet)
    # dR about the tilted axis (1, 1, 1) through (1, 0, 0): typed into the axis and centre fields
    panel.select_operation("discrete_rotation")
    panel.inputs[0].setCurrentIndex(panel.inputs[0].findData(a.id))
    axis = panel.control("axis")
    assert axis.isVisibleTo(panel)
    type_into(qtbot, panel.control("angle").field, "30")
    for spin, value in ((axis.xs, 1), (axis.ys, 1), (axis.zs, 1), (panel.control("center").xs, 1)):
        spin.setFocus()
        qtbot.keyClick(spin, Qt.Key.Key_A, Qt.KeyboardModifier.ControlModifier)
        qtbot.keyClicks(spin, str(value))
        qtbot.keyClick(spin, Qt.Key.Key_Return)
    n = len(doc.objects)
    with task_done(qtbot, win.runner, "operation"):
        qtbot.mouseClick(panel.apply_button, Qt.MouseButton.LeftButton)
    assert len(doc.objects) == n + 1
    turned = doc.objects[-1]
    assert turned.source == mrm.rotate(a.source, 30, (1, 0, 0), axis=(1, 1, 1))
    assert turned.provenance.params["axis"] == [1, 1, 1]
    # one undo step each
    win.doc.history.undo()
    win.doc.history.undo()
    assert [o.id for o in doc.objects] == [a.id]
    # a 2D object hides the axis and the centre's z again
    doc.push(AddObject(doc.make_object(_diamond(), name="B"), select=True))
    panel.inputs[0].setCurrentIndex(panel.inputs[0].findData(doc.objects[-1].id))
    assert not axis.isVisibleTo(panel) and not panel.control("center").zs.isVisibleTo(panel)


def test_an_operation_without_a_3d_form_does_not_offer_voxel_objects(make_window):
    from mrm.core.grids import VoxelSet

    win = make_window()
    doc = win.doc
    doc.push(AddObject(doc.make_object(VoxelSet.box(0, 0, 0, 2, 2, 2), name="cube"), select=True))
    panel = win.operations
    panel.select_operation("discrete_union")  # the set operations do not take 3D objects yet
    assert panel.inputs[0].findData(doc.objects[-1].id) < 0


def test_a_corefinement_of_two_voxel_objects_from_the_panel_adds_three_polyhedra_in_one_undo_step(
    make_window, qtbot
):
    """Issue 30 item 1: EDco on 3D objects from the panel: the library's parts, with provenance."""
    import mrm
    from mrm.core.grids import VoxelSet
    from mrm.ops.account import account_of

    win = make_window()
    doc = win.doc
    a = doc.make_object(VoxelSet.box(0, 0, 0, 3, 3, 3), name="A")
    b = doc.make_object(VoxelSet.box(2, 1, 1, 5, 4, 2), name="B")
    doc.push(AddObject(a))
    doc.push(AddObject(b, select=True))
    panel = win.operations
    panel.select_operation("corefine")
    panel.inputs[0].setCurrentIndex(panel.inputs[0].findData(a.id))  # both 3D objects are offered
    panel.inputs[1].setCurrentIndex(panel.inputs[1].findData(b.id))
    n = len(doc.objects)
    with task_done(qtbot, win.runner, "operation"):
        qtbot.mouseClick(panel.apply_button, Qt.MouseButton.LeftButton)
    made = doc.objects[n:]
    expected = mrm.corefine(a.source, b.source, doc.model)
    assert [o.provenance.params["part"] for o in made] == ["a_minus_b", "a_and_b", "b_minus_a"]
    for obj in made:
        assert (
            isinstance(obj.source, mrm.Polyhedron) and obj.source == expected[obj.provenance.params["part"]]
        )
        assert obj.provenance.operation == "corefine" and list(obj.provenance.inputs) == [a.id, b.id]
    acc = account_of(made[1].provenance)  # the account of A ∩ B: √3, one-sided, a certified interval
    assert acc.error == "" and acc.bound.n == 3 and acc.part == "a_and_b"
    insp = win.inspector  # what the inspector reads is that account
    doc.set_selection([made[1].id])
    insp.refresh()
    qtbot.waitUntil(lambda: insp.measurement is not None, timeout=120_000)
    assert insp.measurement.summary() == acc.summary()
    assert "manifold3d" in insp.measured_label.text()  # the reference of overlapping solids, not GEOS's
    doc.set_selection([made[0].id])  # A ∖ B: a certified interval, shown as one
    insp.refresh()
    qtbot.waitUntil(
        lambda: insp.measurement is not None and insp.measurement.part == "a_minus_b", timeout=HANG_MS
    )
    told = account_of(made[0].provenance).summary()
    assert insp.measurement.summary() == told
    if not told["measured_exact"]:
        lo, hi = told["measured_interval"]
        assert f"∈ [{lo:.6g}, {hi:.6g}] (certified)" in insp.measured_label.text()
    win.doc.history.undo()  # one undo step removes the three parts
    assert [o.id for o in doc.objects] == [a.id, b.id]
