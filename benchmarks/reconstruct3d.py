"""Benchmark: compactness, speed and memory of the 3D continuation R (voxels -> exactly reversible solid).

R = ``mrm.geometry.reconstruct.reconstruct_voxels(VoxelSet(mask, origin), model)``: a valid polyhedron P with
D(P) = A exactly in the model (docs/design.md §11). Its peers work on the same mask:

- MC: ``skimage.measure.marching_cubes`` of the mask padded by one voxel, as float32, at level 0.5 (a closed
  mesh through the midpoints between voxel centres: compact in no sense, and not exactly reversible);
- MC + FS: that mesh decimated by ``fast_simplification`` (quadric edge collapse) to R's triangle count, then
  discretized back exactly (``voxelize_solid``, same model) and compared with A: how many voxels a mesh as
  small as R gets wrong. A decimated mesh that is not a valid polyhedron (exact check: ``Polyhedron``) is
  reported "invalid", a finding too. Skipped, with a note, when fast_simplification is not installed. The
  undecimated MC mesh discretized back the same way is the baseline ("MC wrong").

Sections, in one run:

1. octahedra |x|+|y|+|z| <= r (``--octa-radii``), every model: faces, vertices, triangles, time. Targets:
   gauss exactly 8 faces, standard and supercover at most 32;
2. balls of radius r (``--ball-radii``) centred at (0.3, 0.1, 0.2), an ellipsoid (semi-axes 40, 25, 15) and a
   torus (R = 30, r = 10), every model: R's size against MC's (target: R's triangles <= 0.1 x MC's), the
   surfels, the times, and the voxels MC + FS gets wrong;
3. with ``--big N``: a ball of radius N/2 - 2 in an N³ box and seeded random blobs (gaussian-smoothed noise
   thresholded; ``--big-shapes`` picks), R under ``--big-model`` against MC: median time and tracemalloc
   peak of each.

Times are medians of ``--repeat`` runs in this process, after one warm call (the first call of each row,
reported apart; numba's compilation or cache loading is measured once at the start, on a 3³ cube).

Usage: ``.venv/bin/python benchmarks/reconstruct3d.py [--octa-radii 4 8 16 32 64 100 150 200]
[--ball-radii 8 16 32 64 100] [--repeat 3] [--big 256] [--big-repeat 1] [--big-model gauss]
[--big-shapes ball blobs] [--seed 0]``
"""

from __future__ import annotations

import argparse
import os
import sys
import time
from collections.abc import Callable, Sequence
from typing import Any

import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
if ROOT not in sys.path:
    sys.path.insert(0, ROOT)

from benchmarks.discretize import median_time, peak_memory  # noqa: E402

MODELS = ("gauss", "standard", "supercover")
BALL_CENTRE = (0.3, 0.1, 0.2)  # slightly off the grid: no symmetry of the digital ball to exploit
ELLIPSOID_AXES = (40.0, 25.0, 15.0)
TORUS_RADII = (30.0, 10.0)

Mask = np.ndarray
Origin = tuple[int, int, int]


# ------------------------------------------------------------------------------------------------ shapes
def solid(
    inside: Callable[[np.ndarray, np.ndarray, np.ndarray], np.ndarray], lo: Sequence[int], hi: Sequence[int]
) -> tuple[Mask, Origin]:
    """The voxels p with lo <= p <= hi (x, y, z) where ``inside(x, y, z)``: mask (z, y, x) and origin."""
    z, y, x = np.ogrid[lo[2] : hi[2] + 1, lo[1] : hi[1] + 1, lo[0] : hi[0] + 1]
    mask = np.broadcast_to(
        inside(x.astype(float), y.astype(float), z.astype(float)), (z.size, y.size, x.size)
    )
    return np.ascontiguousarray(mask, dtype=bool), (int(lo[0]), int(lo[1]), int(lo[2]))


def octahedron(r: int) -> tuple[Mask, Origin]:
    return solid(lambda x, y, z: np.abs(x) + np.abs(y) + np.abs(z) <= r, (-r, -r, -r), (r, r, r))


def _box(c: Sequence[float], ext: Sequence[float]) -> tuple[list[int], list[int]]:
    return [int(np.floor(c[i] - ext[i])) for i in range(3)], [int(np.ceil(c[i] + ext[i])) for i in range(3)]


def ball(r: float, c: Sequence[float] = BALL_CENTRE) -> tuple[Mask, Origin]:
    lo, hi = _box(c, (r, r, r))
    return solid(lambda x, y, z: (x - c[0]) ** 2 + (y - c[1]) ** 2 + (z - c[2]) ** 2 <= r * r, lo, hi)


