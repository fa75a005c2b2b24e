"""Label volumes to meshes: one closed mesh per region, common faces shared exactly, burnt back exactly.

Every check is exact and none uses the code under test for its expected values:

* the regions are scipy's 6-connected components of each label (``scipy.ndimage.label``);
* each region's mesh is a valid polyhedron (``Polyhedron``: closed 2-manifold, oriented, no
  self-intersection, positive volume) and D_gauss of it (``voxelize_solid``) is the region exactly;
* the quarter cells each mesh holds are found by voxelizing it exactly on the quarter grid (the mesh scaled
  by 4 and moved by −½, exact in float64, so that quarter-cell centres are integer points): no quarter cell
  is held by two regions (no overlap); a cell held by none lies in or at a background voxel (no gap between
  labels); a region holds every core and face cell of its voxels, and other cells only at a linel or pointel
  of its voxels;
* watertight and shared: a triangle whose far side (the quarter cell across it) is held by region j appears,
  reversed, in j's mesh, and a triangle facing no region appears in no other mesh;
* on volumes without pinches the triangles cover exactly the unit squares between different regions, found
  by brute force (exact areas per region, plane and side);
* the pointel table is checked over all 21,147 patterns; ``mrm polygonize`` writes an OBJ that reads back
  and burns back exactly.
"""

from __future__ import annotations

import json
import time
from collections import Counter
from pathlib import Path

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy import ndimage

from mrm.core.errors import ParameterError
from mrm.core.grids import LabelVolume
from mrm.geometry.discretize.voxels import voxelize_solid
from mrm.geometry.polyhedra import Polyhedron
from mrm.geometry.reconstruct import _label_corners as corners
from mrm.geometry.reconstruct.polygonize_3d import LabelMeshes, polygonize_volume

Origin = tuple[int, int, int]


# -------------------------------------------------------------------------------------------- references
def reference_regions(lab: np.ndarray) -> list[tuple[int, np.ndarray]]:
    """(label, mask) of every 6-connected component of every non-zero label, by scipy."""
    out = []
    for value in np.unique(lab[lab != 0]).tolist():
        comp, n = ndimage.label(lab == value)  # default structure: 6-connectivity
        out.extend((value, comp == i) for i in range(1, n + 1))
    return out


def brute_force_squares(lab: np.ndarray, owner: np.ndarray) -> tuple[Counter, int]:
    """The unit squares between voxels of different regions (``owner``: region index, −1 background), by
    loops: per (region, axis, padded index i of the plane between voxels i and i + 1, outward sign) their
    number, and how many squares there are."""
    nz, ny, nx = lab.shape
    got: Counter = Counter()
    count = 0
    pad = np.full((nz + 2, ny + 2, nx + 2), -1)
    pad[1:-1, 1:-1, 1:-1] = owner
    for k in range(nz + 2):
        for j in range(ny + 2):
            for i in range(nx + 2):
                for axis, (dk, dj, di) in enumerate(((0, 0, 1), (0, 1, 0), (1, 0, 0))):
                    if k + dk >= nz + 2 or j + dj >= ny + 2 or i + di >= nx + 2:
                        continue
                    a, b = pad[k, j, i], pad[k + dk, j + dj, i + di]
                    if a == b:
                        continue
                    count += 1
                    plane = (i, j, k)[axis]
                    if a >= 0:
                        got[(int(a), axis, plane, +1)] += 1
                    if b >= 0:
                        got[(int(b), axis, plane, -1)] += 1
    return got, count


# ------------------------------------------------------------------------------------------------ checks
def oriented(v: np.ndarray, tri: list[int]) -> tuple[tuple[float, ...], ...]:
    """A triangle by its corners' coordinates, turned to start at the smallest: the same for every mesh."""
    pts = [tuple(v[i].tolist()) for i in tri]
    r = min(range(3), key=lambda s: pts[s])
    return tuple(pts[(r + s) % 3] for s in range(3))


def quarter_cells(v: np.ndarray, t: np.ndarray) -> tuple[np.ndarray, tuple[int, int, int]]:
    """The quarter cells inside a mesh: D_gauss of the mesh scaled by 4 and moved by −½ (exact)."""
    return voxelize_solid(4.0 * v - 0.5, t, "gauss", limit=None)


