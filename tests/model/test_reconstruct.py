"""R on hand-made cases: exact outcomes, topology, the corridor, the safety nets and the exact verifier."""

from __future__ import annotations

import numpy as np
import pytest
import shapely
from hypothesis import given, settings
from hypothesis import strategies as st
from shapely.geometry import MultiPolygon, Polygon

from mrm.core.errors import ParameterError
from mrm.core.grids import PixelSet
from mrm.core.models import Model
from mrm.geometry.discretize import discretize
from mrm.geometry.dss.segmentation import chain_points, greedy_segmentation
from mrm.geometry.reconstruct import reconstruct, reconstruct_detailed
from mrm.geometry.reconstruct.border import KIND_NAMES, border_path, border_paths, corridors, visit_counts
from mrm.geometry.reconstruct.safety_net import eroded_net, net_ring, safety_net, staircase
from mrm.geometry.reconstruct.verify import verify
from mrm.reps.region import CrackChain, region_of
from mrm.reps.summary import count_vertices
from tests.oracles.gauss_contract import check_gauss_containment

MODELS = Model.names()


def ps_of(rows: list[str], origin: tuple[int, int] = (0, 0)) -> PixelSet:
    """A pixel set drawn as text, top row first ('#' = in the set)."""
    m = np.array([[ch == "#" for ch in r] for r in rows[::-1]], dtype=bool)
    return PixelSet(m, origin)


def polygons(g: Polygon | MultiPolygon) -> list[Polygon]:
    if g.is_empty:
        return []
    return list(g.geoms) if isinstance(g, MultiPolygon) else [g]


def disk(r: float, c: tuple[float, float] = (1 / 7, 2 / 9)) -> PixelSet:
    n = int(2 * r + 6)
    yy, xx = np.mgrid[-n:n, -n:n]
    return PixelSet((xx - c[0]) ** 2 + (yy - c[1]) ** 2 <= r * r, (-n, -n))


def greedy_count(ps: PixelSet) -> int:
    return sum(
        len(greedy_segmentation(chain_points(ch.start, ch.codes), closed=True))
        for ch in region_of(ps).boundary_chains
    )


def assert_exact(ps: PixelSet, model: str) -> Polygon | MultiPolygon:
    g = reconstruct(ps, model)
    assert g.is_valid, shapely.is_valid_reason(g)
    assert discretize(g, model) == ps
    if model == "gauss":
        check_gauss_containment(g, ps)  # no centre on ∂R, ∂R within the border pixels' voxels
    else:
        assert discretize(g, "supercover") == ps  # ⊂ V(A)
    report = verify(g, ps, model)
    assert report.ok, report.problems
    return g


CASES = {
    "pixel": ["#"],
    "domino": ["##"],
    "tall domino": ["#", "#"],
    "row": ["##########"],
    "diagonal pair": ["#.", ".#"],
    "L": ["#.", "##"],
    "plus": [".#.", "###", ".#."],
    "ring": ["###", "#.#", "###"],
    "thin ring": ["#####", "#...#", "#...#", "#####"],
    "hole at a corner": ["###.", "#.#.", "##.#"],
    "checker": ["#.#.#", ".#.#.", "#.#.#"],
    "staircase": ["#...", "##..", ".##.", "..##"],
    "arm": ["....#######", "###.#......", "#####......", "###........"],
    "nested": ["#######", "#.....#", "#.###.#", "#.#.#.#", "#.###.#", "#.....#", "#######"],
}


@pytest.mark.parametrize("model", MODELS)
@pytest.mark.parametrize("name", list(CASES))
def test_hand_made_cases_are_exact(name: str, model: str) -> None:
    ps = ps_of(CASES[name], (3, -7))
    g = assert_exact(ps, model)
    region = region_of(ps)
    assert len(polygons(g)) == region.n_components
    assert [len(p.interiors) for p in polygons(g)] == [len(c.holes) for c in region.components]


def test_empty_set_gives_an_empty_polygon() -> None:
    for model in MODELS:
        g = reconstruct(PixelSet.empty(), model)
        assert isinstance(g, Polygon) and g.is_empty
        assert verify(g, PixelSet.empty(), model).ok


def test_unknown_model_is_a_parameter_error() -> None:
    with pytest.raises(ParameterError, match="unknown discretization model"):
        reconstruct(ps_of(["#"]), "nearest")


def test_an_isolated_pixel_is_a_triangle_around_its_centre() -> None:
    g = reconstruct(ps_of(["#"], (5, 9)))
    assert isinstance(g, Polygon)
    assert count_vertices(g) == 3
    assert g.contains(shapely.Point(5, 9))
    minx, miny, maxx, maxy = g.bounds
    assert minx > 4.5 and maxx < 5.5 and miny > 8.5 and maxy < 9.5


def test_two_side_by_side_pixels_are_a_triangle() -> None:
    for rows in (["##"], ["#", "#"]):
        for model in ("standard", "supercover"):
            assert count_vertices(assert_exact(ps_of(rows), model)) == 3


def test_diagonal_contact_gives_two_polygons() -> None:
    # Under the cover models two pixels sharing only a corner can never come from one connected polygon.
    for model in MODELS:
        g = assert_exact(ps_of(["#.", ".#"]), model)
        assert isinstance(g, MultiPolygon) and len(g.geoms) == 2
        assert g.geoms[0].distance(g.geoms[1]) > 0


def test_a_hole_touching_the_outside_at_a_corner_is_no_hole() -> None:
    # The gap at (2, 0) meets the outside through a diagonal: the complement is 8-connected there.
    ps = ps_of(["###", "#.#", "##."])
    for model in MODELS:
        g = assert_exact(ps, model)
        assert isinstance(g, Polygon) and len(g.interiors) == 0
    closed = ps_of(["###", "#.#", "###"])
    assert len(reconstruct(closed).interiors) == 1


def test_rectangle_is_a_quadrilateral_inside_its_pixels() -> None:
    ps = PixelSet.box(0, 0, 9, 4)
    for model in MODELS:
        g = assert_exact(ps, model)
        assert count_vertices(g) == 4


