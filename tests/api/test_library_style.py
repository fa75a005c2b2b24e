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


# ---------------------------------------------------------------------------------------------- batches
def _masks():
    rng = np.random.default_rng(7)
    out = [rng.random((6, 8)) < 0.45 for _ in range(3)]
    out.append(np.zeros((4, 4), bool))
    out[3][1:3, 1:3] = True
    return out


def test_a_stack_of_masks_reconstructs_element_wise():
    """A list of 2-D masks was refused (np.asarray made it one 3-D array); now each is reconstructed."""
    masks = _masks()
    for model in ("standard", "supercover", "gauss"):
        out = mrm.reconstruct(masks, model)
        assert isinstance(out, np.ndarray) and out.dtype == object and out.shape == (len(masks),)
        for got, mask in zip(out, masks, strict=True):
            assert got.equals_exact(mrm.reconstruct(mask, model), tolerance=0)
            assert mrm.discretize(got, model) == mrm.PixelSet.from_image(mask)
    # a tuple and an object array of any shape keep working, the shape is kept
    grid = np.empty((2, 2), dtype=object)
    for i, m in enumerate(masks):
        grid[divmod(i, 2)] = m
    assert mrm.reconstruct(grid, "gauss").shape == (2, 2)
    assert len(mrm.reconstruct(tuple(masks[:2]), "gauss")) == 2


def test_a_3d_array_is_never_a_batch_and_nested_lists_stay_one_image():
    stack = np.stack(_masks()[:3])  # (3, 6, 8): not a colour image, not a batch
    with pytest.raises(mrm.MRMError):
        mrm.reconstruct(stack, "gauss")
    nested = [[1, 0, 1], [1, 1, 1]]
    one = mrm.reconstruct(nested, "gauss")
    assert mrm.discretize(one, "gauss") == mrm.PixelSet.from_image(np.array(nested))


def test_vectorized_forms_equal_the_element_wise_calls():
    from shapely.geometry import Point, box

    geoms = [box(0, 0, 3, 2), Point(1, 1).buffer(2.3, 8), box(-2, 1, 0.5, 4.5)]
    for got, g in zip(mrm.discretize(geoms, "gauss"), geoms, strict=True):
        assert got == mrm.discretize(g, "gauss")
    sets = [mrm.discretize(g, "gauss") for g in geoms]
    for got, ps in zip(mrm.scale(sets, 2, model="gauss"), sets, strict=True):
        assert got == mrm.scale(ps, 2, model="gauss")
    for got, ps in zip(mrm.rotate(sets, 30, model="supercover"), sets, strict=True):
        assert got == mrm.rotate(ps, 30, model="supercover")
    for got, g in zip(mrm.simplify(geoms, 0.5), geoms, strict=True):
        assert got.equals_exact(mrm.simplify(g, 0.5), tolerance=0)
    # two arguments broadcast as numpy does: one against many, and many against many
    d = mrm.hausdorff(geoms[0], geoms)
    assert [x.value for x in d] == [mrm.hausdorff(geoms[0], g).value for g in geoms]
    u = mrm.union(geoms, geoms[::-1], "gauss")
    for got, (a, b) in zip(u, zip(geoms, geoms[::-1], strict=True), strict=True):
        assert got.equals_exact(mrm.union(a, b, "gauss"), tolerance=0)
    parts = mrm.corefine(geoms[:2], geoms[2], "gauss")
    assert [sorted(p) for p in parts] == [["a_and_b", "a_minus_b", "b_minus_a"]] * 2
    labels = [np.array([[1, 1, 2], [1, 2, 2]]), np.array([[3, 0], [3, 3]])]
    for got, lab in zip(mrm.polygonize(labels), labels, strict=True):
        assert got.keys() == mrm.polygonize(lab).keys()
        assert all(got[k].equals_exact(p, tolerance=0) for k, p in mrm.polygonize(lab).items())
    assert mrm.discretize([], "gauss").shape == (0,)


def test_a_bad_item_of_a_batch_is_a_one_line_error_naming_the_item():
    from shapely.geometry import box

    with pytest.raises(mrm.MRMError) as e:
        mrm.reconstruct([np.ones((2, 2), bool), np.array([[np.nan]])], "gauss")
    assert "\n" not in str(e.value)
    assert "in item (1,) of the batch" in e.value.__notes__
    with pytest.raises(mrm.MRMError, match="do not broadcast"):
        mrm.hausdorff([box(0, 0, 1, 1)] * 2, [box(0, 0, 1, 1)] * 3)


# ---------------------------------------------------------------------------------------------- GeoJSON
class _Feature:
    """What GeoPandas, Fiona and pyogrio records look like to us: only ``__geo_interface__``."""

    def __init__(self, mapping):
        self._mapping = mapping

    @property
    def __geo_interface__(self):
        return self._mapping


def test_geojson_dicts_and_geo_interface_objects_give_the_shapely_result():
    from shapely.geometry import Polygon

    poly = Polygon([(0, 0), (7, 1), (5, 6), (1, 4)], [[(2, 2), (4, 2), (3, 4)]])
    gi = poly.__geo_interface__  # tuples, as __geo_interface__ usually holds
    as_lists = {"type": "Polygon", "coordinates": [[list(p) for p in ring] for ring in gi["coordinates"]]}
    feature = {"type": "Feature", "properties": {"name": "field"}, "geometry": gi}
    collection = {"type": "FeatureCollection", "features": [feature]}
    as_array = {"type": "Polygon", "coordinates": [np.array(r) for r in gi["coordinates"]]}
    for model in ("standard", "gauss"):
        want = mrm.discretize(poly, model)
        for given in (gi, as_lists, feature, collection, as_array, _Feature(gi), _Feature(feature)):
            assert mrm.discretize(given, model) == want
        assert mrm.scale(_Feature(gi), 2, model=model) == mrm.scale(poly, 2, model=model)
    assert mrm.hausdorff(_Feature(gi), as_lists).value == 0.0
    assert mrm.union(feature, poly, "gauss").equals_exact(mrm.union(poly, poly, "gauss"), tolerance=0)
    # a batch of mixed kinds
    out = mrm.discretize([poly, gi, _Feature(feature)], "gauss")
    assert all(ps == mrm.discretize(poly, "gauss") for ps in out)


