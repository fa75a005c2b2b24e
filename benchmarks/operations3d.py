"""Benchmark: DSS_α of a voxel set, exactly, against scipy's nearest-neighbour zoom (issue 30 item 1).

DSS_α(A) = D(Sc_α(R(A))) (docs/design.md §8, §11) of a 128³ digital ball (default), about the origin:

* R = ``reconstruct(A, model)`` is timed once on its own (an object's Euclidean view holds it: ADR 0039);
* ours = ``voxelize_image(R, α·I, 0, model)``, the exact image voxelized (ADRs 0058, 0062): α = 2 and 1.25
  are dyadic (N = 1: the plain exact voxelization); α = 4/5 and 1/5 voxelize 5·Sc_α(R) on the grid of step 5;
* ours (pooling) = ``scaling_by_pixels`` for α = 1/2 with an aligned centre: A's voxels alone, no R;
* float = the float composition the issue compares with: the same R, its vertices mapped in float64 (rounded;
  for a rotation the unrounded axis-angle matrix), then ``voxelize_solid`` — fast, but not D(T(R(A))) where a
  rounded vertex crosses a voxel side; target ours ≤ 1.3 × float;
* dR rows: the rotation dR applies (ADR 0060: quarter turns exact, other angles the axis-angle matrix rounded
  to 2⁻³⁰), exactly;
* scipy = ``scipy.ndimage.zoom(mask, α, order=0)``: nearest-neighbour resampling of the mask — not exact and
  not the same set (no continuation, its own rounding of the grid), the raster peer for speed only.

EDu and EDco_α rows (issue 30: every 3D operation ≤ 1.3× its float composition): two ``--binary-size`` balls
(64³ by default), the second shifted by a third of its side along x. EDu = R(A ∪ B): the float composition
is the same (no map: D of a voxel set is itself), the numpy union then R; EDco_1/2: ours
(:func:`mrm.ops.boolean.euclidean_discrete_corefinement`, exact) against R(A) and R(B) scaled by ½ in float,
voxelized, the three set operations, R of each part and its vertices scaled back by 2 in float.

Times are medians of ``--repeat`` runs in this process (numba compilation or cache loading measured once,
apart), in seconds; ratio = ours / scipy. Target in the issue: DSS_2 of 128³ ≤ 10× scipy zoom.

Usage: ``.venv/bin/python benchmarks/operations3d.py [--size 128] [--repeat 3] [--model standard]``
"""

from __future__ import annotations

import argparse
import os
import sys
import time
from fractions import Fraction
from typing import Any

import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
if ROOT not in sys.path:
    sys.path.insert(0, ROOT)

from benchmarks.region import median_time  # noqa: E402


def ball(n: int) -> np.ndarray:
    """The digital ball of diameter n - 1 centred in an n³ grid: (x, y, z) with |p − c| ≤ (n − 1)/2."""
    z, y, x = np.mgrid[0:n, 0:n, 0:n]
    c = (n - 1) / 2
    return np.ascontiguousarray((x - c) ** 2 + (y - c) ** 2 + (z - c) ** 2 <= c * c)


def warm_up(model: str) -> float:
    """First calls of R and the exact voxelization on a tiny set: compilation or cache loading (seconds)."""
    from mrm.core.grids import VoxelSet
    from mrm.geometry.discretize.voxel_images import voxelize_image
    from mrm.geometry.reconstruct import reconstruct

    t = time.perf_counter()
    r = reconstruct(VoxelSet(np.ones((3, 3, 3), dtype=bool)), model)
    voxelize_image(r, scaling(Fraction(1, 5)), (0, 0, 0), model)
    return time.perf_counter() - t


def scaling(alpha: Fraction) -> list[list[Fraction]]:
    return [[alpha if i == j else Fraction(0) for j in range(3)] for i in range(3)]