def test_translation_is_exact_and_output_deterministic() -> None:
    ps = disk(7.3)
    g = reconstruct(ps)
    assert shapely.get_coordinates(reconstruct(ps)).tolist() == shapely.get_coordinates(g).tolist()
    for t in ((1, 0), (-13, 7), (1000, -999)):
        g2 = reconstruct(ps.translate(*t))
        assert np.array_equal(shapely.get_coordinates(g2), shapely.get_coordinates(g) + np.array(t, float))


def test_far_from_the_origin_coordinates_stay_exact() -> None:
    # docs/design.md §3 item 8: translation covariance and exactness up to the accepted limit ±2⁴⁰, refused
    # beyond.
    ps = disk(9.3)
    for model in MODELS:
        g = reconstruct(ps, model)
        for t in ((2**26, -(2**26)), (3 * 2**30, 5), (-(2**40) + 12, 2**40 - 12), (2**39 + 7, -(2**35))):
            moved = ps.translate(*t)
            gm = reconstruct(moved, model)
            assert discretize(gm, model) == moved
            assert verify(gm, moved, model).ok
            shift = np.array(t, dtype=float)
            assert np.array_equal(shapely.get_coordinates(gm), shapely.get_coordinates(g) + shift)
    for t in ((2**40 + 1, 0), (0, -(2**40) - 5), (2**48, 0)):
        with pytest.raises(ParameterError, match="too large"):
            reconstruct(ps.translate(*t))


def test_border_paths_and_corridors_far_from_the_origin_are_translated() -> None:
    # The kernels hold element coordinates as int32: border.py works relative to the chains' lowest start.
    ps = disk(6.3) | ps_of(["###"], (6, 0))
    t = (3 * 2**30 + 1, -(2**39) + 5)
    near, far = region_of(ps).boundary_chains, region_of(ps.translate(*t)).boundary_chains
    shift = np.array(t)
    for a, b in zip(border_paths(near), border_paths(far), strict=True):
        assert np.array_equal(b.pixels, a.pixels + shift) and b.pixels.dtype == np.int64
        assert np.array_equal(b.kinds, a.kinds) and np.array_equal(b.step_in, a.step_in)
    for model in MODELS:
        for a, b in zip(corridors(near, model), corridors(far, model), strict=True):
            assert np.array_equal(b.pieces, a.pieces + np.repeat(shift, 2))
            assert np.array_equal(b.gate_left, a.gate_left + shift) and np.array_equal(b.gate_dir, a.gate_dir)


def test_sets_beyond_the_int32_tables_are_refused(monkeypatch) -> None:
    # R's corridor tables are int32 (_base.Corridors): a set too wide or with too many linels is refused with
    # a message (the limits are lowered here: no test can hold a mask 2^28 pixels wide).
    import mrm.geometry.reconstruct as rec

    ps = disk(9.3)
    monkeypatch.setattr(rec, "INT32_SIDE", 10)
    with pytest.raises(ParameterError, match="too large"):
        reconstruct(ps)
    monkeypatch.setattr(rec, "INT32_SIDE", 2**28)
    monkeypatch.setattr(rec, "INT32_LINELS", 10)
    with pytest.raises(ParameterError, match="too large"):
        reconstruct(ps)


def test_coordinates_are_coarse_dyadic_rationals() -> None:
    g = reconstruct(disk(30.5))
    c = shapely.get_coordinates(g).ravel()
    denominators = [v.as_integer_ratio()[1] for v in c.tolist()]
    assert all(d & (d - 1) == 0 for d in denominators)  # powers of two
    assert max(denominators) <= 2**22


@pytest.mark.parametrize(
    ("r", "limit"), [(5, 1.0), (10, 1.15), (20, 1.1), (50, 1.15), (100, 1.1), (200, 1.1), (500, 1.05)]
)
def test_disks_need_about_one_vertex_per_greedy_segment(r: float, limit: float) -> None:
    # docs/algorithms.md §5.2: V4 stays within a few percent of the greedy DSS count, far below MLP (~3.46
    # r^2/3).
    ps = disk(r)
    for model in ("standard", "supercover"):
        g = reconstruct(ps, model)
        assert discretize(g, model) == ps
        assert count_vertices(g) <= limit * greedy_count(ps)


def test_gauss_keeps_every_centre_strictly_inside() -> None:
    ps = disk(12.4) - disk(4.1)
    g = reconstruct(ps, "gauss")
    assert discretize(g, "gauss") == ps
    inside = shapely.contains_xy(g, ps.points()[:, 0].astype(float), ps.points()[:, 1].astype(float))
    assert inside.all()
    boundary = g.boundary
    assert not shapely.intersects(boundary, shapely.points(ps.points().astype(float))).any()


def test_one_pixel_wide_shapes_are_simple_rings() -> None:
    # A one-pixel arm makes the border path visit pixels twice: each visit gets its own part of the pixel.
    for ps in (ps_of(["###########"]), ps_of(["#....", ".##..", "..##.", "...##"])):
        for model in MODELS:
            g = assert_exact(ps, model)
            assert g.area > 0


# ---------------------------------------------------------------------------------------------- border paths


def test_border_path_is_the_4_connected_8_border() -> None:
    ps = disk(9.2) | ps_of(["#########"], (3, 0))
    region = region_of(ps)
    for ch in region.boundary_chains:
        path = border_path(ch)
        steps = np.abs(np.diff(np.vstack([path.pixels, path.pixels[:1]]), axis=0)).sum(axis=1)
        assert (steps == 1).all()
        assert set(KIND_NAMES) >= set(path.kinds.tolist())
    pts = {tuple(p) for path in border_paths(region.boundary_chains) for p in path.pixels.tolist()}
    m = ps.to_array((ps.bbox[0] - 1, ps.bbox[1] - 1, ps.bbox[2] + 1, ps.bbox[3] + 1))
    x0, y0 = ps.bbox[0] - 1, ps.bbox[1] - 1
    eight_border = set()
    for x, y in ps.points().tolist():
        r, c = y - y0, x - x0
        if not m[r - 1 : r + 2, c - 1 : c + 2].all():
            eight_border.add((x, y))
    assert pts == eight_border


