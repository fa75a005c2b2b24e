"""The measured error of an operation or a chain, and the pixels that differ from the direct result.

Measured error (docs/design.md §8)
--------------------------
The paper bounds ``H(T(A_first), A_last)``: the Hausdorff distance between the composite Euclidean transform
of the first Euclidean object and the Euclidean object just before the last discretization. Both are exact
rational polygons here (:class:`~mrm.geometry.discretize.exact_shape.ExactShape`); the distance is computed
by the exact
:mod:`mrm.geometry.hausdorff` on float64 input, so both shapes are first scaled by the odd part ``L`` of the
common denominator of their coordinates, which makes every coordinate dyadic. When the scaled coordinates are
float64 values (always, unless the denominators are huge, e.g. after non-right-angle rotations) the distance
and its comparison with a bound are exact (:attr:`MeasuredError.exact`); otherwise the coordinates are
rounded once to float64 and the distance is exact for the rounded (unscaled) shapes.

Both directed distances are kept: ``result_within`` = h(A_last, T(A_first)) (every point of the result is
that close to the transformed source — the one direction ``gauss`` guarantees) and ``source_within`` =
h(T(A_first), A_last).

Differing pixels (the paper's Fig. 12)
--------------------------------------
:func:`differing_pixels` compares a result with the direct result (the reference): **light grey** are the
pixels in the result but not in the reference, **dark grey** those in the reference but not in the result.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from fractions import Fraction
from typing import Any, Literal

from mrm.core.progress import ProgressLike
from mrm.geometry.discretize.exact_shape import ExactShape, Similarity
from mrm.geometry.discretize.exact_solid import ExactSolid
from mrm.geometry.hausdorff import directed_hausdorff

Direction = Literal["both", "result_within", "source_within"]


@dataclass(frozen=True)
class MeasuredError:
    """The measured Hausdorff distance between T(A_first) and A_last.

    Attributes
    ----------
    value : float
        ``H(T(A_first), A_last)`` (``inf`` when exactly one of them is empty).
    result_within : float
        ``h(A_last, T(A_first))``: every point of A_last lies within it of T(A_first).
    source_within : float
        ``h(T(A_first), A_last)``: every point of T(A_first) lies within it of A_last.
    exact : bool
        True when no coordinate was rounded: the values are the floats nearest to the exact distances
        and :meth:`exceeds` decides exactly.
    intervals : dict or None
        Between solids (3D), certified enclosures ``(lo, hi)`` of the distances instead of exact values:
        ``{"both": …, "result_within": …, "source_within": …}``; the three floats above are then the upper
        ends (docs/adr/0059). None for polygons, whose distances are exact.
    """

    value: float
    result_within: float
    source_within: float
    exact: bool
    _scale: Fraction = field(repr=False, compare=False)
    _result: Any = field(repr=False, compare=False)
    _source: Any = field(repr=False, compare=False)
    intervals: dict[str, tuple[float, float]] | None = None

    def exceeds(self, coefficient: Fraction | int, n: int = 2, direction: Direction = "both") -> bool | None:
        """Is the distance greater than ``coefficient · √n`` (the form of every bound)? Exact.

        ``direction`` picks the two-sided distance (``both``) or one directed distance. None when a
        certified enclosure (3D) holds the bound: neither answer is proven.
        """
        if self.intervals is not None:
            lo, hi = self.intervals[direction]
            c2n = Fraction(coefficient) ** 2 * n  # lo > c√n ⟺ lo² > c²n (both sides ≥ 0): exact on floats
            if lo > 0 and Fraction(lo) ** 2 > c2n:
                return True
            if math.isfinite(hi) and Fraction(hi) ** 2 <= c2n:
                return False
            return None
        c = Fraction(coefficient) * self._scale
        if self._result is None:  # identical shapes: the distance is 0
            return c < 0
        hs = {
            "both": (self._result, self._source),
            "result_within": (self._result,),
            "source_within": (self._source,),
        }
        return any(h.exceeds_sqrt_multiple(c, n) for h in hs[direction])

    def as_dict(self) -> dict[str, Any]:
        """A JSON-ready summary (infinite distances become None)."""

        def num(v: float) -> float | None:
            return v if math.isfinite(v) else None

        out: dict[str, Any] = {
            "measured": num(self.value),
            "result_within": num(self.result_within),
            "source_within": num(self.source_within),
            "exact": self.exact,
        }
        if self.intervals is not None:
            for key, (lo, hi) in self.intervals.items():
                out[f"{'measured' if key == 'both' else key}_interval"] = [num(lo), num(hi)]
        return out


def _odd_denominator(shapes: tuple[ExactShape, ...]) -> int:
    den = 1
    for s in shapes:
        for c in s.coordinates():
            d = c.denominator
            d //= d & -d  # drop the power of two: dyadic coordinates are float64-friendly already
            den = math.lcm(den, d)
    return den


def measured_error(
    reference: ExactShape | Any, result: ExactShape | Any, *, progress: ProgressLike | None = None
) -> MeasuredError:
    """Return the measured error between ``reference`` = T(A_first) and ``result`` = A_last.

    Parameters
    ----------
    reference, result : ExactShape or shapely Polygon / MultiPolygon
        The two Euclidean objects (valid polygonal sets).
    progress : object with ``update(fraction, message)``, optional
        Passed to the Hausdorff computation; its ``Cancelled`` propagates.
    """
    if isinstance(reference, ExactSolid) or isinstance(result, ExactSolid):
        return measured_solid_error(ExactSolid.of(reference), ExactSolid.of(result), progress=progress)
    ref = reference if isinstance(reference, ExactShape) else ExactShape.from_geometry(reference)
    res = result if isinstance(result, ExactShape) else ExactShape.from_geometry(result)
    if ref == res:  # the same polygons, vertex for vertex (e.g. a single DSS: A_last = T(A_first))
        return MeasuredError(0.0, 0.0, 0.0, True, Fraction(1), None, None)
    scale = _odd_denominator((ref, res))
    sim = Similarity.scaling(Fraction(scale))
    ref_s, res_s = ref.map(sim), res.map(sim)
    exact = ref_s.is_float_exact() and res_s.is_float_exact()
    if not exact:  # huge denominators: round the shapes themselves once, unscaled
        scale, ref_s, res_s = 1, ref, res
    g_ref, g_res = ref_s.to_geometry(), res_s.to_geometry()
    h_res = directed_hausdorff(g_res, g_ref, progress=progress)
    h_src = directed_hausdorff(g_ref, g_res, progress=progress)
    rw = h_res.value / scale
    sw = h_src.value / scale
    return MeasuredError(max(rw, sw), rw, sw, exact, Fraction(scale), h_res, h_src)


def measured_solid_error(
    reference: ExactSolid, result: ExactSolid, *, progress: ProgressLike | None = None
) -> MeasuredError:
    """The measured error between two exact solids: certified enclosures (docs/adr/0059).

    The exact images are rounded to float64 once (:meth:`ExactSolid.float_vertices`, which bounds the
    rounding), and :func:`mrm.geometry.hausdorff.solids.solid_hausdorff` encloses both directed distances,
    widened by that rounding.
    """
    if reference == result:  # the same solid under the same map: the distance is 0, exactly
        return MeasuredError(0.0, 0.0, 0.0, True, Fraction(1), None, None)
    from mrm.geometry.hausdorff.solids import solid_hausdorff  # 3D kernels: loaded when a solid is met

    rv, r_err = reference.float_vertices()
    sv, s_err = result.float_vertices()
    h = solid_hausdorff(
        sv,
        result.base.triangles,
        rv,
        reference.base.triangles,
        vertex_error=max(r_err, s_err),
        progress=progress,
    )
    intervals = {"both": h.value, "result_within": h.a_within, "source_within": h.b_within}
    return MeasuredError(
        h.value[1], h.a_within[1], h.b_within[1], h.exact, Fraction(1), None, None, intervals
    )


@dataclass(frozen=True)
class PixelDifference:
    """The pixels where a result and the direct result (the reference) differ (the paper's Fig. 12).

    Attributes
    ----------
    light : PixelSet or VoxelSet
        Light grey: in the result but not in the reference.
    dark : PixelSet or VoxelSet
        Dark grey: in the reference but not in the result.
    """

    light: Any
    dark: Any

    @property
    def count(self) -> int:
        """The number of differing pixels."""
        return len(self.light) + len(self.dark)

    def as_dict(self) -> dict[str, int]:
        """Counts for a JSON summary."""
        return {"light": len(self.light), "dark": len(self.dark)}


def differing_pixels(result: Any, reference: Any) -> PixelDifference:
    """Light grey = ``result ∖ reference``, dark grey = ``reference ∖ result``."""
    return PixelDifference(result - reference, reference - result)
