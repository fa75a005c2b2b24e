"""Discrete smooth scaling DSS_α(A) = D(Sc_α(R(A))) (the paper's Definition 3, docs/design.md §8).

The continuation R(A) has float64 (dyadic) vertices; ``Sc_α`` about the centre C (the origin by default, as
in the paper) maps a vertex v to ``C + α·(v − C)``, computed exactly with rationals
(:mod:`mrm.geometry.discretize.exact_shape`: α = 0.2 means 1/5), and the image is discretized exactly
(:mod:`mrm.geometry.discretize.rational`). So ``DSS_α(A) = D(Sc_α(R(A)))`` holds exactly, for every α > 0 —
not only for the powers of two whose products happen to be float64 values.

The size of the result is estimated from A's bounding box before anything is computed: α = 10⁶ on a large
object is refused at once, with the number of pixels it would have had.
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
from mrm.geometry.discretize.exact_solid import scaling_map
from mrm.ops.declare import alpha_param, center_param, model_param
from mrm.ops.outcome import StepOutcome, register_discrete_similarity


@dataclass(frozen=True)
class DSSParams(Parameters):
    """Parameters of DSS_α: α (read exactly), the centre, the model."""

    alpha: Fraction = alpha_param(
        2, "Scale factor α, read exactly (0.2 is 1/5); the result's size is checked before running."
    )
    center: Point | None = center_param("Centre of the scaling (default: origin).")
    model: Model = model_param()


NAME = "dss"
#: DSS_α, declared once: the panel, the CLI, the chain, the bound rule and the account read this spec.
SPEC = register_discrete_similarity(
    name=NAME,
    title="Discrete smooth scaling DSS_α",
    params=DSSParams,
    similarity=lambda p, n=2: scaling_map(p.alpha, p.center, n),
    symbol="DSS",
    result_name=lambda p: f"DSS {spell(p.alpha)}",
    what=lambda p: f"DSS with α = {spell(p.alpha)}",
    help="DSS_α(A) = D(Sc_α(R(A))): scale the continuation exactly and discretize it (paper, Def. 3).",
    aliases=("discrete_smooth_scaling", "smooth_scaling"),
    grid="scaled",
    command="scale",
)
#: Run DSS_α on one object (a polygon input is read as its discretization D(E)); no validation or provenance.
run = SPEC.run


def discrete_smooth_scaling(
    ps: PixelSet,
    alpha: object,
    center: object = None,
    model: Model | str = Model.STANDARD,
    *,
    limit: int | None = DEFAULT_PIXEL_LIMIT,
    progress: ProgressLike | None = None,
) -> StepOutcome:
    """Return DSS_α(A) = D(Sc_α(R(A))), computed exactly.

    Parameters
    ----------
    ps : PixelSet
        The discrete object A.
    alpha : number
        The scale factor α > 0 (a float is read as the decimal it prints as; Fractions and ``"p/q"`` too).
    center : pair of numbers, optional
        The centre of the scaling (the origin by default).
    model : Model or str
        The discretization model of D and R.
    limit : int or None
        Largest result (pixels of its bounding box); estimated from A's bounding box before running.
    progress : object with ``update(fraction, message)``, optional
        Reports progress; its ``Cancelled`` propagates (nothing is changed: the result is a new value).

    Returns
    -------
    StepOutcome
        ``result`` (the pixel set), ``transform`` (Sc_α), ``euclidean`` (Sc_α(R(A)) exactly: A_last when
        this is the last step of a chain).

    Raises
    ------
    ParameterError
        α ≤ 0, NaN, infinite or not a number; a bad centre or model.
    SizeLimitError
        The result would exceed ``limit`` pixels (the message gives its estimated size).
    """
    return SPEC.outcome(
        ps, DSSParams.read(alpha=alpha, center=center, model=model), limit=limit, progress=progress
    )
