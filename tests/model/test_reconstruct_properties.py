"""The whole contract of R (docs/design.md §3) on random and structured pixel sets, with the exact D as
oracle.

For every generated A and each model: R(A) is a valid Polygon/MultiPolygon with float64 coordinates;
D(R(A)) = A exactly; D_supercover(R(A)) = A too, which proves R(A) ⊂ V(A) (a point outside V(A) would put
an outside pixel in the supercover); its polygons and holes are the 4-components of A and the bounded
8-components of the complement; R(A + t) = R(A) + t exactly; a quarter turn about a pixel centre
discretizes to the turned set; and R(A) never has more vertices than the staircase V(A).

Generators: random sets up to 48×48 at densities 0.1–0.9, checkerboards, digital lines of every slope
(4- and 8-connected, thin and thick), one-pixel arms on blobs, rings and nested rings, square spirals,
digitized random polygons at random offsets and scales, and random flips of all of these.
"""

from __future__ import annotations

import numpy as np
import pytest
import shapely
from hypothesis import given, settings
from hypothesis import strategies as st
from shapely.geometry import MultiPolygon, Polygon

from mrm.core.grids import PixelSet
from mrm.core.models import Model
from mrm.geometry.discretize import discretize
from mrm.geometry.reconstruct import reconstruct
from mrm.reps.region import region_of
from mrm.reps.summary import count_vertices
from tests.oracles.discretize_reference import reference_discretize
from tests.oracles.gauss_contract import check_gauss_containment

MODELS = Model.names()

# ---------------------------------------------------------------------------------------------- generators


def _rng(seed: int) -> np.random.Generator:
    return np.random.default_rng(seed)


@st.composite
def random_sets(draw: st.DrawFn) -> PixelSet:
    seed = draw(st.integers(0, 2**32 - 1))
    h = draw(st.integers(1, 48))
    w = draw(st.integers(1, 48))
    density = draw(st.floats(0.1, 0.9))
    rng = _rng(seed)
    return PixelSet(rng.random((h, w)) < density, (int(rng.integers(-60, 60)), int(rng.integers(-60, 60))))


