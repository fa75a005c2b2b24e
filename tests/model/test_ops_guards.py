"""Guards: sizes estimated and refused before running, parameters refused with a message, nothing lost."""

from __future__ import annotations

from fractions import Fraction

import pytest
import shapely
from hypothesis import given, settings
from hypothesis import strategies as st

import mrm.geometry.reconstruct as reconstruct_module
from mrm.core.errors import Cancelled, ParameterError, SizeLimitError
from mrm.core.grids import PixelSet
from mrm.document import Document
from mrm.document.apply import apply_operation
from mrm.geometry.discretize import discretize
from mrm.geometry.discretize.exact_shape import Similarity
from mrm.ops.boolean import (
    CorefineParams,
    euclidean_discrete_corefinement,
    euclidean_discrete_union,
)
from mrm.ops.estimate import estimated_pixels
from mrm.ops.rotation import RotationParams, discrete_rotation
from mrm.ops.scaling import DSSParams, discrete_smooth_scaling
from mrm.ops.simplify import SimplifyParams, simplification
from tests.oracles.geometry_strategies import star_polygons
from tests.oracles.ops_reference import MODELS, objects

LARGE = PixelSet.box(0, 0, 999, 999)


def box_area(ps: PixelSet) -> int:
    if ps.bbox is None:
        return 0
    x0, y0, x1, y1 = ps.bbox
    return (x1 - x0 + 1) * (y1 - y0 + 1)


@pytest.fixture
def no_reconstruction(monkeypatch):
    """Fail the test if anything is continued: a refusal must come before any work.

    Every path to R goes through its one entry point, which runs the kernels' driver ``_run``.
    """

    def refuse(*args, **kwargs):
        raise AssertionError("R was called before the size check")

    monkeypatch.setattr(reconstruct_module, "_run", refuse)


# ---------------------------------------------------------------------------------------------- sizes
def test_a_huge_scale_is_refused_before_any_work_with_its_size(no_reconstruction):
    with pytest.raises(SizeLimitError) as err:
        discrete_smooth_scaling(LARGE, 1e6)
    # 1000 pixels wide, scaled by 10⁶: about (10⁹)² pixels
    assert err.value.estimated >= (1000 * 10**6) ** 2
    assert err.value.estimated <= (1001 * 10**6 + 2) ** 2
    assert err.value.limit == 200_000_000
    assert f"{err.value.estimated:,}" in str(err.value)


def test_every_operation_checks_its_size_first(no_reconstruction):
    small = PixelSet.box(0, 0, 9, 9)
    with pytest.raises(SizeLimitError):
        discrete_smooth_scaling(small, 5, limit=1000)
    with pytest.raises(SizeLimitError):
        discrete_rotation(LARGE, 45, limit=1_000_000)
    poly = shapely.box(0, 0, 100, 100)
    with pytest.raises(SizeLimitError):
        simplification(poly, 1e5)
    with pytest.raises(SizeLimitError):
        euclidean_discrete_corefinement(poly, small, alpha=1e5)


def test_the_limit_is_configurable():
    a = PixelSet.box(0, 0, 9, 9)
    assert len(discrete_smooth_scaling(a, 5, limit=None).result) > 1000
    with pytest.raises(SizeLimitError) as err:
        discrete_smooth_scaling(a, 5, limit=100)
    assert err.value.limit == 100


@settings(max_examples=40)
@given(
    objects(), st.sampled_from([0.3, 1, 2.5, 4]), st.sampled_from([0, 30, 90, 217]), st.sampled_from(MODELS)
)
def test_the_estimate_bounds_the_result(a, alpha, angle, model):
    for sim, out in (
        (
            Similarity.scaling(Fraction(repr(float(alpha)))),
            discrete_smooth_scaling(a, float(alpha), None, model),
        ),
        (Similarity.rotation(Fraction(angle)), discrete_rotation(a, angle, None, model)),
    ):
        assert box_area(out.result) <= estimated_pixels([a], sim, model)


# ---------------------------------------------------------------------------------------------- parameters
@pytest.mark.parametrize(
    "bad", [0, -1, -0.0, float("nan"), float("inf"), float("-inf"), "", "abc", None, True]
)
def test_scale_factors_are_refused_with_the_parameters_name(bad):
    a = PixelSet.box(0, 0, 3, 3)
    poly = shapely.box(0, 0, 3, 3)
    calls = [lambda: discrete_smooth_scaling(a, bad), lambda: simplification(poly, bad)]
    if bad is not None:  # no α is the plain co-refinement
        calls.append(lambda: euclidean_discrete_corefinement(poly, poly, alpha=bad))
    for call in calls:
        with pytest.raises(ParameterError, match="alpha"):
            call()


