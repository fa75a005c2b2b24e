"""EDu, EDco and EDco_α: what the parts are, that they partition the pixels, and that their polygons tile."""

from __future__ import annotations

import itertools
from fractions import Fraction

import numpy as np
import pytest
import shapely
from hypothesis import given, settings
from hypothesis import strategies as st

from mrm.core.errors import ParameterError
from mrm.core.grids import PixelSet
from mrm.geometry.discretize import discretize
from mrm.geometry.reconstruct import reconstruct
from mrm.ops.boolean import (
    PARTS,
    CorefineParams,
    CorefineResult,
    UnionParams,
    euclidean_discrete_corefinement,
    euclidean_discrete_union,
    run_corefine,
)
from mrm.ops.registry import run_operation
from mrm.reps.region import region_of
from tests.oracles.geometry_strategies import star_polygons
from tests.oracles.ops_reference import MODELS, pixel_sets, polygons_of, reference_discretize_rings, scaled

pairs = st.tuples(
    star_polygons(max_vertices=6, max_radius=4.0), star_polygons(max_vertices=6, max_radius=4.0)
)


def interiors_disjoint(a, b) -> bool:
    # DE-9IM: the interiors do not meet (GEOS's predicates are exact on float input)
    return a.is_empty or b.is_empty or a.relate_pattern(b, "F********")


@settings(max_examples=40)
@given(pairs, st.sampled_from(MODELS))
def test_union_is_the_continuation_of_the_union_of_the_discretizations(ab, model):
    e1, e2 = ab
    out = euclidean_discrete_union(e1, e2, model)
    d = discretize(e1, model) | discretize(e2, model)
    assert out.discrete == d
    assert discretize(out.result, model) == d  # D(EDu(E, E′)) = D(E) ∪ D(E′), the object's discrete rep


@settings(max_examples=40)
@given(pairs, st.sampled_from(MODELS))
def test_corefinement_parts_partition_the_pixels_and_their_polygons_do_not_overlap(ab, model):
    e1, e2 = ab
    out = euclidean_discrete_corefinement(e1, e2, model)
    d1, d2 = discretize(e1, model), discretize(e2, model)
    px = out.extra["pixels"]
    assert px["a_minus_b"] == d1 - d2
    assert px["a_and_b"] == d1 & d2
    assert px["b_minus_a"] == d2 - d1
    assert (px["a_minus_b"] | px["a_and_b"] | px["b_minus_a"]) == d1 | d2
    for p, q in itertools.combinations(PARTS, 2):
        assert not (px[p] & px[q])
        assert interiors_disjoint(out.result[p], out.result[q])
    for i, p in enumerate(PARTS, start=1):
        assert out.extra["label_map"].pixel_set(i) == px[p]
        assert discretize(out.result[p], model) == px[p]  # each part reconstructs its pixels exactly


@settings(max_examples=25)
@given(pairs)
def test_under_gauss_the_parts_are_a_watertight_subdivision(ab):
    e1, e2 = ab
    out = euclidean_discrete_corefinement(e1, e2, "gauss")
    assert out.extra["watertight"]
    px = out.extra["pixels"]
    for p, q in itertools.combinations(PARTS, 2):
        a, b = out.result[p], out.result[q]
        assert interiors_disjoint(a, b)
        neighbours = any(px[p].translate(dx, dy) & px[q] for dx, dy in ((1, 0), (-1, 0), (0, 1), (0, -1)))
        if neighbours:  # 4-adjacent parts share a stretch of boundary: no gap between them
            assert a.boundary.intersection(b.boundary).length > 0
    # and no sliver of a gap anywhere: the parts together have the holes and components of their pixels
    parts = [out.result[p] for p in PARTS if not out.result[p].is_empty]
    if parts:
        whole = shapely.union_all(parts)
        support = region_of(px["a_minus_b"] | px["a_and_b"] | px["b_minus_a"])
        polys = list(getattr(whole, "geoms", [whole]))
        assert len(polys) == support.n_components
        assert sum(len(g.interiors) for g in polys) == support.n_holes


@settings(max_examples=25)
@given(pairs, st.sampled_from([2, 0.5, 3, "3/2"]), st.sampled_from(MODELS))
def test_precise_corefinement_works_on_the_scaled_objects(ab, alpha, model):
    e1, e2 = ab
    a = Fraction(alpha) if isinstance(alpha, str) else Fraction(repr(float(alpha)))
    out = euclidean_discrete_corefinement(e1, e2, model, alpha)
    d1 = reference_discretize_rings(scaled(polygons_of(e1), a), model)
    d2 = reference_discretize_rings(scaled(polygons_of(e2), a), model)
    assert out.extra["pixels"]["a_and_b"] == d1 & d2
    assert out.extra["pixels"]["a_minus_b"] == d1 - d2
    for p in PARTS:
        back = scaled(polygons_of(out.result[p]), a)  # Sc_α of the result is R(part) (up to rounding)
        assert reference_discretize_rings(back, model) == out.extra["pixels"][p]


def test_pixel_inputs_stand_for_themselves():
    a = PixelSet.box(0, 0, 5, 3)
    b = PixelSet.box(3, 2, 8, 6)
    u = euclidean_discrete_union(a, b)
    assert u.discrete == a | b
    co = euclidean_discrete_corefinement(a, b)
    assert co.extra["pixels"]["a_and_b"] == PixelSet.box(3, 2, 5, 3)
    assert discretize(co.result["a_and_b"]) == PixelSet.box(3, 2, 5, 3)


