"""The watertight gauss subdivision of a label map, checked exactly against the definitions.

What a user needs from it, each asserted independently of how it is built:

* every part discretizes (gauss) to exactly its own pixels — checked with the compiled exact discretizer and,
  on small maps, with the Fraction reference of tests/oracles;
* every part is a valid polygon, shells counter-clockwise and holes clockwise;
* neighbours share their boundaries exactly: every directed edge occurs once, its reverse at most once and
  then in another part (same float64 end points, compared with ==); the unmatched edges (the outline) have
  no other part on their far side (their midpoints lie strictly outside every other part, exact integer
  test), and they bound a valid polygon U whose gauss discretization is the support, each of whose holes
  holds a background pixel centre, and which no segment joining the centres of two 4-adjacent pixels of
  different non-zero labels crosses. Together with validity this proves the parts tile U without gap or
  overlap: for a point z off the edges, Σ_L w_z(∂P_L) = w_z(∂U) ∈ {0, 1} because matched edges cancel;
* no more vertices than the crack staircase, about one per digital straight segment on smooth boundaries;
* determinism and covariance under integer translations (exact float equality).
"""

from __future__ import annotations

from collections import Counter, defaultdict
from fractions import Fraction

import numpy as np
import pytest
import shapely
from hypothesis import assume, given, settings
from hypothesis import strategies as st
from hypothesis.extra.numpy import arrays
from shapely.geometry import MultiPolygon, Polygon

from mrm.core.errors import ParameterError
from mrm.core.grids import LabelMap, PixelSet
from mrm.geometry.discretize import discretize
from mrm.geometry.dss.segmentation import greedy_segmentation
from mrm.geometry.reconstruct import _cell_polylines as chains
from mrm.geometry.reconstruct.subdivision import reconstruct_label_map, subdivide, watertight_parts
from mrm.reps.region import region_of
from tests.oracles.discretize_reference import reference_discretize
from tests.oracles.geometry_strategies import star_polygons

Edge = tuple[tuple[float, float], tuple[float, float]]


# ------------------------------------------------------------------------------------------- helpers
def polygons_of(geom: Polygon | MultiPolygon) -> list[Polygon]:
    if geom.is_empty:
        return []
    return list(geom.geoms) if isinstance(geom, MultiPolygon) else [geom]


def rings_of(geom: Polygon | MultiPolygon) -> list[list[tuple[float, float]]]:
    """Every ring without its closing repeat, oriented with the part on its left (asserted)."""
    out = []
    for poly in polygons_of(geom):
        assert shapely.is_ccw(poly.exterior), "a shell must run counter-clockwise"
        out.append(list(poly.exterior.coords)[:-1])
        for h in poly.interiors:
            assert not shapely.is_ccw(h), "a hole must run clockwise"
            out.append(list(h.coords)[:-1])
    return out


def edges_of(geom: Polygon | MultiPolygon) -> list[Edge]:
    out = []
    for ring in rings_of(geom):
        out.extend((ring[k], ring[(k + 1) % len(ring)]) for k in range(len(ring)))
    return out


class Scaler:
    """Maps the dyadic float coordinates of a set of geometries to exact integers (times 2^k)."""

    def __init__(self, coords: list[float]) -> None:
        k = 0
        for v in coords:
            den = Fraction(v).denominator
            k = max(k, den.bit_length() - 1)
        self.k = k + 1  # one more bit: midpoints of edges are integers too
        self.s = 1 << self.k
        big = max((abs(v) for v in coords), default=0.0) * self.s
        assert big < 2**29, "coordinates too fine for the int64 checks below"

    def __call__(self, v: float) -> int:
        f = Fraction(v) * self.s
        assert f.denominator == 1
        return int(f)

    def pts(self, pts: list[tuple[float, float]]) -> np.ndarray:
        return np.array([(self(x), self(y)) for x, y in pts], dtype=np.int64).reshape(-1, 2)


def segments_array(scale: Scaler, geom: Polygon | MultiPolygon) -> np.ndarray:
    """(m, 4) int64 rows ax, ay, bx, by of every ring edge of a geometry."""
    rows = [(scale(a[0]), scale(a[1]), scale(b[0]), scale(b[1])) for a, b in edges_of(geom)]
    return np.array(rows, dtype=np.int64).reshape(-1, 4)


