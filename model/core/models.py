"""The discretization model: one enum for the whole product (docs/design.md §2).

A model fixes the kernel K(p) of every pixel p, and D(E) = { p : E ∩ K(p) ≠ ∅ }:

* ``standard`` (the default, ADR 0001): the open unit square shifted by an infinitesimal τ — Andres' standard
  analytical model, no bubbles, a cover;
* ``supercover``: the closed unit square — symmetric, a cover, with bubbles;
* ``gauss``: the centre, perturbed by τ — a partition of the plane's pixels among the tiles of a tiling.

Every layer that takes a model takes a :class:`Model` (a ``str`` enum, so ``Model.GAUSS == "gauss"`` and JSON
writes it as its name); text from a file, a command line or a form is read once by :meth:`Model.parse`.

The tie rule of a point lives here too, because every model and every view uses it: a point goes to the one
pixel whose half-open cell (k − ½, k + ½] holds each of its coordinates (:func:`cell_index`), in any
dimension.
"""

from __future__ import annotations

import math
from enum import StrEnum
from fractions import Fraction

from mrm.core.errors import ParameterError
from mrm.core.numbers import value_text

__all__ = ["DEFAULT_MODEL", "Model", "cell_index", "cell_of"]


class Model(StrEnum):
    """A discretization model (docs/design.md §2).

    Examples
    --------
    >>> Model.parse(" Gauss ")
    <Model.GAUSS: 'gauss'>
    >>> Model.STANDARD.is_cover, Model.GAUSS.is_cover
    (True, False)
    """

    STANDARD = "standard"
    SUPERCOVER = "supercover"
    GAUSS = "gauss"

    @property
    def is_cover(self) -> bool:
        """True for the covers (``standard``, ``supercover``): E ⊂ V(D(E)); the bounds hold both ways."""
        return self is not Model.GAUSS

    @property
    def kernel(self) -> str:
        """The kernel K(p) in words, for forms and help texts."""
        return _KERNELS[self]

    @classmethod
    def parse(cls, value: object, what: str = "discretization model") -> Model:
        """The model ``value`` names (a Model, or its name in any case with spaces around).

        Raises
        ------
        ParameterError
            For anything else, listing the models.
        """
        if isinstance(value, Model):
            return value
        if isinstance(value, str):
            key = value.strip().lower()
            for m in cls:
                if m.value == key:
                    return m
        names = ", ".join(m.value for m in cls)
        raise ParameterError(f"unknown {what} {value_text(value)}; choose one of {names}")

    @classmethod
    def names(cls) -> tuple[str, ...]:
        """The models' names, in declaration order (``standard`` first: the default)."""
        return tuple(m.value for m in cls)


_KERNELS = {
    Model.STANDARD: "open square shifted by τ (no bubbles, the default)",
    Model.SUPERCOVER: "closed square",
    Model.GAUSS: "centre (a partition)",
}

#: The model of a new document, of the command line and of the library when none is given (ADR 0001).
DEFAULT_MODEL = Model.STANDARD


def cell_index(u: float | Fraction) -> int:
    """The integer k with u ∈ (k − ½, k + ½], exactly: the pixel index of a coordinate.

    A coordinate on a cell side (a half-integer) goes to the cell below it — the side is that cell's right
    or top side. This is the standard model's rule for a point (docs/design.md §2) and the one rule every
    view uses for "the pixel under the cursor".

    Parameters
    ----------
    u : float or Fraction
        A finite coordinate.
    """
    if isinstance(u, Fraction):
        return math.ceil(u - Fraction(1, 2))
    k = math.floor(u + 0.5)  # may be off by one after rounding; fixed below with exact comparisons
    while u > k + 0.5:
        k += 1
    while u <= k - 0.5:
        k -= 1
    return k


def cell_of(point: tuple[float, ...]) -> tuple[int, ...]:
    """The pixel (or voxel) whose half-open cell holds ``point``: :func:`cell_index` of each coordinate."""
    return tuple(cell_index(u) for u in point)
