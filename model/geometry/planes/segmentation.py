"""Segmentation of the closed surfel surfaces of a voxel set into digital plane segments.

Reference: docs/design.md §11 (analytical representation).

**Greedy**: take the first surfel not yet in a segment (in the order given: raster order of its voxel, then
its direction, for :func:`~mrm.geometry.topology.surfels.surfels_of`), and grow a patch from it breadth first
across surfel edges, adding each neighbour that leaves the patch a digital plane segment
(:class:`~.recognition.SurfelPlane`); a neighbour refused once is not tried again for that patch (the preimage
only shrinks, so it would be refused again). Every surfel ends in exactly one segment, and every segment is an
edge-connected patch of one surface.

:func:`plane_segments` runs the compiled kernel (:mod:`._kernels`, int64 with proven bounds);
:func:`plane_segments_reference` the same algorithm on :class:`~.recognition.SurfelPlane` with Python
integers, the readable version the tests hold the kernel to. Finding the fewest segments is NP-hard
(Sivignon & Coeurjolly 2006); the greedy is the usual answer, and DGtal's segmentations are greedy too.
"""

from __future__ import annotations

from collections import deque
from dataclasses import dataclass, field
from fractions import Fraction

import numpy as np
import numpy.typing as npt

from mrm.geometry.planes._kernels import greedy_plane_segments
from mrm.geometry.planes.cone import Cone, Vec, dot, primitive
from mrm.geometry.planes.recognition import DigitalPlane, SurfelPlane, smallest_normal
from mrm.geometry.topology.surfels import DIRS

Int64Array = npt.NDArray[np.int64]
UInt8Array = npt.NDArray[np.uint8]


@dataclass(frozen=True)
class PlaneSegment:
    """One digital plane segment of a surface.

    Attributes
    ----------
    plane : DigitalPlane
        Its standard arithmetic plane, normal pointing out of the object: every voxel of A of the segment
        is in it, and every voxel outside is beyond it (remainder ≥ μ + ω).
    surfels : int64 array
        The indices of its surfels, in the order the segmentation took them.
    preimage : Cone
        The closed cone of normals that separate its voxels of A from the voxels outside (for a single
        surfel, the normals within 45° of its own, where the chosen one is searched).
    offset : Fraction
        The chosen Euclidean plane is plane.normal · x = offset, midway between the two sets of centres.
    """

    plane: DigitalPlane
    surfels: Int64Array
    preimage: Cone
    offset: Fraction


@dataclass(frozen=True)
class PlaneSegmentation:
    """The digital plane segments of a set of surfels; each segment's plane is chosen when first asked.

    Attributes
    ----------
    voxel : int64 (n, 3)
        The (x, y, z) voxel of A of each surfel.
    direction : uint8 (n,)
        The index in :data:`~mrm.geometry.topology.surfels.DIRS` of each surfel's outward normal.
    segment_of : int64 (n,)
        The segment of each surfel.
    members, member_ptr : int64
        The surfels of segment k are ``members[member_ptr[k]:member_ptr[k + 1]]``.
    rays, ray_ptr : int64
        The preimage of segment k has the extreme rays ``rays[ray_ptr[k]:ray_ptr[k + 1]]`` in cyclic order
        (none for a one-surfel segment).
    """

    voxel: Int64Array
    direction: UInt8Array
    segment_of: Int64Array
    members: Int64Array
    member_ptr: Int64Array
    rays: Int64Array
    ray_ptr: Int64Array
    _cache: dict[int, PlaneSegment] = field(default_factory=dict, repr=False, compare=False)

    def __len__(self) -> int:
        return int(self.member_ptr.size - 1)

    def surfels_of(self, k: int) -> Int64Array:
        """The surfels of segment k."""
        return self.members[self.member_ptr[k] : self.member_ptr[k + 1]]

    def preimage(self, k: int) -> Cone:
        """The preimage cone of segment k (see :class:`PlaneSegment`)."""
        a, b = int(self.ray_ptr[k]), int(self.ray_ptr[k + 1])
        if b > a:
            return Cone(tuple((int(x), int(y), int(z)) for x, y, z in self.rays[a:b]))
        e = DIRS[int(self.direction[self.surfels_of(k)[0]])]
        return Cone.pyramid(e)

    def segment(self, k: int) -> PlaneSegment:
        """Segment k with its chosen plane (the smallest separating normal, the plane midway)."""
        if k in self._cache:
            return self._cache[k]
        members = self.surfels_of(k)
        inner = self.voxel[members]
        outer = inner + DIRS[self.direction[members].astype(np.int64)]
        base = inner[0].copy()
        inner_rel, outer_rel = inner - base, outer - base  # small: a segment is a connected patch

        def extremes(n: Vec) -> tuple[int, int]:
            if max(abs(c) for c in n) < (1 << 40):
                nv = np.array(n, np.int64)
                return int((inner_rel @ nv).max()), int((outer_rel @ nv).min())
            ins = [dot(n, (int(x), int(y), int(z))) for x, y, z in inner_rel]
            outs = [dot(n, (int(x), int(y), int(z))) for x, y, z in outer_rel]
            return max(ins), min(outs)

        def accepts(n: Vec) -> bool:
            t, u = extremes(n)
            return t < u

        cone = self.preimage(k)
        n = smallest_normal(cone, accepts, open_cone=True)
        t, u = extremes(n)
        shift = dot(n, (int(base[0]), int(base[1]), int(base[2])))
        omega = abs(n[0]) + abs(n[1]) + abs(n[2])
        seg = PlaneSegment(
            plane=DigitalPlane(n[0], n[1], n[2], t + shift - omega + 1),
            surfels=members,
            preimage=cone,
            offset=Fraction(t + u, 2) + shift,
        )
        self._cache[k] = seg
        return seg

    @property
    def segments(self) -> tuple[PlaneSegment, ...]:
        """Every segment with its chosen plane (computed now for those not asked yet)."""
        return tuple(self.segment(k) for k in range(len(self)))