def test_pieces_of_different_visits_are_disjoint() -> None:
    rng = np.random.default_rng(3)
    for _ in range(30):
        ps = PixelSet(rng.random((12, 12)) < 0.6)
        chains = region_of(ps).boundary_chains
        counts = visit_counts(border_paths(chains))
        for model in MODELS:
            rects = np.vstack([c.pieces for c in corridors(chains, model)])
            for i in range(rects.shape[0]):
                a = rects[i]
                overlap = (np.minimum(a[1], rects[:, 1]) > np.maximum(a[0], rects[:, 0])) & (
                    np.minimum(a[3], rects[:, 3]) > np.maximum(a[2], rects[:, 2])
                )
                assert overlap.sum() == 1  # itself only
        assert all(v >= 1 for v in counts.values())


def test_gate_ends_lie_on_the_pieces_they_join() -> None:
    chains = region_of(ps_of(CASES["arm"])).boundary_chains
    for cor in corridors(chains, "gauss") + corridors(chains, "standard"):
        for k in range(len(cor)):
            for end in (cor.gate_left[k], cor.gate_right[k]):
                for piece in (cor.pieces[k - 1], cor.pieces[k]):
                    assert piece[0] <= end[0] <= piece[1] and piece[2] <= end[1] <= piece[3]


# ---------------------------------------------------------------------------------------------- safety nets


@pytest.mark.parametrize("model", MODELS)
def test_safety_nets_are_exact(model: str) -> None:
    rng = np.random.default_rng(11)
    for _ in range(40):
        ps = PixelSet(rng.random((10, 13)) < rng.uniform(0.2, 0.9), (-4, 6))
        net = safety_net(ps, model)
        assert net.is_valid
        assert discretize(net, model) == ps
        assert len(polygons(net)) == region_of(ps).n_components


def test_eroded_net_is_a_quarter_inside_the_crack() -> None:
    ch = CrackChain((0, 0), "00121233")  # the L of pixels (0, 0), (1, 0), (0, 1)
    assert region_of(ps_of(["#.", "##"])).components[0].outer == ch
    ring = net_ring(ch)
    assert ring.tolist() == [
        [-0.25, -0.25],
        [1.25, -0.25],
        [1.25, 0.25],
        [0.25, 0.25],
        [0.25, 1.25],
        [-0.25, 1.25],
    ]
    assert eroded_net(ps_of(["#.", "##"])).equals(shapely.Polygon(ring))


def test_staircase_cuts_pinched_corners_under_gauss() -> None:
    ps = ps_of(["##.", "#.#", ".##"])  # one component? no: the diagonal pair splits it
    g = staircase(ps)
    assert g.is_valid
    assert discretize(g, "gauss") == ps


def test_reconstruction_is_not_the_safety_net() -> None:
    ps = disk(40.3)
    for model in MODELS:
        d = reconstruct_detailed(ps, model)
        assert d.n_fallback == 0
        assert not d.geometry.equals(safety_net(ps, model))
    assert count_vertices(reconstruct(ps)) < count_vertices(eroded_net(ps)) / 4


# ---------------------------------------------------------------------------------------------- verify


def test_verify_rejects_what_is_not_reversible() -> None:
    ps = disk(6.2)
    g = reconstruct(ps)
    assert verify(g, ps).ok
    # a vertex pushed onto a pixel corner, out of its pixel
    shell = np.asarray(g.exterior.coords)
    moved = shell.copy()
    moved[0] = np.round(moved[0] - 0.5) + 0.5
    moved[-1] = moved[0]
    bad = Polygon(moved)
    assert not verify(bad, ps).ok
    # one pixel more than the geometry covers
    assert not verify(g, ps | PixelSet.from_points([(20, 20)])).ok
    # the safety net of another set
    assert not verify(eroded_net(disk(6.0)), ps).ok or eroded_net(disk(6.0)).equals(eroded_net(ps))
    # wrong type
    assert not verify(shapely.LineString([(0, 0), (1, 1)]), ps).ok


def jittered(g: Polygon | MultiPolygon, rng: np.random.Generator, sigma: float) -> Polygon | MultiPolygon:
    """Every vertex moved by a random multiple of 1/64 (rings stay closed)."""

    def ring(coords: object) -> np.ndarray:
        xy = np.asarray(coords)[:-1]
        return xy + np.round(rng.normal(0, sigma, xy.shape) * 64) / 64

    parts = [Polygon(ring(p.exterior.coords), [ring(h.coords) for h in p.interiors]) for p in polygons(g)]
    return parts[0] if len(parts) == 1 else MultiPolygon(parts)


@pytest.mark.parametrize("model", MODELS)
def test_what_verify_accepts_discretizes_exactly(model: str) -> None:
    # Soundness of the exact checker against the independent oracle: perturbed reconstructions.
    rng = np.random.default_rng(7)
    accepted = rejected = 0
    for _ in range(60):
        ps = PixelSet(rng.random((9, 9)) < 0.7)
        g = reconstruct(ps, model)
        jitter = jittered(g, rng, float(rng.choice([0.004, 0.02, 0.1])))
        if not jitter.is_valid:
            continue
        if verify(jitter, ps, model).ok:
            accepted += 1
            assert discretize(jitter, model) == ps
        else:
            rejected += 1
    assert accepted > 0 and rejected > 0


# ---------------------------------------------------------------------------------------------- details


def test_detailed_reconstruction_explains_each_ring() -> None:
    ps = disk(15.7) - disk(5.2)
    d = reconstruct_detailed(ps)
    assert d.geometry.equals_exact(reconstruct(ps), 0)
    assert [r.hole for r in d.rings] == [False, True]
    for r in d.rings:
        assert r.status == "v4"
        assert len(r.sources) == r.vertices.shape[0] == r.edge_window.size
        assert set(r.sources) <= {"lines", "patch"}
        assert r.lines.shape == (len(r.pieces), 4) and r.reach.shape == (len(r.pieces),)
        # every vertex made by two lines lies strictly inside a piece of the ring's corridor
        for v in r.vertices.tolist():
            assert any(p[0] < v[0] < p[1] and p[2] < v[1] < p[3] for p in r.pieces.tolist())
    assert d.n_vertices == count_vertices(d.geometry)


