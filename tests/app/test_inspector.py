"""The error inspector: the model's account of a result, pinned to the inputs as they were.

DSS_α(A) = D(Sc_α(R(A))) (docs/design.md §8). The chain DSS_5 then DSS_0.2 (read as 1/5) has the paper's bound
√2/5 ≈ 0.2828 (Theorem 4); the inspector must show it, the exactly measured Hausdorff distance below it, and
the pixels that differ from the direct result in light and dark grey — and keep showing exactly that after the
input is edited, saying that it changed and offering to re-run on the current input.
"""

from __future__ import annotations

import json
from fractions import Fraction

import numpy as np
from PySide6 import QtCore
from shapely import affinity

from mrm.core.grids import PixelSet
from mrm.document.commands import AddObject
from mrm.document.edits import PaintPixels
from mrm.geometry.discretize import discretize
from mrm.geometry.reconstruct import reconstruct
from mrm.ops.account import account_of
from mrm.ops.provenance import Provenance
from tests.app.helpers import colour_at, wait_drawn


def dss(ps: PixelSet, alpha: float) -> PixelSet:
    """D(Sc_α(R(A))) about the origin, from the definition (α a power of two or an integer here)."""
    return discretize(affinity.scale(reconstruct(ps, "standard"), alpha, alpha, origin=(0, 0)), "standard")


def _octagon() -> PixelSet:
    yy, xx = np.mgrid[-6:7, -6:7]
    return PixelSet((np.abs(xx) + np.abs(yy) <= 8) & (np.abs(xx) <= 6) & (np.abs(yy) <= 6), (-6, -6))


def _chain(win, steps):  # type: ignore[no-untyped-def]
    """Apply DSS steps through the operation panel's model call; returns the objects, origin first."""
    from mrm.document.apply import apply_operation
    from mrm.ops.scaling import DSSParams

    doc = win.doc
    a = doc.make_object(_octagon(), name="A")
    doc.push(AddObject(a))
    objs = [a]
    for alpha in steps:
        (new,) = apply_operation(doc, "dss", [objs[-1].id], DSSParams(alpha=alpha))
        objs.append(doc.get(new))
    doc.set_selection([objs[-1].id])
    return objs


def test_inspector_shows_chain_bound_measured_and_difference(make_window, qtbot):
    win = make_window()
    a, o1, o2 = _chain(win, (5.0, 0.2))
    insp = win.inspector
    qtbot.waitUntil(lambda: insp.measurement is not None, timeout=60_000)
    acc = insp.measurement
    assert [link.label for link in acc.chain] == ["DSS 5", "DSS 0.2"]
    # 0.2 is read as 1/5, as the operation computed it: the bound is exactly √2·(1/5).
    assert acc.bound.coefficient == Fraction(1, 5)
    assert "0.2828" in insp.bound_label.text()
    assert acc.within_bound is True and acc.measured.value <= acc.bound.bound
    assert "within the bound" in insp.measured_label.text()
    # The direct result is D(T(R(A))) with T = Sc_1 here: A itself (D(R(A)) = A).
    assert acc.direct == a.source
    assert acc.difference.light == o2.source - a.source and acc.difference.dark == a.source - o2.source
    rows = [insp.chain.topLevelItem(i).text(1) for i in range(insp.chain.topLevelItemCount())]
    assert rows == ["A", o1.name, o2.name]


def test_the_inspector_prints_what_the_cli_and_the_api_print(make_window, qtbot, tmp_path):
    """One account: the inspector's numbers are those of ``mrm account --json`` and of account_of."""
    from mrm.cli import run_cli
    from mrm.io.project import save_project

    win = make_window()
    *_, last = _chain(win, (2.0, 5.0, 0.1))
    insp = win.inspector
    qtbot.waitUntil(lambda: insp.measurement is not None, timeout=60_000)
    gui = insp.measurement.summary()
    path = tmp_path / "chain.mrm"
    save_project(win.doc, path)
    import contextlib
    import io

    out = io.StringIO()
    with contextlib.redirect_stdout(out):
        assert run_cli(["account", str(path), "--object", last.name, "--json"]) == 0
    cli = json.loads(out.getvalue())
    api = account_of(last.provenance).summary()
    assert json.loads(json.dumps(gui)) == json.loads(json.dumps(api))
    assert {k: cli[k] for k in api} == json.loads(json.dumps(api))
    assert f"{gui['measured']:.4g}" in insp.measured_label.text()


def test_editing_the_input_never_changes_the_account(make_window, qtbot):
    """The issue's report: paint on the input of a DSS result, then select the result."""
    win = make_window()
    a, o1 = _chain(win, (0.5,))
    insp = win.inspector
    qtbot.waitUntil(lambda: insp.measurement is not None, timeout=60_000)
    before = insp.measurement.summary()
    bound_text = insp.bound_label.text()
    assert not insp.changes_label.isVisible() and not insp.rerun_button.isVisible()
    # Paint a large block onto A, then select the result again.
    win.doc.push(PaintPixels(a.id, PixelSet.box(-30, -30, 30, 30)))
    win.doc.set_selection([])
    win.doc.set_selection([o1.id])
    insp.refresh()
    qtbot.waitUntil(lambda: insp.measurement is not None, timeout=60_000)
    assert insp.measurement.summary() == before
    assert insp.bound_label.text() == bound_text
    assert "has changed since" in insp.changes_label.text() and insp.changes_label.isVisible()
    rows = [insp.chain.topLevelItem(i).text(1) for i in range(insp.chain.topLevelItemCount())]
    assert rows[0] == "A (changed since)"
    assert insp.chain.topLevelItem(0).text(2) == f"{a.source.count:,}"  # the pixels it was made from
    # Re-run on the current input: a new result, one undo step; the old one keeps its account.
    assert insp.rerun_button.isVisible()
    n = len(win.doc.objects)
    qtbot.mouseClick(insp.rerun_button, QtCore.Qt.MouseButton.LeftButton)
    qtbot.waitUntil(lambda: len(win.doc.objects) == n + 1, timeout=60_000)
    new = win.doc.objects[-1]
    assert new.source == dss(win.doc.get(a.id).source, 0.5)
    assert new.provenance.sources == (win.doc.get(a.id).source,)
    assert account_of(o1.provenance).summary() == before
    win.doc.undo()
    assert len(win.doc.objects) == n