def main() -> None:
    ap = argparse.ArgumentParser(description=(__doc__ or "").splitlines()[0])
    ap.add_argument("--size", type=int, default=128)
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--model", default="standard", choices=["standard", "supercover", "gauss"])
    ap.add_argument("--binary-size", type=int, default=64, help="side of the EDu / EDco balls")
    args = ap.parse_args()

    import scipy.ndimage as ndi

    from mrm.core.grids import VoxelSet
    from mrm.geometry.discretize.exact_solid import rotation_matrix
    from mrm.geometry.discretize.voxel_images import voxelize_image
    from mrm.geometry.discretize.voxels import voxelize_solid
    from mrm.geometry.reconstruct import reconstruct
    from mrm.ops.outcome import scaling_by_pixels

    model = args.model
    print(f"first call of R + voxelize_image (numba compile or cache load): {warm_up(model) * 1000:.0f} ms")
    mask = ball(args.size)
    a = VoxelSet(mask)
    t = time.perf_counter()
    r = reconstruct(a, model)
    t_r = time.perf_counter() - t
    print(
        f"A: {args.size}³ digital ball, {len(a):,} voxels, model {model}; R(A): {r.n_vertices:,} vertices, "
        f"{r.n_triangles:,} triangles, {t_r:.2f} s (once, not in the rows)"
    )
    print(f"times: median of {args.repeat} runs, seconds\n")
    head = (
        f"{'operation':<22} {'result voxels':>14} | {'ours':>7} {'float':>7} {'scipy':>7} | "
        f"{'÷ float':>7} {'÷ scipy':>7}"
    )
    print(head)
    print("-" * len(head))
    rows: list[tuple[str, Any, str]] = [
        ("DSS_2", Fraction(2), "image"),
        ("DSS_1.25", Fraction(5, 4), "image"),
        ("DSS_0.5", Fraction(1, 2), "image"),
        ("DSS_0.5 (pooling A)", Fraction(1, 2), "pool"),
        ("DSS_0.8 (N = 5)", Fraction(4, 5), "image"),
        ("DSS_0.2 (N = 5)", Fraction(1, 5), "image"),
        ("dR_90 about x", (Fraction(90), (1, 0, 0)), "rotation"),
        ("dR_30 about (1,1,1)", (Fraction(30), (1, 1, 1)), "rotation"),
    ]
    verts = np.asarray(r.vertices)
    tris = np.asarray(r.triangles)
    for name, alpha, how in rows:
        float_map: np.ndarray | None = None
        if how in ("image", "rotation"):
            if how == "image":
                lin = scaling(alpha)
                float_map = float(alpha) * np.eye(3)
            else:
                theta, axis = alpha
                lin = [list(row) for row in rotation_matrix(theta, axis)]
                float_map = _rodrigues(float(theta), axis)

            def ours(_: object, lin: list[list[Fraction]] = lin) -> VoxelSet:
                return voxelize_image(r, lin, (0, 0, 0), model)
        else:
            # Sc_1/2 about C = (½, ½, ½) (covers) or the origin (gauss): blocks aligned with A's voxels
            c = Fraction(0) if model == "gauss" else Fraction(-1, 2)
            t_off = (1 - alpha) * c

            def ours(_: object, alpha: Fraction = alpha, t_off: Fraction = t_off) -> VoxelSet:
                out = scaling_by_pixels(a, (alpha, (t_off, t_off, t_off)), model)
                assert out is not None
                return out

        result = ours(None)
        t_ours = median_time(ours, None, args.repeat)
        if float_map is not None:
            # the float composition: the same R, its vertices mapped in float64 (rounded), voxelized
            t_float = median_time(
                lambda m: voxelize_solid(verts @ m.T, tris, model, limit=None), float_map, args.repeat
            )
        else:
            t_float = float("nan")
        if how == "rotation":
            t_scipy = float("nan")  # scipy.ndimage.rotate turns about one axis only: no peer row
        else:
            t_scipy = median_time(lambda m, f=float(alpha): ndi.zoom(m, f, order=0), mask, args.repeat)
        print(
            f"{name:<22} {len(result):>14,} | {t_ours:>7.3f} {t_float:>7.3f} {t_scipy:>7.3f} | "
            f"{t_ours / t_float:>7.2f} {t_ours / t_scipy:>7.2f}",
            flush=True,
        )
    binary_rows(args.binary_size, model, args.repeat)


def binary_rows(side: int, model: str, repeat: int) -> None:
    """EDu and EDco_1/2 of two overlapping balls against their float compositions (see the docstring)."""
    from mrm.core.grids import VoxelSet
    from mrm.geometry.discretize.voxels import voxelize_solid
    from mrm.geometry.reconstruct import reconstruct
    from mrm.ops.boolean import euclidean_discrete_corefinement, euclidean_discrete_union

    a = VoxelSet(ball(side))
    b = VoxelSet(ball(side), (side // 3, 0, 0))

    def float_union(_: object) -> Any:
        return reconstruct(a | b, model)

    def float_corefine(_: object) -> list[Any]:
        scaled = []
        for s in (a, b):
            r = reconstruct(s, model)
            mask, origin = voxelize_solid(np.asarray(r.vertices) * 0.5, r.triangles, model, limit=None)
            scaled.append(VoxelSet(mask, origin))
        sa, sb = scaled
        out = []
        for part in (sa - sb, sa & sb, sb - sa):
            p = reconstruct(part, model)
            out.append(np.asarray(p.vertices) * 2.0)
        return out

    print(f"\nEDu, EDco: two {side}³ balls, the second shifted by {side // 3} along x ({model})")
    for name, ours, flo in (
        ("EDu", lambda _: euclidean_discrete_union(a, b, model), float_union),
        (
            "EDco_1/2",
            lambda _: euclidean_discrete_corefinement(a, b, model, Fraction(1, 2)),
            float_corefine,
        ),
    ):
        t_ours = median_time(ours, None, repeat)
        t_float = median_time(flo, None, repeat)
        print(
            f"{name:<22} {'':>14} | {t_ours:>7.3f} {t_float:>7.3f} {'':>7} | {t_ours / t_float:>7.2f}",
            flush=True,
        )


def _rodrigues(theta: float, axis: Any) -> np.ndarray:
    """The float64 rotation matrix of the axis-angle formula (not rounded: the float composition's map)."""
    import math

    u = np.asarray(axis, float) / np.linalg.norm(axis)
    k = np.array([[0.0, -u[2], u[1]], [u[2], 0.0, -u[0]], [-u[1], u[0], 0.0]])
    t = math.radians(theta)
    return np.asarray(np.eye(3) + math.sin(t) * k + (1.0 - math.cos(t)) * (k @ k))


if __name__ == "__main__":
    main()
