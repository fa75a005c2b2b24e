"""Discrete-Euclidean rotation dR_θ,C(A) = D(rot_θ,C(R(A))) (the paper's Definition 11, docs/design.md §8).

What "rotation" means for float input
-------------------------------------
cos θ and sin θ are irrational for almost every angle, so no implementation applies the exact rot_θ,C to
float vertices. Here rot_θ,C is the **exact rational rotation** of
:func:`mrm.geometry.discretize.exact_shape.rotation_cos_sin`: θ is reduced to (−45°, 45°] by exact quarter
turns, and
``c = (1 − t²)/(1 + t²)``, ``s = 2t/(1 + t²)`` with ``t`` the float64 value of tan(θ/2) read exactly. It is an
exact isometry (c² + s² = 1) whose angle is θ up to one float64 rounding (< 10⁻¹⁵ radian). The rotated
vertices are rational and discretized exactly — nothing is rounded between R and D — so the error bounds of
the paper (Theorems 12 and 13) hold for the rotation actually applied, and every result is reproducible
bit for bit.

Multiples of 90° are exact quarter turns (t = 0): about a pixel centre C they map pixel corners to pixel
corners, and since R keeps its boundary away from every tie (docs/design.md §3.6), dR_90k,C(A) = rot_90k,C(A)
exactly.
"""

from __future__ import annotations

from dataclasses import dataclass
from fractions import Fraction

from mrm.core.grids import PixelSet
from mrm.core.limits import DEFAULT_PIXEL_LIMIT
from mrm.core.models import Model
from mrm.core.numbers import Point, spell
from mrm.core.params import Parameters
from mrm.core.progress import ProgressLike
from mrm.geometry.discretize.exact_solid import rotation_map
from mrm.ops.declare import angle_param, axis_param, center_param, model_param
from mrm.ops.outcome import StepOutcome, register_discrete_similarity


@dataclass(frozen=True)
class RotationParams(Parameters):
    """Parameters of dR_θ,C: θ in degrees (read exactly), the centre C, the model, the axis (3D)."""

    angle: Fraction = angle_param(
        30, "Rotation angle in degrees, counter-clockwise; multiples of 90° about a pixel centre are exact."
    )
    center: Point | None = center_param("Centre C of the rotation (default: origin).")
    model: Model = model_param()
    axis: Point | None = axis_param(
        "3D only: the axis, three numbers (default z); quarter turns about x, y or z are exact."
    )


NAME = "discrete_rotation"
#: dR_θ,C, declared once: the panel, the CLI, the chain, the bound rule and the account read this spec.
SPEC = register_discrete_similarity(
    name=NAME,
    title="Discrete-Euclidean rotation dR_θ,C",
    params=RotationParams,
    similarity=lambda p, n=2: rotation_map(p.angle, p.center, p.axis, n),
    symbol="ROT",
    result_name=lambda p: f"dR {spell(p.angle)}°",
    what=lambda p: f"dR with θ = {spell(p.angle)}°",
    help="dR_θ,C(A) = D(rot_θ,C(R(A))): rotate the continuation exactly, discretize it (paper, Def. 11).",
    aliases=("dR", "rotation"),
    grid="same",
    command="rotate",
)
#: Run dR_θ,C on one object (a polygon input is read as its discretization D(E)); no validation or provenance.
run = SPEC.run


def discrete_rotation(
    ps: PixelSet,
    angle: object,
    center: object = None,
    model: Model | str = Model.STANDARD,
    *,
    limit: int | None = DEFAULT_PIXEL_LIMIT,
    progress: ProgressLike | None = None,
) -> StepOutcome:
    """Return dR_θ,C(A) = D(rot_θ,C(R(A))) with the exact rational rotation (module docstring).

    Parameters
    ----------
    ps : PixelSet
        The discrete object A.
    angle : number
        θ in degrees, counter-clockwise (y up); any finite value.
    center : pair of numbers, optional
        The centre C (the origin by default).
    model : Model or str
        The discretization model of D and R.
    limit : int or None
        Largest result (pixels of its bounding box), estimated before running.
    progress : object with ``update(fraction, message)``, optional
        Reports progress; its ``Cancelled`` propagates.

    Returns
    -------
    StepOutcome
        ``result`` (the pixel set), ``transform`` (the rotation), ``euclidean`` (rot_θ,C(R(A)), exact).

    Raises
    ------
    ParameterError
        A non-finite angle, a bad centre or model.
    SizeLimitError
        The result would exceed ``limit`` pixels.
    """
    params = RotationParams.read(angle=angle, center=center, model=model)
    return SPEC.outcome(ps, params, limit=limit, progress=progress)
