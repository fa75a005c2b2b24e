"""The example projects in resources/examples: they load, keep D(Euclidean) = discrete, match their script,
and reproduce what the paper's figures show (Figs. 8–10, 12, 13)."""

from __future__ import annotations

import importlib.util
import re
from fractions import Fraction
from pathlib import Path

import pytest

import mrm
from mrm.geometry.discretize import discretize
from mrm.io.project import dumps, load_project
from mrm.ops.account import account_of

EXAMPLES = Path(__file__).parents[2] / "resources" / "examples"
FILES = sorted(EXAMPLES.glob("*.mrm"))


def _script():  # type: ignore[no-untyped-def]
    spec = importlib.util.spec_from_file_location("make_examples", EXAMPLES / "make_examples.py")
    assert spec is not None and spec.loader is not None
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod


def _by_name(doc):  # type: ignore[no-untyped-def]
    return {o.name: o for o in doc.objects}


def test_the_paper_figures_are_among_the_examples():
    names = {f.name for f in FILES}
    assert set(_script().EXAMPLES) <= names


@pytest.mark.parametrize("path", FILES, ids=lambda p: p.name)
def test_every_example_loads_and_its_discrete_is_d_of_its_euclidean(path):
    doc = load_project(path)
    assert doc.objects and not doc.is_modified
    for o in doc.objects:
        d = doc.derived(o.id)
        # mrm.discretize: D of a polygon, or of a polyhedron (a 3D example's R(A)) into voxels
        assert mrm.discretize(d.get("euclidean"), doc.model) == d.get("discrete"), o.name


@pytest.mark.parametrize("name", sorted(_script().EXAMPLES))
def test_examples_are_what_their_script_writes(name):
    doc = _script().EXAMPLES[name]()
    doc.set_selection([])

    def strip(b: bytes) -> bytes:
        return re.sub(rb'\n "generator": "[^"]*",', b"", b)

    assert strip(dumps(doc)) == strip((EXAMPLES / name).read_bytes())


def test_fig12_chain_bound_and_measured_error():
    doc = load_project(EXAMPLES / "fig12-dss-combinations.mrm")
    last = _by_name(doc)["DSS 0.8"]
    acc = account_of(last.provenance)
    assert [link.params["alpha"] for link in acc.chain] == [1.25, 5.0, 0.2, 0.8]
    # docs/design.md §8: √2 · Σ_{i=2..k} Π_{j=i..k} s_j with s = (1.25, 5, 0.2, 0.8), read as the decimals
    # they are (what the operations computed with: 0.2 is 1/5).
    s = [Fraction(5, 4), Fraction(5), Fraction(1, 5), Fraction(4, 5)]
    assert acc.bound.coefficient == s[1] * s[2] * s[3] + s[2] * s[3] + s[3] == Fraction(44, 25)
    assert acc.within_bound is True
    assert acc.measured.value == 0.05  # the report: exactly 0.05, not 0.05000000000000071


def test_fig12_in_3d_the_octahedron_chain_is_within_its_sqrt3_bound():
    """The paper's Figure 12 on a digital octahedron: each result's certified distance is within its bound."""
    import math

    doc = load_project(EXAMPLES / "fig12-3d-octahedron.mrm")
    objs = _by_name(doc)
    s = [Fraction(5, 4), Fraction(5), Fraction(1, 5), Fraction(4, 5)]
    # √3 · Σ_{i=2..k} Π_{j=i..k} s_j for the chains of 2, 3 and 4 steps (docs/design.md §8, §11)
    expected = {
        "DSS 5": s[1],
        "DSS 0.2": s[1] * s[2] + s[2],
        "DSS 0.8": s[1] * s[2] * s[3] + s[2] * s[3] + s[3],
    }
    for name, coefficient in expected.items():
        acc = account_of(objs[name].provenance)
        assert acc.bound.coefficient == coefficient and acc.bound.n == 3, name
        lo, hi = acc.measured.intervals["both"]
        assert lo <= hi <= float(coefficient) * math.sqrt(3) and acc.within_bound is True, name
    # DSS_0.2∘DSS_5 gives A1 back on this octahedron (no voxel differs from D(Sc_1.25(R(A))))
    assert objs["DSS 0.2"].source == objs["DSS 1.25"].source


