"""The parameters the paper's operations share, declared once: the model, a factor α, an angle θ, a centre.

Each is a :func:`mrm.core.params.param` field with its range, unit and help; an operation's parameters
dataclass lists the ones it takes. The ranges are the product's, not the mathematics': beyond them a result is
below one pixel or beyond any pixel limit, and the exact arithmetic would only spend time.
"""

from __future__ import annotations

from fractions import Fraction
from typing import Any

from mrm.core.models import DEFAULT_MODEL, Model
from mrm.core.params import param

__all__ = [
    "ALPHA_MAX",
    "ALPHA_MIN",
    "ANGLE_LIMIT",
    "alpha_param",
    "angle_param",
    "axis_param",
    "center_param",
    "model_param",
]

#: The range of every scale and precision factor α (DSS_α, Sp_α, EDco_α, the Euclidean scale).
ALPHA_MIN, ALPHA_MAX = Fraction(1, 10**6), Fraction(10**6)
#: The range of every rotation angle, in degrees (ten turns either way).
ANGLE_LIMIT = Fraction(3600)


def model_param() -> Any:
    """The ``model`` field every operation that discretizes carries: the model of D and R."""
    return param(
        DEFAULT_MODEL,
        kind="model",
        choices=tuple(Model),
        label="model",
        help="Discretization model of D and R.",
    )


def alpha_param(default: Any, help: str, *, optional: bool = False, label: str = "α") -> Any:
    """A factor with its declared range [ALPHA_MIN, ALPHA_MAX], read exactly (0.2 is 1/5).

    A chain's text writes it after the operation's name (``DSS 5``).
    """
    return param(
        default,
        kind="number",
        label=label,
        unit="×",
        minimum=ALPHA_MIN,
        maximum=ALPHA_MAX,
        optional=optional,
        positional=True,
        help=help,
    )


def angle_param(default: Any, help: str) -> Any:
    """A rotation angle in degrees with its declared range [−ANGLE_LIMIT, ANGLE_LIMIT] (``ROT 30``)."""
    return param(
        default,
        kind="number",
        label="θ",
        unit="°",
        minimum=-ANGLE_LIMIT,
        maximum=ANGLE_LIMIT,
        positional=True,
        help=help,
    )


def center_param(help: str, *, default: Any = None) -> Any:
    """A centre (a point; None means the origin), written ``about x,y`` (``about x,y,z`` in 3D) in a chain.

    Two or three coordinates: the operation checks them against its inputs' dimension.
    """
    return param(
        default, kind="point", optional=default is None, label="centre", unit="px", help=help, dimension=0
    )


def axis_param(help: str) -> Any:
    """The axis of a 3D rotation (three numbers, not all zero; None means the z axis)."""
    return param(None, kind="point", optional=True, label="axis", help=help, dimension=3)
