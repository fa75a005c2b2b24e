"""Label maps to polygons: one per region, boundaries shared exactly, burnt back by GDAL to the labels.

Checked on seeded random label maps (several labels, noise, diagonal contacts, holes) and a quantized real
image:

* one polygon per region (4-connected component of one non-zero label), with its label and pixel count;
* D_gauss(polygon) is the region exactly, and ``rasterio.features.rasterize`` of the polygons with their
  labels (GDAL's default centre rule) gives back the label image exactly;
* watertight, exactly: every edge is, with the same float64 end points, an edge of exactly one other region
  traversed the other way, or lies on the outline; the outline edges close into rings and the exact
  (Fraction) areas add up: Σ area(region) = area(outline) — so there is no gap and no overlap;
* ``mrm polygonize`` reads grey and palette PNG, PGM and NPZ (with or without ``origin``) and writes one
  Feature per region with ``label`` and ``pixels``.
"""

from __future__ import annotations

import itertools
import json
from collections import Counter
from fractions import Fraction
from pathlib import Path

import numpy as np
import pytest
import rasterio.features
import shapely
from affine import Affine
from PIL import Image
from shapely.geometry import Polygon, shape

from mrm.core.errors import ParameterError
from mrm.core.grids import LabelMap
from mrm.geometry.discretize import discretize
from mrm.geometry.reconstruct.polygonize import Region, polygonize
from mrm.geometry.topology.labeling import label