def checkerboard(h: int, w: int, phase: int, cell: int) -> np.ndarray:
    yy, xx = np.mgrid[0:h, 0:w]
    return ((yy // cell + xx // cell + phase) % 2) == 0


def digital_line(a: int, b: int, length: int, thick: int, eight: bool) -> np.ndarray:
    # Pixels of a standard (4-connected) or naive (8-connected) digital line of direction (b, a), thickened.
    pts = set()
    om = max(abs(a), abs(b)) if eight else abs(a) + abs(b)
    for x in range(-length, length + 1):
        for y in range(-length, length + 1):
            r = a * x - b * y
            if 0 <= r < om * thick and abs(x) + abs(y) <= length:
                pts.add((x, y))
    if not pts:
        pts.add((0, 0))
    xs = [p[0] for p in pts]
    ys = [p[1] for p in pts]
    m = np.zeros((max(ys) - min(ys) + 1, max(xs) - min(xs) + 1), dtype=bool)
    for x, y in pts:
        m[y - min(ys), x - min(xs)] = True
    return m


def blob_with_arms(rng: np.random.Generator, size: int, arms: int) -> np.ndarray:
    n = size + 24
    yy, xx = np.mgrid[0:n, 0:n]
    c = n / 2 + rng.uniform(-0.5, 0.5, 2)
    m = (xx - c[0]) ** 2 + (yy - c[1]) ** 2 <= (size / 2) ** 2
    steps = np.array([[1, 0], [0, 1], [-1, 0], [0, -1]])
    for _ in range(arms):
        x, y = int(c[0]), int(c[1])
        d = int(rng.integers(4))
        for _k in range(int(rng.integers(3, 12 + size // 2))):
            if rng.random() < 0.2:
                d = (d + int(rng.choice([1, 3]))) % 4
            x = min(max(x + steps[d, 0], 0), n - 1)
            y = min(max(y + steps[d, 1], 0), n - 1)
            m[y, x] = True
    return m


def rings(rng: np.random.Generator, nested: int) -> np.ndarray:
    r_out = float(rng.uniform(2, 10)) * nested + 2
    n = int(2 * r_out + 6)
    yy, xx = np.mgrid[0:n, 0:n]
    c = n / 2 + rng.uniform(-0.5, 0.5, 2)
    d2 = (xx - c[0]) ** 2 + (yy - c[1]) ** 2
    m = np.zeros((n, n), dtype=bool)
    r = r_out
    for _ in range(nested):
        width = float(rng.uniform(0.6, 3.0))
        m |= (d2 <= r * r) & (d2 > (r - width) ** 2)
        r -= width + float(rng.uniform(0.6, 3.0))
        if r <= 1:
            break
    return m


def spiral(turns: int, gap: int) -> np.ndarray:
    n = 4 * turns * (gap + 1) + 3
    m = np.zeros((n, n), dtype=bool)
    x = y = n // 2
    steps = [(1, 0), (0, 1), (-1, 0), (0, -1)]
    length = 1
    d = 0
    for _ in range(4 * turns):
        for _k in range(length * (gap + 1)):
            m[y, x] = True
            x += steps[d][0]
            y += steps[d][1]
            if not (0 <= x < n and 0 <= y < n):
                return m
        d = (d + 1) % 4
        if d % 2 == 0:
            length += 1
    return m


def digitized_polygon(rng: np.random.Generator, scale: float, model: str) -> PixelSet:
    k = int(rng.integers(3, 9))
    angles = np.sort(rng.uniform(0, 2 * np.pi, k))
    radii = rng.uniform(0.3, 1.0, k) * scale
    ox, oy = rng.uniform(-20, 20, 2)
    pts = [(ox + r * np.cos(a), oy + r * np.sin(a)) for a, r in zip(angles, radii, strict=True)]
    poly = Polygon(pts)
    if not poly.is_valid:
        poly = poly.convex_hull
    return discretize(poly, model)


def flip(rng: np.random.Generator, ps: PixelSet, amount: float) -> PixelSet:
    if ps.is_empty() or amount == 0:
        return ps
    x0, y0, x1, y1 = ps.bbox  # type: ignore[misc]
    box = (x0 - 1, y0 - 1, x1 + 1, y1 + 1)
    m = ps.to_array(box)
    m ^= rng.random(m.shape) < amount
    return PixelSet(m, (box[0], box[1]))


@st.composite
def structured_sets(draw: st.DrawFn) -> PixelSet:
    kind = draw(st.sampled_from(["checker", "line", "arms", "rings", "spiral", "polygon"]))
    seed = draw(st.integers(0, 2**32 - 1))
    rng = _rng(seed)
    if kind == "checker":
        m = checkerboard(
            draw(st.integers(1, 24)),
            draw(st.integers(1, 24)),
            draw(st.integers(0, 1)),
            draw(st.integers(1, 3)),
        )
        ps = PixelSet(m)
    elif kind == "line":
        a = draw(st.integers(-9, 9))
        b = draw(st.integers(-9, 9))
        if a == 0 and b == 0:
            a = 1
        m = digital_line(a, b, draw(st.integers(1, 24)), draw(st.integers(1, 3)), draw(st.booleans()))
        ps = PixelSet(m)
    elif kind == "arms":
        ps = PixelSet(blob_with_arms(rng, draw(st.integers(0, 16)), draw(st.integers(1, 6))))
    elif kind == "rings":
        ps = PixelSet(rings(rng, draw(st.integers(1, 3))))
    elif kind == "spiral":
        ps = PixelSet(spiral(draw(st.integers(1, 4)), draw(st.integers(1, 2))))
    else:
        ps = digitized_polygon(rng, draw(st.floats(0.5, 20.0)), draw(st.sampled_from(MODELS)))
    ps = flip(rng, ps, draw(st.sampled_from([0.0, 0.0, 0.02, 0.1])))
    return ps.translate(int(rng.integers(-40, 40)), int(rng.integers(-40, 40)))


pixel_sets = st.one_of(random_sets(), structured_sets())

# ---------------------------------------------------------------------------------------------- the contract


def corners(ps: PixelSet) -> int:
    """Number of vertices of the staircase V(A): the turns of its crack rings."""
    total = 0
    for ch in region_of(ps).boundary_chains:
        c = ch.code_array()
        total += int(np.count_nonzero(c != np.roll(c, 1)))
    return total


def turned(geom: Polygon | MultiPolygon, k: int, c: tuple[int, int]) -> Polygon | MultiPolygon:
    """The geometry turned by k quarter turns counter-clockwise about the pixel centre c, exactly."""

    def f(xy: np.ndarray) -> np.ndarray:
        x = xy[:, 0] - c[0]
        y = xy[:, 1] - c[1]
        for _ in range(k):
            x, y = -y, x
        return np.stack([x + c[0], y + c[1]], axis=1)

    return shapely.transform(geom, f)


def check_contract(ps: PixelSet, model: str, rng: np.random.Generator) -> Polygon | MultiPolygon:
    g = reconstruct(ps, model)
    # 1. a valid (Multi)Polygon with float64 coordinates
    assert isinstance(g, Polygon | MultiPolygon)
    assert g.is_valid, shapely.is_valid_reason(g)
    coords = shapely.get_coordinates(g)
    assert coords.dtype == np.float64 and np.all(np.isfinite(coords))
    if ps.is_empty():
        assert g.is_empty
        return g
    # 3. exact reversibility; 2. cover models: R(A) ⊂ V(A) (a point outside V(A) would add an outside pixel
    # here); gauss: no centre on the boundary, which stays within the voxels of the border pixels
    assert discretize(g, model) == ps
    if model == "gauss":
        check_gauss_containment(g, ps)
    elif model != "supercover":
        assert discretize(g, "supercover") == ps
    # 4. topology
    region = region_of(ps)
    polys = list(g.geoms) if isinstance(g, MultiPolygon) else [g]
    assert len(polys) == region.n_components
    assert [len(p.interiors) for p in polys] == [len(c.holes) for c in region.components]
    # 5. translation covariance (and determinism)
    t = (int(rng.integers(-1000, 1000)), int(rng.integers(-1000, 1000)))
    g2 = reconstruct(ps.translate(*t), model)
    assert np.array_equal(shapely.get_coordinates(g2), coords + np.array(t, dtype=np.float64))
    # 6. a quarter turn about a pixel centre is exact
    x0, y0, x1, y1 = ps.bbox  # type: ignore[misc]
    c = (int(rng.integers(x0 - 3, x1 + 4)), int(rng.integers(y0 - 3, y1 + 4)))
    k = int(rng.integers(1, 4))
    assert discretize(turned(g, k, c), model) == ps.rotate90(k, c)
    # 7. never more vertices than the staircase, at least three per ring
    assert count_vertices(g) <= corners(ps)
    assert all(len(r.coords) >= 4 for p in polys for r in (p.exterior, *p.interiors))
    return g


@pytest.mark.parametrize("model", MODELS)
@settings(max_examples=2000)
@given(ps=pixel_sets, seed=st.integers(0, 2**16))
def test_contract(model: str, ps: PixelSet, seed: int) -> None:
    check_contract(ps, model, _rng(seed))


@pytest.mark.slow
@pytest.mark.parametrize("model", MODELS)
@settings(max_examples=20000)
@given(ps=pixel_sets, seed=st.integers(0, 2**16))
def test_contract_long(model: str, ps: PixelSet, seed: int) -> None:
    check_contract(ps, model, _rng(seed))


@pytest.mark.parametrize("model", MODELS)
@settings(max_examples=300)
@given(ps=pixel_sets)
def test_polygons_are_the_components_in_canonical_order(model: str, ps: PixelSet) -> None:
    # Polygon k discretizes to component k alone (canonical order), holes included.
    g = reconstruct(ps, model)
    polys = list(g.geoms) if isinstance(g, MultiPolygon) else ([] if g.is_empty else [g])
    region = region_of(ps)
    for poly, comp in zip(polys, region.components, strict=True):
        assert discretize(poly, model) == region.labels.pixel_set(comp.label)


@pytest.mark.parametrize("model", MODELS)
@settings(max_examples=300)
@given(ps=pixel_sets, e=st.integers(30, 40), sx=st.sampled_from([-1, 1]), sy=st.sampled_from([-1, 1]))
def test_far_from_the_origin_r_is_translation_covariant(
    model: str, ps: PixelSet, e: int, sx: int, sy: int
) -> None:
    # docs/design.md §3 item 8: offsets 2^30 … 2^40 (the accepted limit): the same polygons, translated
    # exactly.
    if ps.is_empty():
        return
    x0, y0, x1, y1 = ps.bbox  # type: ignore[misc]
    # the largest |coordinate| after the move is at most 2^e
    t = (sx * (2**e) - (x1 if sx > 0 else x0), sy * (2**e) - (y1 if sy > 0 else y0))
    moved = ps.translate(*t)
    g = reconstruct(ps, model)
    gm = reconstruct(moved, model)
    assert np.array_equal(
        shapely.get_coordinates(gm), shapely.get_coordinates(g) + np.array(t, dtype=np.float64)
    )
    assert discretize(gm, model) == moved


@st.composite
def small_sets(draw: st.DrawFn) -> PixelSet:
    seed = draw(st.integers(0, 2**32 - 1))
    rng = _rng(seed)
    h, w = draw(st.integers(1, 7)), draw(st.integers(1, 7))
    return PixelSet(
        rng.random((h, w)) < draw(st.floats(0.2, 0.9)), (int(rng.integers(-5, 5)), int(rng.integers(-5, 5)))
    )


@pytest.mark.parametrize("model", MODELS)
@settings(max_examples=60)
@given(ps=small_sets())
def test_against_the_fraction_reference(model: str, ps: PixelSet) -> None:
    # The independent reference (Fractions and the definitions, no shared code) agrees: D(R(A)) = A.
    g = reconstruct(ps, model)
    assert reference_discretize(g, model) == set(map(tuple, ps.points().tolist()))
