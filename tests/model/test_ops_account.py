"""The account of a result (mrm.ops.account): one set of numbers for the API, ``mrm … --json`` and the GUI.

Per operation: the bound is the paper's (checked against the formula written out here), the measured
distance is exact and within the bound in the directions that hold, the direct result is D(T(A_first))
computed by the slow Fraction reference, Sp_α∘Sp_α = Sp_α is checked; the account of a result never changes
when its input is edited or deleted, survives a save and load, and a hostile record gives a message.
"""

from __future__ import annotations

import contextlib
import io
import json
import math
from fractions import Fraction
from pathlib import Path

import numpy as np
import pytest
import shapely
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from mrm.cli import run_cli
from mrm.core.errors import FileFormatError, ParameterError
from mrm.core.grids import PixelSet
from mrm.document import Document, Settings
from mrm.document.apply import apply_operation, push_plan
from mrm.document.commands import AddObject, RemoveObjects
from mrm.document.edits import PaintPixels
from mrm.geometry.hausdorff import hausdorff_distance
from mrm.geometry.reconstruct import reconstruct
from mrm.io.pixel_files import write_pixels
from mrm.io.project import dumps, load_project, loads, save_project
from mrm.ops.account import account_of, changed_inputs, rerun_request
from mrm.ops.provenance import Provenance, content_digest
from mrm.ops.registry import plan_operation
from tests.oracles.ops_reference import as_mask_set, polygons_of, reference_discretize_rings, rotated, scaled

EXAMPLES = Path(__file__).parents[2] / "resources" / "examples"
SQRT2 = math.sqrt(2)


def _cli(argv: list[str]) -> dict:
    out = io.StringIO()
    with contextlib.redirect_stdout(out):
        assert run_cli(argv) == 0
    return json.loads(out.getvalue())


def _json(d: dict) -> dict:
    return json.loads(json.dumps(d))


def _diamond(r: int = 6) -> PixelSet:
    yy, xx = np.mgrid[-r : r + 1, -r : r + 1]
    return PixelSet(np.abs(xx) + np.abs(yy) <= r, (-r, -r))


def _doc(source, model: str = "standard") -> tuple[Document, int]:
    doc = Document(Settings(model=model))
    obj = doc.make_object(source, "A")
    doc.push(AddObject(obj))
    return doc, obj.id


# ---------------------------------------------------------------------------------------------- one account
@pytest.mark.parametrize("path", sorted(EXAMPLES.glob("*.mrm")), ids=lambda p: p.name)
def test_the_cli_prints_the_api_account_for_every_example_result(path):
    doc = load_project(path)
    results = [o for o in doc.objects if o.provenance is not None]
    for obj in results:
        api = _json(account_of(obj.provenance).summary())
        cli = _cli(["account", str(path), "--object", obj.name, "--json"])
        assert {k: cli[k] for k in api} == api, obj.name
        assert api["error"] is None, (obj.name, api["error"])


def test_a_one_step_cli_run_prints_the_api_account(tmp_path):
    a = _diamond()
    png = tmp_path / "a.png"
    write_pixels(a, png)
    cli = _cli(
        ["scale", str(png), "--alpha", "0.2", "--center", "1,1", "-o", str(tmp_path / "o.png"), "--json"]
    )
    prov = Provenance("dss", {"alpha": 0.2, "center": [1, 1], "model": "standard"}, (0,), (a,), (None,))
    assert cli["account"] == _json(account_of(prov).summary())
    assert cli["bound"] == 0.0 and cli["measured"] == 0.0  # one DSS: A_last = Sc_α(R(A)) = T(A_first)


def test_a_cli_run_on_a_project_result_continues_its_chain(tmp_path):
    path = EXAMPLES / "fig12-dss-combinations.mrm"
    cli = _cli(
        ["scale", str(path), "--object", "DSS 0.2", "--alpha", "0.8", "-o", str(tmp_path / "o.png"), "--json"]
    )
    api = account_of(load_project(path).objects[-1].provenance).summary()
    assert cli["chain"] == ["DSS 1.25", "DSS 5", "DSS 0.2", "DSS 0.8"] == api["chain"]
    assert cli["bound_coefficient"] == "44/25" and cli["measured"] == api["measured"] == 0.05