def test_deleting_the_input_keeps_the_account(make_window, qtbot):
    from mrm.document.commands import RemoveObjects

    win = make_window()
    a, o1 = _chain(win, (2.0,))
    insp = win.inspector
    qtbot.waitUntil(lambda: insp.measurement is not None, timeout=60_000)
    before = insp.measurement.summary()
    win.doc.push(RemoveObjects([a.id]))
    win.doc.set_selection([o1.id])
    insp.refresh()
    qtbot.waitUntil(lambda: insp.measurement is not None, timeout=60_000)
    assert insp.measurement.summary() == before
    assert "was deleted" in insp.changes_label.text() and not insp.rerun_button.isVisible()


def test_hostile_provenance_gives_a_message_never_an_exception(make_window, qtbot):
    win = make_window()
    doc = win.doc
    a = doc.make_object(_octagon(), name="A")
    doc.push(AddObject(a))
    cases = [
        ({"alpha": 2.0, "colour": "red"}, "unknown parameter"),
        ({"alpha": 5e-324}, "allowed: 1e-06 ≤ α ≤ 1e+06"),
        ({"alpha": 2.0, "center": [1.0, 2.0, 3.0]}, "must be 2 numbers"),
        ({"alpha": 2.0, "center": "here"}, "must be 2 or 3 numbers"),
    ]
    for params, message in cases:
        prov = Provenance("dss", params, (a.id,), (a.source,), (None,))
        o = doc.make_object(a.source, name="odd", provenance=prov)
        doc.push(AddObject(o, select=True))
        win.inspector.refresh()
        assert message in win.inspector.bound_label.text(), (params, win.inspector.bound_label.text())
        assert not win.inspector.measure_button.isEnabled()
    prov = Provenance("blur", {"radius": 3}, (a.id,), (a.source,), (None,))
    doc.push(AddObject(doc.make_object(a.source, name="blurred", provenance=prov), select=True))
    win.inspector.refresh()
    assert "unknown operation 'blur'" in win.inspector.bound_label.text()


def test_difference_pixels_drawn_light_and_dark_grey(make_window, qtbot):
    win = make_window()
    # α₁ = 2 then α₂ = 5, back by 1/10: errors appear (the paper's Figure 12).
    _chain(win, (2.0, 5.0, 0.1))
    insp = win.inspector
    qtbot.waitUntil(lambda: insp.measurement is not None, timeout=60_000)
    m = insp.measurement
    assert m.within_bound is True
    insp.overlay.setChecked(True)
    wait_drawn(qtbot, win)
    light, dark = m.difference.light, m.difference.dark
    assert not (light.is_empty() and dark.is_empty())
    if not light.is_empty():
        x, y = (int(v) for v in light.points()[0])
        c = colour_at(win.views.discrete, x, y)
        assert (c.red(), c.green(), c.blue()) == (200, 200, 200)
    if not dark.is_empty():
        x, y = (int(v) for v in dark.points()[0])
        c = colour_at(win.views.discrete, x, y)
        assert (c.red(), c.green(), c.blue()) == (95, 95, 95)


def test_inspector_without_provenance(make_window):
    win = make_window()
    a = win.doc.make_object(_octagon(), name="drawn")
    win.doc.push(AddObject(a, select=True))
    win.inspector.refresh()
    assert "no provenance" in win.inspector.title.text()
    assert not win.inspector.measure_button.isEnabled()


def test_a_changed_origin_is_reported_and_the_chain_re_run(make_window, qtbot):
    from mrm.document.apply import apply_operation

    win = make_window()
    a, _o1, o2 = _chain(win, (2.0, 0.5))
    insp = win.inspector
    win.doc.push(PaintPixels(a.id, PixelSet.box(8, 8, 10, 10)))
    win.doc.set_selection([o2.id])
    insp.refresh()
    qtbot.waitUntil(lambda: insp.measurement is not None, timeout=60_000)
    assert "of the step 1 before has changed" in insp.changes_label.text()
    assert insp.rerun_button.isVisible()
    n = len(win.doc.objects)
    qtbot.mouseClick(insp.rerun_button, QtCore.Qt.MouseButton.LeftButton)
    qtbot.waitUntil(lambda: len(win.doc.objects) == n + 1, timeout=60_000)
    new = win.doc.objects[-1]
    (x,) = apply_operation(win.doc, "dss", [a.id], {"alpha": 2.0})
    (y,) = apply_operation(win.doc, "dss", [x], {"alpha": 0.5})
    assert new.source == win.doc.get(y).source and new.source != o2.source
