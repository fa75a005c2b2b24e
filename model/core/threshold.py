"""How the samples of an imported grey or colour image become a pixel set.

The rules, in order (``binarize``):

1. Colour samples become a luminance first, with the integer ITU-R BT.601 weights Pillow uses for its "L"
   conversion: ``L = (19595·R + 38470·G + 7471·B + 32768) >> 16`` (exact, at any bit depth).
2. An alpha channel marks transparent pixels (alpha 0) as background. When the visible pixels all have the
   same luminance, the picture is in the alpha channel alone (a black or white shape on a transparent
   layer), so the alpha values are used as the grey image; otherwise the image is composited over black,
   ``round(L·alpha / maxalpha)``.
3. A binary image — its values are 0 and at most one other value — is not thresholded: non-zero is in the set.
   With an explicit ``threshold`` every grey image is cut at it instead.
4. Otherwise the threshold t is Otsu's (``otsu_threshold``), computed exactly on the integer histogram.

A pixel is in the set when its value is **greater than** t (``value > t``), so bright pixels are the object,
consistently with "non-zero = in the set" for binary images.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np
import numpy.typing as npt

from mrm.core.errors import ParameterError
from mrm.core.numbers import value_text

BoolArray = npt.NDArray[np.bool_]

# Pillow's fixed-point BT.601 luminance weights (they sum to 2**16).
_LUMA_WEIGHTS = (19595, 38470, 7471)


def luminance(rgb: npt.NDArray[Any]) -> npt.NDArray[np.int64]:
    """Return the integer luminance of an (..., 3) array of non-negative integer R, G, B samples.

    ``L = (19595·R + 38470·G + 7471·B + 32768) >> 16``, the BT.601 weights as Pillow rounds them, so an 8-bit
    image gives the same values as ``Image.convert("L")`` and a grey colour (R = G = B) keeps its value.
    """
    a = np.asarray(rgb)
    if a.ndim < 1 or a.shape[-1] != 3:
        raise ValueError(f"luminance needs R, G, B samples in the last axis, got shape {a.shape}")
    r = a[..., 0].astype(np.int64)
    g = a[..., 1].astype(np.int64)
    b = a[..., 2].astype(np.int64)
    out: npt.NDArray[np.int64] = (
        _LUMA_WEIGHTS[0] * r + _LUMA_WEIGHTS[1] * g + _LUMA_WEIGHTS[2] * b + 32768
    ) >> 16
    return out


def otsu_threshold(hist: npt.ArrayLike) -> int:
    """Return Otsu's threshold of an integer histogram, computed exactly.

    Parameters
    ----------
    hist : array_like of int
        ``hist[v]`` is the number of pixels of value v (v = 0, 1, 2, ...).

    Returns
    -------
    int
        The value t maximising the between-class variance of the split {v ≤ t} / {v > t}; the object is
        ``value > t``. Among equal variances the smallest t is returned, and t is always a value that occurs
        (the largest value of the lower class), as in ``skimage.filters.threshold_otsu``. A histogram with a
        single occupied value returns that value.

    Notes
    -----
    For a split with n₀, n₁ pixels and value sums s₀, s₁, the between-class variance is proportional to
    (s₀·n₁ − s₁·n₀)² / (n₀·n₁). The candidates are compared by cross-multiplication in Python integers, so
    ties are real ties and the result does not depend on rounding.
    """
    h = np.asarray(hist)
    if h.ndim != 1 or h.dtype.kind not in "iu":
        raise ValueError("otsu_threshold needs a 1-D integer histogram")
    values = np.flatnonzero(h)
    if values.size == 0:
        raise ValueError("otsu_threshold needs a non-empty histogram")
    if values.size == 1:
        return int(values[0])
    return _otsu_sparse([int(v) for v in values], [int(c) for c in h[values]])


def _otsu_sparse(vals: list[int], counts: list[int]) -> int:
    """Otsu's threshold of the occupied values ``vals`` (increasing) with their pixel counts."""
    if len(vals) == 1:
        return vals[0]
    n = sum(counts)
    s = sum(c * v for c, v in zip(counts, vals, strict=True))
    best_t = vals[0]
    best_num, best_den = -1, 1
    n0 = s0 = 0
    for v, c in zip(vals[:-1], counts[:-1], strict=True):
        n0 += c
        s0 += c * v
        n1, s1 = n - n0, s - s0
        num = (s0 * n1 - s1 * n0) ** 2
        den = n0 * n1
        if num * best_den > best_num * den:
            best_t, best_num, best_den = v, num, den
    return best_t


def _check_threshold(threshold: float) -> float:
    if isinstance(threshold, bool) or not isinstance(threshold, int | float | np.integer | np.floating):
        raise ParameterError(f"the threshold must be a number, got {value_text(threshold)}")
    try:
        value = float(threshold)
    except OverflowError:  # an integer beyond float64
        value = math.inf
    if not math.isfinite(value):
        raise ParameterError(f"the threshold must be finite, got {value_text(threshold)}")
    return value


def grey_of(
    samples: npt.NDArray[Any], *, alpha: npt.NDArray[Any] | None = None, max_alpha: int = 255
) -> npt.NDArray[Any]:
    """Return the integer grey image of grey or colour samples with an optional alpha channel (rules 1–2).

    Parameters
    ----------
    samples : ndarray of non-negative int, shape (rows, cols) or (rows, cols, 3)
        Grey values, or R, G, B.
    alpha : ndarray of int, shape (rows, cols), optional
        Opacity, 0 = transparent.
    max_alpha : int
        The value of a fully opaque pixel (255 for 8-bit images).
    """
    if alpha is None and samples.ndim == 2:
        return samples
    grey = luminance(samples) if samples.ndim == 3 else samples.astype(np.int64)
    if alpha is None:
        return grey
    a = alpha.astype(np.int64)
    visible = a > 0
    if not visible.any():
        return np.zeros_like(grey)
    shown = grey[visible]
    if shown.min() == shown.max():
        # One colour on a transparent layer: the shape is drawn by the alpha channel.
        return a
    # Composite over black with round-half-up integer arithmetic.
    out: npt.NDArray[np.int64] = (grey * a + max_alpha // 2) // max_alpha
    return out


def binarize(grey: npt.NDArray[Any], threshold: float | None = None) -> BoolArray:
    """Return the mask of a non-negative integer grey image (rules 3–4).

    Parameters
    ----------
    grey : ndarray of non-negative int
        The grey image (see :func:`grey_of`).
    threshold : float, optional
        Pixels with a value greater than it are in the set. By default binary images (0 and one other value)
        keep their non-zero pixels and other images are cut at Otsu's threshold.

    Raises
    ------
    ParameterError
        If ``threshold`` is not a finite number.
    """
    g = np.asarray(grey)
    if threshold is not None:
        out: BoolArray = g > _check_threshold(threshold)
        return out
    if g.size == 0:
        return np.zeros(g.shape, dtype=bool)
    if g.min() < 0:
        raise ValueError("grey values must be non-negative")
    if int(g.max()) < (1 << 20):
        hist = np.bincount(g.ravel().astype(np.intp, copy=False))
        occupied = np.flatnonzero(hist)
        vals, counts = [int(v) for v in occupied], [int(c) for c in hist[occupied]]
    else:  # deep integer images: a sparse histogram instead of a huge dense one
        u, c = np.unique(g, return_counts=True)
        vals, counts = [int(v) for v in u], [int(k) for k in c]
    binary = len(vals) <= 1 or (len(vals) == 2 and vals[0] == 0)
    out = g != 0 if binary else g > _otsu_sparse(vals, counts)
    return out