def test_fig13_rotation_back_is_not_the_original():
    doc = load_project(EXAMPLES / "fig13-rotations.mrm")
    objs = _by_name(doc)
    a = objs["A (square)"].source
    back = objs["dR-45,(0,0)(A1)"].source
    # The paper: dR_−45 is not the exact inverse of dR_45.
    assert back != a
    # ...but the chain's bound holds: H(A, dR−45(dR45(A))) ≤ √2 (ratios 1, 1).
    acc = account_of(objs["dR-45,(0,0)(A1)"].provenance)
    assert acc.bound.coefficient == 1
    assert acc.within_bound is True


def test_fig09_10_union_and_corefinement_are_the_pixel_set_operations():
    doc = load_project(EXAMPLES / "fig09-10-union-corefinement.mrm")
    objs = _by_name(doc)
    da = discretize(objs["E (pentagon)"].source, doc.model)
    db = discretize(objs["E' (tilted square)"].source, doc.model)
    assert discretize(objs["EDu(E, E')"].source, doc.model) == da | db
    assert discretize(objs["EDco: E ∖ E'"].source, doc.model) == da - db
    assert discretize(objs["EDco: E ∩ E'"].source, doc.model) == da & db
    assert discretize(objs["EDco: E' ∖ E"].source, doc.model) == db - da


def test_fig08_simplification_is_its_definition_at_each_alpha():
    from shapely import affinity

    from mrm.geometry.reconstruct import reconstruct

    doc = load_project(EXAMPLES / "fig08-simplification.mrm")
    objs = _by_name(doc)
    e = objs["E (star)"].source
    for alpha in (1.0, 0.5, 0.25):  # powers of two: shapely's scalings are exact here
        # Sp_α(E) = Sc_1/α(R(D(Sc_α(E)))) (paper, Def. 14), about the origin.
        coarse = reconstruct(discretize(affinity.scale(e, alpha, alpha, origin=(0, 0)), doc.model), doc.model)
        expected = affinity.scale(coarse, 1 / alpha, 1 / alpha, origin=(0, 0))
        assert objs[f"Sp {alpha:g}"].source.equals(expected), alpha


@pytest.mark.parametrize(
    "name", ["fig12-dss-combinations.mrm", "fig13-rotations.mrm", "fig08-simplification.mrm",
             "fig09-10-union-corefinement.mrm", "fig12-3d-octahedron.mrm", "rotation-3d.mrm"],
)  # fmt: skip
def test_the_inspector_cli_and_api_print_identical_numbers(make_window, qtbot, name):
    """One account (mrm.ops.account): what the inspector holds is what ``mrm account --json`` prints."""
    import contextlib
    import io
    import json

    from mrm.cli import run_cli
    from mrm.ops.account import account_of

    win = make_window()
    assert win.files.open(EXAMPLES / name, ask=False)
    insp = win.inspector
    for obj in [o for o in win.doc.objects if o.provenance is not None]:
        win.doc.set_selection([obj.id])
        insp.refresh()
        qtbot.waitUntil(lambda: insp.measurement is not None, timeout=120_000)
        gui = json.loads(json.dumps(insp.measurement.summary()))
        api = json.loads(json.dumps(account_of(obj.provenance).summary()))
        out = io.StringIO()
        with contextlib.redirect_stdout(out):
            assert run_cli(["account", str(EXAMPLES / name), "--object", obj.name, "--json"]) == 0
        cli = json.loads(out.getvalue())
        assert gui == api == {k: cli[k] for k in api}, obj.name
        if gui.get("measured_interval") and not gui["measured_exact"]:  # 3D: a certified enclosure
            lo, hi = gui["measured_interval"]
            assert f"∈ [{lo:.6g}, {hi:.6g}] (certified)" in insp.measured_label.text()
        elif gui["measured"] is not None:
            assert f"= {gui['measured']:.4g}" in insp.measured_label.text()