def test_disjoint_objects_give_an_empty_common_part():
    e1 = shapely.box(0, 0, 3, 3)
    e2 = shapely.box(10, 0, 13, 3)
    out = euclidean_discrete_corefinement(e1, e2)
    assert out.result["a_and_b"].is_empty
    assert discretize(out.result["a_minus_b"]) == discretize(e1)


def test_specs_give_named_parts_with_provenance():
    e1 = shapely.box(0, 0, 4, 4)
    e2 = shapely.box(2, 2, 6, 6)
    res = run_operation("corefine", [e1, e2], CorefineParams(alpha=2.0, model="supercover"))
    assert [name for name, _ in res.outputs] == list(PARTS)
    assert res.provenance == {
        "operation": "corefine",
        "params": {"alpha": 2.0, "model": "supercover"},
        "inputs": [{"input": 0}, {"input": 1}],
    }
    expected = euclidean_discrete_corefinement(e1, e2, "supercover", 2.0)
    assert res.label_map == expected.extra["label_map"]
    assert res.part_bounds["a_and_b"].directions == ("source_within",)
    assert res.part_bounds["a_minus_b"].directions == ("result_within",)
    u = run_operation("union", [e1, e2], UnionParams())
    assert discretize(u.output) == discretize(e1) | discretize(e2)
    assert u.provenance["operation"] == "union"
    with pytest.raises(ParameterError, match="2 input"):
        run_operation("union", [e1], UnionParams())
    with pytest.raises(ParameterError, match="alpha"):
        run_corefine([e1, e2], CorefineParams(alpha=float("nan")))
    with pytest.raises(ParameterError, match="alpha"):
        run_operation("corefine", [e1, e2], CorefineParams(alpha=-1.0))
    # a chain of the framework continues with the first part, A ∖ B
    r = run_operation("corefine", [e1, e2], CorefineParams())
    assert isinstance(r, CorefineResult) and r.output.equals_exact(r.outputs[0][1], 0)


def test_the_reconstruction_of_a_union_is_the_continuation_of_the_pixels():
    e1 = shapely.Polygon([(0, 0), (7, 1), (2, 6)])
    e2 = shapely.Polygon([(4, 3), (9, 2), (8, 8)])
    out = euclidean_discrete_union(e1, e2)
    assert out.result.equals_exact(reconstruct(discretize(e1) | discretize(e2)), 0)


@settings(max_examples=100, deadline=None)
@given(pixel_sets(max_side=9), pixel_sets(max_side=9))
def test_the_parts_label_map_labels_each_part(a, b):
    from mrm.core.grids import LabelMap
    from mrm.ops.boolean import parts_label_map

    lm = parts_label_map(a, b)
    checked = LabelMap.from_pixel_sets([a - b, a & b, b - a])  # through the validating constructor
    assert lm == checked and hash(lm) == hash(checked) and lm.origin == checked.origin
    assert not lm.labels.flags.writeable
    assert lm.pixel_set(1) == a - b and lm.pixel_set(2) == (a & b) and lm.pixel_set(3) == b - a
    assert parts_label_map(a, PixelSet.empty()) == LabelMap.from_pixel_sets(
        [a, PixelSet.empty(), PixelSet.empty()]
    )


@pytest.mark.parametrize("model", MODELS)
@pytest.mark.parametrize("alpha", [0.25, "1/524288"])
def test_a_tiny_but_valid_shape_is_corefined_exactly_at_a_small_alpha(alpha, model):
    """Issue 32: Sc_α of a triangle with legs 3·2⁻⁴⁰⁰ left D's float range and EDco_α refused it."""
    tiny = 3 * 2.0**-400
    e1 = shapely.Polygon([(0, 0), (8, 0), (8, tiny)])
    e2 = shapely.Polygon([(0, 0), (tiny, 0), (0, tiny)])
    a = Fraction(alpha) if isinstance(alpha, str) else Fraction(repr(float(alpha)))
    out = euclidean_discrete_corefinement(e1, e2, model, alpha)
    d1 = reference_discretize_rings(scaled(polygons_of(e1), a), model)
    d2 = reference_discretize_rings(scaled(polygons_of(e2), a), model)
    assert out.extra["pixels"]["a_and_b"] == d1 & d2
    assert out.extra["pixels"]["a_minus_b"] == d1 - d2
    assert out.extra["pixels"]["b_minus_a"] == d2 - d1


def test_a_gauss_corefinement_of_noise_is_refused_by_the_subdivisions_cost_first(monkeypatch):
    """Issue 32: under gauss the parts are one watertight subdivision, bounded like mrm polygonize."""
    from mrm.core.errors import LimitError
    from mrm.geometry.reconstruct import subdivision

    monkeypatch.setattr(subdivision, "_subdivide", lambda _lm: pytest.fail("subdivided before the check"))
    dots = np.zeros((700, 700), bool)
    dots[::2, ::2] = True  # 122,500 one-pixel regions
    with pytest.raises(LimitError, match="co-refinement's parts together has 122,5"):
        euclidean_discrete_corefinement(PixelSet(dots), PixelSet.box(0, 0, 1, 1), "gauss")