# ------------------------------------------------------------------------------------------ mrm reconstruct

INFO_KEYS = {"model", "pixels", "components", "holes", "euler", "boundary_chains", "segments", "vertices"}


def mrm(capsys: pytest.CaptureFixture[str], *argv: object) -> tuple[int, str, str]:
    from mrm.cli import run_cli

    code = run_cli([str(a) for a in argv])
    out, err = capsys.readouterr()
    return code, out, err


def test_cli_reconstruct_writes_geojson_that_discretizes_back(capsys, tmp_path) -> None:
    import json

    from mrm.io.pixel_files import write_pixels
    from mrm.io.vector_files import read_geometry

    ps = disk(8.3) - disk(2.2)
    ps = ps.translate(40, -3)
    write_pixels(ps, tmp_path / "a.png")
    for model in MODELS:
        out = tmp_path / f"a-{model}.geojson"
        code, text, err = mrm(
            capsys, "reconstruct", tmp_path / "a.png", "-o", out, "--model", model, "--json"
        )
        assert code == 0, err
        summary = json.loads(text)
        assert INFO_KEYS | {"seconds"} <= set(summary)
        assert summary["model"] == model and summary["holes"] == 1 and summary["components"] == 1
        geom = read_geometry(out)
        assert discretize(geom, model) == ps
        assert summary["vertices"] == count_vertices(geom) == count_vertices(reconstruct(ps, model))


@pytest.mark.parametrize("seed", range(12))
def test_vertex_count_is_the_ring_points_without_their_closing_repeat(seed) -> None:
    # count_vertices asks GEOS for all coordinates at once; the reference walks every ring.
    def by_rings(g) -> int:
        polys = getattr(g, "geoms", [g])
        return sum(len(r.coords) - 1 for p in polys if not p.is_empty for r in (p.exterior, *p.interiors))

    rng = np.random.default_rng(seed)
    ps = PixelSet(rng.random((20, 17)) < rng.uniform(0.2, 0.8), (int(rng.integers(-50, 50)), 7))
    for model in MODELS:
        g = reconstruct(ps, model)
        assert count_vertices(g) == by_rings(g) > 0
        with_empty = MultiPolygon([*getattr(g, "geoms", [g])])
        assert count_vertices(shapely.GeometryCollection([with_empty, Polygon()])) == by_rings(g)


def test_cli_reconstruct_many_inputs_into_a_directory_or_pattern(capsys, tmp_path) -> None:
    import json

    from mrm.io.pixel_files import write_pixels
    from mrm.io.vector_files import read_geometry

    sets = {"one": disk(4.4), "two": ps_of(CASES["checker"]), "three": ps_of(CASES["nested"])}
    for name, ps in sets.items():
        write_pixels(ps, tmp_path / f"{name}.npz")
    inputs = [tmp_path / f"{n}.npz" for n in sets]
    code, text, err = mrm(capsys, "reconstruct", *inputs, "-o", tmp_path / "out", "--jobs", "2", "--json")
    assert code == 0, err
    summary = json.loads(text)
    assert summary["inputs"] == 3 and len(summary["files"]) == 3
    assert summary["components"] == sum(region_of(p).n_components for p in sets.values())
    for name, ps in sets.items():
        assert discretize(read_geometry(tmp_path / "out" / f"{name}.geojson"), "standard") == ps
    code, _, err = mrm(capsys, "reconstruct", *inputs, "-o", tmp_path / "pat" / "{stem}-R.wkt")
    assert code == 0, err
    assert discretize(read_geometry(tmp_path / "pat" / "two-R.wkt"), "standard") == sets["two"]


@pytest.mark.parametrize(
    ("argv", "message"),
    [
        (["missing.png", "-o", "x.geojson"], "No such file"),
        (["a.png", "-o", "x.txt"], "not a vector output file"),
        (["a.txt", "-o", "x.geojson"], "not a supported input file"),
        (["a.png", "a.png", "-o", "x.geojson"], "directory or a pattern"),
        (["bad.png", "-o", "x.geojson"], ""),
    ],
)
def test_cli_reconstruct_bad_input_is_a_clear_error(capsys, tmp_path, monkeypatch, argv, message) -> None:
    from mrm.io.pixel_files import write_pixels

    monkeypatch.chdir(tmp_path)
    write_pixels(ps_of(["#"]), tmp_path / "a.png")
    (tmp_path / "bad.png").write_bytes(b"not a png at all")
    code, _out, err = mrm(capsys, "reconstruct", *argv)
    assert code == 2
    assert err.startswith("mrm reconstruct: error: ") and message in err
    assert "Traceback" not in err
    assert not (tmp_path / "x.geojson").exists()


# ---------------------------------------------------------------------------------------------- reach kernels


def _corridor_arrays(ps: PixelSet, gauss: bool) -> tuple:
    # gauss: the dual corridor (dual squares of the crack pointels), in the dual frame
    from mrm.geometry.reconstruct import _dual as dk
    from mrm.geometry.reconstruct import _kernels as k
    from mrm.geometry.topology.cracks import trace_mask

    m = np.ascontiguousarray(ps.mask.view(np.uint8))
    rings = trace_mask(m)
    if gauss:
        return dk.dual_corridors_all(rings.codes, rings.off, rings.sx, rings.sy, m.shape[0], m.shape[1], 20)
    return k.corridors_all(rings.codes, rings.off, rings.sx, rings.sy, m.shape[0], m.shape[1], 20)


