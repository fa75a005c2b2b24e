"""Issue 31 item 3: the library in the shapely 2 / rasterio style (vectorized forms, GeoJSON and
``__geo_interface__`` inputs, ``transform=``, NaN refused)."""

from __future__ import annotations

from fractions import Fraction

import numpy as np
import pytest
import shapely

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


# ---------------------------------------------------------------------------------------------- transform=
def _rasterio_corners(height: int, width: int, transform) -> dict[tuple[int, int], tuple[float, float]]:
    """Every pixel corner (col, row) → the floats rasterio.features.shapes (GDAL's polygonize) gives it.

    One value per pixel makes every pixel its own polygon, so every corner of the raster is emitted.
    """
    from rasterio.features import shapes

    ids = np.arange(height * width, dtype=np.int32).reshape(height, width)
    approx = np.array(transform).reshape(3, 3)[:2]
    out: dict[tuple[int, int], tuple[float, float]] = {}
    for geom, value in shapes(ids, transform=transform):
        row, col = divmod(int(value), width)
        ring = [tuple(map(float, p)) for p in geom["coordinates"][0]]
        for corner in ((col, row), (col + 1, row), (col + 1, row + 1), (col, row + 1)):
            want = approx @ np.array([corner[0], corner[1], 1.0])
            got = min(ring, key=lambda p: (p[0] - want[0]) ** 2 + (p[1] - want[1]) ** 2)
            assert out.setdefault(corner, got) == got  # a corner shared by four pixels has one place
    return out


def _transforms():
    from affine import Affine

    return {
        "dyadic north-up": Affine(0.5, 0.0, 1000.25, 0.0, -0.25, 5000.5),
        "dyadic sheared": Affine(0.5, 0.25, 10.0, -0.125, -0.5, 20.0),
        "decimal degrees": Affine(0.1, 0.0, 12.3, 0.0, -0.1, 45.6),
        "UTM 30 m": Affine(30.0, 0.0, 499985.0, 0.0, -30.0, 4200015.0),
        "rotated": Affine.translation(631.7, 42.9) @ Affine.rotation(17) @ Affine.scale(0.3, -0.3),
    }


@pytest.mark.parametrize("name", list(_transforms()))
def test_transform_places_every_corner_where_rasterio_shapes_does(name):
    """polygonize / reconstruct with transform=: the grid polygons, each vertex at a pixel corner on the very
    float pair rasterio.features.shapes gives that corner; other vertices (where a diagonal cut meets a pixel
    side) exactly where the affine puts them (Fractions) when the transform is dyadic."""
    t = _transforms()[name]
    rng = np.random.default_rng(31)
    labels = rng.integers(0, 4, (7, 9)).astype(np.int32)
    h, w = labels.shape
    corners = _rasterio_corners(h, w, t)
    exact = [Fraction(v) for v in tuple(t)[:6]]
    dyadic = name.startswith("dyadic")  # few bits: every product and sum below is exact in float64
    checked = 0

    def check(grid_poly, world_poly, why):
        nonlocal checked
        g, placed = shapely.get_coordinates(grid_poly), shapely.get_coordinates(world_poly)
        assert g.shape == placed.shape, why
        for (u, v), xy in zip(g.tolist(), placed.tolist(), strict=True):
            col, row = u + 0.5, h - 0.5 - v  # grid point (u, v) is raster position (col, row)
            if col.is_integer() and row.is_integer():
                assert tuple(xy) == corners[(int(col), int(row))], (why, (col, row))
                checked += 1
            elif dyadic:
                a, b, c, d, e, f = exact
                fc, fr = Fraction(col), Fraction(row)
                assert tuple(xy) == (float(c + fc * a + fr * b), float(f + fc * d + fr * e)), why
            else:
                want = np.array(t).reshape(3, 3)[:2] @ np.array([col, row, 1.0])
                assert np.allclose(xy, want, rtol=1e-12, atol=0), why

    grid = mrm.polygonize(labels)
    for kind, world in (
        ("an Affine", mrm.polygonize(labels, transform=t)),
        ("six numbers", mrm.polygonize(labels.tolist(), transform=tuple(t)[:6])),
    ):
        assert sorted(world) == sorted(grid), kind
        for label, poly in grid.items():
            check(poly, world[label], (kind, label))
    for model in ("gauss", "standard"):
        mask = labels == 2
        check(mrm.reconstruct(mask, model), mrm.reconstruct(mask, model, transform=t), model)
    assert checked > 100