def strictly_outside(points: np.ndarray, segs: np.ndarray) -> np.ndarray:
    """For integer points (n, 2) and the integer edges (m, 4) of a polygon: strictly outside it (not on an
    edge, even crossing count). Exact: every product stays below 2^62."""
    if segs.shape[0] == 0:
        return np.ones(points.shape[0], dtype=bool)
    x, y = points[:, 0:1], points[:, 1:2]
    ax, ay, bx, by = (segs[:, i][None, :] for i in range(4))
    cr = (bx - ax) * (y - ay) - (by - ay) * (x - ax)
    on = (
        (cr == 0)
        & (np.minimum(ax, bx) <= x)
        & (x <= np.maximum(ax, bx))
        & (np.minimum(ay, by) <= y)
        & (y <= np.maximum(ay, by))
    )
    straddle = (ay > y) != (by > y)
    # the crossing abscissa is right of x  <=>  cr has the sign of (by − ay)
    right = np.where(by > ay, cr > 0, cr < 0)
    inside = np.count_nonzero(straddle & right, axis=1) % 2 == 1
    return ~on.any(axis=1) & ~inside


def segments_meet(p: np.ndarray, q: np.ndarray, segs: np.ndarray) -> np.ndarray:
    """For n segments p→q (int) and m segments (int rows ax, ay, bx, by): does each p→q meet any of them
    (closed segments, touching included)? Exact orientation tests."""
    if segs.shape[0] == 0 or p.shape[0] == 0:
        return np.zeros(p.shape[0], dtype=bool)
    px, py, qx, qy = p[:, 0:1], p[:, 1:2], q[:, 0:1], q[:, 1:2]
    ax, ay, bx, by = (segs[:, i][None, :] for i in range(4))

    def orient(ux, uy, vx, vy, wx, wy):  # type: ignore[no-untyped-def]
        return np.sign((vx - ux) * (wy - uy) - (vy - uy) * (wx - ux))

    o1, o2 = orient(px, py, qx, qy, ax, ay), orient(px, py, qx, qy, bx, by)
    o3, o4 = orient(ax, ay, bx, by, px, py), orient(ax, ay, bx, by, qx, qy)
    proper = (o1 * o2 < 0) & (o3 * o4 < 0)

    def on(ux, uy, vx, vy, wx, wy, o):  # type: ignore[no-untyped-def]
        return (
            (o == 0)
            & (np.minimum(ux, vx) <= wx)
            & (wx <= np.maximum(ux, vx))
            & (np.minimum(uy, vy) <= wy)
            & (wy <= np.maximum(uy, vy))
        )

    touch = (
        on(px, py, qx, qy, ax, ay, o1)
        | on(px, py, qx, qy, bx, by, o2)
        | on(ax, ay, bx, by, px, py, o3)
        | on(ax, ay, bx, by, qx, qy, o4)
    )
    return (proper | touch).any(axis=1)


def clockwise_key(back: tuple[int, int], d: tuple[int, int]) -> tuple[int, Fraction]:
    """Sort key of direction d by its clockwise angle from direction ``back`` (exact, no trigonometry)."""
    cr = back[0] * d[1] - back[1] * d[0]
    dot = back[0] * d[0] + back[1] * d[1]
    # clockwise angle in (0, 2π): half 0 for cr < 0 (within π clockwise), then half 1; inside a half the
    # angle grows as the cotangent −dot/|cr| falls
    if cr < 0:
        return 0, Fraction(dot, -cr)
    if cr > 0:
        return 1, Fraction(-dot, cr)
    return (0, Fraction(-(10**30))) if dot < 0 else (2, Fraction(0))  # straight on, or straight back


def loops_from_edges(scale: Scaler, edges: list[Edge]) -> list[list[tuple[float, float]]]:
    """The boundary rings that directed edges (region on the left) form: at a vertex with several ways out,
    take the first one clockwise from the way back (the region's own corner), then split each closed walk
    where it passes a vertex twice, so every loop is a simple closed polyline."""
    out_edges: dict[tuple[float, float], list[tuple[float, float]]] = defaultdict(list)
    for a, b in sorted(edges):
        out_edges[a].append(b)

    def vec(u: tuple[float, float], v: tuple[float, float]) -> tuple[int, int]:
        return scale(v[0]) - scale(u[0]), scale(v[1]) - scale(u[1])

    loops: list[list[tuple[float, float]]] = []
    for start in sorted(out_edges):
        while out_edges[start]:
            walk = [start]
            prev, v = start, out_edges[start].pop(0)
            while True:
                if v == start and (not out_edges[v] or len(walk) > 1):
                    break
                walk.append(v)
                back = vec(v, prev)
                nxt = min(out_edges[v], key=lambda w: clockwise_key(back, vec(v, w)))
                out_edges[v].remove(nxt)
                prev, v = v, nxt
            # split at repeated vertices
            stack: list[tuple[float, float]] = []
            seen: dict[tuple[float, float], int] = {}
            for u in [*walk, start]:
                if u in seen:
                    k = seen[u]
                    loop = stack[k:]
                    for w in loop:
                        del seen[w]
                    del stack[k:]
                    loops.append(loop)
                seen[u] = len(stack)
                stack.append(u)
    return loops


