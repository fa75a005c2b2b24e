"""The error inspector on a chain of discrete smooth scalings built as the operation defines them.

DSS_α(A) = D(Sc_α(R(A))) (DESIGN §8). The chain DSS_5 then DSS_1/5 has the paper's bound √2/5 ≈ 0.28
(Theorem 4); the inspector must show it, the exactly measured Hausdorff distance below it, and the pixels
that differ from the direct result in light and dark grey.
"""

from __future__ import annotations

from fractions import Fraction

import numpy as np
from shapely import affinity

from mrm.commands import AddObject
from mrm.document import Provenance
from mrm.geometry.discretize import discretize
from mrm.geometry.reconstruct import reconstruct
from mrm.reps.pixels import PixelSet
from tests.app.helpers import colour_at, wait_drawn


def dss(ps: PixelSet, alpha: float) -> PixelSet:
    """D(Sc_α(R(A))) about the origin, from the definition."""
    return discretize(affinity.scale(reconstruct(ps, "standard"), alpha, alpha, origin=(0, 0)), "standard")


def _octagon() -> PixelSet:
    yy, xx = np.mgrid[-6:7, -6:7]
    return PixelSet((np.abs(xx) + np.abs(yy) <= 8) & (np.abs(xx) <= 6) & (np.abs(yy) <= 6), (-6, -6))


def test_inspector_shows_chain_bound_measured_and_difference(make_window, qtbot):
    win = make_window()
    doc = win.doc
    a = doc.make_object(_octagon(), name="A")
    doc.push(AddObject(a))
    a1 = dss(a.source, 5)
    o1 = doc.make_object(a1, name="DSS 5", provenance=Provenance("dss", {"alpha": 5.0}, (a.id,)))
    doc.push(AddObject(o1))
    a2 = dss(a1, 0.2)
    o2 = doc.make_object(a2, name="DSS 0.2", provenance=Provenance("dss", {"alpha": 0.2}, (o1.id,)))
    doc.push(AddObject(o2, select=True))
    insp = win.inspector
    qtbot.waitUntil(lambda: insp.measurement is not None, timeout=60_000)
    acc = insp.account
    assert [link.obj.id for link in acc.links] == [o1.id, o2.id] and acc.origin.id == a.id
    # The bound of DSS 5, DSS 1/5 (0.2 is read exactly as the float it is, a hair above 1/5).
    assert acc.bound.coefficient == Fraction(0.2)
    assert abs(acc.bound.bound - 0.2828) < 1e-3
    assert "0.2828" in insp.bound_label.text()
    m = insp.measurement
    assert m.exceeds_bound is False
    assert m.measured <= acc.bound.bound
    assert "within the bound" in insp.measured_label.text()
    # The direct result is D(T(R(A))) with T = Sc_1 here: A itself (D(R(A)) = A).
    assert m.direct == a.source
    assert m.light == a2 - a.source and m.dark == a.source - a2
    # The provenance chain is listed: start, then each operation.
    rows = [insp.chain.topLevelItem(i).text(1) for i in range(insp.chain.topLevelItemCount())]
    assert rows == ["A", "DSS 5", "DSS 0.2"]


def test_difference_pixels_drawn_light_and_dark_grey(make_window, qtbot):
    win = make_window()
    doc = win.doc
    a = doc.make_object(_octagon(), name="A")
    doc.push(AddObject(a))
    # α₁ = 2 then α₂ = 5, back by 1/10: errors appear (the paper's Figure 12, bound ≈ 1.55).
    chain = [(2.0, "DSS 2"), (5.0, "DSS 5"), (0.1, "DSS 0.1")]
    prev, ps = a, a.source
    for alpha, name in chain:
        ps = dss(ps, alpha)
        o = doc.make_object(ps, name=name, provenance=Provenance("dss", {"alpha": alpha}, (prev.id,)))
        doc.push(AddObject(o, select=True))
        prev = o
    insp = win.inspector
    qtbot.waitUntil(lambda: insp.measurement is not None, timeout=60_000)
    m = insp.measurement
    assert m.exceeds_bound is False
    insp.overlay.setChecked(True)
    wait_drawn(qtbot, win)
    if not m.light.is_empty():
        x, y = (int(v) for v in m.light.points()[0])
        c = colour_at(win.views.discrete, x, y)
        assert (c.red(), c.green(), c.blue()) == (200, 200, 200)
    if not m.dark.is_empty():
        x, y = (int(v) for v in m.dark.points()[0])
        c = colour_at(win.views.discrete, x, y)
        assert (c.red(), c.green(), c.blue()) == (95, 95, 95)
    assert not (m.light.is_empty() and m.dark.is_empty()) or m.measured == 0


def test_inspector_without_provenance(make_window):
    win = make_window()
    a = win.doc.make_object(_octagon(), name="drawn")
    win.doc.push(AddObject(a, select=True))
    win.inspector.refresh()
    assert "no provenance" in win.inspector.title.text()
    assert not win.inspector.measure_button.isEnabled()
