"""The analytical representation of a voxel set: every surfel surface cut into digital plane segments.

Reference: docs/design.md §11 (analytical representation); the 2D counterpart is :mod:`mrm.reps.analytical`.

Each closed surface of :attr:`mrm.reps.region_3d.Region3D.surfaces` (a component's outer surface, one per
cavity) is segmented greedily into digital plane segments (:mod:`mrm.geometry.planes`): connected surfel
patches whose voxels of A lie in one standard arithmetic plane μ ≤ a·x + b·y + c·z < μ + ω, with
ω = |a| + |b| + |c| and (a, b, c) primitive and pointing outward, and every voxel outside beyond it. Each
segment carries its preimage (the cone of separating normals) and its chosen plane (the smallest such normal,
the Euclidean plane midway between the two sets of voxel centres); both are computed when first asked.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import numpy.typing as npt

from mrm.geometry.planes.segmentation import PlaneSegment, PlaneSegmentation, plane_segments
from mrm.reps.region_3d import Region3D

IntArray = npt.NDArray[np.int64]


@dataclass(frozen=True)
class Analytical3D:
    """The digital plane segments of every surface of a voxel set.

    Attributes
    ----------
    segmentation : PlaneSegmentation
        The segments of all surfaces; surfel indices run over the surfaces in the order of
        :attr:`Region3D.surfaces`, each surface's surfels in its own order.
    surface_of : int64 array
        The index in :attr:`Region3D.surfaces` of each segment's surface.
    """

    segmentation: PlaneSegmentation
    surface_of: IntArray

    def __len__(self) -> int:
        return len(self.segmentation)

    @property
    def n_segments(self) -> int:
        """The number of digital plane segments."""
        return len(self.segmentation)

    def segment(self, k: int) -> PlaneSegment:
        """Segment k with its plane, preimage and chosen Euclidean plane."""
        return self.segmentation.segment(k)

    def segments_of_surface(self, i: int) -> IntArray:
        """The indices of the segments of surface i."""
        return np.flatnonzero(self.surface_of == i)


def analytical_3d_of(region: Region3D) -> Analytical3D:
    """The greedy digital plane segmentation of a voxel set's surfaces.

    Parameters
    ----------
    region : Region3D
        The region representation (:func:`mrm.reps.region_3d.region_3d_of`); its surfaces are built if they
        were not yet.

    Returns
    -------
    Analytical3D

    Examples
    --------
    >>> import numpy as np
    >>> from mrm.reps.region_3d import region_3d_of
    >>> g = np.arange(-5, 6)
    >>> z, y, x = np.meshgrid(g, g, g, indexing="ij")
    >>> octahedron = region_3d_of(abs(x) + abs(y) + abs(z) <= 4, (-5, -5, -5))
    >>> an = analytical_3d_of(octahedron)
    >>> len(an), an.segment(0).plane.omega
    (8, 3)
    """
    surfaces = region.surfaces
    sizes = np.array([len(s) for s in surfaces], np.int64)
    start = np.concatenate([[0], np.cumsum(sizes)])
    if start[-1] == 0:
        empty = np.zeros(0, np.int64)
        seg = plane_segments(np.zeros((0, 3), np.int64), np.zeros(0, np.uint8), np.zeros((0, 4), np.int64))
        return Analytical3D(seg, empty)
    voxel = np.concatenate([s.voxels for s in surfaces])
    direction = np.concatenate([s.directions for s in surfaces])
    neighbour = np.concatenate([s.neighbours + start[i] for i, s in enumerate(surfaces)])
    seg = plane_segments(voxel, direction, neighbour)
    surface_of_surfel = np.repeat(np.arange(len(surfaces), dtype=np.int64), sizes)
    first = seg.members[seg.member_ptr[:-1]]
    return Analytical3D(seg, surface_of_surfel[first])