def ellipsoid(
    axes: Sequence[float] = ELLIPSOID_AXES, c: Sequence[float] = BALL_CENTRE
) -> tuple[Mask, Origin]:
    a, b, d = axes
    lo, hi = _box(c, axes)
    return solid(
        lambda x, y, z: ((x - c[0]) / a) ** 2 + ((y - c[1]) / b) ** 2 + ((z - c[2]) / d) ** 2 <= 1, lo, hi
    )


def torus(radii: Sequence[float] = TORUS_RADII, c: Sequence[float] = BALL_CENTRE) -> tuple[Mask, Origin]:
    big, small = radii
    lo, hi = _box(c, (big + small, big + small, small))

    def inside(x: np.ndarray, y: np.ndarray, z: np.ndarray) -> np.ndarray:
        rho = np.sqrt((x - c[0]) ** 2 + (y - c[1]) ** 2)
        return (rho - big) ** 2 + (z - c[2]) ** 2 <= small * small

    return solid(inside, lo, hi)


def blobs(n: int, seed: int) -> Mask:
    """Seeded random blobs in an n³ box: noise smoothed by a gaussian (sigma n/64, at least 2), thresholded at
    its median (about half the voxels in, many components and cavities)."""
    rng = np.random.default_rng(seed)
    noise = rng.random((n, n, n), dtype=np.float32)
    sigma = max(2.0, n / 64)
    try:
        from scipy.ndimage import gaussian_filter

        smooth = gaussian_filter(noise, sigma)
    except ImportError:  # three box filters per axis approach the gaussian
        smooth = noise
        w = max(1, round(np.sqrt(4 * sigma * sigma + 1) / 2))  # window 2w: variance 3·((2w)² − 1)/12 ≈ σ²
        for axis in range(3):
            for _ in range(3):
                c = np.cumsum(
                    np.pad(smooth, [(w, w) if a == axis else (0, 0) for a in range(3)], mode="edge"), axis
                )
                hi = np.take(c, np.arange(2 * w, c.shape[axis]), axis)
                lo = np.take(c, np.arange(0, c.shape[axis] - 2 * w), axis)
                smooth = (hi - lo) / (2 * w)
    return np.ascontiguousarray(smooth > np.median(smooth))


# ---------------------------------------------------------------------------------------------- measures
def surfels(mask: Mask) -> int:
    """The boundary faces of A: 6-neighbour pairs (voxel of A, voxel outside A)."""
    p = np.pad(mask, 1)
    return sum(int(np.count_nonzero(np.diff(p, axis=a))) for a in range(3))


def marching_cubes(mask: Mask) -> tuple[np.ndarray, np.ndarray]:
    """The peer: scikit-image's marching cubes of the padded mask at 0.5 (vertices: padded (z, y, x))."""
    from skimage.measure import marching_cubes as mc

    verts, faces, _, _ = mc(np.pad(mask, 1).astype(np.float32), level=0.5)
    return verts, faces


def mc_to_world(verts: np.ndarray, faces: np.ndarray, origin: Origin) -> tuple[np.ndarray, np.ndarray]:
    """MC's mesh in world (x, y, z) coordinates (origin + index, minus the padding), triangles outward."""
    v = verts[:, ::-1].astype(np.float64) + (np.asarray(origin, dtype=np.float64) - 1.0)
    t = np.ascontiguousarray(faces, dtype=np.int64)
    if signed_volume(v, t) < 0:
        t = np.ascontiguousarray(t[:, ::-1])
    return v, t


def signed_volume(v: np.ndarray, t: np.ndarray) -> float:
    a, b, c = v[t[:, 0]], v[t[:, 1]], v[t[:, 2]]
    return float(np.einsum("ij,ij->", a, np.cross(b, c))) / 6.0


