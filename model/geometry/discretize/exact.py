"""Exact helpers for float64 geometry on the pixel grid (docs/design.md §2, docs/algorithms.md §1.6).

Every float64 is a dyadic rational, so every decision here is made exactly: either with float comparisons
that cannot round (comparing a float with a half-integer that is itself a float), or with an argument that
a given float computation is free of rounding. Nothing here uses an epsilon.

The pixel p = (i, j) is centred on (i, j). Its *standard cell* is the half-open square
(i − ½, i + ½] × (j − ½, j + ½]: the cells partition the plane and a point belongs to exactly one of them
(:func:`mrm.core.models.cell_index`, the one tie rule of the product).
"""

from __future__ import annotations

import numpy as np
import numpy.typing as npt

from mrm.core.models import cell_index

#: Largest supported |coordinate|. Beyond it pixel indices and half-integers stop being exact floats
#: (2^53 is the last integer with a unit gap), and the exact predicates need a little headroom.
MAX_ABS_COORD = 2.0**51

#: Smallest supported non-zero |coordinate|. The exact fallback multiplies differences of coordinates;
#: below this bound those products could underflow and lose bits (see ._kernels).
MIN_ABS_COORD = 2.0**-400

#: Half-width, in units of the coarsest common dyadic step, under which products of coordinate
#: differences are exact in float64 (see :func:`float_predicates_are_exact`).
_EXACT_UNITS = 2.0**25

#: The same bound for 3×3 determinants: differences below 2L, products of three below 8L³, and the sums of
#: Shewchuk's orient3d form below 48L³ ≤ 2^53.
EXACT_UNITS_3D = 2.0**15


def closed_cell_range(u: float) -> tuple[int, int]:
    """Return (lo, hi): the indices k whose closed interval [k − ½, k + ½] holds ``u`` (one or two)."""
    k = cell_index(u)
    return (k, k + 1) if u == k + 0.5 else (k, k)


def check_coordinate_range(values: npt.NDArray[np.float64]) -> tuple[int, float] | None:
    """Return (index, value) of the first coordinate outside the supported range, or None.

    Supported: finite, |v| ≤ :data:`MAX_ABS_COORD`, and v = 0 or |v| ≥ :data:`MIN_ABS_COORD`.
    """
    a = np.abs(values)
    bad = ~np.isfinite(values) | (a > MAX_ABS_COORD) | ((a < MIN_ABS_COORD) & (a != 0.0))
    if not bad.any():
        return None
    i = int(np.flatnonzero(bad)[0])
    return i, float(values[i])


def float_predicates_are_exact(
    values: npt.NDArray[np.float64], units: float = _EXACT_UNITS, *, step: int = 1
) -> bool:
    """True when plain float64 evaluation of the grid predicates is free of rounding.

    Let 2^-K be the coarsest dyadic step that every value (and the half-integers of the grid) is a multiple
    of, u = 2^-(K+1), and L = (max |v| + 2·step) / u. Grid points used by the kernels (integers and
    half-integers within one pixel of the data, on the grid of that step) are multiples of u below L·u in
    magnitude. When
    L ≤ 2^25, differences of such numbers are integers below 2^26 in units of u, products of two
    differences are below 2^52 in units of u², and a difference of two products is below 2^53 u²: all of
    them are exact float64 values. Orientation signs computed in plain float arithmetic are then exact,
    including the zero (tie) cases. Typical for snapped input (integers, half-integers, 2^-k grids).

    Parameters
    ----------
    values : ndarray of float64
        All coordinates of a geometry (already checked finite and in range).
    units : float
        The bound on L; the default fits the 2×2 determinants of 2D. The 3×3 determinants of 3D (products of
        three differences, sums of six such products) need L ≤ 2^15 (``EXACT_UNITS_3D``).
    step : int
        The grid step (a positive integer): pixels of side ``step`` centred on step·p, whose grid points
        step·p ± step/2 reach ``step`` times farther from the data.
    """
    v = values[values != 0.0]
    if v.size == 0:
        return True
    mant, expo = np.frexp(np.abs(v))  # |v| = mant · 2^expo, mant ∈ [0.5, 1)
    m = (mant * 2.0**53).astype(np.int64)  # exact: a 53-bit integer
    low_bit = m & -m  # the lowest set bit of each mantissa
    tz = np.log2(low_bit.astype(np.float64)).astype(np.int64)  # exact for powers of two
    # |v| = (m >> tz) · 2^(expo − 53 + tz): the number of fractional bits is 53 − expo − tz.
    k = max(0, int((53 - expo.astype(np.int64) - tz).max()))
    if k > 60:
        return False
    return (float(np.abs(v).max()) + 2.0 * step) * 2.0 ** (k + 1) <= units
