"""The convex polytope of a few half-spaces a·x ≤ β (a integer, β rational), exactly.

Used by the covers' R of a digitally convex set (:mod:`.convex_3d`): its faces are conv(A)'s facet planes,
each moved by its own rational amount, so the face structure may change (a facet can shrink to a point, as
the octahedron's six tip facets do) and a homothety cannot follow it. A box holding the polytope is cut by
each half-space in turn (Sutherland–Hodgman on every face, the cut's own face chained from the clipped
faces' sides on the plane), in Fractions: no tolerance anywhere. The cost is about faces × corners Fraction
operations per cut, which is why the caller keeps it for hulls of few facets.
"""

from __future__ import annotations

import logging
from fractions import Fraction
from typing import NamedTuple

logger = logging.getLogger(__name__)

Point = tuple[Fraction, Fraction, Fraction]
Normal = tuple[int, int, int]


class ConvexPolytope(NamedTuple):
    """A bounded convex polytope with volume: its corners and its faces.

    ``faces[f]`` lists the corners of the face on plane ``planes[f]`` (an index into the half-spaces given)
    counter-clockwise seen from outside; every corner lies on three faces or more.
    """

    corners: list[Point]
    planes: list[int]
    faces: list[list[int]]


def _dot(a: Normal, p: Point) -> Fraction:
    return a[0] * p[0] + a[1] * p[1] + a[2] * p[2]


def _newell(pts: list[Point]) -> Point:
    # The polygon's area vector (twice its area times its unit normal), exactly.
    nx = ny = nz = Fraction(0)
    for i, p in enumerate(pts):
        q = pts[(i + 1) % len(pts)]
        nx += (p[1] - q[1]) * (p[2] + q[2])
        ny += (p[2] - q[2]) * (p[0] + q[0])
        nz += (p[0] - q[0]) * (p[1] + q[1])
    return nx, ny, nz


def convex_polytope(
    normals: list[Normal], offsets: list[Fraction], lo: Point, hi: Point
) -> ConvexPolytope | None:
    """The polytope { x : normals[i] · x ≤ offsets[i] for all i }, exactly, or None when it has no volume.

    Parameters
    ----------
    normals : the half-spaces' integer normals, pairwise not parallel in the same direction.
    offsets : their right-hand sides.
    lo, hi : a box strictly holding the polytope (a box face left at the end means it did not: None).

    Face f lies on the plane of half-space ``planes[f]``.
    """
    corners: list[Point] = [
        (hi[0] if i & 1 else lo[0], hi[1] if i & 2 else lo[1], hi[2] if i & 4 else lo[2]) for i in range(8)
    ]
    box_normals: list[Normal] = [(-1, 0, 0), (1, 0, 0), (0, -1, 0), (0, 1, 0), (0, 0, -1), (0, 0, 1)]
    box_faces = [[0, 4, 6, 2], [1, 3, 7, 5], [0, 1, 5, 4], [2, 6, 7, 3], [0, 2, 3, 1], [4, 5, 7, 6]]
    planes = [-1 - k for k in range(6)]  # the box's faces: negative, apart from every half-space's index
    faces = [_outward(f, corners, a) for f, a in zip(box_faces, box_normals, strict=True)]
    box = ConvexPolytope(corners, planes, faces)
    cut = cut_polytope(box, normals, offsets, 0)
    if cut is None or any(p < 0 for p in cut.planes):
        return None  # no volume left, or the box was not cut away everywhere: it did not hold the polytope
    return cut


def cut_polytope(
    poly: ConvexPolytope, normals: list[Normal], offsets: list[Fraction], first: int
) -> ConvexPolytope | None:
    """``poly`` cut by the half-spaces normals[i] · x ≤ offsets[i] in turn, or None when no volume is left.

    The face a half-space makes gets the plane index ``first + i``.
    """
    corners, planes, faces = poly.corners, poly.planes, poly.faces
    for i, (a, beta) in enumerate(zip(normals, offsets, strict=True)):
        cut = _cut(corners, planes, faces, a, beta, first + i)
        if cut is None:
            return None
        corners, planes, faces = cut
    return _tidy(corners, planes, faces)


def _outward(face: list[int], corners: list[Point], a: Normal) -> list[int]:
    n = _newell([corners[v] for v in face])
    return face if _dot(a, n) > 0 else face[::-1]


def _cut(
    corners: list[Point], planes: list[int], faces: list[list[int]], a: Normal, beta: Fraction, plane: int
) -> tuple[list[Point], list[int], list[list[int]]] | None:
    # The polytope cut by a·x ≤ beta: each face clipped, the cut face chained from the clipped faces' sides
    # that lie on the plane (a face's side p→q there is the cut face's side q→p).
    s = [_dot(a, p) - beta for p in corners]
    if max(s) <= 0:
        return corners, planes, faces
    if min(s) >= 0:
        return None  # nothing (or only a point, a side or a face) is left
    corners = list(corners)
    on_edge: dict[tuple[int, int], int] = {}

    def crossing(u: int, w: int) -> int:
        key = (min(u, w), max(u, w))
        if key not in on_edge:
            t = s[u] / (s[u] - s[w])
            pu, pw = corners[u], corners[w]
            corners.append(
                (pu[0] + t * (pw[0] - pu[0]), pu[1] + t * (pw[1] - pu[1]), pu[2] + t * (pw[2] - pu[2]))
            )
            s.append(Fraction(0))
            on_edge[key] = len(corners) - 1
        return on_edge[key]

    new_planes: list[int] = []
    new_faces: list[list[int]] = []
    cap_next: dict[int, int] = {}
    for p, face in zip(planes, faces, strict=True):
        out: list[int] = []
        for k, u in enumerate(face):
            w = face[(k + 1) % len(face)]
            if s[u] <= 0:
                out.append(u)
            if (s[u] < 0 < s[w]) or (s[w] < 0 < s[u]):
                out.append(crossing(u, w))
        if len(out) < 3:
            continue  # the face is gone (or only a side or a corner of it is left, on the plane)
        for k, u in enumerate(out):
            w = out[(k + 1) % len(out)]
            if s[u] == 0 and s[w] == 0:
                cap_next[w] = u
        new_planes.append(p)
        new_faces.append(out)
    if len(cap_next) >= 3:
        start = min(cap_next)
        cap = [start]
        step = cap_next.get(start)
        while step != start:
            if step is None or len(cap) >= len(cap_next):  # cannot happen on a convex polytope: a bug
                logger.error("the cut face by plane %d does not close: the polytope is refused", plane)
                return None
            cap.append(step)
            step = cap_next.get(step)
        new_planes.append(plane)
        new_faces.append(cap)
    return corners, new_planes, new_faces


def _tidy(corners: list[Point], planes: list[int], faces: list[list[int]]) -> ConvexPolytope | None:
    # Keep the corners on three faces or more (a corner on two is a point on a side), numbered anew.
    count: dict[int, int] = {}
    for face in faces:
        for v in face:
            count[v] = count.get(v, 0) + 1
    keep = sorted(v for v, c in count.items() if c >= 3)
    index = {v: i for i, v in enumerate(keep)}
    out = [[index[v] for v in face if v in index] for face in faces]
    if len(keep) < 4 or any(len(f) < 3 for f in out):
        return None
    return ConvexPolytope([corners[v] for v in keep], planes, out)