def _stabbable(gates: list[tuple[tuple[int, int], tuple[int, int]]]) -> bool:
    """Independent oracle: is there a line with every left end P strictly left and right end Q strictly right?

    A linear program in Fractions: lines n(t)·X + c = 0 with n = (−σy t, σx (1 − t)), t ∈ [0, 1], in each
    direction quadrant (σx, σy); maximise the margin m subject to f(P) ≥ m, −f(Q) ≥ m; the optimum is at a
    vertex where three constraints are tight, so every triple is solved and the best feasible one kept.
    """
    from fractions import Fraction
    from itertools import combinations

    best = None
    (px, py), (qx, qy) = gates[0]
    # the two quadrants of directions that cross the first gate (P on the left)
    quadrants = [(sx, sy) for sx in (1, -1) for sy in (1, -1) if sx * (py - qy) > 0 or -sy * (px - qx) > 0]
    for sx, sy in quadrants:
        rows = []  # a·(t, c, m) >= b
        for p, q in gates:
            for (x, y), sign in ((p, 1), (q, -1)):
                # sign * (t (−sy x − sx y) + sx y + c) − m >= 0
                rows.append(((sign * (-sy * x - sx * y), sign, -1), -sign * sx * y))
        rows.append(((1, 0, 0), 0))  # t >= 0
        rows.append(((-1, 0, 0), -1))  # t <= 1
        for tri in combinations(rows, 3):
            a = [[Fraction(v) for v in r[0]] for r in tri]
            b = [Fraction(r[1]) for r in tri]
            det = (
                a[0][0] * (a[1][1] * a[2][2] - a[1][2] * a[2][1])
                - a[0][1] * (a[1][0] * a[2][2] - a[1][2] * a[2][0])
                + a[0][2] * (a[1][0] * a[2][1] - a[1][1] * a[2][0])
            )
            if det == 0:
                continue
            sol = []
            for col in range(3):
                mm = [row[:] for row in a]
                for r in range(3):
                    mm[r][col] = b[r]
                sol.append(
                    (
                        mm[0][0] * (mm[1][1] * mm[2][2] - mm[1][2] * mm[2][1])
                        - mm[0][1] * (mm[1][0] * mm[2][2] - mm[1][2] * mm[2][0])
                        + mm[0][2] * (mm[1][0] * mm[2][1] - mm[1][1] * mm[2][0])
                    )
                    / det
                )
            if all(sum(c * v for c, v in zip(r[0], sol, strict=True)) >= r[1] for r in rows):
                best = sol[2] if best is None else max(best, sol[2])
    return best is not None and best > 0


def test_exact_preimage_reach_against_a_fraction_linear_program() -> None:
    from mrm.geometry.reconstruct import _kernels as k

    rng = np.random.default_rng(5)
    checked = 0
    for _ in range(12):
        ps = PixelSet(rng.random((6, 6)) < 0.75)
        for gauss in (False, True):
            cor = _corridor_arrays(ps, gauss)
            poff, gp, gq, gdir, special = cor[10], cor[13], cor[14], cor[15], cor[17]
            for r in range(poff.size - 1):
                a, b = int(poff[r]), int(poff[r + 1])
                n = b - a
                if special[r] == 1 or n < 3:
                    continue
                reach = np.zeros(n, np.int64)
                lines = np.zeros((n, 4))
                k.general_reach(gp[a:b], gq[a:b], gdir[a:b], np.ones(n, bool), reach, lines)
                for i in rng.choice(n, size=min(n, 3), replace=False).tolist():
                    j = i + int(reach[i])
                    if j - i > 4:
                        continue
                    window = [(tuple(gp[a + g % n]), tuple(gq[a + g % n])) for g in range(i + 1, j + 1)]
                    assert _stabbable(window)
                    if j + 1 < i + n - 1:
                        g = (j + 1) % n
                        assert not _stabbable([*window, (tuple(gp[a + g]), tuple(gq[a + g]))])
                    checked += 1
    assert checked > 25


@st.composite
def _thin_sets(draw: st.DrawFn) -> PixelSet:
    """Sets with long one-pixel-wide lines (every pixel visited twice: long windows of split pieces)."""
    h, w = draw(st.integers(3, 14)), draw(st.integers(3, 70))
    rng = np.random.default_rng(draw(st.integers(0, 2**32 - 1)))
    m = np.zeros((h, w), bool)
    for _ in range(draw(st.integers(1, 4))):
        if rng.random() < 0.5:
            r = int(rng.integers(h))
            m[r, int(rng.integers(w)) :] = True
        else:
            c = int(rng.integers(w))
            m[int(rng.integers(h)) :, c] = True
    m |= rng.random((h, w)) < draw(st.sampled_from([0.0, 0.05, 0.3, 0.6]))
    return PixelSet(m)


@settings(max_examples=150, deadline=None)
@given(
    ps=st.one_of(
        _thin_sets(),
        st.builds(lambda s: PixelSet(np.random.default_rng(s).random((12, 12)) < 0.6), st.integers(0, 2**16)),
        st.builds(lambda s: PixelSet(np.random.default_rng(s).random((4, 4)) < 0.5), st.integers(0, 2**16)),
    ),
    gauss=st.booleans(),
    seed=st.integers(0, 2**16),
)
def test_the_sliding_pass_gives_the_reaches_and_lines_of_the_per_window_preimages(
    ps: PixelSet, gauss: bool, seed: int
) -> None:
    # sliding_reach (one pass, two stacks of suffix preimages) against general_reach (each window built
    # from scratch), on every start or a random subset: the same reaches and the very same lines.
    from mrm.geometry.reconstruct import _kernels as k
    from mrm.geometry.reconstruct._sliding import sliding_reach

    rng = np.random.default_rng(seed)
    cor = _corridor_arrays(ps, gauss)
    poff, gp, gq, gdir, special = cor[10], cor[13], cor[14], cor[15], cor[17]
    for r in range(poff.size - 1):
        a, b = int(poff[r]), int(poff[r + 1])
        n = b - a
        if special[r] == 1 or n < 2:
            continue
        todo = np.ones(n, bool) if rng.random() < 0.5 else rng.random(n) < 0.4
        want_reach, want_lines = np.zeros(n, np.int64), np.zeros((n, 4))
        k.general_reach(gp[a:b], gq[a:b], gdir[a:b], todo, want_reach, want_lines)
        got_reach, got_lines = np.zeros(n, np.int64), np.zeros((n, 4))
        assert sliding_reach(gp[a:b], gq[a:b], gdir[a:b], todo, got_reach, got_lines)
        assert np.array_equal(got_reach[todo], want_reach[todo])
        assert np.array_equal(got_lines[todo], want_lines[todo])


