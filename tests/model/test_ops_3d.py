"""The paper's operations on voxel sets: the same registry, the same chain runner, √3 per round trip (§11).

Issue 30 item 1. Results are checked against the definitions evaluated independently (the Fraction oracle of
tests/oracles/voxelize_reference.py on the exact image of R(A)), against the exact permutations a quarter turn
must give, and the bound against the paper's rule written out by hand.
"""

from __future__ import annotations

import contextlib
import io
import json
import math
from fractions import Fraction

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

import mrm
from mrm.cli import run_cli
from mrm.core.errors import ParameterError
from mrm.core.grids import VoxelSet
from mrm.geometry.discretize.exact_solid import ROTATION_BITS, Similarity3, rotation_matrix
from mrm.geometry.reconstruct import reconstruct
from mrm.io.voxel_files import read_voxels, write_voxels
from mrm.ops.account import account_of
from mrm.ops.provenance import Provenance
from mrm.ops.registry import run_operation
from tests.oracles.voxelize_reference import reference_voxelize, voxel_set

MODELS = ("standard", "supercover", "gauss")


def _octahedron(r: int) -> VoxelSet:
    zz, yy, xx = np.mgrid[-r : r + 1, -r : r + 1, -r : r + 1]
    return VoxelSet(np.abs(xx) + np.abs(yy) + np.abs(zz) <= r, (-r, -r, -r))


@st.composite
def voxel_sets(draw: st.DrawFn, side: int = 3) -> VoxelSet:
    bits = draw(st.lists(st.booleans(), min_size=side**3, max_size=side**3))
    origin = draw(st.tuples(*[st.integers(-3, 3)] * 3))
    return VoxelSet(np.array(bits, dtype=bool).reshape(side, side, side), origin)


def _exact_triangles(poly, matrix, centre) -> list:  # type: ignore[no-untyped-def]
    """The triangles of T(P), T(v) = C + M·(v − C), with exact rational vertices (for the oracle).

    Written out here, not with the library's maps, so that the oracle shares nothing with the code tested.
    """
    c = [Fraction(x) for x in (centre or (0, 0, 0))]

    def image(p):  # type: ignore[no-untyped-def]
        d = [Fraction(float(x)) - c[k] for k, x in enumerate(p)]
        return tuple(c[i] + sum(Fraction(matrix[i][k]) * d[k] for k in range(3)) for i in range(3))

    return [[image(poly.vertices[i]) for i in tri] for tri in poly.triangles]