def _inputs(
    voxel: npt.ArrayLike, direction: npt.ArrayLike, neighbour: npt.ArrayLike
) -> tuple[Int64Array, UInt8Array, Int64Array]:
    vox = np.ascontiguousarray(voxel, np.int64).reshape(-1, 3)
    dirs = np.ascontiguousarray(direction, np.uint8).reshape(-1)
    nb = np.ascontiguousarray(neighbour, np.int64).reshape(-1, 4)
    if not (len(vox) == len(dirs) == len(nb)):
        raise ValueError("voxel, direction and neighbour must have one row per surfel")
    return vox, dirs, nb


def plane_segments(
    voxel: npt.ArrayLike, direction: npt.ArrayLike, neighbour: npt.ArrayLike
) -> PlaneSegmentation:
    """The greedy segmentation of surfels into digital plane segments (compiled).

    Parameters
    ----------
    voxel : int array (n, 3)
        The (x, y, z) voxel of A of each surfel.
    direction : int array (n,)
        The index in :data:`~mrm.geometry.topology.surfels.DIRS` of each surfel's outward normal.
    neighbour : int array (n, 4)
        The surfels across each surfel's four edges (as :func:`~mrm.geometry.topology.surfels.surfels_of`
        links them); the segments grow across these.

    Returns
    -------
    PlaneSegmentation
    """
    vox, dirs, nb = _inputs(voxel, direction, neighbour)
    segment_of, members, member_ptr, rays, ray_ptr = greedy_plane_segments(
        vox, DIRS[dirs.astype(np.int64)], nb
    )
    return PlaneSegmentation(vox, dirs, segment_of, members, member_ptr, rays, ray_ptr)


def plane_segments_reference(
    voxel: npt.ArrayLike, direction: npt.ArrayLike, neighbour: npt.ArrayLike
) -> PlaneSegmentation:
    """:func:`plane_segments` on :class:`~.recognition.SurfelPlane` and Python integers (slow, readable)."""
    vox, dirs, nb = _inputs(voxel, direction, neighbour)
    n = len(dirs)
    segment_of = np.full(n, -1, np.int64)
    members: list[int] = []
    member_ptr = [0]
    rays: list[Vec] = []
    ray_ptr = [0]
    for seed in range(n):
        if segment_of[seed] >= 0:
            continue
        k = len(member_ptr) - 1
        rec = SurfelPlane()
        queue = deque([seed])
        queued = {seed}
        while queue:
            i = queue.popleft()
            p: Vec = (int(vox[i, 0]), int(vox[i, 1]), int(vox[i, 2]))
            e = DIRS[dirs[i]]
            if not rec.add(p, (int(e[0]), int(e[1]), int(e[2]))):
                continue
            segment_of[i] = k
            members.append(i)
            for j in nb[i]:
                jj = int(j)
                if jj not in queued and segment_of[jj] < 0:
                    queued.add(jj)
                    queue.append(jj)
        member_ptr.append(len(members))
        cone = rec.cone
        if cone is not None:
            rays.extend(primitive(r) for r in cone.rays)
        ray_ptr.append(len(rays))
    return PlaneSegmentation(
        vox,
        dirs,
        segment_of,
        np.asarray(members, np.int64),
        np.asarray(member_ptr, np.int64),
        np.asarray(rays, np.int64).reshape(-1, 3),
        np.asarray(ray_ptr, np.int64),
    )
