"""Benchmark: exact validation of a closed triangle mesh (mrm Polyhedron) against trimesh's checks.

Compares, on the same closed meshes of about 100,000 triangles and more:

- ours:    ``Polyhedron(vertices, triangles)`` — the exact validation of docs/design.md §11: finite distinct
           vertices, no flat triangle, closed 2-manifold (edges and vertex fans), consistent orientation,
           no self-intersection (a grid over triangle boxes, exact orient3d/orient2d), each shell oriented as
           its nesting requires;
- trimesh: ``Trimesh(process=False)`` then ``is_watertight`` and ``is_winding_consistent`` (each on a fresh
           mesh, so nothing is cached) — it checks less: no self-intersection, no non-manifold vertex, no
           nesting, no flat triangle, and in floating point.

Times are medians of ``--repeat`` warm runs in this process (numba's compilation/cache loading comes first,
apart); the ratio is ours / trimesh's, measured in the same run.

Usage: ``.venv/bin/python benchmarks/polyhedra.py [--repeat 7]``
"""

from __future__ import annotations

import argparse
import os
import sys
import time

import numpy as np
import trimesh

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
if ROOT not in sys.path:
    sys.path.insert(0, ROOT)

from benchmarks.discretize import median_time  # noqa: E402
from mrm.geometry.polyhedra import Polyhedron  # noqa: E402


def meshes() -> dict[str, tuple[np.ndarray, np.ndarray]]:
    """Closed meshes: two spheres, a torus, a finely triangulated cube, many small cubes, a fine sphere."""
    out: dict[str, tuple[np.ndarray, np.ndarray]] = {}
    s6 = trimesh.creation.icosphere(subdivisions=6)  # 81,920
    s5 = trimesh.creation.icosphere(subdivisions=5)
    s5.apply_translation([3.0, 0.0, 0.0])
    out["2 spheres 102k"] = (
        np.vstack([s6.vertices, s5.vertices]),
        np.vstack([s6.faces, s5.faces + len(s6.vertices)]),
    )
    torus = trimesh.creation.torus(major_radius=3.0, minor_radius=1.0, major_sections=500, minor_sections=100)
    out["torus 100k"] = (np.asarray(torus.vertices), np.asarray(torus.faces))
    # A cube whose faces are fine grids: every neighbour pair exactly coplanar (the exact stages' worst case).
    box = trimesh.creation.box()
    fine = box.subdivide().subdivide().subdivide().subdivide().subdivide().subdivide()
    fine = trimesh.Trimesh(fine.vertices, fine.faces, process=True)  # merge the split edges' vertices
    out[f"flat cube {len(fine.faces) // 1000}k"] = (np.asarray(fine.vertices), np.asarray(fine.faces))
    # Many shells: 22³ small cubes (the nesting test's worst case: every shell against every other).
    cube = trimesh.creation.box(extents=(0.5, 0.5, 0.5))
    offsets = np.array([(x, y, z) for x in range(22) for y in range(22) for z in range(22)], dtype=np.float64)
    out["10,648 cubes 128k"] = (
        (np.asarray(cube.vertices)[None] + offsets[:, None]).reshape(-1, 3),
        (np.asarray(cube.faces)[None] + 8 * np.arange(len(offsets))[:, None, None]).reshape(-1, 3),
    )
    s7 = trimesh.creation.icosphere(subdivisions=7)
    out["sphere 328k"] = (np.asarray(s7.vertices), np.asarray(s7.faces))
    return out


def trimesh_checks(v: np.ndarray, t: np.ndarray) -> bool:
    m = trimesh.Trimesh(vertices=v, faces=t, process=False, validate=False)
    return bool(m.is_watertight and m.is_winding_consistent)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=7)
    args = parser.parse_args()
    t0 = time.perf_counter()
    tiny = trimesh.creation.box()
    Polyhedron(tiny.vertices, tiny.faces)
    print(f"first call (numba compile or cache load): {time.perf_counter() - t0:.2f} s")
    print(f"{'mesh':<18} {'triangles':>9} {'ours ms':>9} {'trimesh ms':>11} {'ratio':>6}  faces shells")
    for name, (v, t) in meshes().items():
        p = Polyhedron(v, t)  # warm, and valid
        assert trimesh_checks(v, t)
        ours = median_time(lambda v=v, t=t: Polyhedron(v, t), args.repeat)
        peer = median_time(lambda v=v, t=t: trimesh_checks(v, t), args.repeat)
        print(
            f"{name:<18} {len(t):>9,} {ours * 1e3:>9.0f} {peer * 1e3:>11.0f} {ours / peer:>6.1f}  "
            f"{p.n_faces:>5} {p.n_shells:>6}"
        )


if __name__ == "__main__":
    main()