# ------------------------------------------------------------------------------------------ exact results
@settings(max_examples=25, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(voxel_sets(), st.sampled_from(MODELS))
def test_dss_1_gives_every_voxel_set_back(a: VoxelSet, model: str) -> None:
    # D(Sc_1(R(A))) = D(R(A)) = A: the continuation contract, through the operation (§11 item 3)
    assert run_operation("dss", [a], {"alpha": 1, "model": model}).output == a


@pytest.mark.parametrize("model", MODELS)
@pytest.mark.parametrize("axis", [(1, 0, 0), (0, 1, 0), (0, 0, 1), (0, 0, -2)])
@pytest.mark.parametrize("quarters", [1, 2, 3])
def test_a_quarter_turn_about_a_coordinate_axis_is_the_exact_permutation(model, axis, quarters):
    a = VoxelSet.from_points([(0, 0, 0), (1, 0, 0), (2, 0, 0), (2, 1, 0), (2, 1, 3), (-1, 2, 1)])
    centre = (1, 1, 0)
    out = run_operation(
        "discrete_rotation", [a], {"angle": 90 * quarters, "axis": axis, "center": centre, "model": model}
    ).output
    k = quarters if sum(axis) > 0 else -quarters  # counter-clockwise seen from the axis's tip
    assert out == a.rotate90(k, axis=next(i for i in range(3) if axis[i]), center=centre)


@settings(max_examples=12, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(
    voxel_sets(side=2),
    st.sampled_from(MODELS),
    st.sampled_from([Fraction(1, 2), Fraction(1, 5), Fraction(4, 5), Fraction(5, 4), Fraction(3, 2)]),
    st.sampled_from([None, (0, 0, 0), (1, 0, 2), (Fraction(1, 3), 0, Fraction(1, 2))]),
)
def test_dss_of_a_voxel_set_is_the_definition_on_the_exact_image(a, model, alpha, centre):
    """DSS_α(A) = D(Sc_α(R(A))) with nothing rounded: the oracle evaluates D on the rational image."""
    out = run_operation("dss", [a], {"alpha": alpha, "center": centre, "model": model}).output
    scale = [[alpha if i == k else 0 for k in range(3)] for i in range(3)]
    image = _exact_triangles(reconstruct(a, model), scale, centre)
    assert voxel_set(out.mask, out.origin) == reference_voxelize(image, model, solid=True)


def test_a_rotation_about_a_tilted_axis_is_the_definition_on_its_exact_image():
    a = VoxelSet.box(0, 0, 0, 2, 1, 1)
    for model in MODELS:
        out = mrm.rotate(a, 30, (1, 0, 0), model, axis=(1, 1, 1))
        image = _exact_triangles(reconstruct(a, model), rotation_matrix(Fraction(30), (1, 1, 1)), (1, 0, 0))
        assert voxel_set(out.mask, out.origin) == reference_voxelize(image, model, solid=True), model


def test_the_rotation_applied_is_within_its_stated_stretch_and_angle():
    for theta, axis in ((30, (1, 1, 1)), (-72.5, (0, 2, 1)), (10, (0, 0, 1)), (135, (1, 0, 0))):
        m = np.array([[float(x) for x in row] for row in rotation_matrix(Fraction(theta), axis)])
        assert all(x * 2**ROTATION_BITS == int(x * 2**ROTATION_BITS) for x in m.ravel())  # dyadic entries
        lo, hi = Similarity3.rotation(Fraction(theta), None, axis).stretch
        sv = np.linalg.svd(m, compute_uv=False)
        assert float(lo) - 1e-15 <= sv.min() and sv.max() <= float(hi) + 1e-15
        assert hi - lo < Fraction(1, 2**27)
        u = np.array(axis, dtype=float) / np.linalg.norm(axis)
        # the angle of the map: the axis is (almost) fixed and the trace is 1 + 2 cos θ
        assert np.allclose(m @ u, u, atol=1e-8)
        assert math.isclose((np.trace(m) - 1) / 2, math.cos(math.radians(theta)), abs_tol=1e-8)


# ------------------------------------------------------------------------------------------ bounds and chains
def test_the_paper_figure_12_chain_on_an_octahedron_is_within_sqrt3_times_its_coefficient():
    from mrm.document import Document
    from mrm.document.apply import apply_operation
    from mrm.document.commands import AddObject

    doc = Document()
    obj = doc.make_object(_octahedron(4), "A")
    doc.push(AddObject(obj))
    cur = obj.id
    for alpha in ("1.25", "5", "0.2", "0.8"):
        (cur,) = apply_operation(doc, "dss", [cur], {"alpha": alpha})
    acc = account_of(doc.get(cur).provenance)
    # √n · Σ_{i=2..k} Π_{j=i..k} s_j with s = (5/4, 5, 1/5, 4/5), n = 3 (docs/design.md §8, §11)
    s = [Fraction(5, 4), Fraction(5), Fraction(1, 5), Fraction(4, 5)]
    assert acc.bound.coefficient == s[1] * s[2] * s[3] + s[2] * s[3] + s[3]
    assert acc.bound.n == 3 and acc.bound.bound == pytest.approx(float(acc.bound.coefficient) * math.sqrt(3))
    lo, hi = acc.measured.intervals["both"]
    assert 0 < lo <= hi <= acc.bound.bound and acc.within_bound is True
    assert acc.measured.value == hi  # the number shown is the certified upper end


def test_inputs_of_both_dimensions_are_refused_in_one_line():
    a = _octahedron(2)
    with pytest.raises(ParameterError, match="mix 2D and 3D"):
        run_operation("union", [a, mrm.PixelSet.box(0, 0, 1, 1)], {})


def test_a_centre_of_the_wrong_dimension_is_refused_naming_the_parameter():
    with pytest.raises(ParameterError, match=r"'center'.*3 numbers"):
        mrm.scale(_octahedron(2), 2, (1, 1))
    with pytest.raises(ParameterError, match=r"'center'.*2 numbers"):
        mrm.scale(mrm.PixelSet.box(0, 0, 1, 1), 2, (1, 1, 1))
    with pytest.raises(ParameterError, match="turns about the z axis"):
        mrm.rotate(mrm.PixelSet.box(0, 0, 1, 1), 30, axis=(1, 0, 0))


# ------------------------------------------------------------------------------------------ command line
def _cli(argv: list[str]) -> dict:
    out = io.StringIO()
    with contextlib.redirect_stdout(out):
        assert run_cli(argv) == 0
    return json.loads(out.getvalue())


def test_mrm_scale_on_a_voxel_file_prints_the_api_account_and_writes_the_api_result(tmp_path):
    a = _octahedron(3)
    src = tmp_path / "a.npz"
    write_voxels(a, src)
    out = tmp_path / "o.npz"
    cli = _cli(["scale", str(src), "--alpha", "0.2", "--center", "1,1,1", "-o", str(out), "--json"])
    assert read_voxels(out) == mrm.scale(a, "0.2", (1, 1, 1))
    assert cli["voxels"] == len(read_voxels(out))
    prov = Provenance("dss", {"alpha": 0.2, "center": [1, 1, 1], "model": "standard"}, (0,), (a,), (None,))
    assert cli["account"] == json.loads(json.dumps(account_of(prov).summary()))


def test_mrm_rotate_writes_the_mesh_of_the_rotated_voxels(tmp_path):
    a = VoxelSet.from_points([(0, 0, 0), (1, 0, 0), (1, 1, 0), (1, 1, 1)])
    src = tmp_path / "a.npz"
    write_voxels(a, src)
    mesh = tmp_path / "o.obj"
    _cli(["rotate", str(src), "--angle", "90", "--axis", "1,0,0", "-o", str(mesh), "--json"])
    # the mesh is R of the result: voxelized again it gives the result, the exact quarter turn of A
    assert mrm.discretize(mrm.read_mesh(mesh), "standard") == a.rotate90(1, axis=0)


# ------------------------------------------------------------------------------------------ Sp_α in 3D
@pytest.mark.parametrize("model", MODELS)
@pytest.mark.parametrize("alpha", ["1/2", "1/3", "2/3"])
def test_sp_of_a_voxel_ball_is_idempotent_and_within_sqrt3_over_alpha(model, alpha):
    """Sp_α(E) = Sc_1/α(R(D(Sc_α(E)))) of R(A) (Theorem 15 with n = 3: H ≤ √3/α for the covers)."""
    z, y, x = np.mgrid[-5:6, -5:6, -5:6]
    a = VoxelSet(x**2 + y**2 + z**2 <= 25, (-5, -5, -5))
    sp = mrm.simplify(a, alpha, model=model)
    assert isinstance(sp, mrm.Polyhedron)
    # D(Sc_α(Sp_α(E))) is the coarse voxel set Sp_α went through: Sp_α(Sp_α(E)) = Sp_α(E)
    assert mrm.simplify(sp, alpha, model=model) == sp
    prov = Provenance("simplify", {"alpha": alpha, "center": None, "model": model}, (0,), (a,), (None,))
    acc = account_of(prov)
    assert acc.idempotent is True and acc.bound.n == 3
    assert acc.bound.coefficient == 1 / Fraction(alpha)
    lo, hi = acc.measured.intervals["both"]
    if model != "gauss":  # a partition model keeps the one-sided bound only (docs/design.md §8)
        assert hi <= float(1 / Fraction(alpha)) * math.sqrt(3) and acc.within_bound is True
    assert lo > 0  # the ball was simplified: something moved


def test_sp_with_an_alpha_whose_result_is_not_float64_is_refused_in_one_line():
    with pytest.raises(ParameterError, match="numerator is a power of two"):
        mrm.simplify(VoxelSet.box(0, 0, 0, 4, 4, 4), "0.3")