def test_the_sliding_pass_refuses_polygons_beyond_its_capacity_and_general_reach_takes_over() -> None:
    # With room for 4 vertices per polygon (a gate's own) the pass must stop (False), never write past its
    # buffers; the per-window preimage then gives the answer, as ring_reach does.
    from mrm.geometry.reconstruct import _kernels as k
    from mrm.geometry.reconstruct._sliding import sliding_reach

    m = np.zeros((5, 60), bool)
    m[2] = True
    m[1, 30:] = True
    cor = _corridor_arrays(PixelSet(m), False)
    a, b = int(cor.poff[0]), int(cor.poff[1])
    n = b - a
    todo = np.ones(n, bool)
    args = (cor.gp[a:b], cor.gq[a:b], cor.gdir[a:b], todo)
    assert not sliding_reach(*args, np.zeros(n, np.int64), np.zeros((n, 4)), 2)
    want_reach, want_lines = np.zeros(n, np.int64), np.zeros((n, 4))
    k.general_reach(*args, want_reach, want_lines)
    got_reach, got_lines = np.zeros(n, np.int64), np.zeros((n, 4))
    assert sliding_reach(*args, got_reach, got_lines)
    assert np.array_equal(got_reach, want_reach) and np.array_equal(got_lines, want_lines)


def test_a_long_one_pixel_line_is_exact_and_compact_under_every_model() -> None:
    # 3,000 pixels in a row: every window runs the length of the line (quadratic one window at a time).
    m = np.zeros((3, 3000), bool)
    m[1] = True
    ps = PixelSet(m, (-1500, 7))
    for model in MODELS:
        geom = reconstruct(ps, model)
        assert discretize(geom, model) == ps
        assert len(geom.exterior.coords) - 1 <= 6


@pytest.mark.parametrize("gauss", [False, True])
def test_fast_reach_kernels_agree_with_the_exact_preimage(gauss: bool) -> None:
    # On whole squares (pixels under the cover models, dual squares of pointels under gauss) the O(n)
    # standard DSS reach equals the exact preimage's.
    from mrm.geometry.reconstruct import _kernels as k

    rng = np.random.default_rng(9)
    sets = [disk(r) for r in (3.3, 7.8, 15.1, 30.2, 45.7)]
    sets += [PixelSet(rng.random((20, 20)) < 0.7) for _ in range(15)]
    compared = 0
    for ps in sets:
        cor = _corridor_arrays(ps, gauss)
        eoff, ec, er = cor[0], cor[1], cor[2]
        poff, gp, gq, gdir = cor[10], cor[13], cor[14], cor[15]
        special, full = cor[17], cor[18]
        for r in range(poff.size - 1):
            a, b = int(poff[r]), int(poff[r + 1])
            n = b - a
            if special[r] == 1 or n < 2:
                continue
            exact = np.zeros(n, np.int64)
            fast = np.zeros(n, np.int64)
            k.general_reach(gp[a:b], gq[a:b], gdir[a:b], np.ones(n, bool), exact, np.zeros((n, 4)))
            if full[r]:
                k.dss_reach(int(eoff[r]), ec, er, n, fast, np.zeros((n, 4)))
            else:
                continue
            assert np.array_equal(exact, fast)
            compared += n
    assert compared > 500


@pytest.mark.parametrize("model", MODELS)
def test_safety_net_rings_pass_the_exact_corridor_check(model: str) -> None:
    from mrm.geometry.reconstruct import _kernels as k

    rng = np.random.default_rng(13)
    for _ in range(40):
        ps = PixelSet(rng.random((16, 16)) < rng.uniform(0.2, 0.9))
        cor = _corridor_arrays(ps, model == "gauss")
        r0off, r0, r0t, poff, rect, gp, gq, gdir, kmax, special = (
            cor[7],
            cor[8],
            cor[9],
            cor[10],
            cor[11],
            cor[13],
            cor[14],
            cor[15],
            cor[16],
            cor[17],
        )
        assert k.check_nets(poff, rect, gp, gq, gdir, kmax, special, r0off, r0, r0t).all()


# --------------------------------------------------------------------------------------------- straight edges


def _edges(g: Polygon) -> np.ndarray:
    return np.diff(np.asarray(g.exterior.coords), axis=0)


@pytest.mark.parametrize("box", [(0, 0, 9, 9), (3, -2, 20, 5), (-7, 4, -4, 30)])
@pytest.mark.parametrize("model", MODELS)
def test_a_box_of_pixels_is_an_axis_aligned_rectangle(box: tuple[int, int, int, int], model: str) -> None:
    ps = PixelSet.box(*box)
    g = assert_exact(ps, model)
    assert isinstance(g, Polygon) and count_vertices(g) == 4
    e = _edges(g)
    assert np.all((e[:, 0] == 0) != (e[:, 1] == 0))  # every edge horizontal or vertical
    xmin, ymin, xmax, ymax = box
    if model == "gauss":
        # halfway between the border centres inside and outside: the pixel sides, V(A) itself
        assert g.bounds == (xmin - 0.5, ymin - 0.5, xmax + 0.5, ymax + 0.5)
        return
    assert xmin - 0.5 < g.bounds[0] and g.bounds[2] < xmax + 0.5  # ... inside the pixels
    assert ymin - 0.5 < g.bounds[1] and g.bounds[3] < ymax + 0.5


def test_digitized_squares_come_back_with_their_edge_slopes() -> None:
    axis = Polygon([(0.3, 0.2), (20.3, 0.2), (20.3, 15.2), (0.3, 15.2)])
    diamond = Polygon([(10.1, 0.3), (20.1, 10.3), (10.1, 20.3), (0.1, 10.3)])
    for model in ("standard", "supercover"):
        for shape, slope_ok in (
            (axis, lambda e: (e[:, 0] == 0) != (e[:, 1] == 0)),
            (diamond, lambda e: np.abs(e[:, 0]) == np.abs(e[:, 1])),
        ):
            ps = discretize(shape, model)
            g = assert_exact(ps, model)
            assert count_vertices(g) == 4
            assert np.all(slope_ok(_edges(g))), _edges(g)