chain_steps = st.lists(
    st.one_of(
        st.tuples(st.just("dss"), st.sampled_from([0.5, 2.0, 3.0, 0.2, 1.25])),
        st.tuples(st.just("discrete_rotation"), st.sampled_from([90.0, 30.0, -45.0])),
        st.tuples(st.just("simplify"), st.sampled_from([0.5, 1.0, 2.0])),
    ),
    min_size=1,
    max_size=3,
)


@settings(max_examples=8, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(chain_steps, st.sampled_from(["standard", "supercover"]))
def test_random_chains_one_account_api_and_cli(tmp_path, steps, model):
    doc, cur = _doc(_diamond(4), model)
    for name, value in steps:
        key = "angle" if name == "discrete_rotation" else "alpha"
        (cur,) = apply_operation(doc, name, [cur], {key: value, "model": model})
    obj = doc.get(cur)
    path = tmp_path / "chain.mrm"
    save_project(doc, path)
    acc = account_of(obj.provenance)
    api = _json(acc.summary())
    cli = _cli(["account", str(path), "--object", obj.name, "--json"])
    assert {k: cli[k] for k in api} == api
    assert acc.within_bound is True  # the paper's theorems, exactly, under a cover model
    assert len(acc.chain) == len(steps)


@pytest.mark.parametrize(("operation", "params"), [("union", {}), ("corefine", {"alpha": 2.0})])
def test_two_input_results_from_a_project_carry_both_chains_in_api_and_cli(tmp_path, operation, params):
    """``mrm union|corefine`` on project objects gives the account the application gives (both chains)."""
    doc, a = _doc(_diamond(4))
    (a2,) = apply_operation(doc, "dss", [a], {"alpha": 2.0})
    b = doc.make_object(shapely.box(1, -3, 9, 5), "B")
    doc.push(AddObject(b))
    (b2,) = apply_operation(doc, "discrete_rotation", [b.id], {"angle": 30.0})
    (result, *_) = apply_operation(doc, operation, [a2, b2], params)
    path = tmp_path / "two.mrm"
    save_project(doc, path)
    api = _json(account_of(doc.get(result).provenance).summary())
    assert [len(c) for c in api["input_chains"]] == [1, 1]  # DSS_2 of A, dR_30° of B
    names = [doc.get(a2).name, doc.get(b2).name]
    extra = ["--alpha", "2"] if operation == "corefine" else []
    out = tmp_path / f"{operation}.geojson"
    cli = _cli(
        [
            operation,
            str(path),
            str(path),
            "--object",
            names[0],
            "--object",
            names[1],
            *extra,
            "-o",
            str(out),
            "--json",
        ]
    )
    assert cli["input_chains"] == api["input_chains"]
    assert cli["measured"] == api["measured"] and cli["bound"] == api["bound"]


# ---------------------------------------------------------------------------------------------- per operation
def test_dss_chain_bound_measured_and_direct_result_against_the_reference():
    doc, a = _doc(_diamond(5))
    (b,) = apply_operation(doc, "dss", [a], {"alpha": 3.0})
    (c,) = apply_operation(doc, "dss", [b], {"alpha": 0.2, "center": [0.5, 0.5]})
    acc = account_of(doc.get(c).provenance)
    # Theorem 4 chained: √2 · s₂ for DSS_3 then DSS_1/5.
    assert acc.bound.coefficient == Fraction(1, 5) and acc.bound.bound == pytest.approx(SQRT2 / 5)
    assert acc.within_bound is True and acc.bound.directions == ("result_within", "source_within")
    # direct = D(Sc_{3/5, about the composite centre}(R(A))), by the Fraction reference.
    polys = polygons_of(reconstruct(doc.get(a).source, "standard"))
    t = scaled(scaled(polys, Fraction(3)), Fraction(1, 5), (Fraction(1, 2), Fraction(1, 2)))
    assert as_mask_set(acc.direct) == as_mask_set(reference_discretize_rings(t, "standard"))
    assert acc.difference.light == acc.result - acc.direct and acc.difference.dark == acc.direct - acc.result
    assert acc.result == doc.get(c).source


def test_rotation_chain_is_bounded_and_measured():
    doc, a = _doc(_diamond(5))
    (b,) = apply_operation(doc, "discrete_rotation", [a], {"angle": 30.0})
    (c,) = apply_operation(doc, "discrete_rotation", [b], {"angle": -30.0, "center": [1.0, 0.0]})
    acc = account_of(doc.get(c).provenance)
    assert acc.bound.coefficient == 1 and acc.within_bound is True  # Theorem 13: √2 for two rotations
    from mrm.geometry.discretize.exact_shape import rotation_cos_sin

    polys = polygons_of(reconstruct(doc.get(a).source, "standard"))
    c1, s1 = rotation_cos_sin(Fraction(30))
    c2, s2 = rotation_cos_sin(Fraction(-30))
    t = rotated(rotated(polys, c1, s1, (Fraction(0), Fraction(0))), c2, s2, (Fraction(1), Fraction(0)))
    assert as_mask_set(acc.direct) == as_mask_set(reference_discretize_rings(t, "standard"))


@pytest.mark.parametrize("alpha", [0.5, 0.3, 2.0])
def test_simplification_theorem_15_and_idempotence(alpha):
    e = shapely.Polygon([(0.2, 0.1), (7.3, 1.7), (4.1, 6.6), (1.3, 3.9)])
    doc, a = _doc(e)
    (b,) = apply_operation(doc, "simplify", [a], {"alpha": alpha})
    acc = account_of(doc.get(b).provenance)
    assert acc.bound.coefficient == 1 / Fraction(str(alpha))  # √2/α
    assert acc.within_bound is True and acc.idempotent is True
    # The measured distance is H(E, Sp_α(E)) for the stored result (exact when the result is float-exact).
    h = hausdorff_distance(e, doc.get(b).source)
    assert acc.measured.value == pytest.approx(h.value, abs=1e-12)


def test_union_account_has_a_bound_a_measurement_and_both_chains():
    p = shapely.box(0, 0, 4, 3)
    q = shapely.Polygon([(5, 0), (9, 1), (7, 4)])
    doc, a = _doc(p)
    bq = doc.make_object(q, "B")
    doc.push(AddObject(bq))
    (a2,) = apply_operation(doc, "simplify", [a], {"alpha": 2.0})
    (u,) = apply_operation(doc, "union", [a2, bq.id], {})
    acc = account_of(doc.get(u).provenance)
    assert acc.bound.bound == pytest.approx(SQRT2) and acc.within_bound is True
    assert acc.reference_exact is True  # disjoint inputs: E ∪ E′ is exact
    assert [[link.label for link in c] for c in acc.input_chains] == [["SP 2"], []]
    # Disjoint inputs: E ∪ E′ is the multipolygon of both, and the measured distance is H to it.
    both = shapely.MultiPolygon([doc.get(a2).source, q])
    assert acc.measured.value == hausdorff_distance(both, doc.get(u).source).value


@pytest.mark.parametrize("alpha", [None, 2.0])
def test_corefinement_accounts_per_part_with_their_directions(alpha):
    p, q = shapely.box(0, 0, 6, 4), shapely.box(3.5, 1.5, 9, 7)
    doc, a = _doc(p)
    bq = doc.make_object(q, "B")
    doc.push(AddObject(bq))
    ids = apply_operation(doc, "corefine", [a, bq.id], {"alpha": alpha})
    coefficient = 1 if alpha is None else Fraction(1, 2)
    for oid, part, direction in zip(
        ids,
        ("a_minus_b", "a_and_b", "b_minus_a"),
        ("result_within", "source_within", "result_within"),
        strict=True,
    ):
        acc = account_of(doc.get(oid).provenance)
        assert acc.part == part and acc.bound.directions == (direction,)
        assert acc.bound.bound is None and acc.bound.coefficient == coefficient  # one-sided: √2/α
        assert acc.within_bound is True
        assert [pa.part for pa in acc.parts] == ["a_minus_b", "a_and_b", "b_minus_a"]
        assert all(pa.measured is not None for pa in acc.parts)


def test_exact_operations_say_why_there_is_no_error():
    doc, a = _doc(PixelSet.box(0, 0, 3, 3))
    b = doc.make_object(PixelSet.box(2, 2, 5, 5), "B")
    doc.push(AddObject(b))
    (u,) = apply_operation(doc, "discrete_union", [a, b.id])
    acc = account_of(doc.get(u).provenance)
    assert acc.bound is None and "exact" in acc.no_bound and acc.error == ""


# ---------------------------------------------------------------------------------------------- pinning
def test_editing_or_deleting_the_input_never_changes_the_account():
    doc, a = _doc(_diamond(4))
    (b,) = apply_operation(doc, "dss", [a], {"alpha": 2.0})
    (c,) = apply_operation(doc, "dss", [b], {"alpha": 0.5})
    before = account_of(doc.get(c).provenance).summary()
    doc.push(PaintPixels(a, PixelSet.box(-20, -20, 20, 20)))
    doc.push(PaintPixels(b, PixelSet.box(30, 30, 31, 31)))
    assert account_of(doc.get(c).provenance).summary() == before
    changes = changed_inputs(doc, doc.get(c).provenance)
    assert [(ch.id, ch.step, ch.state) for ch in changes] == [(b, 0, "changed"), (a, 1, "changed")]
    doc.push(RemoveObjects([a, b]))
    assert account_of(doc.get(c).provenance).summary() == before
    changes = changed_inputs(doc, doc.get(c).provenance)
    assert [(ch.id, ch.state) for ch in changes] == [(b, "deleted"), (a, "deleted")]
    # ... and after a save and a load, the pinned contents come back (each stored once).
    data = dumps(doc)
    back = loads(data)
    assert account_of(back.get(c).provenance).summary() == before
    assert data.count(b'"kind": "discrete"') == 1 + 2  # the result itself, then A and DSS_2(A) once each


def test_re_running_on_the_current_input_is_a_new_result():
    doc, a = _doc(_diamond(4))
    (b,) = apply_operation(doc, "dss", [a], {"alpha": 2.0})
    old = account_of(doc.get(b).provenance).summary()
    doc.push(PaintPixels(a, PixelSet.box(10, 10, 12, 12)))
    (new,) = push_plan(doc, rerun_request(doc, b).plan())
    assert doc.get(new).provenance.digests == (content_digest(doc.get(a).source),)
    assert account_of(doc.get(b).provenance).summary() == old
    assert changed_inputs(doc, doc.get(new).provenance) == []


def test_re_running_a_chain_starts_from_the_oldest_changed_input():
    doc, a = _doc(_diamond(4))
    (b,) = apply_operation(doc, "dss", [a], {"alpha": 2.0})
    (c,) = apply_operation(doc, "dss", [b], {"alpha": 0.5})
    doc.push(PaintPixels(a, PixelSet.box(10, 10, 12, 12)))
    changes = changed_inputs(doc, doc.get(c).provenance)
    assert [(ch.id, ch.step, ch.state) for ch in changes] == [(a, 1, "changed")]
    assert "of the step 1 before" in changes[0].text()
    request = rerun_request(doc, c)
    assert [name for name, _ in request.steps] == ["dss", "dss"]
    (new,) = push_plan(doc, request.plan())
    fresh = apply_operation(doc, "dss", apply_operation(doc, "dss", [a], {"alpha": 2.0}), {"alpha": 0.5})
    assert doc.get(new).source == doc.get(fresh[0]).source
    acc = account_of(doc.get(new).provenance)
    assert acc.chain[0].inputs == (a,) and acc.chain[1].inputs == (0,)  # the intermediate was not kept
    assert changed_inputs(doc, doc.get(new).provenance) == []
    assert loads(dumps(doc)).get(new).provenance.inputs == (0,)  # saved and read back
    doc.push(RemoveObjects([a]))
    with pytest.raises(ParameterError, match="deleted one cannot"):
        rerun_request(doc, new)


def test_plan_operation_needs_no_document():
    from mrm.document import DocObject

    a = DocObject(id=7, name="A", source=_diamond(3))
    plan = plan_operation([a], "dss", {"alpha": 2.0})
    (r,) = plan.results
    assert r.provenance.inputs == (7,) and r.provenance.sources == (a.source,)
    assert plan.label == "DSS 2"  # the undo step reads as the chain would write it
    assert plan.outcome.bound.bound == 0.0


# ---------------------------------------------------------------------------------------------- bad records
@pytest.mark.parametrize(
    ("operation", "params", "message"),
    [
        ("dss", {"alpha": 2.0, "colour": "red"}, "unknown parameter(s) colour"),
        ("dss", {"alpha": 5e-324}, "allowed: 1e-06 ≤ α ≤ 1e+06"),
        ("dss", {"alpha": 2.0, "center": [1, 2, 3]}, "must be 2 numbers (x, y)"),
        ("dss", {"alpha": 2.0, "center": "middle"}, "must be 2 or 3 numbers (x, y, z)"),
        ("dss", {"alpha": [1, 2]}, "must be a number"),
        ("discrete_rotation", {"angle": 1e308}, "allowed: -3600 ≤ θ ≤ 3600"),
        ("corefine", {"part": "everything"}, "unknown corefine part 'everything'"),
        ("blur", {}, "unknown operation 'blur'"),
    ],
)
def test_a_hostile_record_gives_a_message_never_an_exception(operation, params, message):
    a = PixelSet.box(0, 0, 3, 3)
    n = 2 if operation == "corefine" else 1
    prov = Provenance(operation, params, tuple(range(1, n + 1)), (a,) * n, (None,) * n)
    acc = account_of(prov)
    assert message in acc.error and acc.bound is None and acc.measured is None
    assert acc.summary()["error"] == acc.error


def test_hostile_provenance_in_a_project_file_loads_and_is_explained(tmp_path):
    doc, a = _doc(PixelSet.box(0, 0, 3, 3))
    (b,) = apply_operation(doc, "dss", [a], {"alpha": 2.0})
    text = dumps(doc).decode().replace('"alpha": 2,', '"alpha": 5e-324, "extra": {"x": 1},')
    back = loads(text.encode())
    acc = account_of(back.get(b).provenance)
    assert "unknown parameter(s) extra" in acc.error
    # A digest that does not name its content, or names no content, is refused at load with its path.
    bad = dumps(doc).decode()
    digest = content_digest(doc.get(a).source)
    with pytest.raises(FileFormatError, match=r"\$.objects\[1\].provenance.input_contents\[0\]"):
        loads(bad.replace(f'"input_contents": ["{digest}"]', '"input_contents": ["0000"]').encode())
    with pytest.raises(FileFormatError, match="does not match its digest"):
        loads(bad.replace(f'"{digest}": {{', '"ffff": {').replace(digest, "ffff").encode())


# ------------------------------------------------------------------------------------------- every operation
def _registered() -> list[str]:
    from mrm.ops.registry import operations

    return [spec.name for spec in operations()]


@pytest.mark.parametrize("name", _registered())
@pytest.mark.parametrize("model", ["standard", "supercover", "gauss"])
def test_every_operation_has_an_account_with_a_bound_or_words_for_why_not(name, model):
    """No registered operation is left without an account: a bound in a stated direction, or why not."""
    from mrm.ops.registry import get_operation

    spec = get_operation(name)
    params = spec.params().to_json()
    if "model" in params:
        params["model"] = model
    a = PixelSet.box(0, 0, 3, 3) if spec.reads == "discrete" else shapely.box(0, 0, 3.5, 3)
    b = PixelSet.box(2, 2, 5, 5) if spec.reads == "discrete" else shapely.box(2, 1.5, 5, 5)
    sources = (a, b)[: spec.arity]
    parts = ["a_minus_b", "a_and_b", "b_minus_a"] if name == "corefine" else [None]
    for part in parts:
        p = params if part is None else {**params, "part": part}
        prov = Provenance(name, p, tuple(range(1, spec.arity + 1)), sources, (None,) * spec.arity)
        acc = account_of(prov, measure=False)
        assert acc.error == "", (name, acc.error)
        if acc.bound is not None and acc.bound.directions:
            assert acc.no_bound == "" and acc.bound.guarantee
        else:
            assert len(acc.no_bound.split()) >= 4, (name, part, acc.no_bound)  # a sentence, not a code


hostile_values = st.one_of(
    st.none(),
    st.booleans(),
    st.floats(allow_nan=True, allow_infinity=True),
    st.integers(-(10**400), 10**400),
    st.text(max_size=12),
    st.lists(st.one_of(st.floats(), st.text(max_size=4), st.integers()), max_size=3),
    st.dictionaries(st.text(max_size=3), st.integers(), max_size=2),
)


@settings(max_examples=150, deadline=None)
@given(
    st.sampled_from([*_registered(), "blur", ""]),
    st.dictionaries(
        st.sampled_from(["alpha", "angle", "factor", "center", "model", "part", "dx", "colour"]),
        hostile_values,
        max_size=4,
    ),
)
def test_any_recorded_parameters_give_an_account_or_a_message_never_an_exception(name, params):
    """A project whose result records anything as its operation and parameters: a message, never a crash."""
    doc, a = _doc(PixelSet.box(0, 0, 3, 3))
    (b,) = apply_operation(doc, "dss", [a], {"alpha": 2.0})
    data = json.loads(dumps(doc))
    (record,) = [o for o in data["objects"] if o["id"] == b]
    record["provenance"].update(operation=name, params=params)
    try:
        back = loads(json.dumps(data).encode())
    except FileFormatError as e:  # refused on load, in one message
        assert str(e).startswith("project")
        return
    acc = account_of(back.get(b).provenance, measure=False)
    assert acc.error or acc.bound is not None or acc.no_bound
    assert json.loads(json.dumps(acc.summary())) is not None


# --------------------------------------------------------------------------------- schema-1 files: cycles
def _schema1_project(path: Path, inputs: dict[int, list[int]]) -> None:
    """A version 1 project whose objects are DSS results of the given input ids (a 2 × 2 block each)."""
    style = {"fill": "#4c72b0", "stroke": "#1f2a44", "opacity": 0.6, "stroke_width": 1.5, "visible": True}
    source = {"kind": "discrete", "origin": [0, 0], "shape": [2, 2], "bits": "8A=="}
    objects = [
        {
            "id": oid,
            "name": f"o{oid}",
            "style": style,
            "provenance": None
            if ins is None
            else {"operation": "dss", "params": {"alpha": 2, "model": "gauss"}, "inputs": ins},
            "source": source,
        }
        for oid, ins in inputs.items()
    ]
    data = {"format": "mrm-project", "schema_version": 1, "settings": {"model": "gauss"}, "objects": objects}
    path.write_text(json.dumps(data), encoding="utf-8")


def _account_cli(capsys, path: Path, name: str) -> tuple[int, str, str]:
    code = run_cli(["account", str(path), "--object", name, "--json"])
    out, err = capsys.readouterr()
    return code, out, err


def test_a_provenance_cycle_in_a_schema_1_project_is_reported_not_a_traceback(tmp_path, capsys):
    """Issue 32: o1 = DSS(o2) and o2 = DSS(o1) in a version 1 file made `mrm account` fail (IndexError)."""
    path = tmp_path / "cycle.mrm"
    _schema1_project(path, {1: [2], 2: [1], 3: [1]})
    for name in ("o1", "o2"):
        code, out, err = _account_cli(capsys, path, name)
        assert code == 0 and "Traceback" not in err, err
        assert "not recorded" in json.loads(out)["error"]  # a cycle records no input content: nothing pinned
    code, out, err = _account_cli(capsys, path, "o3")  # a result of a cycle's member: its input is known
    assert code == 0 and "Traceback" not in err, err
    assert json.loads(out)["chain"] == ["DSS 2"] and json.loads(out)["error"] is None