def compact(v: np.ndarray, t: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Drop the vertices no triangle uses (a decimator leaves them): Polyhedron would refuse them."""
    used, inverse = np.unique(t, return_inverse=True)
    return np.ascontiguousarray(v[used]), inverse.reshape(t.shape).astype(np.int64)


def wrong_voxels(a: Mask, oa: Origin, b: Mask, ob: Origin) -> int:
    """|A Δ B| for two masks (z, y, x) with origins (x, y, z), aligned on a common box."""
    boxes = [(o, m.shape[::-1]) for m, o in ((a, oa), (b, ob)) if m.size and m.any()]
    if not boxes:
        return 0
    lo = [min(o[i] for o, _ in boxes) for i in range(3)]
    hi = [max(o[i] + s[i] for o, s in boxes) for i in range(3)]
    out = []
    for m, o in ((a, oa), (b, ob)):
        full = np.zeros((hi[2] - lo[2], hi[1] - lo[1], hi[0] - lo[0]), dtype=bool)
        if m.size:
            sx, sy, sz = (o[i] - lo[i] for i in range(3))
            full[sz : sz + m.shape[0], sy : sy + m.shape[1], sx : sx + m.shape[2]] = m
        out.append(full)
    return int(np.count_nonzero(out[0] ^ out[1]))


def load_fast_simplification() -> Any:
    try:
        import fast_simplification
    except ImportError:
        return None
    return fast_simplification


def mesh_error(v: np.ndarray, t: np.ndarray, mask: Mask, origin: Origin, model: str) -> str:
    """|D(mesh) Δ A| under ``model``, or 'invalid' when the mesh is not a valid polyhedron."""
    from mrm.core.errors import MRMError
    from mrm.geometry.discretize.voxels import voxelize_solid
    from mrm.geometry.polyhedra import Polyhedron

    try:
        Polyhedron(v, t)  # exact validation: voxelize_solid assumes a valid polyhedron and does not check all
        got, o = voxelize_solid(v, t, model, limit=None)
    except MRMError:
        return "invalid"
    return f"{wrong_voxels(mask, origin, got, o):,}"


def decimated_error(
    fs: Any, mc_v: np.ndarray, mc_t: np.ndarray, target: int, mask: Mask, origin: Origin, model: str
) -> tuple[str, str]:
    """MC decimated by fast_simplification to ``target`` triangles: (its triangles, :func:`mesh_error`)."""
    if target >= len(mc_t):
        return "-", "n/a"
    v, t = fs.simplify(mc_v, mc_t.astype(np.int32), target_reduction=1.0 - target / len(mc_t))
    v, t = compact(np.asarray(v, dtype=np.float64), np.asarray(t, dtype=np.int64))
    return f"{len(t):,}", mesh_error(v, t, mask, origin, model)


# ------------------------------------------------------------------------------------------------ output
def table(headers: Sequence[str], rows: Sequence[Sequence[Any]], n_text: int = 1) -> None:
    """A markdown table, columns aligned: the first ``n_text`` (names) left, the numbers right."""
    cells = [[str(h) for h in headers]] + [[str(c) for c in r] for r in rows]
    widths = [max(len(r[i]) for r in cells) for i in range(len(headers))]
    left = [i < n_text for i in range(len(headers))]

    def line(r: Sequence[str]) -> str:
        padded = (c.ljust(w) if lf else c.rjust(w) for c, w, lf in zip(r, widths, left, strict=True))
        return "| " + " | ".join(padded) + " |"

    rules = (":" + "-" * (w + 1) if lf else "-" * (w + 1) + ":" for w, lf in zip(widths, left, strict=True))
    print(line(cells[0]))
    print("|" + "|".join(rules) + "|")
    for r in cells[1:]:
        print(line(r))
    print()


def ms(seconds: float) -> str:
    return f"{seconds * 1e3:,.1f}"


# ---------------------------------------------------------------------------------------------- sections
def first_calls() -> None:
    from mrm.core.grids import VoxelSet
    from mrm.geometry.reconstruct import reconstruct_voxels

    cube = np.ones((3, 3, 3), dtype=bool)
    parts = []
    for model in MODELS:
        t0 = time.perf_counter()
        reconstruct_voxels(VoxelSet(cube, (0, 0, 0)), model)
        parts.append(f"{model} {ms(time.perf_counter() - t0)} ms")
    t0 = time.perf_counter()
    marching_cubes(cube)
    parts.append(f"marching_cubes {ms(time.perf_counter() - t0)} ms")
    print("first call on a 3³ cube (numba compilation or cache loading, imports): " + ", ".join(parts) + "\n")


def octahedra(radii: Sequence[int], repeat: int) -> None:
    from mrm.core.grids import VoxelSet
    from mrm.geometry.reconstruct import reconstruct_voxels

    print("## Octahedra |x|+|y|+|z| <= r")
    print("target: gauss exactly 8 faces; standard and supercover at most 32 faces\n")
    rows = []
    for r in radii:
        mask, origin = octahedron(r)
        vs = VoxelSet(mask, origin)
        for model in MODELS:
            t0 = time.perf_counter()
            p = reconstruct_voxels(vs, model)
            first = time.perf_counter() - t0
            t = median_time(lambda vs=vs, model=model: reconstruct_voxels(vs, model), repeat)
            ok = p.n_faces == 8 if model == "gauss" else p.n_faces <= 32
            rows.append(
                [f"octa {r}", model, f"{len(vs):,}", f"{p.n_faces:,}", f"{p.n_vertices:,}",
                 f"{p.n_triangles:,}", ms(first), ms(t), "yes" if ok else "no"]
            )  # fmt: skip
    heads = ["shape", "model", "voxels", "faces", "vertices", "triangles", "first ms", "R ms", "target"]
    table(heads, rows, 2)


def smooth_shapes(radii: Sequence[int], repeat: int, fs: Any) -> None:
    from mrm.core.grids import VoxelSet
    from mrm.geometry.reconstruct import reconstruct_voxels

    print(f"## Balls (centre {BALL_CENTRE}), ellipsoid, torus: R against marching cubes")
    print("target: R's triangles <= 0.1 x marching cubes' triangles\n")
    shapes: list[tuple[str, Callable[[], tuple[Mask, Origin]]]] = [
        (f"ball {r}", lambda r=r: ball(r)) for r in radii
    ]
    shapes.append(("ellipsoid {:g},{:g},{:g}".format(*ELLIPSOID_AXES), ellipsoid))
    shapes.append(("torus {:g},{:g}".format(*TORUS_RADII), torus))
    rows = []
    for name, make in shapes:
        mask, origin = make()
        vs = VoxelSet(mask, origin)
        n_surfels = surfels(mask)
        mc_v, mc_t = marching_cubes(mask)  # the warm call
        t_mc = median_time(lambda mask=mask: marching_cubes(mask), repeat)
        world = mc_to_world(mc_v, mc_t, origin)
        for model in MODELS:
            t0 = time.perf_counter()
            p = reconstruct_voxels(vs, model)
            first = time.perf_counter() - t0
            t_r = median_time(lambda vs=vs, model=model: reconstruct_voxels(vs, model), repeat)
            mc_wrong = mesh_error(*world, mask, origin, model)
            if fs is not None:
                fs_tris, fs_wrong = decimated_error(fs, *world, p.n_triangles, mask, origin, model)
            else:
                fs_tris, fs_wrong = "missing", "missing"
            ratio = p.n_triangles / len(mc_t)
            rows.append(
                [name, model, f"{len(vs):,}", f"{n_surfels:,}", f"{p.n_faces:,}", f"{p.n_vertices:,}",
                 f"{p.n_triangles:,}", f"{len(mc_t):,}", f"{ratio:.3f}", "yes" if ratio <= 0.1 else "no",
                 ms(first), ms(t_r), ms(t_mc), f"{t_r / t_mc:.1f}", mc_wrong, fs_tris, fs_wrong]
            )  # fmt: skip
    table(
        ["shape", "model", "voxels", "surfels", "faces", "vertices", "triangles", "MC tris", "÷ MC", "≤ 0.1",
         "R first ms", "R ms", "MC ms", "time ÷ MC", "MC wrong", "FS tris", "FS wrong"],
        rows,
        2,
    )  # fmt: skip


def big(n: int, model: str, repeat: int, seed: int, which: Sequence[str]) -> None:
    from mrm.core.grids import VoxelSet
    from mrm.geometry.reconstruct import reconstruct_voxels

    print(f"## Speed and memory at {n}³, model {model}\n")
    c = (n - 1) / 2
    rb = n / 2 - 2
    z, y, x = np.ogrid[0:n, 0:n, 0:n]
    shapes: list[tuple[str, Callable[[], Mask]]] = [
        (
            f"ball r={rb:g} in {n}³",
            lambda: np.ascontiguousarray((x - c) ** 2 + (y - c) ** 2 + (z - c) ** 2 <= rb * rb),
        ),
        (f"blobs {n}³ seed {seed}", lambda: blobs(n, seed)),
    ]
    rows = []
    for name, make in shapes:
        if name.split()[0] not in which:
            continue
        mask = make()
        vs = VoxelSet(mask, (0, 0, 0))
        t0 = time.perf_counter()
        p = reconstruct_voxels(vs, model)
        first = time.perf_counter() - t0
        t_r = median_time(lambda vs=vs: reconstruct_voxels(vs, model), repeat)
        _, mc_t = marching_cubes(mask)
        t_mc = median_time(lambda mask=mask: marching_cubes(mask), repeat)
        m_r = peak_memory(lambda vs=vs: reconstruct_voxels(vs, model))
        m_mc = peak_memory(lambda mask=mask: marching_cubes(mask))
        rows.append(
            [name, f"{len(vs):,}", f"{surfels(mask):,}", f"{p.n_triangles:,}", f"{len(mc_t):,}",
             f"{first:.3f}", f"{t_r:.3f}", f"{t_mc:.3f}", f"{t_r / t_mc:.1f}",
             f"{m_r / 2**20:,.0f}", f"{m_mc / 2**20:,.0f}", f"{m_r / m_mc:.1f}"]
        )  # fmt: skip
    table(
        ["shape", "voxels", "surfels", "R tris", "MC tris", "R first s", "R s", "MC s", "time ÷ MC",
         "R peak MiB", "MC peak MiB", "mem ÷ MC"],
        rows,
    )  # fmt: skip


LEGEND = """\
Legend:
- voxels: |A|; surfels: A's boundary faces (6-neighbour pairs voxel in A / voxel out), numpy;
- faces, vertices, triangles: R(A)'s (a face = a maximal set of exactly coplanar edge-adjacent triangles);
- MC tris: skimage.measure.marching_cubes(mask padded by 1, float32, level=0.5), the same for every model;
- ÷ MC: R's triangles / MC's (target <= 0.1); ≤ 0.1: whether that target is met;
- R first ms: the row's first call of R (warm-up, not in the median); R ms, MC ms: medians of --repeat warm
  runs (MC's includes the padding and the float32 copy it needs); time ÷ MC: R ms / MC ms;
- MC wrong: |D(MC's mesh) Δ A| with the exact voxelize_solid in the row's model, undecimated: the baseline
  of FS wrong (MC's surface passes midway between voxel centres, a gauss continuation: under the covers
  D of it gains about the outer layer of voxels);
- FS tris: MC's mesh decimated by fast_simplification.simplify to R's triangle count (what it reached);
  FS wrong: |D(decimated mesh) Δ A| with the exact voxelize_solid in the row's model ("invalid": the decimated
  mesh is not a valid polyhedron — open, non-manifold or self-intersecting — so D of it is undefined;
  "n/a": R has no fewer triangles than MC, nothing to decimate; "missing": fast_simplification not installed);
- --big: R peak MiB, MC peak MiB: tracemalloc peak of one call (numpy and numba arrays are traced; memory a
  C/Cython extension mallocs itself is not); mem ÷ MC: their ratio; times in seconds.
"""


def main() -> None:
    ap = argparse.ArgumentParser(description=(__doc__ or "").splitlines()[0])
    ap.add_argument("--octa-radii", type=int, nargs="*", default=[4, 8, 16, 32, 64, 100, 150, 200])
    ap.add_argument("--ball-radii", type=int, nargs="+", default=[8, 16, 32, 64, 100])
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument(
        "--big", type=int, default=0, metavar="N", help="also time R and MC on N³ volumes (0: off)"
    )
    ap.add_argument(
        "--big-repeat",
        type=int,
        default=None,
        metavar="K",
        help="runs of each --big row's timing (default: --repeat); one R of 256³ blobs takes minutes",
    )
    ap.add_argument("--big-model", default="gauss", choices=MODELS)
    ap.add_argument("--seed", type=int, default=0, help="seed of the --big random blobs")
    ap.add_argument("--big-shapes", nargs="+", default=["ball", "blobs"], choices=["ball", "blobs"])
    ap.add_argument(
        "--product-limit",
        action="store_true",
        help="keep limits.MAX_COMPACT_R_TRIANGLES (bigger sets then get the safety net, as in the product)",
    )
    args = ap.parse_args()
    if not args.product_limit:
        from mrm.core import limits

        # The product keeps the safety net above this size (the decimation is slow); the benchmark measures
        # the compact R at every size.
        limits.MAX_COMPACT_R_TRIANGLES = 1 << 62
        print("MAX_COMPACT_R_TRIANGLES lifted: the compact R at every size (--product-limit keeps it)\n")

    fs = load_fast_simplification()
    if fs is None:
        print(
            "fast_simplification is missing (pip install fast-simplification): the FS columns are skipped\n"
        )
    print(LEGEND)
    first_calls()
    octahedra(args.octa_radii, args.repeat)
    smooth_shapes(args.ball_radii, args.repeat, fs)
    if args.big:
        big_repeat = args.repeat if args.big_repeat is None else args.big_repeat
        big(args.big, args.big_model, big_repeat, args.seed, args.big_shapes)


if __name__ == "__main__":
    main()
