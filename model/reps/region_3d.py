"""The region representation of a voxel set: components, cavities, tunnels, Euler characteristic, surfaces.

Reference: docs/design.md §11 (region representation); the 2D counterpart is :mod:`mrm.reps.region`.

Topology (6, 26): the components of a voxel set A are its 6-connected components; a cavity is a bounded
26-connected component of Z³ ∖ A, attached to the component that encloses it. The Euler characteristic
χ = b0 − b1 + b2 is that of the cubical complex of A (vertices at voxel centres, edges between 6-adjacent
voxels, squares and cubes filling 2×2 and 2×2×2 blocks), i.e. of V(A) eroded by ¼; so
χ = components − tunnels + cavities, and per component χ(X) = 1 − tunnels(X) + cavities(X).

Boundaries are surfels (see :mod:`mrm.geometry.topology.surfels`) grouped into one closed surface per
component (its outer surface) and one per cavity.

Canonical orders: components are numbered 1..n in raster order (z, y, x) of their first voxel (lowest z
first), the cavities of a component in the same order. Coordinates are the world's: voxel (x, y, z) is
``mask[z − z0, y − y0, x − x0]``; boxes are (xmin, ymin, zmin, xmax, ymax, zmax), bounds included.

Region → discrete is exact: :meth:`Region3D.mask` rebuilds the voxels from the runs kept with the region.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
import numpy.typing as npt

from mrm.core.errors import ParameterError
from mrm.core.grids import VoxelSet
from mrm.core.limits import check_pixels
from mrm.geometry.topology.labeling import _group_by_label
from mrm.geometry.topology.labeling_3d import (
    Runs3D,
    as_u8_3d,
    euler_per_label,
    label_runs_3d,
    paint_3d,
    paint_background_3d,
    surfel_count,
)
from mrm.geometry.topology.surfels import Surfels, surfels_of

IntArray = npt.NDArray[np.int64]
BoolArray = npt.NDArray[np.bool_]

#: A box of voxels (xmin, ymin, zmin, xmax, ymax, zmax), bounds included.
Box3 = tuple[int, int, int, int, int, int]

Origin3 = tuple[int, int, int]


@dataclass(frozen=True, slots=True)
class Cavity3D:
    """A cavity: a bounded 26-connected component of the complement.

    Attributes
    ----------
    voxels : int
        Its number of voxels (not counting the components nested inside it).
    bbox : Box3
        The box of its voxels.
    """

    voxels: int
    bbox: Box3


@dataclass(frozen=True, slots=True)
class Component3D:
    """A 6-connected component with its cavities.

    Attributes
    ----------
    label : int
        Its number, 1..n in canonical order (its value in :meth:`Region3D.labels`).
    voxels : int
        Its number of voxels.
    bbox : Box3
        The box of its voxels.
    euler : int
        Its Euler characteristic, 1 − tunnels + cavities.
    cavities : tuple of Cavity3D
        The cavities it encloses, in raster order of their first voxel.
    """

    label: int
    voxels: int
    bbox: Box3
    euler: int
    cavities: tuple[Cavity3D, ...]

    @property
    def tunnels(self) -> int:
        """Its number of tunnels (first Betti number; the genus of a solid with no cavity)."""
        return 1 + len(self.cavities) - self.euler


@dataclass(frozen=True, slots=True)
class Surface3D:
    """A closed surfel surface: the boundary between a component and one component of its complement.

    Attributes
    ----------
    component : int
        The label of the component on its inside.
    cavity : int
        −1 for the component's outer surface, else the index of the cavity in ``component.cavities``.
    voxels : ndarray of int64, shape (n, 3)
        The (x, y, z) voxel of A each surfel belongs to, in raster order (z, y, x), then by direction.
    directions : ndarray of uint8, shape (n,)
        The index of each surfel's outward normal in :data:`mrm.geometry.topology.surfels.DIRS`.
    neighbours : ndarray of int64, shape (n, 4)
        The surfels (indices in this surface) across each surfel's four edges (the (6, 26) rule).
    """

    component: int
    cavity: int
    voxels: IntArray = field(repr=False, compare=False)
    directions: npt.NDArray[np.uint8] = field(repr=False, compare=False)
    neighbours: IntArray = field(repr=False, compare=False)

    def __len__(self) -> int:
        return int(self.directions.size)


@dataclass(frozen=True, slots=True, init=False)
class Region3D:
    """The region representation of a voxel set (:func:`region_3d_of`).

    Attributes
    ----------
    components : tuple of Component3D
        The 6-connected components in canonical order (``components[k].label == k + 1``).
    origin : tuple of int
        The (x0, y0, z0) of the canonical mask the region was computed from.
    shape : tuple of int
        That mask's (nz, ny, nx).
    """

    components: tuple[Component3D, ...]
    origin: Origin3
    shape: tuple[int, int, int]
    _runs: Runs3D | None = field(repr=False, compare=False, hash=False)
    _cavity_index: tuple[tuple[int, int], ...] = field(repr=False, compare=False, hash=False)
    _surfaces: list[tuple[Surface3D, ...]] = field(repr=False, compare=False, hash=False)

    def __init__(
        self,
        components: tuple[Component3D, ...],
        origin: Origin3,
        shape: tuple[int, int, int],
        runs: Runs3D | None,
        cavity_index: tuple[tuple[int, int], ...] = (),
    ) -> None:
        object.__setattr__(self, "components", components)
        object.__setattr__(self, "origin", origin)
        object.__setattr__(self, "shape", shape)
        object.__setattr__(self, "_runs", runs)
        object.__setattr__(self, "_cavity_index", cavity_index)
        object.__setattr__(self, "_surfaces", [])

    @property
    def n_components(self) -> int:
        """The number of 6-connected components."""
        return len(self.components)

    @property
    def n_cavities(self) -> int:
        """The number of cavities (bounded 26-components of the complement)."""
        return sum(len(c.cavities) for c in self.components)

    @property
    def n_tunnels(self) -> int:
        """The number of tunnels (first Betti number)."""
        return sum(c.tunnels for c in self.components)

    @property
    def euler(self) -> int:
        """The Euler characteristic χ = components − tunnels + cavities."""
        return sum(c.euler for c in self.components)

    @property
    def voxels(self) -> int:
        """The number of voxels of the set."""
        return sum(c.voxels for c in self.components)

    @property
    def n_surfels(self) -> int:
        """The number of surfels (voxel faces between the set and the outside), counted from the runs."""
        return surfel_count(self._runs_or_empty())

    def _runs_or_empty(self) -> Runs3D:
        if self._runs is None:
            return label_runs_3d(np.zeros(self.shape, bool))
        return self._runs

    def mask(self) -> BoolArray:
        """The voxel set's (canonical) mask, rebuilt from the runs: region → discrete is exact."""
        return paint_3d(self._runs_or_empty()) > 0

    def labels(self) -> npt.NDArray[np.int32]:
        """The (nz, ny, nx) component label volume at :attr:`origin` (0 off the set)."""
        return paint_3d(self._runs_or_empty())

    def component_voxels(self, label: int) -> VoxelSet:
        """The voxels of component ``label`` (1..n): what deleting the component removes.

        Raises
        ------
        ParameterError
            When there is no such component.
        """
        if not 1 <= int(label) <= len(self.components):
            raise ParameterError(f"there is no component {label} (the object has {len(self.components)})")
        return VoxelSet(self.labels() == int(label), self.origin)

    def cavity_voxels(self, component: int, cavity: int) -> VoxelSet:
        """The voxels of cavity ``cavity`` (0-based) of component ``component``: what filling it adds.

        The components nested inside the cavity are not part of it; filling it makes them one with its
        component.

        Raises
        ------
        ParameterError
            When there is no such cavity.
        """
        key = (int(component), int(cavity))
        if key not in self._cavity_index:
            raise ParameterError(f"component {component} has no cavity {cavity + 1}")
        b = self._cavity_index.index(key) + 1
        return VoxelSet(paint_background_3d(self._runs_or_empty()) == b, self.origin)

    @property
    def surfaces(self) -> tuple[Surface3D, ...]:
        """The surfel surfaces: for each component, its outer surface then one per cavity (computed once)."""
        if not self._surfaces:
            self._surfaces.append(self._compute_surfaces())
        return self._surfaces[0]

    def _compute_surfaces(self) -> tuple[Surface3D, ...]:
        if not self.components:
            return ()
        s: Surfels = surfels_of(self._runs_or_empty())
        x0, y0, z0 = self.origin
        start, order = _group_by_label(s.surface, s.n_surfaces - 1)  # each surface's surfels, in raster order
        local = np.empty(order.size, np.int64)
        local[order] = np.arange(order.size) - np.repeat(start[:-1], np.diff(start))
        world = s.voxel + np.array([x0, y0, z0], np.int64)
        out = []
        t = 0
        # the surfaces come by component, the outer one then one per cavity: the order of Region3D.surfaces
        for c in self.components:
            for cav in range(-1, len(c.cavities)):
                idx = order[start[t] : start[t + 1]]
                out.append(Surface3D(c.label, cav, world[idx], s.direction[idx], local[s.neighbour[idx]]))
                t += 1
        return tuple(out)


