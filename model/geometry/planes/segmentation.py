"""Segmentation of the closed surfel surfaces of a voxel set into digital plane segments.

Reference: docs/design.md §11 (analytical representation).

**Greedy** (the default): take the first surfel not yet in a segment (raster order of its voxel, then its
direction), and grow a patch from it breadth first across surfel edges, adding each neighbour that leaves the
patch a digital plane segment (:class:`~.recognition.SurfelPlane`); a neighbour refused once is refused for
good (the preimage only shrinks), so each surfel is tried at most four times per patch. Every surfel ends in
exactly one segment, and every segment is an edge-connected patch of one surface.

Finding the fewest segments is NP-hard (Sivignon & Coeurjolly 2006); the greedy is the usual answer and is
what DGtal's segmentations do too.
"""

from __future__ import annotations

from collections import deque
from dataclasses import dataclass
from fractions import Fraction

import numpy as np
import numpy.typing as npt

from mrm.geometry.planes.cone import Cone, Vec
from mrm.geometry.planes.recognition import DigitalPlane, SurfelPlane
from mrm.geometry.topology.surfels import DIRS, Surfels

Int64Array = npt.NDArray[np.int64]


@dataclass(frozen=True)
class PlaneSegment:
    """One digital plane segment of a surface.

    Attributes
    ----------
    plane : DigitalPlane
        Its standard arithmetic plane (normal pointing out of the object), in the coordinates the surfels
        were given in (array indices plus the origin passed to :func:`segment_surfels`).
    surfels : int64 array
        The indices of its surfels in the :class:`~mrm.geometry.topology.surfels.Surfels`.
    surface : int
        The surface it lies on.
    preimage : Cone
        The closed cone of normals that separate its voxels of A from the voxels outside.
    offset : Fraction
        The chosen Euclidean plane is plane.normal · x = offset, midway between the two sets of centres.
    """

    plane: DigitalPlane
    surfels: Int64Array
    surface: int
    preimage: Cone
    offset: Fraction


@dataclass(frozen=True)
class PlaneSegmentation:
    """The digital plane segments of every surface, and the segment of each surfel."""

    segments: tuple[PlaneSegment, ...]
    segment_of: Int64Array

    def __len__(self) -> int:
        return len(self.segments)


def segment_surfels(surfels: Surfels, origin: tuple[int, int, int] = (0, 0, 0)) -> PlaneSegmentation:
    """The greedy segmentation of every surface of ``surfels`` into digital plane segments.

    Parameters
    ----------
    surfels : Surfels
        From :func:`~mrm.geometry.topology.surfels.surfels_of`.
    origin : (int, int, int)
        Added to the surfels' array indices, so that the planes are in world coordinates.

    Returns
    -------
    PlaneSegmentation
    """
    n = len(surfels.direction)
    segment_of = np.full(n, -1, np.int64)
    voxel = surfels.voxel
    dirs = DIRS[surfels.direction.astype(np.int64)] if n else np.zeros((0, 3), np.int64)
    ox, oy, oz = (int(c) for c in origin)
    segments: list[PlaneSegment] = []
    # Surfels arrive in raster order of their voxel; the seeds follow it.
    for seed in range(n):
        if segment_of[seed] >= 0:
            continue
        k = len(segments)
        rec = SurfelPlane()
        members: list[int] = []
        queue = deque([seed])
        queued = {seed}
        while queue:
            i = queue.popleft()
            p: Vec = (int(voxel[i, 0]) + ox, int(voxel[i, 1]) + oy, int(voxel[i, 2]) + oz)
            e: Vec = (int(dirs[i, 0]), int(dirs[i, 1]), int(dirs[i, 2]))
            if not rec.add(p, e):
                continue
            segment_of[i] = k
            members.append(i)
            for j in surfels.neighbour[i]:
                jj = int(j)
                if jj not in queued and segment_of[jj] < 0:
                    queued.add(jj)
                    queue.append(jj)
        normal, offset = rec.euclidean_plane()
        segments.append(
            PlaneSegment(
                plane=rec.plane(normal),
                surfels=np.asarray(members, np.int64),
                surface=int(surfels.surface[seed]),
                preimage=rec.preimage(),
                offset=offset,
            )
        )
    return PlaneSegmentation(tuple(segments), segment_of)
