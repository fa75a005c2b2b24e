"""Issue 31 item 3: the library in the shapely 2 / rasterio style (vectorized forms, GeoJSON and
``__geo_interface__`` inputs, ``transform=``, NaN refused)."""

from __future__ import annotations

import numpy as np
import pytest

import mrm

NON_FINITE = {
    "nan float image": np.array([[np.nan, 1.0], [0.0, 0.0]]),
    "nan float image, inverted": (np.array([[np.nan, 1.0], [0.0, 0.0]]), {"invert": True}),
    "inf float image": np.array([[np.inf, 0.0], [0.0, 0.0]]),
    "-inf float32 image": np.array([[-np.inf, 1.0]], dtype=np.float32),
    "nan colour image": np.array([[[np.nan, 1.0, 1.0], [0.0, 0.0, 0.0]]]),
}


@pytest.mark.parametrize("case", NON_FINITE.values(), ids=NON_FINITE.keys())
def test_nan_and_infinite_pixels_are_refused_with_one_line(case):
    """NaN != 0 and NaN > t is False: a NaN sample was silently a pixel (inverted, or in a mask)."""
    image, kw = case if isinstance(case, tuple) else (case, {})
    for call in (
        lambda: mrm.PixelSet.from_image(image, **kw),
        lambda: mrm.reconstruct(image, "gauss"),
    ):
        with pytest.raises(mrm.MRMError) as e:
            call()
        msg = str(e.value)
        assert "\n" not in msg and "NaN or infinite" in msg and "index (0, 0" in msg


def test_nan_in_a_mask_is_refused_not_counted_as_a_pixel():
    with pytest.raises(mrm.MRMError, match="NaN or infinite"):
        mrm.PixelSet(np.array([[np.nan, 0.0], [0.0, 1.0]]))
    with pytest.raises(mrm.MRMError, match="NaN or infinite"):
        mrm.VoxelSet(np.full((1, 2, 1), np.nan))
    # finite floats keep their meaning: non-zero is in the set
    assert sorted(mrm.PixelSet(np.array([[0.0, 2.5]]))) == [(1, 0)]