def area2(scale: Scaler, ring: list[tuple[float, float]]) -> int:
    p = scale.pts(ring)
    q = np.roll(p, -1, axis=0)
    return int(np.sum(p[:, 0] * q[:, 1] - q[:, 0] * p[:, 1]))


def staircase_vertices(lm: LabelMap) -> int:
    """Pointels where the crack boundaries of a label map turn or branch (the staircase's vertices)."""
    p = np.pad(lm.labels, 1)
    a, b, c, d = p[:-1, :-1], p[:-1, 1:], p[1:, :-1], p[1:, 1:]  # bl, br, tl, tr around each pointel
    down, up, left, right = a != b, c != d, a != c, b != d
    deg = down.astype(int) + up + left + right
    straight = (deg == 2) & ((down & up) | (left & right))
    return int(np.count_nonzero((deg >= 2) & ~straight))


def check_subdivision(
    lm: LabelMap, parts: dict[int, Polygon | MultiPolygon], reference: bool = False
) -> None:
    labels = lm.label_values()
    assert list(parts) == labels
    # 1. validity and exact gauss discretization
    for v, g in parts.items():
        assert shapely.is_valid(g), (v, shapely.is_valid_reason(g))
        assert discretize(g, "gauss") == lm.pixel_set(v), v
        if reference:
            assert reference_discretize(g, "gauss") == set(map(tuple, lm.pixel_set(v).points().tolist())), v
    # 2. exact edge sharing
    owner: dict[Edge, int] = {}
    for v, g in parts.items():
        for e in edges_of(g):
            assert e not in owner, f"edge {e} twice"
            owner[e] = v
    outline: dict[int, list[Edge]] = defaultdict(list)
    for e, v in owner.items():
        w = owner.get((e[1], e[0]))
        assert w != v, "an edge and its reverse in the same part"
        if w is None:
            outline[v].append(e)
    all_outline = [e for es in outline.values() for e in es]
    coords = [c for e in owner for pt in e for c in pt]
    scale = Scaler(coords)
    segs = {v: segments_array(scale, g) for v, g in parts.items()}
    # 3. the far side of every unmatched edge belongs to no other part
    for v, es in outline.items():
        mids = np.array(
            [((scale(a[0]) + scale(b[0])) // 2, (scale(a[1]) + scale(b[1])) // 2) for a, b in es],
            dtype=np.int64,
        )
        for w in labels:
            if w != v:
                assert strictly_outside(mids, segs[w]).all(), (v, w)
    # 4. the outline bounds a valid polygon U with D(U) = support, each hole holding a background centre
    shells, holes = [], []
    for loop in loops_from_edges(scale, all_outline):
        (shells if area2(scale, loop) > 0 else holes).append(loop)
    assert shells
    owned: list[list[list[tuple[float, float]]]] = [[] for _ in shells]
    for h in holes:
        mid = scale.pts([h[0]]) + scale.pts([h[1]])
        inside = [
            k
            for k, s in enumerate(shells)
            if not strictly_outside(mid // 2, segments_array(scale, Polygon(s))).all()
        ]
        assert inside, "a hole of the outline outside every shell"
        owned[min(inside, key=lambda k: area2(scale, shells[k]))].append(h)
        assert not discretize(Polygon(h[::-1]), "gauss").is_empty(), "a gap: a hole with no pixel centre"
    union = MultiPolygon([Polygon(s, hs) for s, hs in zip(shells, owned, strict=True)])
    assert shapely.is_valid(union), shapely.is_valid_reason(union)
    assert discretize(union, "gauss") == lm.support()
    # 5. no unmatched edge between two 4-adjacent pixels of different non-zero labels
    lab, (x0, y0) = lm.labels, lm.origin
    rungs_p, rungs_q = [], []
    for dr, dc in ((0, 1), (1, 0)):
        a = lab[: lab.shape[0] - dr, : lab.shape[1] - dc]
        b = lab[dr:, dc:]
        rr, cc = np.nonzero((a != b) & (a != 0) & (b != 0))
        rungs_p.extend(zip((cc + x0).tolist(), (rr + y0).tolist(), strict=True))
        rungs_q.extend(zip((cc + dc + x0).tolist(), (rr + dr + y0).tolist(), strict=True))
    if rungs_p and all_outline:
        p = np.array(rungs_p, dtype=np.int64) * scale.s
        q = np.array(rungs_q, dtype=np.int64) * scale.s
        out_segs = np.array(
            [(scale(a[0]), scale(a[1]), scale(b[0]), scale(b[1])) for a, b in all_outline], dtype=np.int64
        )
        assert not segments_meet(p, q, out_segs).any(), "an outline edge between two labelled pixels"
    # 6. no more vertices than the staircase
    vertices = {pt for e in owner for pt in e}
    assert len(vertices) <= staircase_vertices(lm)


def coordinates(parts: dict[int, Polygon | MultiPolygon]) -> dict[int, np.ndarray]:
    return {v: shapely.get_coordinates(g) for v, g in parts.items()}


# ------------------------------------------------------------------------------------------ strategies
@st.composite
def label_maps(draw, max_size: int = 40):  # type: ignore[no-untyped-def]
    """Random blobs (smoothed noise cut into levels, level 0 the background) plus salt-and-pepper noise."""
    h = draw(st.integers(1, max_size))
    w = draw(st.integers(1, max_size))
    k = draw(st.integers(2, 6))
    seed = draw(st.integers(0, 2**32 - 1))
    rng = np.random.default_rng(seed)
    field = rng.random((h + 4, w + 4))
    for _ in range(draw(st.integers(0, 4))):  # box blur, a few passes: blobs of growing size
        field = (
            field
            + np.roll(field, 1, 0)
            + np.roll(field, -1, 0)
            + np.roll(field, 1, 1)
            + np.roll(field, -1, 1)
        ) / 5
    field = field[2:-2, 2:-2]
    cuts = np.quantile(field, np.sort(rng.random(k - 1)))
    lab = np.searchsorted(cuts, field).astype(np.int32)
    noise = draw(st.sampled_from([0.0, 0.0, 0.05, 0.2, 0.6]))
    flip = rng.random((h, w)) < noise
    lab[flip] = rng.integers(0, k, int(flip.sum()))
    origin = (draw(st.integers(-50, 50)), draw(st.integers(-50, 50)))
    lm = LabelMap(lab, origin)
    assume(lm.label_values())
    return lm


tiny_maps = arrays(np.int32, st.tuples(st.integers(1, 6), st.integers(1, 6)), elements=st.integers(0, 3)).map(
    LabelMap
)


# ------------------------------------------------------------------------------------------------ tests
@settings(max_examples=120)
@given(label_maps())
def test_random_label_maps_form_a_watertight_subdivision(lm: LabelMap) -> None:
    check_subdivision(lm, reconstruct_label_map(lm))


@settings(max_examples=120)
@given(tiny_maps)
def test_tiny_maps_checkerboards_and_pinches_match_the_reference(lm: LabelMap) -> None:
    assume(lm.label_values())
    check_subdivision(lm, reconstruct_label_map(lm), reference=True)


@pytest.mark.parametrize(
    "rows",
    [
        ["1"],
        ["12", "21"],  # 2-label checkerboard: every pointel inside is a pinch
        ["1212", "2121", "1212", "2121"],
        ["111", "101", "011"],  # a ring that closes diagonally: its shell touches itself
        ["0110", "1001", "1001", "0110"],  # four pixels touching only at corners, around a hole
        ["22222", "21112", "21312", "21112", "22222"],  # nested closed 1-cells
        ["1111111", "1000001", "1022201", "1020201", "1022201", "1000001", "1111111"],
        ["10101", "01010", "10101"],
        ["111111111"],  # one pixel wide
        ["1", "1", "1", "2", "2"],
        ["3112", "3112", "3332"],
    ],
)
def test_handmade_configurations(rows: list[str]) -> None:
    lab = np.array([[int(c) for c in r] for r in rows[::-1]], dtype=np.int32)
    lm = LabelMap(lab, (3, -2))
    check_subdivision(lm, reconstruct_label_map(lm), reference=True)


def corefinement_parts(e: Polygon, f: Polygon) -> list[PixelSet]:
    a, b = discretize(e, "gauss"), discretize(f, "gauss")
    return [a - b, a & b, b - a]


@settings(max_examples=60)
@given(
    star_polygons(max_vertices=12, max_radius=6.0),
    star_polygons(max_vertices=12, max_radius=6.0),
    st.sampled_from([1.0, 2.0, 3.0, 4.0]),
    st.integers(-8, 8),
    st.integers(-8, 8),
)
def test_corefinement_parts_share_their_boundaries(
    e: Polygon, f: Polygon, zoom: float, dx: int, dy: int
) -> None:
    # two digitized random polygons (vertices on centres, corners, dyadic or raw floats), enlarged by a
    # power-of-two-friendly factor so the parts have long shared boundaries
    e = shapely.affinity.scale(e, zoom, zoom, origin=(0, 0))
    f = shapely.affinity.translate(shapely.affinity.scale(f, zoom, zoom, origin=(0, 0)), dx, dy)
    assume(e.is_valid and f.is_valid)
    parts = corefinement_parts(e, f)
    assume(any(not p.is_empty() for p in parts))
    polys = watertight_parts(parts)
    assert len(polys) == 3
    for g, p in zip(polys, parts, strict=True):
        assert discretize(g, "gauss") == p
        assert g.is_empty == p.is_empty()
    lm = LabelMap.from_pixel_sets(parts)
    check_subdivision(lm, {k + 1: g for k, g in enumerate(polys) if not g.is_empty})


@settings(max_examples=25)
@given(label_maps(max_size=25), st.integers(-1000, 1000), st.integers(-1000, 1000))
def test_deterministic_and_translation_covariant(lm: LabelMap, dx: int, dy: int) -> None:
    base = coordinates(reconstruct_label_map(lm))
    again = coordinates(reconstruct_label_map(LabelMap(np.array(lm.labels), lm.origin)))
    moved = coordinates(reconstruct_label_map(LabelMap(lm.labels, (lm.origin[0] + dx, lm.origin[1] + dy))))
    assert base.keys() == again.keys() == moved.keys()
    for v in base:
        assert np.array_equal(base[v], again[v])
        assert np.array_equal(base[v] + np.array([dx, dy]), moved[v])


@pytest.mark.parametrize("radius", [20, 50, 100])
def test_smooth_boundaries_need_about_one_edge_per_digital_straight_segment(radius: int) -> None:
    yy, xx = np.mgrid[-radius - 1 : radius + 2, -radius - 1 : radius + 2]
    disk = (xx - 0.3) ** 2 + (yy - 0.17) ** 2 <= radius**2
    lm = LabelMap(disk.astype(np.int32))
    (poly,) = reconstruct_label_map(lm).values()
    chain = region_of(PixelSet(disk)).components[0].outer
    greedy = len(greedy_segmentation(chain.points(), closed=True))
    edges = len(poly.exterior.coords) - 1
    assert edges <= greedy + 3
    check_subdivision(lm, {1: poly})


def test_three_labels_of_two_overlapping_disks_are_compact() -> None:
    yy, xx = np.mgrid[-60:61, -60:81]
    a = (xx + 5) ** 2 + yy**2 <= 50**2
    b = (xx - 25) ** 2 + (yy - 8) ** 2 <= 40**2
    parts = [PixelSet(a & ~b), PixelSet(a & b), PixelSet(b & ~a)]
    polys = watertight_parts(parts)
    lm = LabelMap.from_pixel_sets(parts)
    check_subdivision(lm, {k + 1: g for k, g in enumerate(polys)})
    sd = subdivide(lm)
    # the staircase has hundreds of vertices; a joint reconstruction a few dozen
    assert sd.n_vertices * 5 < staircase_vertices(lm)
    assert not any(sd.staircase[k] for k, c in enumerate(sd.cells.one_cells) if len(c.chain) > 10)


def test_shared_polylines_are_the_same_floats_in_both_parts() -> None:
    lab = np.zeros((30, 30), dtype=np.int32)
    yy, xx = np.mgrid[0:30, 0:30]
    lab[(xx - 12) ** 2 + (yy - 14) ** 2 < 100] = 1
    lab[(xx - 19) ** 2 + (yy - 15) ** 2 < 80] = 2
    lm = LabelMap(lab)
    sd = subdivide(lm)
    e1, e2 = set(edges_of(sd.parts[1])), set(edges_of(sd.parts[2]))
    shared = {(a, b) for a, b in e1 if (b, a) in e2}
    assert shared, "labels 1 and 2 are neighbours"
    for c, pl in zip(sd.cells.one_cells, sd.polylines, strict=True):
        if (c.left, c.right) == (2, 1):
            for a, b in zip(pl[:-1].tolist(), pl[1:].tolist(), strict=True):
                assert ((b[0], b[1]), (a[0], a[1])) in shared


def test_any_polyline_the_verifier_accepts_keeps_the_subdivision_exact(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    # Replace the construction by random polylines (staircase vertices dropped at random, the others
    # jittered inside their pieces): the exact per-1-cell verifier must accept only polylines that keep every
    # part exact and valid, so the final per-part check never has to step in.
    import mrm.geometry.reconstruct.subdivision as sub

    rng = np.random.default_rng(7)

    def random_polyline(ch):  # type: ignore[no-untyped-def]
        stair = ch.staircase()
        keep = [stair[0]] + [v for v in stair[1:-1] if rng.random() < 0.7] + [stair[-1]]
        out = [keep[0]]
        for (x, y, e), k in keep[1:-1]:
            jx, jy = rng.integers(-7, 8, 2)  # eighths of a Q unit, inside the open piece
            out.append((chains._vertex((x << 3) + int(jx), (y << 3) + int(jy), e + 3), k))
        return [*out, keep[-1]]

    rejected = []
    real_part_ok = sub._part_ok

    def part_ok(geom, ps):  # type: ignore[no-untyped-def]
        ok = real_part_ok(geom, ps)
        rejected.append(not ok)
        return ok

    monkeypatch.setattr(sub, "_KERNEL", False)  # the Python construction, whose _greedy is replaced
    monkeypatch.setattr(chains, "_greedy", random_polyline)
    monkeypatch.setattr(sub, "_part_ok", part_ok)
    accepted = 0
    for seed in range(40):
        r = np.random.default_rng(seed)
        lab = r.integers(0, 4, (10, 12)).astype(np.int32)
        lab[r.random(lab.shape) < 0.5] = 1  # bigger blobs, longer 1-cells
        lm = LabelMap(lab)
        sd = sub.subdivide(lm)
        accepted += sum(not s for s in sd.staircase)
        check_subdivision(lm, sd.parts)
    assert accepted > 20, "the experiment must exercise accepted random polylines"
    assert not any(rejected)


def test_empty_and_errors() -> None:
    assert reconstruct_label_map(LabelMap(np.zeros((3, 3), dtype=np.int32))) == {}
    assert watertight_parts([]) == []
    one = PixelSet.box(0, 0, 2, 2)
    out = watertight_parts([PixelSet.empty(), one, PixelSet.empty()])
    assert out[0].is_empty and out[2].is_empty and discretize(out[1], "gauss") == one
    with pytest.raises(ParameterError, match="gauss"):
        reconstruct_label_map(LabelMap(np.ones((2, 2), dtype=np.int32)), "standard")
    with pytest.raises(ParameterError):
        reconstruct_label_map(LabelMap(np.ones((2, 2), dtype=np.int32)), "nonsense")
    with pytest.raises(ParameterError, match="disjoint"):
        watertight_parts([one, PixelSet.box(1, 1, 3, 3)])


def test_staircase_vertex_counter_on_a_known_map() -> None:
    # a 2×2 block: its 4 corners; with a second label on the right half, 2 more (T-junctions)
    assert staircase_vertices(LabelMap(np.ones((2, 2), dtype=np.int32))) == 4
    assert staircase_vertices(LabelMap(np.array([[1, 2], [1, 2]], dtype=np.int32))) == 6
    assert Counter(edges_of(Polygon([(0, 0), (1, 0), (1, 1)]))) == Counter(
        [((0.0, 0.0), (1.0, 0.0)), ((1.0, 0.0), (1.0, 1.0)), ((1.0, 1.0), (0.0, 0.0))]
    )


def test_the_checker_catches_independent_reconstructions_and_moved_vertices() -> None:
    # The checks above must be able to fail: parts reconstructed one by one do not share their edges, and
    # one shared vertex moved by 2^-10 in a single part opens a sliver.
    from mrm.geometry.reconstruct import reconstruct

    lab = np.zeros((20, 20), dtype=np.int32)
    lab[2:15, 3:12] = 1
    lab[5:18, 9:17] = 2
    lm = LabelMap(lab)
    separate = {v: reconstruct(lm.pixel_set(v), "gauss") for v in lm.label_values()}
    with pytest.raises(AssertionError):
        check_subdivision(lm, separate)
    parts = reconstruct_label_map(lm)
    check_subdivision(lm, parts)
    shared = {b for a, b in edges_of(parts[1]) if (b, a) in set(edges_of(parts[2]))}
    target = sorted(shared)[len(shared) // 2]

    def nudge(c: np.ndarray) -> np.ndarray:
        hit = (c[:, 0] == target[0]) & (c[:, 1] == target[1])
        c = c.copy()
        c[hit, 0] += 2.0**-10
        return c

    moved = dict(parts)
    moved[1] = shapely.transform(parts[1], nudge)
    with pytest.raises(AssertionError):
        check_subdivision(lm, moved)


def test_a_vertex_without_an_exact_float64_value_is_refused_with_a_message() -> None:
    # Far from the origin a fine dyadic vertex cannot be written in float64: a ParameterError that says
    # so (the audit found an AssertionError from `mrm corefine --model gauss` at x = 2^45).
    from mrm.core.errors import ParameterError
    from mrm.geometry.reconstruct._cell_polylines import _Chain, _to_plane

    pts = np.array([[2**45, 0], [2**45 + 1, 0], [2**45 + 2, 0]], dtype=np.int64)
    ch = _Chain(pts, closed=False)
    assert _to_plane(ch, [(1, 1, 0)]).tolist() == [[2**45, 0.0]]  # (Q - 1) / 2 of the origin pointel
    with pytest.raises(ParameterError, match="too far from the origin"):
        _to_plane(ch, [(1, 1, 12)])  # 13 fractional bits at 2^45: 58 bits


# ------------------------------------------------------------------- the fast paths against the definitions
def nested_rings(k: int) -> LabelMap:
    """k concentric square rings of label 1 (each ring a shell with a hole) and a few labels between them."""
    size = 4 * k + 1
    lab = np.zeros((size, size), dtype=np.int32)
    for i in range(k):
        a, b = 2 * i, size - 2 * i
        lab[a:b, a:b] = 1
        lab[a + 1 : b - 1, a + 1 : b - 1] = 2 + i % 2
    lab[2 * k, 2 * k] = 1
    return LabelMap(lab)


@settings(max_examples=150)
@given(st.one_of(label_maps(), st.integers(1, 6).map(nested_rings)))
def test_hole_owners_from_components_are_the_owners_by_point_in_ring(lm: LabelMap) -> None:
    # The owner of each hole read from the label's 4-components must be the smallest shell that contains
    # the hole, found by point-in-ring tests against every shell (the definition); the rings' sort keys
    # and first left pixels are checked against their pointels.
    import mrm.geometry.reconstruct.subdivision as sub

    cells = sub.cells_of(lm)
    asm = sub._Assembler(lm, cells, sub._cell_points(lm, cells))
    pixels = sub._label_pixel_sets(lm)
    left_of = {(1, 0): (0, 0), (0, 1): (-1, 0), (-1, 0): (-1, -1), (0, -1): (0, -1)}
    several = 0
    for v, ps in pixels.items():
        shells, holes = sub._rings(asm, v)
        for lp, key in [(s[0], s[2]) for s in shells] + holes:
            pts = asm.loop_points(lp)
            low = min((int(y), int(x)) for x, y in pts.tolist())
            assert divmod(key, asm.key_w) == (low[0] - asm.key_y0, low[1] - asm.key_x0)
            step = (int(pts[1, 0] - pts[0, 0]), int(pts[1, 1] - pts[0, 1]))
            o = left_of[step]
            assert asm.first_left[lp[0]] == (int(pts[0, 0]) + o[0], int(pts[0, 1]) + o[1])
            assert asm.first_left[lp[0]] in ps  # the label is on the left
        rings = [(a2, asm.loop_points(lp)) for lp, a2, _ in shells]
        hole_pts = [asm.loop_points(lp) for lp, _ in holes]
        by_rings = sub._owners_by_rings(rings, hole_pts)
        first = [asm.first_left[s[0][0]] for s in shells], [asm.first_left[h[0][0]] for h in holes]
        assert sub._owners_by_components(*first, ps) == by_rings
        assert sub._owners(asm, shells, holes, ps) == by_rings
        several += len(shells) > 1 and bool(holes)
    assume(several)


@settings(max_examples=80)
@given(label_maps())
def test_cell_points_and_areas_are_those_of_each_chain(lm: LabelMap) -> None:
    import mrm.geometry.reconstruct.subdivision as sub

    cells = sub.cells_of(lm)
    _, _, points, area2 = sub._cell_points(lm, cells)
    ox, oy = lm.origin
    for c, pts, a2 in zip(cells.one_cells, points, area2, strict=True):
        ref = c.chain.points()
        assert pts.tolist() == ref.tolist()
        xs = [int(x) - ox for x in ref[:, 0]]
        ys = [int(y) - oy for y in ref[:, 1]]
        assert a2 == sum(xs[k] * ys[k + 1] - xs[k + 1] * ys[k] for k in range(len(xs) - 1))


@settings(max_examples=80)
@given(label_maps())
def test_the_staircase_is_the_chain_with_its_straight_pointels_dropped(lm: LabelMap) -> None:
    import mrm.geometry.reconstruct.subdivision as sub

    cells = sub.cells_of(lm)
    zero = {z.point for z in cells.zero_cells}
    for c in cells.one_cells:
        pts = [tuple(p) for p in c.chain.points().tolist()]
        closed = c.chain.start not in zero
        n = len(pts) - 1
        ch = chains._Chain(c.chain.points(), closed)
        x0, y0 = pts[0]

        def straight(k: int, pts: list[tuple[int, ...]] = pts, n: int = n) -> bool:
            a, b, d = pts[(k - 1) % n], pts[k], pts[k + 1]
            return (b[0] - a[0], b[1] - a[1]) == (d[0] - b[0], d[1] - b[1])

        ks = (
            [k for k in range(n) if not straight(k)]
            if closed
            else [0, *(k for k in range(1, n) if not straight(k)), n]
        )
        want = [((2 * (pts[k][0] - x0), 2 * (pts[k][1] - y0), 0), k) for k in ks]
        assert ch.staircase() == want


def python_and_kernel_polylines(lm: LabelMap, limit: int) -> tuple[list[tuple[list, bool]], list[int], list]:  # type: ignore[type-arg]
    """Per 1-cell: the Python construction's (vertices, staircase?), the kernel's status and vertices."""
    import mrm.geometry.reconstruct._subdivision_kernels as K
    import mrm.geometry.reconstruct.subdivision as sub

    cells = sub.cells_of(lm)
    zero = {z.point for z in cells.zero_cells}
    pts_all, off, points, _ = sub._cell_points(lm, cells)
    closed = np.array([c.chain.start not in zero for c in cells.one_cells], dtype=bool)
    python = [chains._polyline(chains._Chain(p, bool(c))) for p, c in zip(points, closed, strict=True)]
    loc = pts_all - np.repeat(pts_all[off[:-1]], np.diff(off), axis=0)
    status, count, verts = K.polylines_kernel(loc, off, closed, limit)
    kernel = [[tuple(v) for v in verts[off[i] : off[i] + count[i]].tolist()] for i in range(len(points))]
    return python, status.tolist(), kernel


@settings(max_examples=100)
@given(label_maps(max_size=60), st.sampled_from([2**60, 2**60, 2**24, 2**14]))
def test_the_compiled_construction_is_the_python_one_or_steps_aside(lm: LabelMap, limit: int) -> None:
    # Chain by chain, the kernel returns exactly the Python construction's polyline (or its staircase), or
    # FALLBACK when a product would pass the limit; with small limits the fallback is exercised too.
    import mrm.geometry.reconstruct._subdivision_kernels as K

    python, status, kernel = python_and_kernel_polylines(lm, limit)
    for (verts, is_stair), s, kv in zip(python, status, kernel, strict=True):
        if s == K.FALLBACK:
            continue
        assert (s == K.STAIRCASE) == is_stair
        assert kv == verts


def test_the_compiled_construction_builds_real_polylines_and_falls_back_under_a_small_limit(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    # The experiment above must see both outcomes: polylines built by the kernel under the real limit, and
    # fallbacks when the limit is tiny; the subdivision stays exact either way.
    import mrm.geometry.reconstruct._subdivision_kernels as K
    import mrm.geometry.reconstruct.subdivision as sub

    yy, xx = np.mgrid[-30:31, -30:31]
    lab = ((xx * xx + yy * yy) < 28**2).astype(np.int32) + ((xx - 9) ** 2 + yy * yy < 15**2)
    lm = LabelMap(lab.astype(np.int32))
    _, status, _ = python_and_kernel_polylines(lm, K.LIMIT)
    assert status.count(K.POLYLINE) >= 2 and K.FALLBACK not in status
    _, status, _ = python_and_kernel_polylines(lm, 2**12)
    assert K.FALLBACK in status
    sd = sub.subdivide(lm)
    check_subdivision(lm, sd.parts)
    assert not all(sd.staircase)
    monkeypatch.setattr(K, "LIMIT", 2**12)  # most chains now go through the Python functions
    fell_back = sub.subdivide(lm)
    assert fell_back.staircase == sd.staircase
    assert all(np.array_equal(p, q) for p, q in zip(fell_back.polylines, sd.polylines, strict=True))


@pytest.mark.parametrize("x0", [2**20, 2**44, 2**47])
def test_far_from_the_origin_the_compiled_path_gives_the_python_answer_or_the_same_refusal(
    monkeypatch: pytest.MonkeyPatch, x0: int
) -> None:
    import mrm.geometry.reconstruct.subdivision as sub

    yy, xx = np.mgrid[-12:13, -12:13]
    lab = ((xx * xx + yy * yy) < 11**2).astype(np.int32) + (xx * 2 + yy * 3 > 4)
    lm = LabelMap(lab.astype(np.int32), (x0, -(x0 // 2)))

    def run() -> object:
        try:
            sd = sub.subdivide(lm)
        except ParameterError as e:
            return str(e)
        return [p.tolist() for p in sd.polylines]

    fast = run()
    monkeypatch.setattr(sub, "_KERNEL", False)
    assert fast == run()


def concentric_labels(k: int) -> LabelMap:
    """k square rings, each its own label: from k = 13 the labels' boxes together pass 4 times the array."""
    yy, xx = np.mgrid[-k : k + 1, -k : k + 1]
    return LabelMap((np.maximum(abs(xx), abs(yy)) + 1).astype(np.int32), (3, -2))


@settings(max_examples=80)
@given(st.one_of(label_maps(), st.integers(1, 20).map(concentric_labels)))
def test_label_pixel_sets_are_the_pixels_of_each_label(lm: LabelMap) -> None:
    import mrm.geometry.reconstruct.subdivision as sub

    got = sub._label_pixel_sets(lm)
    assert list(got) == lm.label_values()
    for v, ps in got.items():
        assert ps == lm.pixel_set(v)