BAD_GEOJSON = {
    "unknown type": ({"type": "Circle", "coordinates": [0, 0]}, "unsupported GeoJSON geometry type 'Circle'"),
    "nan": ({"type": "Point", "coordinates": [float("nan"), 0]}, "must be finite"),
    "bow tie": ({"type": "Polygon", "coordinates": [[[0, 0], [2, 2], [2, 0], [0, 2], [0, 0]]]}, "Self-"),
    "text": ({"type": "Point", "coordinates": ["1", "2"]}, "must be numbers"),
    "no coordinates": ({"type": "LineString"}, "has no 'coordinates'"),
    "geo interface not a mapping": (_Feature(42), "__geo_interface__, got _Feature"),
    "deep collection": ({"type": "GeometryCollection", "geometries": []}, "nested more than"),
}
_deep = BAD_GEOJSON["deep collection"][0]
for _ in range(200):
    _inner: dict = {"type": "GeometryCollection", "geometries": []}
    _deep["geometries"].append(_inner)
    _deep = _inner


@pytest.mark.parametrize("case", BAD_GEOJSON.values(), ids=BAD_GEOJSON.keys())
def test_hostile_geojson_is_refused_with_one_line_saying_what_is_wrong(case):
    doc, says = case
    with pytest.raises(mrm.MRMError) as e:
        mrm.discretize(doc, "gauss")
    assert "\n" not in str(e.value) and says in str(e.value)


BAD_TRANSFORMS = {
    "five numbers": ((1, 0, 0, 0, -1), "six numbers"),
    "not numbers": (("a", 0, 0, 0, -1, 0), "six numbers"),
    "singular": ((1, 0, 0, 2, 0, 0), "not invertible"),
    "nan": ((float("nan"), 0, 0, 0, -1, 0), "not invertible"),
    "a 3x3 with a wrong last row": ((1, 0, 0, 0, -1, 0, 1, 0, 1), "GDAL's geotransform"),
}


@pytest.mark.parametrize("case", BAD_TRANSFORMS.values(), ids=BAD_TRANSFORMS.keys())
def test_a_bad_transform_is_refused_with_one_line(case):
    transform, says = case
    image = np.array([[1, 0], [1, 1]])
    for call in (
        lambda: mrm.reconstruct(image.astype(bool), "gauss", transform=transform),
        lambda: mrm.polygonize(image, transform=transform),
    ):
        with pytest.raises(mrm.MRMError) as e:
            call()
        assert "\n" not in str(e.value) and says in str(e.value)


def test_a_pixel_set_is_placed_by_its_georef_not_by_six_numbers():
    image = np.array([[1, 0], [1, 1]], bool)
    ps = mrm.PixelSet.from_image(image)
    with pytest.raises(mrm.MRMError, match="GeoRef"):
        mrm.reconstruct(ps, "gauss", transform=(1, 0, 0, 0, -1, 0))
    with pytest.raises(mrm.MRMError, match="GeoRef"):
        mrm.polygonize(mrm.LabelMap.from_pixel_sets([ps]), transform=(1, 0, 0, 0, -1, 0))
    georef = mrm.GeoRef((2.0, 0.0, 100.0, 0.0, -2.0, 50.0), 2, 2)
    by_georef = mrm.reconstruct(ps, "gauss", transform=georef)
    assert by_georef.equals_exact(mrm.reconstruct(image, "gauss", transform=georef.transform), tolerance=0)


def test_3d_values_are_refused_by_the_2d_operations_not_read_as_nothing():
    """Passed through as they are, simplify(VoxelSet) gave POLYGON EMPTY; a one-line refusal instead.

    DSS, dR, Sp, EDu and EDco take 3D objects now (issue 30, ADRs 0060, 0061): they give 3D results, never an
    empty 2D one.
    """
    vs = mrm.VoxelSet.box(0, 0, 0, 1, 1, 1)
    assert isinstance(mrm.simplify(vs, 0.5), mrm.Polyhedron) and not mrm.simplify(vs, 0.5).is_empty
    r = mrm.reconstruct(vs, "standard")  # DSS_2(A) = D(Sc_2(R(A))), here through the float mesh
    assert mrm.scale(vs, 2) == mrm.voxelize(mrm.Polyhedron(2 * r.vertices, r.triangles), "standard")
    assert mrm.rotate([vs], 90, axis=(0, 0, 1))[0] == vs.rotate90(1)
    assert mrm.voxelize(mrm.union(vs, vs), "standard") == vs
    assert mrm.voxelize(mrm.corefine(vs, vs)["a_and_b"], "standard") == vs
    lm = mrm.LabelMap.from_pixel_sets([mrm.PixelSet.box(0, 0, 1, 1)])
    for call in (
        lambda: mrm.union(vs, mrm.PixelSet.box(0, 0, 1, 1)),
        lambda: mrm.hausdorff(vs, vs),
        lambda: mrm.corefine(lm, lm),
    ):
        with pytest.raises(mrm.MRMError) as e:
            call()
        assert "\n" not in str(e.value)