def check(lab: np.ndarray, origin: Origin = (0, 0, 0)) -> LabelMeshes:
    lab = np.asarray(lab, np.int32)
    out = polygonize_volume(lab, origin)
    ref = reference_regions(lab)
    assert len(out.regions) == len(ref)
    x0, y0, z0 = origin
    nz, ny, nx = lab.shape
    # quarter grid of the volume plus one voxel around: cell (a, b, c) is [a/4, (a+1)/4] from x0 − 1.5
    qshape = (4 * (nz + 2), 4 * (ny + 2), 4 * (nx + 2))
    held = np.full(qshape, -1, np.int64)
    seen: dict[tuple[tuple[float, ...], ...], int] = {}
    triangles: list[tuple[np.ndarray, np.ndarray]] = []
    matched = set()
    for idx, region in enumerate(out.regions):
        v, t = out.mesh(idx)
        Polyhedron(v, t, limit=None)  # exact validity
        mask, (ox, oy, oz) = voxelize_solid(v, t, "gauss", limit=None)
        vox = np.zeros(lab.shape, bool)
        vox[
            oz - z0 : oz - z0 + mask.shape[0],
            oy - y0 : oy - y0 + mask.shape[1],
            ox - x0 : ox - x0 + mask.shape[2],
        ] = mask
        hits = [r for r, (lv, m) in enumerate(ref) if lv == region.label and np.array_equal(m, vox)]
        assert len(hits) == 1 and hits[0] not in matched, (
            f"region {idx} (label {region.label}) burns back wrong"
        )
        matched.add(hits[0])
        assert region.voxels == int(vox.sum())
        q, (qx, qy, qz) = quarter_cells(v, t)
        # the cell whose centre is the quarter point qx has index qx − 4·(x0 − 1.5) in held
        ax, ay, az = qx - 4 * (x0 - 1) + 2, qy - 4 * (y0 - 1) + 2, qz - 4 * (z0 - 1) + 2
        sub = held[az : az + q.shape[0], ay : ay + q.shape[1], ax : ax + q.shape[2]]
        assert not (sub[q] >= 0).any(), "two regions hold one quarter cell"
        sub[q] = idx
        for tri in t.tolist():
            key = oriented(v, tri)
            assert key not in seen, "a triangle twice in the same orientation"
            seen[key] = idx
        triangles.append((v, t))
    # no gap between labels, and each region's cells where they belong
    vox_of_cell = np.arange(qshape[0]) // 4, np.arange(qshape[1]) // 4, np.arange(qshape[2]) // 4
    ck, cj, ci = np.meshgrid(*vox_of_cell, indexing="ij")
    offset = [np.arange(s) % 4 for s in qshape]
    ok_ = [(o == 1) | (o == 2) for o in offset]
    inner_k, inner_j, inner_i = np.meshgrid(*ok_, indexing="ij")
    n_outer = 3 - (inner_k.astype(int) + inner_j + inner_i)
    # region index of each voxel, by the mesh that burns back to it
    owner = np.full((nz + 2, ny + 2, nx + 2), -1, np.int64)
    for idx, (v, t) in enumerate(triangles):
        mask, (ox, oy, oz) = voxelize_solid(v, t, "gauss", limit=None)
        owner[oz - z0 + 1 : oz - z0 + 1 + mask.shape[0], oy - y0 + 1 : oy - y0 + 1 + mask.shape[1]][
            :, :, ox - x0 + 1 : ox - x0 + 1 + mask.shape[2]
        ][mask] = idx
    own_cell = owner[ck, cj, ci]
    # core and face cells never move: held by their voxel's region (or by none in the background)
    fixed = n_outer <= 1
    assert np.array_equal(held[fixed], own_cell[fixed])
    # an edge or corner cell is held by its voxel's region or by the region of a voxel sharing its closure
    for a, b, c in zip(*np.nonzero(~fixed & (held != own_cell)), strict=True):
        near = set()
        for dk in (-1, 0, 1):
            for dj in (-1, 0, 1):
                for di in (-1, 0, 1):
                    # the voxel across each outer side of the cell
                    kk = ck[a, b, c] + (dk if (a % 4 == 3 and dk == 1) or (a % 4 == 0 and dk == -1) else 0)
                    jj = cj[a, b, c] + (dj if (b % 4 == 3 and dj == 1) or (b % 4 == 0 and dj == -1) else 0)
                    ii = ci[a, b, c] + (di if (c % 4 == 3 and di == 1) or (c % 4 == 0 and di == -1) else 0)
                    if 0 <= kk < nz + 2 and 0 <= jj < ny + 2 and 0 <= ii < nx + 2:
                        near.add(int(owner[kk, jj, ii]))
        assert int(held[a, b, c]) in near, "a cell taken by a region that does not touch it"
        # a cell held by no region (a gap) is only allowed at the background
        if held[a, b, c] < 0:
            assert -1 in near, "a gap between regions"
    # shared: the cell across each triangle decides which mesh holds its reverse
    for idx, (v, t) in enumerate(triangles):
        s = 4.0 * v - 0.5  # quarter-cell centres at integers; vertices at multiples of ½
        for tri in t.tolist():
            p = s[tri]
            normal = np.cross(p[1] - p[0], p[2] - p[0])
            axis = int(np.flatnonzero(normal)[0])
            assert np.count_nonzero(normal) == 1
            six = 2 * p.sum(axis=0)  # 6 × centroid, integers
            cell = [int((int(six[d]) + 3) // 6) for d in range(3)]
            sign = 1 if normal[axis] > 0 else -1
            cell[axis] = (int(six[axis]) + 3 * sign) // 6
            inside = list(cell)
            inside[axis] = (int(six[axis]) - 3 * sign) // 6
            base = [4 * (x0 - 1) - 2, 4 * (y0 - 1) - 2, 4 * (z0 - 1) - 2]
            far = held[cell[2] - base[2], cell[1] - base[1], cell[0] - base[0]]
            near_ = held[inside[2] - base[2], inside[1] - base[1], inside[0] - base[0]]
            assert near_ == idx
            key = oriented(v, tri[::-1])
            assert seen.get(key, -1) == far, "a shared face not shared exactly"
    return out


# --------------------------------------------------------------------------------------------- the table
def test_the_pointel_table_makes_every_pattern_a_manifold() -> None:
    keys, entries = corners.table()
    lookup = dict(zip(keys.tolist(), entries.tolist(), strict=True))
    rows, bgs = [], []
    for g, bg in corners.patterns():
        entry = lookup.get(corners.pattern_key(g, bg), list(range(8)))
        cells = corners._default_cells(g, bg)
        for p in range(8):
            cells[corners.CORNERS[p]] = g[entry[p]]
        rows.append(cells)
        bgs.append(bg)
    rows_a = np.array(rows)
    bgs_a = np.array(bgs)
    ok = np.ones(len(rows), bool)
    for bg in np.unique(bgs_a).tolist():
        sel = bgs_a == bg
        ok[sel] = corners.cells_valid(rows_a[sel], bg)
    assert len(rows) == 21_147 and ok.all()


def test_the_linel_rule_makes_every_cross_section_a_manifold() -> None:
    # The middle of a linel: both layers of edge cells have the same cross-section; in 2D, around each of the
    # 9 lattice points near the linel, no non-zero region (nor its complement) is two diagonal cells alone.
    fours = {g[:4] for g, _ in corners.patterns() if g[4:] == (0, 0, 0, 0)}
    assert len(fours) == 15  # Bell(4)
    for g in fours:
        for bg in (-1, *range(max(g) + 1)):
            src = corners.linel_sources(g, bg)  # type: ignore[arg-type]
            cell = {}
            for ci in range(-2, 2):
                for di in range(-2, 2):
                    q = (0 if ci < 0 else 1) + 2 * (0 if di < 0 else 1)
                    edge = ci in (-1, 0) and di in (-1, 0)
                    cell[ci, di] = g[src[q]] if edge else g[q]
            for wc in (-1, 0, 1):
                for wd in (-1, 0, 1):
                    quad = [cell[wc - 1, wd - 1], cell[wc, wd - 1], cell[wc, wd], cell[wc - 1, wd]]
                    for r in set(quad) - {bg}:
                        s = [x == r for x in quad]
                        assert s not in ([True, False, True, False], [False, True, False, True]), (g, bg)


@pytest.mark.parametrize("index", range(0, 21_147, 1_409))
def test_the_table_is_what_the_search_finds(index: int) -> None:
    g, bg = corners.patterns()[index]
    keys, entries = corners.table()
    at = np.searchsorted(keys, corners.pattern_key(g, bg))
    found = tuple(entries[at].tolist()) if at < keys.size and keys[at] == corners.pattern_key(g, bg) else None
    assert corners.search_entry(g, bg) == (found or tuple(range(8)))


# ---------------------------------------------------------------------------------------------- volumes
@st.composite
def label_volumes(draw: st.DrawFn) -> tuple[np.ndarray, Origin]:
    shape = tuple(draw(st.integers(1, 8)) for _ in range(3))
    n = draw(st.integers(2, 50))
    seed = draw(st.integers(0, 2**32 - 1))
    rng = np.random.default_rng(seed)
    if draw(st.booleans()):  # blocky: labels in 2³ blocks, then noise
        small = rng.integers(0, n + 1, tuple(s // 2 + 1 for s in shape))
        lab = np.kron(small, np.ones((2, 2, 2), int))[: shape[0], : shape[1], : shape[2]]
        lab[rng.random(shape) < 0.15] = int(rng.integers(0, n + 1))
    else:
        lab = rng.integers(0, n + 1, shape)
        lab[rng.random(shape) < draw(st.sampled_from([0.0, 0.3, 0.6]))] = 0
    far = draw(st.sampled_from([0, 10**6, -(2**30)]))
    origin = tuple(far + draw(st.integers(-5, 5)) for _ in range(3))
    return lab.astype(np.int32), origin  # type: ignore[return-value]


@settings(max_examples=60)
@given(label_volumes())
def test_random_label_volumes_are_watertight_and_burn_back(case: tuple[np.ndarray, Origin]) -> None:
    lab, origin = case
    check(lab, origin)


def test_translation_moves_every_vertex_exactly_and_the_output_is_deterministic() -> None:
    lab = np.random.default_rng(3).integers(0, 4, (5, 6, 4)).astype(np.int32)
    a = polygonize_volume(lab, (0, 0, 0))
    b = polygonize_volume(lab, (1000, -77, 5))
    c = polygonize_volume(lab, (0, 0, 0))
    assert np.array_equal(a.vertices + np.array([1000, -77, 5]), b.vertices)
    assert all(np.array_equal(r.triangles, s.triangles) for r, s in zip(a.regions, b.regions, strict=True))
    assert np.array_equal(a.vertices, c.vertices)


def mesh_euler(out: LabelMeshes, i: int) -> int:
    v, t = out.mesh(i)
    edges = {tuple(sorted((tri[a], tri[(a + 1) % 3]))) for tri in t.tolist() for a in range(3)}
    return len(v) - len(edges) + len(t)


def test_labels_touching_along_an_edge_or_at_a_corner() -> None:
    edge = np.zeros((1, 2, 2), np.int32)
    edge[0, 0, 0] = edge[0, 1, 1] = 1  # one label, two regions meeting along an edge
    edge[0, 0, 1] = 2
    out = check(edge)
    assert [r.label for r in out.regions] == [1, 1, 2]
    corner = np.zeros((2, 2, 2), np.int32)
    corner[0, 0, 0] = 1
    corner[1, 1, 1] = 2
    corner[1, 0, 0] = 3
    check(corner)


def test_a_region_meeting_itself_along_an_edge_is_kept_apart_there() -> None:
    # A ring of voxels closed only by an edge contact is no tunnel under 6-connectivity: one sphere.
    lab = np.zeros((1, 3, 3), np.int32)
    lab[0, 0, :] = 1
    lab[0, :, 0] = 1
    lab[0, 1, 1] = 0
    lab[0, 2, 1] = 1  # (1, 2) touches (0, 2)? no: (x=1, y=2) meets (x=0, y=1)… only along an edge
    lab[0, 1, 2] = 1
    lab[0, 2, 2] = 2
    out = check(lab)
    ones = [i for i, r in enumerate(out.regions) if r.label == 1]
    for i in ones:
        assert mesh_euler(out, i) == 2  # every region of label 1 is a sphere (genus 0)
    # and at a pointel: two voxels of one region meeting only at a corner
    lab = np.zeros((2, 2, 2), np.int32)
    lab[0, 0, :] = 1
    lab[0, :, 1] = 1
    lab[1, :, 1] = 1
    lab[1, 1, :] = 1
    lab[1, 1, 0] = 1
    lab[0, 1, 0] = 2
    out = check(lab)
    assert all(mesh_euler(out, i) == 2 for i in range(len(out.regions)))


def test_a_cavity_a_thin_sheet_and_a_checkerboard() -> None:
    cavity = np.ones((5, 5, 5), np.int32)
    cavity[1:4, 1:4, 1:4] = 2
    cavity[2, 2, 2] = 0
    out = check(cavity)
    assert [r.voxels for r in out.regions] == [98, 26]
    sheet = np.ones((4, 3, 3), np.int32)
    sheet[2:] = 3
    sheet[1] = 2  # one voxel thick between labels 1 and 3
    check(sheet, (-1000, 7, 2**30))
    k, j, i = np.indices((4, 4, 4))
    checker = ((i + j + k) % 3 + 1).astype(np.int32)
    check(checker)
    check(((i + j + k) % 2 + 1).astype(np.int32))


def test_without_pinches_the_triangles_cover_the_brute_force_squares_exactly() -> None:
    # Boxes and slabs (no region meets itself or another only along an edge): the meshes are the staircase.
    lab = np.zeros((6, 7, 8), np.int32)
    lab[:, :, :4] = 1
    lab[:, :, 4:] = 2
    lab[1:5, 2:5, 2:6] = 3
    lab[2:4, 3:4, 3:5] = 0  # a cavity inside label 3
    lab[:, 6, :] = 4
    origin = (3, -4, 5)
    out = check(lab, origin)
    owner = np.full(lab.shape, -1)
    for idx in range(len(out.regions)):
        v, t = out.mesh(idx)
        mask, (ox, oy, oz) = voxelize_solid(v, t, "gauss", limit=None)
        z, y, x = oz - origin[2], oy - origin[1], ox - origin[0]
        owner[z : z + mask.shape[0], y : y + mask.shape[1], x : x + mask.shape[2]][mask] = idx
    want, surfels = brute_force_squares(lab, owner)
    got: Counter = Counter()
    for idx in range(len(out.regions)):
        v, t = out.mesh(idx)
        q = (4 * v).astype(np.int64)  # quarter units, exact
        for tri in q[t]:
            normal = np.cross(tri[1] - tri[0], tri[2] - tri[0])  # twice the area, in quarters²
            axis = int(np.flatnonzero(normal)[0])
            # the plane world = origin + (i − 1) + ½ lies between padded voxels i and i + 1
            plane = (int(tri[0][axis]) - 4 * origin[axis] + 2) // 4
            got[(idx, axis, plane, int(np.sign(normal[axis])))] += int(abs(normal[axis]))
    assert got == Counter({key: 32 * n for key, n in want.items()})  # a unit square: 16 quarters², doubled
    assert out.surfels == surfels


def test_only_gauss_is_accepted_and_bad_arrays_are_refused() -> None:
    with pytest.raises(ParameterError, match="needs the gauss model"):
        polygonize_volume(np.ones((1, 1, 1), np.int32), model="standard")
    with pytest.raises(ParameterError, match="3-D integer array"):
        polygonize_volume(np.ones((2, 2)))
    with pytest.raises(ParameterError, match="non-negative"):
        polygonize_volume(-np.ones((1, 1, 1), np.int32))
    empty = polygonize_volume(np.zeros((2, 2, 2), np.int32))
    assert empty.regions == [] and empty.vertices.shape == (0, 3)
    lv = LabelVolume(np.array([[[0, 5]]], np.int32), (4, 5, 6))
    out = polygonize_volume(lv)
    assert [(r.label, r.voxels) for r in out.regions] == [(5, 1)]
    assert out.vertices.min(axis=0).tolist() == [4.5, 4.5, 5.5]


def test_a_big_blob_volume_is_fast() -> None:
    rng = np.random.default_rng(0)
    fields = ndimage.gaussian_filter(rng.standard_normal((12, 48, 48, 48)), (0, 4, 4, 4))
    lab = (fields.argmax(axis=0) + 1).astype(np.int32)
    polygonize_volume(lab[:4, :4, :4])  # compiled or loaded
    t0 = time.perf_counter()
    out = polygonize_volume(lab)
    assert time.perf_counter() - t0 < 10
    assert sum(r.voxels for r in out.regions) == lab.size


# ------------------------------------------------------------------------------------------------ the CLI
def run(capsys: pytest.CaptureFixture[str], *argv: object) -> tuple[int, str, str]:
    from mrm.cli import run_cli

    code = run_cli([str(a) for a in argv])
    out, err = capsys.readouterr()
    return code, out, err


def read_polygons(path: Path) -> tuple[np.ndarray, dict[str, list[list[int]]]]:
    """The vertices and the faces (vertex lists) of each ``o`` object of an OBJ file, read here."""
    vertices: list[list[float]] = []
    objects: dict[str, list[list[int]]] = {}
    current = None
    for line in path.read_text(encoding="ascii").splitlines():
        parts = line.split()
        if not parts:
            continue
        if parts[0] == "v":
            vertices.append([float(x) for x in parts[1:4]])
        elif parts[0] == "o":
            current = parts[1]
            objects[current] = []
        elif parts[0] == "f":
            assert current is not None
            objects[current].append([int(x) - 1 for x in parts[1:]])
    return np.array(vertices), objects


def read_objects(path: Path) -> tuple[np.ndarray, dict[str, np.ndarray]]:
    """The vertices and the triangles (a polygon's fan) of each ``o`` object of an OBJ file, read here."""
    vertices, objects = read_polygons(path)
    fans = {
        name: np.array([(f[0], f[j], f[j + 1]) for f in faces for j in range(1, len(f) - 1)], np.int64)
        for name, faces in objects.items()
    }
    return vertices, fans


@pytest.mark.parametrize("faces", ["polygons", "triangles"])
def test_cli_polygonize_writes_one_obj_object_per_region_that_burns_back(capsys, tmp_path, faces) -> None:
    rng = np.random.default_rng(7)
    lab = rng.integers(0, 4, (4, 5, 6)).astype(np.int32)
    origin = (-3, 100, 2**20)
    np.savez(tmp_path / "seg.npz", labels=lab, origin=np.array(origin, np.int64))
    extra = ["--triangles"] if faces == "triangles" else []
    code, text, err = run(
        capsys, "polygonize", tmp_path / "seg.npz", "-o", tmp_path / "seg.obj", "--json", *extra
    )
    assert code == 0, err
    summary = json.loads(text)
    ref = reference_regions(lab)
    assert summary["regions"] == len(ref) and summary["labels"] == 3
    assert summary["voxels"] == int(np.count_nonzero(lab)) and summary["model"] == "gauss"
    vertices, objects = read_objects(tmp_path / "seg.obj")
    assert len(objects) == len(ref)
    if faces == "triangles":  # the summary counts the triangles and vertices written
        assert summary["vertices"] == len(vertices)
        assert summary["triangles"] == summary["faces"] == sum(len(t) for t in objects.values())
    else:  # fewer: a face between two regions is one polygon, the same in both, reversed
        assert len(vertices) < summary["vertices"]
        _, polygons = read_polygons(tmp_path / "seg.obj")
        assert sum(map(len, polygons.values())) == summary["faces"] < summary["triangles"]
        seen: dict[frozenset[int], list[int]] = {}
        shared = 0
        for faces_of_one in polygons.values():
            for f in faces_of_one:
                key = frozenset(f)
                if key in seen:  # the other side of a face between two regions: the same loop, reversed
                    other = seen[key][::-1]
                    k = other.index(f[0])
                    assert other[k:] + other[:k] == f
                    shared += 1
                else:
                    seen[key] = f
        assert shared > 0
    burnt = np.zeros_like(lab)
    for name, t in objects.items():
        label = int(name.split("_")[1])
        used, inverse = np.unique(t, return_inverse=True)
        v, tt = vertices[used], inverse.reshape(t.shape)
        Polyhedron(v, tt, limit=None)
        mask, (ox, oy, oz) = voxelize_solid(v, tt, "gauss", limit=None)
        sub = burnt[
            oz - origin[2] : oz - origin[2] + mask.shape[0],
            oy - origin[1] : oy - origin[1] + mask.shape[1],
            ox - origin[0] : ox - origin[0] + mask.shape[2],
        ]
        assert not sub[mask].any()
        sub[mask] = label
    assert np.array_equal(burnt, lab)


def test_label_meshes_read_back_region_by_region(capsys, tmp_path) -> None:
    # What `mrm polygonize` writes comes back: each region alone (mrm.read_mesh_objects, read_mesh with
    # object_name, `--object` in the command line, one object each in the desktop), burning back under gauss
    # to that region's voxels; the file as a whole is no solid, and the refusal says how to read it.
    import mrm
    from mrm.document import Document
    from mrm.io.imports import import_file

    rng = np.random.default_rng(11)
    lab = rng.integers(0, 4, (4, 5, 6)).astype(np.int32)
    np.savez(tmp_path / "seg.npz", labels=lab, origin=np.array((5, -2, 0), np.int64))
    assert run(capsys, "polygonize", tmp_path / "seg.npz", "-o", tmp_path / "seg.obj")[0] == 0
    vertices, objects = read_objects(tmp_path / "seg.obj")  # the file read here, independently
    parts = mrm.read_mesh_objects(tmp_path / "seg.obj")
    assert [name for name, _ in parts] == list(objects)
    for name, poly in parts:
        label = int(name.split("_")[1])
        region = mrm.voxelize(poly, "gauss")
        assert all(lab[z, y + 2, x - 5] == label for x, y, z in region.points())
        used = np.unique(objects[name])
        assert sorted(map(tuple, poly.vertices.tolist())) == sorted(map(tuple, vertices[used].tolist()))
        assert mrm.read_mesh(tmp_path / "seg.obj", object_name=name) == poly
    assert sum(len(mrm.voxelize(p, "gauss")) for _, p in parts) == np.count_nonzero(lab)
    with pytest.raises(mrm.MRMError, match=r"holds \d+ objects .*object_name=NAME \(--object NAME\)"):
        mrm.read_mesh(tmp_path / "seg.obj")
    with pytest.raises(mrm.MRMError, match="no object named 'label_9_1'; the file's objects: 'label_"):
        mrm.read_mesh(tmp_path / "seg.obj", object_name="label_9_1")
    first = parts[0][0]
    code, text, err = run(capsys, "info", tmp_path / "seg.obj", "--object", first, "--json")
    assert code == 0, err
    summary = json.loads(text)
    assert summary["object"] == first and summary["voxels"] == len(mrm.voxelize(parts[0][1], "standard"))
    code, _, err = run(capsys, "voxelize", tmp_path / "seg.obj", "--object", first, "--model", "gauss", "-o",
                       tmp_path / "one.npz")  # fmt: skip
    assert code == 0, err
    assert mrm.read_voxels(tmp_path / "one.npz") == mrm.voxelize(parts[0][1], "gauss")
    code, _, err = run(capsys, "info", tmp_path / "seg.obj")
    assert code != 0 and "--object NAME" in err and "Traceback" not in err
    doc = Document()
    ids = import_file(doc, tmp_path / "seg.obj")  # File ▸ Import: one polyhedron object per region
    assert [doc.get(i).name for i in ids] == [f"seg {name}" for name, _ in parts]


def test_cli_polygonize_refuses_bad_volumes_with_a_message_and_writes_nothing(capsys, tmp_path) -> None:
    np.savez(tmp_path / "empty.npz", labels=np.zeros((2, 2, 2), np.int32))
    code, _out, err = run(capsys, "polygonize", tmp_path / "empty.npz", "-o", tmp_path / "e.obj")
    assert code == 2 and "no label" in err and "Traceback" not in err
    assert not (tmp_path / "e.obj").exists()
    np.savez(tmp_path / "seg.npz", labels=np.ones((2, 2, 2), np.int32))
    code, _out, err = run(
        capsys, "polygonize", tmp_path / "seg.npz", "-o", tmp_path / "s.obj", "--model", "supercover"
    )
    assert code == 2 and "needs the gauss model" in err
    assert not (tmp_path / "s.obj").exists()
    code, _out, err = run(capsys, "polygonize", tmp_path / "seg.npz", "-o", tmp_path / "s.geojson")
    assert code == 2 and ".obj" in err
    assert not (tmp_path / "s.geojson").exists()
    code, _out, err = run(
        capsys, "polygonize", tmp_path / "seg.npz", "-o", tmp_path / "s.obj", "--connectivity", "8"
    )
    assert code == 2 and "6-connected" in err
    assert not (tmp_path / "s.obj").exists()


def test_a_face_is_cut_where_the_region_on_its_other_side_changes(tmp_path) -> None:
    # A 3×3×1 slab (label 1) with one voxel (label 2) on its top's middle: the slab's top is one plane, but
    # its middle square is shared with label 2 and the rest faces the background. The shared square is one
    # polygon in both objects, the same loop reversed; the rest of the slab's top is its own.
    from mrm.geometry.reconstruct.polygonize_3d import polygonize_volume
    from mrm.io.mesh_files import write_label_meshes

    lab = np.zeros((2, 3, 3), np.int32)
    lab[0] = 1
    lab[1, 1, 1] = 2
    out = polygonize_volume(lab)
    objects = [(f"label_{r.label}_1", f"label_{r.label}", r.triangles) for r in out.regions]
    write_label_meshes(out.vertices, objects, tmp_path / "two.obj", out.polygons())
    vertices, polygons = read_polygons(tmp_path / "two.obj")
    slab, cube = polygons["label_1_1"], polygons["label_2_1"]
    bottom = [f for f in cube if np.all(vertices[f][:, 2] == vertices[f][0, 2]) and vertices[f][0, 2] < 1]
    assert len(bottom) == 1
    loop = bottom[0][::-1]
    matches = [f for f in slab if set(f) == set(loop)]
    assert len(matches) == 1
    k = loop.index(matches[0][0])
    assert loop[k:] + loop[:k] == matches[0]
    _, fans = read_objects(tmp_path / "two.obj")
    for t in fans.values():
        used, inverse = np.unique(t, return_inverse=True)
        Polyhedron(vertices[used], inverse.reshape(t.shape), limit=None)


def test_the_other_side_of_each_triangle_is_found_with_or_without_packed_keys(monkeypatch) -> None:
    # Each region's triangles know the region across them (−1: the background), by one packed key per
    # triangle below 2²¹ vertices, by a row sort above: the same answer, and each shared triangle's two
    # sides lie in two regions, the second holding it reversed.
    import mrm.geometry.reconstruct.polygonize_3d as p3

    lab = np.random.default_rng(3).integers(0, 4, (5, 6, 7)).astype(np.int32)
    out = p3.polygonize_volume(lab)
    packed = p3._other_sides(out.regions)
    monkeypatch.setattr(p3, "_PACK_BITS", 1)
    rows = p3._other_sides(out.regions)
    assert all(np.array_equal(a, b) for a, b in zip(packed, rows, strict=True))

    def canonical(tri: list[int]) -> tuple[int, ...]:  # the rotation starting at the smallest index
        k = tri.index(min(tri))
        return tuple(tri[k:] + tri[:k])

    owner = {canonical(t): j for j, r in enumerate(out.regions) for t in r.triangles.tolist()}
    for r, other in zip(out.regions, packed, strict=True):  # each triangle's reverse, looked up directly
        expected = [owner.get(canonical(t[::-1]), -1) for t in r.triangles.tolist()]
        assert other.tolist() == expected
    assert any((o >= 0).any() for o in packed) and any((o < 0).any() for o in packed)