def test_simplest_line_is_the_simplest_direction_crossing_the_gates() -> None:
    # Oracle: the definition — a line dx·Y − dy·X = c crosses the open gate [P, Q] (P its left end) iff
    # P is strictly on its left and Q strictly on its right; try every primitive direction up to the answer.
    from math import gcd

    from mrm.geometry.reconstruct import _kernels as k

    def offsets(d: tuple[int, int], window: list) -> tuple[int, int]:
        lo = max(d[0] * q[1] - d[1] * q[0] for _p, q in window)
        hi = min(d[0] * p[1] - d[1] * p[0] for p, _q in window)
        return lo, hi

    rng = np.random.default_rng(11)
    checked = 0
    for _ in range(10):
        ps = PixelSet(rng.random((7, 7)) < 0.7)
        for gauss in (False, True):
            cor = _corridor_arrays(ps, gauss)
            poff, gp, gq, special = cor[10], cor[13], cor[14], cor[17]
            for r in range(poff.size - 1):
                a, b = int(poff[r]), int(poff[r + 1])
                n = b - a
                if special[r] == 1 or n < 4:
                    continue
                for i in rng.choice(n, size=min(n, 3), replace=False).tolist():
                    for length in (1, 2, 4, 7):
                        window = [
                            (tuple(gp[a + g % n].tolist()), tuple(gq[a + g % n].tolist()))
                            for g in range(i, i + length)
                        ]
                        # a known direction: from the first gate's midpoint to the last one's, if it stabs
                        (p0, q0), (p1, q1) = window[0], window[-1]
                        ex, ey = p1[0] + q1[0] - p0[0] - q0[0], p1[1] + q1[1] - p0[1] - q0[1]
                        if length == 1:
                            ex, ey = {0: (1, 0), 1: (0, 1), 2: (-1, 0), 3: (0, -1)}[int(cor[15][a + i % n])]
                        if (ex, ey) == (0, 0) or offsets((ex, ey), window)[0] >= offsets((ex, ey), window)[1]:
                            continue
                        ok, dx, dy, c2 = k.simplest_line(gp[a:b], gq[a:b], i, i + length - 1, n, ex, ey, 200)
                        assert ok
                        lo, hi = offsets((dx, dy), window)
                        assert 2 * lo < c2 < 2 * hi and c2 == lo + hi  # inside, centred
                        size = abs(dx) + abs(dy)
                        assert gcd(dx, dy) == 1
                        for s in range(1, size):
                            for u in range(-s, s + 1):
                                for v in (s - abs(u), abs(u) - s):
                                    if gcd(u, v) == 1:
                                        lo2, hi2 = offsets((u, v), window)
                                        assert lo2 >= hi2, ((u, v), (dx, dy), window)
                        checked += 1
    assert checked > 100


def test_cli_reconstruct_writes_one_feature_per_component(capsys, tmp_path) -> None:
    import json

    from shapely.geometry import shape

    from mrm.io.pixel_files import write_pixels

    ps = ps_of(CASES["checker"], (3, 4)) | (disk(5.2) - disk(1.5)).translate(30, 0)
    write_pixels(ps, tmp_path / "a.png")
    region = region_of(ps)
    for model in MODELS:
        out = tmp_path / f"{model}.geojson"
        code, _text, err = mrm(
            capsys, "reconstruct", tmp_path / "a.png", "-o", out, "--model", model, "--features", "components"
        )
        assert code == 0, err
        feats = json.loads(out.read_text(encoding="utf-8"))["features"]
        assert [f["properties"]["part"] for f in feats] == list(range(region.n_components))
        for f, comp in zip(feats, region.components, strict=True):
            assert discretize(shape(f["geometry"]), model) == region.labels.pixel_set(comp.label)


@pytest.mark.parametrize("model", MODELS)
def test_rings_split_between_threads_give_the_single_thread_result(model: str, monkeypatch) -> None:
    # R shares the rings of a large set between threads (the kernels release the GIL); the chunks'
    # rings are joined in order, so the polygons are the very same as one thread's.
    import mrm.geometry.reconstruct as rec

    rng = np.random.default_rng(21)
    ps = PixelSet(rng.random((90, 110)) < 0.55)
    monkeypatch.setattr(rec, "_threads", lambda: 3)
    plan = rec._ring_plan(np.diff(rec._k.corridors_all(*_rings_arrays(ps)).poff))
    assert len(plan) == 3
    threaded = reconstruct(ps, model)
    monkeypatch.setattr(rec, "_threads", lambda: 1)
    assert shapely.to_wkb(reconstruct(ps, model)) == shapely.to_wkb(threaded)
    detail = reconstruct_detailed(ps, model)
    assert shapely.to_wkb(detail.geometry) == shapely.to_wkb(threaded)


@pytest.mark.parametrize("model", MODELS)
def test_a_big_ring_among_small_ones_gets_a_thread_to_itself(model: str, monkeypatch) -> None:
    # One large object among many small ones (camera, 4096² blobs): cut into consecutive halves, the
    # thread that took the big ring with its neighbours did most of the work. The big ring is a share of
    # its own, the threads' work is balanced to within one ring, and the polygons are one thread's.
    import mrm.geometry.reconstruct as rec

    rng = np.random.default_rng(8)
    small = PixelSet(rng.random((8, 300)) < 0.15)
    ps = small | disk(300).translate(300, 320) | small.translate(0, 640)
    pieces = np.diff(rec._k.corridors_all(*_rings_arrays(ps)).poff)
    big = int(np.argmax(pieces))
    assert pieces[big] > 0.5 * pieces.sum()  # a big ring in the middle of the ring order
    assert 0 < big < pieces.size - 1
    monkeypatch.setattr(rec, "_threads", lambda: 2)
    monkeypatch.setattr(rec, "PARALLEL_PIECES", 100)
    plan = rec._ring_plan(pieces)
    # (that every ring is taken once: test_the_thread_plan_takes_every_ring_once)
    assert any((big, big + 1) in share for share in plan)
    cost = np.where(pieces > 0, pieces + rec.RING_COST, 0)
    loads = [sum(int(cost[a:b].sum()) for a, b in share) for share in plan]
    assert max(loads) - min(loads) <= max(int(cost[a:b].sum()) for share in plan for a, b in share)
    threaded = shapely.to_wkb(reconstruct(ps, model))
    monkeypatch.setattr(rec, "_threads", lambda: 1)
    assert shapely.to_wkb(reconstruct(ps, model)) == threaded


