"""Draw the picture of docs/polygonize-3d.md from the project's own polygonization of a label volume.

Run from the repository root::

    .venv/bin/python docs/figures/make_polygonize_3d_figure.py

It writes ``docs/img/polygonize-3d.png``: a label volume of three labels (left), the three regions' meshes
from :func:`mrm.geometry.reconstruct.polygonize_3d.polygonize_volume` pulled apart (middle; the common faces
are the same triangles in two meshes), and a ring of label 1 closed only along an edge (right: kept apart
there by the quarter cells it gives to its neighbours). Only the drawing is done here, with matplotlib's
mplot3d and the helpers of ``make_discretization_figures.py``; z is up.
"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT))
sys.path.insert(0, str(Path(__file__).resolve().parent))

import matplotlib.pyplot as plt  # noqa: E402
from make_discretization_figures import draw_voxels, rgb, titled, voxel_axes  # noqa: E402
from mpl_toolkits.mplot3d.art3d import Poly3DCollection  # noqa: E402

from mrm.core.grids import VoxelSet  # noqa: E402
from mrm.geometry.discretize.voxels import voxelize_solid  # noqa: E402
from mrm.geometry.reconstruct.polygonize_3d import polygonize_volume  # noqa: E402

OUT = ROOT / "docs" / "img"
COLOURS = {1: (66, 133, 204), 2: (226, 132, 52), 3: (90, 170, 100)}
LIGHT = np.array([0.3, -0.6, 0.75]) / np.linalg.norm([0.3, -0.6, 0.75])
#: How far each region's mesh is pulled out of the volume in the middle panel, by label.
PULL = {1: (0.0, 0.0, -1.6), 2: (0.0, 0.0, 1.6), 3: (1.8, 0.0, 0.0)}


def volume() -> np.ndarray:
    """Three labels in a 4 × 4 × 3 box (z, y, x order): a floor, a block on it and an L beside the block."""
    lab = np.zeros((3, 4, 4), np.int32)
    lab[0] = 1  # the floor
    lab[1:, :2, :2] = 2  # a block on the floor
    lab[1, 2:, 2:] = 3  # an L beside it
    lab[1, 3, 3] = 0
    return lab


def ring() -> np.ndarray:
    """A ring of label 1 closed only along an edge (a pinch), label 2 in the corner beside the pinch."""
    lab = np.ones((1, 3, 3), np.int32)
    lab[0, 1, 1] = 0
    lab[0, 2, 2] = 2
    lab[0, 1, 2] = 1
    lab[0, 2, 1] = 1
    lab[0, 1, 1] = 0
    return lab


def shaded(vertices: np.ndarray, triangles: np.ndarray, colour: tuple[int, int, int]) -> tuple[list, list]:
    """The triangles, each shaded by the light on its normal."""
    pieces, fills = [], []
    for t in triangles.tolist():
        tri = vertices[t]
        n = np.cross(tri[1] - tri[0], tri[2] - tri[0])
        shade = 0.62 + 0.38 * max(0.0, float(n @ LIGHT / np.linalg.norm(n)))
        pieces.append(tri)
        fills.append(rgb(tuple(round(shade * c) for c in colour)))
    return pieces, fills


def main() -> None:
    """Draw the three panels."""
    lab = volume()
    out = polygonize_volume(lab)
    for i, r in enumerate(out.regions):  # every mesh burns back to its region (the contract, checked here)
        v, t = out.mesh(i)
        mask, _ = voxelize_solid(v, t, "gauss", limit=None)
        assert int(mask.sum()) == r.voxels
    fig = plt.figure(figsize=(12.6, 4.4), dpi=100)
    box = (-1, -1, -2, 5, 4, 4)
    ax = voxel_axes(fig, (0.0, 0.0, 1 / 3, 0.86), box, zoom=1.2)
    layers = []
    for value, colour in COLOURS.items():
        k, j, i = np.nonzero(lab == value)
        layers.append((VoxelSet.from_points(np.stack([i, j, k], axis=1).tolist()), colour, (60, 60, 60)))
    draw_voxels(ax, layers)
    titled(fig, 0.0, "a label volume", f"3 labels, {len(out.regions)} regions, label 0 around")
    ax = voxel_axes(fig, (1 / 3, 0.0, 1 / 3, 0.86), box, zoom=1.2)
    pieces, fills = [], []
    for i, r in enumerate(out.regions):
        v, t = out.mesh(i)
        p, f = shaded(v + np.array(PULL[r.label]), t, COLOURS[r.label])
        pieces += p
        fills += f
    ax.add_collection3d(
        Poly3DCollection(pieces, facecolors=fills, edgecolors=rgb((40, 40, 40)), linewidths=0.5)
    )
    n_tri = out.n_triangles
    titled(
        fig, 1 / 3, "one closed mesh per region", f"pulled apart; {n_tri} triangles, shared faces reversed"
    )
    small = polygonize_volume(ring())
    ax = voxel_axes(fig, (2 / 3, 0.0, 1 / 3, 0.86), (0, 0, -1, 3, 3, 2), zoom=1.3)
    pieces, fills = [], []
    for i, r in enumerate(small.regions):
        v, t = small.mesh(i)
        p, f = shaded(v + np.array([0.5, 0.5, 0.0]) * (r.label - 1), t, COLOURS[r.label])
        pieces += p
        fills += f
    ax.add_collection3d(
        Poly3DCollection(pieces, facecolors=fills, edgecolors=rgb((40, 40, 40)), linewidths=0.5)
    )
    titled(
        fig, 2 / 3, "a region meeting itself along an edge", "kept apart by quarter cells its neighbours take"
    )
    fig.savefig(OUT / "polygonize-3d.png")
    plt.close(fig)


if __name__ == "__main__":
    main()