def test_models_and_centres_are_checked():
    a = PixelSet.box(0, 0, 3, 3)
    with pytest.raises(ParameterError, match="model"):
        discrete_rotation(a, 30, None, "closest")
    with pytest.raises(ParameterError, match="model"):
        euclidean_discrete_union(a, a, "")
    with pytest.raises(ParameterError, match="center"):
        discrete_smooth_scaling(a, 2, ("1", "inf"))


# ---------------------------------------------------------------------------------------------- nothing lost
class Cancelling:
    """A progress whose user pressed Cancel after ``n`` reports."""

    def __init__(self, n: int) -> None:
        self.n = n
        self.calls = 0

    def update(self, fraction=None, message=None) -> None:
        self.calls += 1
        if self.calls > self.n:
            raise Cancelled("cancelled by the user")


def make_doc() -> tuple[Document, int, int]:
    doc = Document()
    from mrm.document.commands import AddObject

    a = doc.make_object(PixelSet.box(0, 0, 19, 14), "rect")
    doc.push(AddObject(a))
    b = doc.make_object(shapely.Polygon([(3, 2), (30, 5), (10, 25)]), "tri")
    doc.push(AddObject(b))
    return doc, a.id, b.id


def snapshot(doc: Document):
    return (doc.objects, doc.selection, doc.history.can_undo(), doc.revision)


@pytest.mark.parametrize(
    ("op", "inputs", "params"),
    [
        ("dss", 1, DSSParams(alpha=3.0)),
        ("discrete_rotation", 1, RotationParams(angle=33.0)),
        ("simplify", 1, SimplifyParams(alpha=0.7)),
        ("union", 2, None),
        ("corefine", 2, CorefineParams(alpha=1.5)),
    ],
)
def test_a_cancelled_operation_leaves_the_document_as_it_was(op, inputs, params):
    from mrm.ops.boolean import UnionParams

    params = params or UnionParams()
    doc, a, b = make_doc()
    ids = [a, b][:inputs]
    done = Cancelling(10**9)
    apply_operation(doc, op, ids, params, done)
    assert done.calls >= 2  # the operation reports as it goes
    doc, a, b = make_doc()
    before = snapshot(doc)
    for n in (0, done.calls // 2, done.calls - 1):
        p = Cancelling(n)
        with pytest.raises(Cancelled):
            apply_operation(doc, op, ids, params, p)
        assert p.calls == n + 1  # stopped at the first report after the cancel
        assert snapshot(doc) == before


def test_a_refused_operation_leaves_the_document_as_it_was_and_a_success_is_one_undo_step():
    doc, a, b = make_doc()
    before = snapshot(doc)
    with pytest.raises(SizeLimitError):
        apply_operation(doc, "dss", [a], DSSParams(alpha=1e6))
    with pytest.raises(ParameterError):
        apply_operation(doc, "union", [a], None)
    assert snapshot(doc) == before
    new = apply_operation(doc, "corefine", [a, b], CorefineParams())
    assert len(new) == 3
    for i in new:
        prov = doc.get(i).provenance
        assert prov.operation == "corefine" and prov.inputs == (a, b)
    assert discretize(doc.get(new[1]).source) == PixelSet.box(0, 0, 19, 14) & discretize(doc.get(b).source)
    doc.undo()
    assert doc.objects == before[0]


@settings(max_examples=40)
@given(star_polygons(max_vertices=6), st.sampled_from([0.3, 1.0, 2.5]), st.sampled_from(MODELS))
def test_the_registered_estimates_bound_the_results_of_polygon_inputs(poly, alpha, model):
    from mrm.ops import rotation, scaling, simplify

    p = DSSParams(alpha=alpha, model=model)
    assert box_area(scaling.run([poly], p).output) <= scaling.SPEC.estimate([poly], p)
    r = RotationParams(angle=37.0, center=(0.5, 1.0), model=model)
    assert box_area(rotation.run([poly], r).output) <= rotation.SPEC.estimate([poly], r)
    s = SimplifyParams(alpha=alpha, model=model)
    assert box_area(simplification(poly, alpha, None, model).discrete) <= simplify.estimate([poly], s)