def _box(b: IntArray, origin: Origin3) -> Box3:
    x0, y0, z0 = origin
    return (
        int(b[0]) + x0,
        int(b[1]) + y0,
        int(b[2]) + z0,
        int(b[3]) + x0,
        int(b[4]) + y0,
        int(b[5]) + z0,
    )


def region_3d_of(mask: npt.ArrayLike, origin: Origin3 = (0, 0, 0), limit: int | None = None) -> Region3D:
    """Compute the region representation of a voxel set.

    Parameters
    ----------
    mask : array_like of bool, shape (nz, ny, nx)
        The voxel set A; ``mask[k, j, i]`` is voxel (x0 + i, y0 + j, z0 + k). Need not be cropped.
    origin : tuple of int
        (x0, y0, z0).
    limit : int, optional
        Refuse a mask of more voxels than this (:func:`mrm.core.limits.check_pixels`).

    Returns
    -------
    Region3D
        The 6-connected components in canonical order, each with its voxel count, box, Euler characteristic
        and cavities (bounded 26-components of the complement, with theirs); the surfaces on demand.
    """
    m = np.asarray(mask)
    if m.ndim != 3:
        raise ValueError(f"a voxel mask must be 3-D, got shape {m.shape}")
    check_pixels(int(m.size), limit, "the voxel set")
    ox, oy, oz = (int(v) for v in origin)
    u8 = as_u8_3d(m)
    nz_ax = np.flatnonzero(u8.any(axis=(1, 2)))
    if nz_ax.size == 0:
        return Region3D((), (0, 0, 0), (0, 0, 0), None)
    ny_ax = np.flatnonzero(u8.any(axis=(0, 2)))
    nx_ax = np.flatnonzero(u8.any(axis=(0, 1)))
    k0, j0, i0 = int(nz_ax[0]), int(ny_ax[0]), int(nx_ax[0])
    crop = u8[k0 : int(nz_ax[-1]) + 1, j0 : int(ny_ax[-1]) + 1, i0 : int(nx_ax[-1]) + 1]
    org = (ox + i0, oy + j0, oz + k0)
    runs = label_runs_3d(crop, 6)
    chi = euler_per_label(runs)
    # Cavities by component, in raster order of their first voxel (their background ids are in that order).
    by_comp: list[list[int]] = [[] for _ in range(runs.n_labels + 1)]
    for b in range(1, runs.n_bg):
        by_comp[int(runs.encloser[b])].append(b)
    cavity_index = [(0, 0)] * (runs.n_bg - 1)
    comps = []
    for c in range(1, runs.n_labels + 1):
        cavs = []
        for t, b in enumerate(by_comp[c]):
            cavity_index[b - 1] = (c, t)
            cavs.append(Cavity3D(int(runs.bg_counts[b]), _box(runs.bg_box[b], org)))
        comps.append(Component3D(c, int(runs.counts[c]), _box(runs.box[c], org), int(chi[c]), tuple(cavs)))
    return Region3D(tuple(comps), org, crop.shape, runs, tuple(cavity_index))