@settings(max_examples=200, deadline=None)
@given(
    pieces=st.lists(st.one_of(st.integers(0, 40), st.integers(0, 30_000)), min_size=1, max_size=400),
    threads=st.integers(1, 4),
)
def test_the_thread_plan_takes_every_ring_once(pieces: list[int], threads: int) -> None:
    # Whatever the ring sizes (twins count 0), the threads' ranges cover the rings exactly once, each
    # range is consecutive, and no thread is left with nothing while another has two ranges.
    from unittest import mock

    import mrm.geometry.reconstruct as rec

    arr = np.array(pieces, dtype=np.int64)
    with mock.patch.object(rec, "_threads", lambda: threads):
        plan = rec._ring_plan(arr)
    assert 1 <= len(plan) <= threads
    covered = sorted(k for share in plan for a, b in share for k in range(a, b))
    assert covered == list(range(arr.size))
    assert all(a < b for share in plan for a, b in share)
    if arr.sum() >= rec.PARALLEL_PIECES and arr.size >= threads:
        assert len(plan) == threads or all(len(share) == 1 for share in plan)


@pytest.mark.parametrize("model", MODELS)
def test_rings_taken_a_batch_at_a_time_give_the_same_polygons(model: str, monkeypatch) -> None:
    # R keeps the reach table and the lines of one batch of rings at a time (40 bytes a piece: 40 MB on a
    # 1024² noise image); batches of any size, with threads or not, give the very same polygons, and
    # reconstruct_detailed (which keeps the whole tables) too.
    import mrm.geometry.reconstruct as rec

    rng = np.random.default_rng(5)
    ps = PixelSet(rng.random((80, 120)) < 0.5) | disk(30).translate(60, 40)
    # every table of the corridor is sliced with its batch (a new one must be classified too)
    sliced = (*rec._PER_RING, *rec._PER_ELEMENT, *rec._PER_PIECE, *rec._PER_NET_VERTEX)
    sliced += ("eoff", "poff", "r0off")
    assert sorted(sliced) == sorted(rec._k.Corridors._fields)
    whole = shapely.to_wkb(reconstruct(ps, model))
    poff = rec._k.corridors_all(*_rings_arrays(ps)).poff
    for size, threads in ((40, 1), (333, 2), (2000, 3)):
        monkeypatch.setattr(rec, "BATCH_PIECES", size)
        monkeypatch.setattr(rec, "_threads", lambda threads=threads: threads)
        assert len(rec._batches(poff, 0, poff.size - 1)) > 2
        assert shapely.to_wkb(reconstruct(ps, model)) == whole
        assert shapely.to_wkb(reconstruct_detailed(ps, model).geometry) == whole


def _rings_arrays(ps: PixelSet) -> tuple[object, ...]:
    from mrm.geometry.topology.cracks import trace_mask

    m = np.ascontiguousarray(ps.mask.view(np.uint8))
    r = trace_mask(m)
    return r.codes, r.off, r.sx, r.sy, m.shape[0], m.shape[1], 10


def test_mrm_threads_1_keeps_r_on_one_thread(monkeypatch) -> None:
    # A batch of processes (mrm … --jobs N) sets it so that its workers do not each start threads.
    import mrm.geometry.reconstruct as rec

    rng = np.random.default_rng(21)
    poff = rec._k.corridors_all(*_rings_arrays(PixelSet(rng.random((90, 110)) < 0.55))).poff
    monkeypatch.setenv("MRM_THREADS", "2")
    assert rec._threads() == 2 and len(rec._ring_plan(np.diff(poff))) == 2
    monkeypatch.setenv("MRM_THREADS", "1")
    assert rec._threads() == 1 and rec._ring_plan(np.diff(poff)) == [[(0, poff.size - 1)]]


@pytest.mark.parametrize("model", MODELS)
@settings(max_examples=60, deadline=None)
@given(
    shape=st.lists(st.lists(st.booleans(), min_size=5, max_size=5), min_size=5, max_size=5),
    places=st.lists(st.tuples(st.integers(0, 19), st.integers(0, 19)), min_size=2, max_size=4, unique=True),
)
def test_the_same_shape_anywhere_in_an_image_gets_the_same_polygon_moved(
    model: str, shape: list[list[bool]], places: list[tuple[int, int]]
) -> None:
    # A shape repeated across an image (specks, letters, dots) is reconstructed once and moved (ADR 0036):
    # every copy's polygon is the first copy's translated exactly, and the whole stays reversible.
    tile = np.array(shape, dtype=bool)
    if not tile.any():
        return
    m = np.zeros((20 * 7, 20 * 7), dtype=bool)
    for c, r in places:
        m[7 * r : 7 * r + 5, 7 * c : 7 * c + 5] = tile
    ps = PixelSet(m, (-3000, 41))
    g = reconstruct(ps, model)
    assert discretize(g, model) == ps
    lone = polygons(reconstruct(PixelSet(tile), model))
    polys = polygons(g)
    assert len(polys) == len(lone) * len(places)
    # the copies' polygons, grouped by copy: each component's lowest-leftmost pixel tells which copy it is in
    by_copy: dict[tuple[int, int], list[np.ndarray]] = {}
    for p in polys:
        x0, y0 = p.bounds[0] + 3000, p.bounds[1] - 41
        key = (int(x0 + 1) // 7, int(y0 + 1) // 7)
        by_copy.setdefault(key, []).append(shapely.get_coordinates(p) - (7 * key[0] - 3000, 7 * key[1] + 41))
    first, *others = by_copy.values()
    for other in others:
        assert len(other) == len(first)
        for a, b in zip(first, other, strict=True):
            assert np.array_equal(a, b)