def random_map(seed: int) -> LabelMap:
    rng = np.random.default_rng(seed)
    h, w = int(rng.integers(3, 16)), int(rng.integers(3, 16))
    n = int(rng.integers(2, 5))
    a = rng.integers(0, n + 1, size=(h, w))
    if seed % 2:
        # blocky: labels in 2×2 or 3×3 blocks, then a little noise
        k = int(rng.integers(2, 4))
        a = np.kron(rng.integers(0, n + 1, size=(h // k + 1, w // k + 1)), np.ones((k, k), int))[:h, :w]
        a[rng.random((h, w)) < 0.1] = int(rng.integers(0, n + 1))
    return LabelMap(a.astype(np.int32), (int(rng.integers(-50, 50)), int(rng.integers(-50, 50))))


def quantized_coins() -> LabelMap:
    import skimage.data

    img = skimage.data.coins()[::-1][100:150, 120:180]
    return LabelMap((img // 64).astype(np.int32) + 1, (7, -3))


MAPS = [random_map(s) for s in range(14)]


def regions_of(lm: LabelMap) -> Counter[tuple[int, int]]:
    """(label, pixel count) of every 4-connected component of every non-zero label (the oracle)."""
    out: Counter[tuple[int, int]] = Counter()
    for v in np.unique(lm.labels):
        if v == 0:
            continue
        lab, n = label(lm.labels == v, 4)
        counts = np.bincount(lab.ravel(), minlength=n + 1)[1:]
        out.update((int(v), int(c)) for c in counts)
    return out


def burn(regions: list[Region], lm: LabelMap) -> np.ndarray:
    """GDAL's rasterization of the regions with their labels on the label map's grid (row 0 = lowest y)."""
    x0, y0 = lm.origin
    h, w = lm.labels.shape
    transform = Affine(1.0, 0.0, x0 - 0.5, 0.0, -1.0, y0 + h - 0.5)
    img = rasterio.features.rasterize(
        [(r.geometry, r.label) for r in regions], out_shape=(h, w), transform=transform, dtype="int32"
    )
    return img[::-1]


def exact_area(ring: np.ndarray) -> Fraction:
    x = [Fraction(v) for v in ring[:, 0].tolist()]
    y = [Fraction(v) for v in ring[:, 1].tolist()]
    n = len(x) - 1  # closed ring
    return sum((x[i] * y[i + 1] - x[i + 1] * y[i] for i in range(n)), Fraction(0)) / 2


def polygon_area(p: Polygon) -> Fraction:
    a = abs(exact_area(np.asarray(p.exterior.coords)))
    return a - sum((abs(exact_area(np.asarray(h.coords))) for h in p.interiors), Fraction(0))


def directed_edges(p: Polygon) -> list[tuple[tuple[float, float], tuple[float, float]]]:
    out = []
    for ring in (p.exterior, *p.interiors):
        c = [tuple(v) for v in np.asarray(ring.coords).tolist()]
        out.extend(itertools.pairwise(c))
    return out


def check_watertight(regions: list[Region]) -> None:
    owner: dict[tuple[tuple[float, float], tuple[float, float]], int] = {}
    for i, r in enumerate(regions):
        g = shapely.orient_polygons(r.geometry)  # shell counter-clockwise, holes clockwise
        for e in directed_edges(g):
            assert e not in owner, "an edge used twice in the same direction"
            owner[e] = i
    outline = []
    for (a, b), i in owner.items():
        j = owner.get((b, a))
        if j is None:
            outline.append(shapely.LineString([a, b]))
        else:
            assert j != i, "a region meets itself along an edge"
    # Shared edges cancel, so at every point off the edges the regions' winding numbers add up to that of the
    # unmatched (outline) edges. It must be 0 or 1 on every face of their arrangement: then, the regions being
    # valid polygons (winding 0 or 1 each), no two overlap and every point inside the outline is covered.
    cut, dangles, invalid = shapely.polygonize_full(outline)[1:]
    assert cut.is_empty and dangles.is_empty and invalid.is_empty
    directed = [
        ((Fraction(a[0]), Fraction(a[1])), (Fraction(b[0]), Fraction(b[1])))
        for (a, b), _ in owner.items()
        if (b, a) not in owner
    ]
    covered = Fraction(0)
    for f in shapely.get_parts(shapely.polygonize(outline)):
        p = f.representative_point()
        w = winding((Fraction(p.x), Fraction(p.y)), directed)
        assert w in (0, 1), w
        if w == 1:
            covered += polygon_area(f)
    assert sum((polygon_area(r.geometry) for r in regions), Fraction(0)) == covered


def winding(p: tuple[Fraction, Fraction], edges: list) -> int:
    """Exact winding number of the directed edges around p (p on no edge)."""
    w = 0
    px, py = p
    for (ax, ay), (bx, by) in edges:
        cr = (bx - ax) * (py - ay) - (by - ay) * (px - ax)
        assert cr != 0 or not (min(ax, bx) <= px <= max(ax, bx) and min(ay, by) <= py <= max(ay, by))
        if ay <= py < by and cr > 0:
            w += 1
        elif by <= py < ay and cr < 0:
            w -= 1
    return w


@pytest.mark.parametrize("lm", [*MAPS, quantized_coins()], ids=[*(f"seed{i}" for i in range(14)), "coins"])
def test_polygonize_is_exact_watertight_and_burns_back(lm: LabelMap) -> None:
    regions = polygonize(lm)
    assert Counter((r.label, r.pixels) for r in regions) == regions_of(lm)
    for r in regions:
        assert isinstance(r.geometry, Polygon) and r.geometry.is_valid
        got = discretize(r.geometry, "gauss")
        assert len(got) == r.pixels
        assert np.all(
            lm.labels[got.points()[:, 1] - lm.origin[1], got.points()[:, 0] - lm.origin[0]] == r.label
        )
    assert np.array_equal(burn(regions, lm), lm.labels)
    check_watertight(regions)


def test_polygonize_is_translation_covariant_and_deterministic() -> None:
    lm = MAPS[3]
    a = polygonize(lm)
    b = polygonize(LabelMap(np.array(lm.labels), (lm.origin[0] + 1000, lm.origin[1] - 77)))
    assert [(r.label, r.pixels) for r in a] == [(r.label, r.pixels) for r in b]
    for ra, rb in zip(a, b, strict=True):
        ca = shapely.get_coordinates(ra.geometry)
        assert np.array_equal(shapely.get_coordinates(rb.geometry), ca + np.array([1000.0, -77.0]))
    assert [shapely.get_coordinates(r.geometry).tolist() for r in polygonize(lm)] == [
        shapely.get_coordinates(r.geometry).tolist() for r in a
    ]


def test_polygonize_accepts_an_array_with_an_origin() -> None:
    a = np.array([[1, 1, 2], [0, 2, 2]], dtype=np.int32)
    regions = polygonize(a, origin=(10, 20))
    assert [(r.label, r.pixels) for r in regions] == [(1, 2), (2, 3)]
    assert discretize(regions[0].geometry, "gauss").points().tolist() == [[10, 20], [11, 20]]


@pytest.mark.parametrize(
    ("arg", "message"),
    [
        ({"model": "standard"}, "needs the gauss model"),
        ({"model": "nope"}, "unknown discretization model"),
        ({"labels": np.zeros((2, 2, 2), dtype=np.int32)}, "2-D integer array"),
        ({"labels": np.array([[-1, 2]])}, "non-negative"),
    ],
)
def test_polygonize_refuses_bad_input_with_a_message(arg: dict, message: str) -> None:
    labels = arg.get("labels", np.ones((2, 2), dtype=np.int32))
    with pytest.raises(ParameterError, match=message):
        polygonize(labels, model=arg.get("model", "gauss"))


# ---------------------------------------------------------------------------------------------- CLI


def run(capsys: pytest.CaptureFixture[str], *argv: object) -> tuple[int, str, str]:
    from mrm.cli import run_cli

    code = run_cli([str(a) for a in argv])
    out, err = capsys.readouterr()
    return code, out, err


def features_map(path: object, lm: LabelMap) -> tuple[list[dict], np.ndarray]:
    data = json.loads(Path(str(path)).read_text(encoding="utf-8"))
    feats = data["features"]
    regions = [
        Region(f["properties"]["label"], f["properties"]["pixels"], shape(f["geometry"])) for f in feats
    ]
    return feats, burn(regions, lm)


def test_cli_polygonize_reads_every_label_format(capsys, tmp_path) -> None:
    rows = np.array([[0, 1, 1, 3], [2, 2, 1, 3], [2, 0, 3, 3], [4, 4, 0, 1]], dtype=np.uint8)  # image rows
    lm = LabelMap(rows[::-1].astype(np.int32))  # y up
    Image.fromarray(rows, mode="L").save(tmp_path / "grey.png")
    pal = Image.fromarray(rows, mode="P")
    pal.putpalette([0, 0, 0, 255, 0, 0, 0, 255, 0, 0, 0, 255, 255, 255, 0] + [0] * (3 * 251))
    pal.save(tmp_path / "pal.png")
    (tmp_path / "a.pgm").write_bytes(b"P5 4 4 255\n" + rows.tobytes())
    np.savez(tmp_path / "plain.npz", labels=rows[::-1].astype(np.int32))
    np.savez(tmp_path / "placed.npz", labels=rows[::-1].astype(np.int32), origin=np.array([0, 0]))
    want = regions_of(lm)
    for name in ("grey.png", "pal.png", "a.pgm", "plain.npz", "placed.npz"):
        out = tmp_path / f"{name}.geojson"
        code, text, err = run(capsys, "polygonize", tmp_path / name, "-o", out, "--json")
        assert code == 0, (name, err)
        summary = json.loads(text)
        assert summary["regions"] == sum(want.values()) and summary["labels"] == 4
        assert summary["pixels"] == int(np.count_nonzero(rows))
        feats, burnt = features_map(out, lm)
        assert Counter((f["properties"]["label"], f["properties"]["pixels"]) for f in feats) == want
        assert np.array_equal(burnt, lm.labels), name


def test_cli_polygonize_errors_are_one_line_messages(capsys, tmp_path) -> None:
    Image.fromarray(np.ones((3, 3), np.uint8)).save(tmp_path / "a.png")
    code, _out, err = run(
        capsys, "polygonize", tmp_path / "a.png", "-o", tmp_path / "o.geojson", "--model", "standard"
    )
    assert code == 2 and "needs the gauss model" in err and "Traceback" not in err
    code, _out, err = run(capsys, "polygonize", tmp_path / "a.png", "-o", tmp_path / "o.svg")
    assert code == 2 and "GeoJSON" in err
    Image.fromarray(np.zeros((3, 3, 3), np.uint8)).save(tmp_path / "rgb.png")
    code, _out, err = run(capsys, "polygonize", tmp_path / "rgb.png", "-o", tmp_path / "o.geojson")
    assert code == 2 and "grey" in err
    assert not (tmp_path / "o.geojson").exists()


@pytest.mark.parametrize("seed", range(4))
def test_cell_tracing_without_the_jit_gives_the_compiled_cells(seed: int) -> None:
    # NUMBA_DISABLE_JIT=1 (debugging, a platform without LLVM) runs the kernels as plain Python, where numpy
    # bools add as a logical or: the linel count came out short and the trace wrote past its array.
    from mrm.geometry.topology.cracks import _trace_cells

    rng = np.random.default_rng(seed)
    lab = np.pad(rng.integers(0, 3, (9, 7)).astype(np.int32), 1)
    compiled = _trace_cells(lab)
    plain = _trace_cells.py_func(lab)
    for a, b in zip(compiled, plain, strict=True):
        assert np.array_equal(a, b)


def test_a_polygon_the_labelling_cannot_place_is_counted_by_its_exact_discretization(monkeypatch) -> None:
    # If a region's first pixel ever fell in no polygon (or two), the label's regions are counted by the exact
    # discretization instead: the same regions, sizes and order.
    import mrm.geometry.reconstruct.polygonize as pz

    lm = MAPS[5]
    want = [(r.label, r.pixels, r.geometry.wkb) for r in polygonize(lm)]
    real = pz.label_regions

    def shifted(labels):  # first pixels moved far off: centres that sit in no polygon
        reg = real(labels)
        return reg._replace(first_col=reg.first_col + 10_000)

    monkeypatch.setattr(pz, "label_regions", shifted)
    assert [(r.label, r.pixels, r.geometry.wkb) for r in polygonize(lm)] == want


# ------------------------------------------------------------------------------------ the cost, bounded first
def checkerboard(n: int) -> np.ndarray:
    yy, xx = np.mgrid[0:n, 0:n]
    return ((xx + yy) % 2 + 1).astype(np.uint8)


@pytest.fixture
def no_subdivision(monkeypatch: pytest.MonkeyPatch) -> None:
    """The refusals below must come from the estimate, before any of the subdivision's work."""
    from mrm.geometry.reconstruct import subdivision

    def refuse(_lm: LabelMap) -> None:
        raise AssertionError("the subdivision started before its cost was checked")

    monkeypatch.setattr(subdivision, "_subdivide", refuse)


def test_cli_polygonize_refuses_65535_labels_in_a_tiny_png_before_any_work(capsys, tmp_path, no_subdivision):
    """Issue 32: a 693-byte 16-bit PNG with 65,535 labels (256²) took 90 s."""
    lab = np.arange(256 * 256, dtype=np.uint16).reshape(256, 256)
    Image.fromarray(lab).save(tmp_path / "labels.png")  # 16-bit grey, labels 0 … 65535
    assert (tmp_path / "labels.png").stat().st_size < 200_000
    code, _out, err = run(capsys, "polygonize", tmp_path / "labels.png", "-o", tmp_path / "o.geojson")
    assert code == 2 and "Traceback" not in err
    assert err.count("\n") == 1 and "65,535 labels" in err and "20,000" in err
    assert not (tmp_path / "o.geojson").exists()


def test_cli_polygonize_refuses_a_2000_checkerboard_by_its_boundary_length(capsys, tmp_path, no_subdivision):
    """Issue 32: a 28 KB 2000² checkerboard ran 5 min 37 s and exhausted 8 GB."""
    Image.fromarray(checkerboard(2000)).save(tmp_path / "board.png")
    code, _out, err = run(capsys, "polygonize", tmp_path / "board.png", "-o", tmp_path / "o.geojson")
    assert code == 2 and err.count("\n") == 1 and "Traceback" not in err
    assert "8,004,000 pixel edges" in err and "2,000,000" in err  # 2·2000·2001 edges between labels
    assert not (tmp_path / "o.geojson").exists()


@pytest.mark.parametrize(
    "kind, words",
    [
        ("checkerboard", ("129,600 regions", "130,317 corners")),
        ("dots", ("251,002 regions", "4,000 corners")),
    ],
)
def test_polygonize_refuses_too_many_regions_and_junctions_in_the_library_too(kind, words, no_subdivision):
    """Few labels and a short enough boundary, but each region and junction is a cell of a few kB."""
    import mrm
    from mrm.core.errors import LimitError

    if kind == "checkerboard":
        lab = checkerboard(360)  # 129,600 regions; junctions at every inner corner and half the border
    else:
        lab = np.full((1001, 1001), 2, np.uint8)
        lab[::2, ::2] = 1  # 501² one-pixel islands in one region of label 2, which meet the outside
    for call in (lambda: polygonize(lab), lambda: mrm.polygonize(lab)):
        with pytest.raises(LimitError) as e:
            call()
        assert all(w in str(e.value) for w in words) and "120,000" in str(e.value)


def test_polygonize_just_below_the_limits_still_works() -> None:
    lab = checkerboard(60).astype(np.int32)
    regions = polygonize(LabelMap(lab))
    assert len(regions) == 3600 and {r.pixels for r in regions} == {1}
