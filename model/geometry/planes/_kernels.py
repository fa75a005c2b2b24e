"""The compiled greedy segmentation of surfel surfaces into digital plane segments.

The same algorithm as :class:`~mrm.geometry.planes.recognition.SurfelPlane` driven by
:func:`~mrm.geometry.planes.segmentation.segment_surfels` (the readable reference, tested against it), on
int64 values with proven bounds instead of Python integers:

- points are taken relative to the segment's seed voxel and a segment never reaches further than
  :data:`MAX_EXTENT` from it, so a constraint vector q − p is below 2¹⁷ + 1 in each coordinate;
- a cone ray is the primitive cross product of two constraint vectors (or of the first surfel's direction
  and one), below 2³⁶; the witness is the sum of at most :data:`MAX_RAYS` rays, below 2⁴²;
- so every dot product taken (ray or witness with a point or a constraint) is below 3 · 2⁴² · 2¹⁷ < 2⁶¹.

A surfel that would break either bound (farther than :data:`MAX_EXTENT` from the seed, or a cone of more than
:data:`MAX_RAYS` rays) is refused like one that no plane separates: the segments stay exact planes, only
smaller. Neither bound is met by the voxel sets the tests and benchmarks use; the reference has none.

The new vertex where an edge (r, s) of the cone crosses the great circle v⊥ is the primitive cross product
of v with the edge's own constraint vector, signed so that it lies in the cone being cut (the one of ±x that
does: the cone is pointed, or it is the first lune, whose only opposite pair is its axis and is never such a
vertex). A cut leaves a full cone exactly when some vertex is strictly inside the new half-space, since the
cone was full before: no determinant is needed.
"""

from __future__ import annotations

import numpy as np
import numpy.typing as npt

from mrm.geometry._jit import leaf_njit, njit

Int64Array = npt.NDArray[np.int64]

#: How far (in each coordinate) a segment reaches from its seed voxel in the compiled segmentation.
MAX_EXTENT = 1 << 16
#: The most vertices a segment's preimage may have in the compiled segmentation.
MAX_RAYS = 64


@leaf_njit(cache=True)
def _gcd(a: int, b: int) -> int:  # pragma: no cover - compiled
    a, b = abs(a), abs(b)
    while b:
        a, b = b, a % b
    return a


@leaf_njit(cache=True)
def _set_primitive(out: Int64Array, k: int, x: int, y: int, z: int) -> None:  # pragma: no cover
    g = _gcd(_gcd(x, y), z)
    if g > 1:
        x, y, z = x // g, y // g, z // g
    out[k, 0], out[k, 1], out[k, 2] = x, y, z


@leaf_njit(cache=True)
def _clip(
    rays: Int64Array,
    cons: Int64Array,
    m: int,
    vx: int,
    vy: int,
    vz: int,
    out_r: Int64Array,
    out_c: Int64Array,
) -> int:  # pragma: no cover - compiled
    """Cut the cone (rays[:m], cons[i] the constraint of the edge rays[i] → rays[i+1]) by n · v ≥ 0.

    Writes the result to out_r/out_c and returns its vertex count: 0 when it is not full, −1 when it would
    have more than MAX_RAYS vertices, m itself (out untouched) when nothing is cut.
    """
    if vx == 0 and vy == 0 and vz == 0:
        return 0
    lo, hi = 0, 0
    for i in range(m):
        s = rays[i, 0] * vx + rays[i, 1] * vy + rays[i, 2] * vz
        if i == 0 or s < lo:
            lo = s
        if i == 0 or s > hi:
            hi = s
    if lo >= 0:
        return m
    if hi <= 0:
        return 0
    k = 0
    for i in range(m):
        j = i + 1 if i + 1 < m else 0
        si = rays[i, 0] * vx + rays[i, 1] * vy + rays[i, 2] * vz
        sj = rays[j, 0] * vx + rays[j, 1] * vy + rays[j, 2] * vz
        if si >= 0:
            if k >= MAX_RAYS:
                return -1
            out_r[k, 0], out_r[k, 1], out_r[k, 2] = rays[i, 0], rays[i, 1], rays[i, 2]
            # The edge leaving a kept vertex keeps its constraint (a vertex on v⊥ whose old edge is cut away
            # gets v instead, in the pass below).
            out_c[k, 0], out_c[k, 1], out_c[k, 2] = cons[i, 0], cons[i, 1], cons[i, 2]
            k += 1
        if (si > 0 and sj < 0) or (si < 0 and sj > 0):
            if k >= MAX_RAYS:
                return -1
            cx, cy, cz = cons[i, 0], cons[i, 1], cons[i, 2]
            _set_primitive(out_r, k, vy * cz - vz * cy, vz * cx - vx * cz, vx * cy - vy * cx)
            inside = True
            for t in range(m):
                if out_r[k, 0] * cons[t, 0] + out_r[k, 1] * cons[t, 1] + out_r[k, 2] * cons[t, 2] < 0:
                    inside = False
                    break
            if not inside:
                out_r[k, 0], out_r[k, 1], out_r[k, 2] = -out_r[k, 0], -out_r[k, 1], -out_r[k, 2]
            if si > 0:
                # Leaving the half-space: the new edge from here runs along v⊥ to where the cone re-enters.
                out_c[k, 0], out_c[k, 1], out_c[k, 2] = vx, vy, vz
            else:
                # Entering: the edge from here continues along the old edge to rays[j].
                out_c[k, 0], out_c[k, 1], out_c[k, 2] = cx, cy, cz
            k += 1
    # The vertex kept with sign 0 right before the cut part: its outgoing edge now runs along v⊥.
    for i in range(k):
        j = i + 1 if i + 1 < k else 0
        a = out_r[i, 0] * vx + out_r[i, 1] * vy + out_r[i, 2] * vz
        b = out_r[j, 0] * vx + out_r[j, 1] * vy + out_r[j, 2] * vz
        if a == 0 and b == 0:
            out_c[i, 0], out_c[i, 1], out_c[i, 2] = vx, vy, vz
    return _split_half_turns(out_r, out_c, k, vx, vy, vz, rays, cons, m)


@leaf_njit(cache=True)
def _split_half_turns(
    out_r: Int64Array,
    out_c: Int64Array,
    k: int,
    vx: int,
    vy: int,
    vz: int,
    old_r: Int64Array,
    old_c: Int64Array,
    old_m: int,
) -> int:  # pragma: no cover - compiled
    # An edge between two opposite vertices (the first lune's axis, cut through both ends) gets its midpoint
    # on v⊥, the one of ±(v × r) inside the old cone, as in Cone._split_half_turns.
    i = 0
    while i < k:
        j = i + 1 if i + 1 < k else 0
        if out_r[i, 0] == -out_r[j, 0] and out_r[i, 1] == -out_r[j, 1] and out_r[i, 2] == -out_r[j, 2]:
            if k >= MAX_RAYS:
                return -1
            for t in range(k, i + 1, -1):
                out_r[t, 0], out_r[t, 1], out_r[t, 2] = out_r[t - 1, 0], out_r[t - 1, 1], out_r[t - 1, 2]
                out_c[t, 0], out_c[t, 1], out_c[t, 2] = out_c[t - 1, 0], out_c[t - 1, 1], out_c[t - 1, 2]
            rx, ry, rz = out_r[i, 0], out_r[i, 1], out_r[i, 2]
            _set_primitive(out_r, i + 1, vy * rz - vz * ry, vz * rx - vx * rz, vx * ry - vy * rx)
            inside = True
            for t in range(old_m):
                if (
                    out_r[i + 1, 0] * old_c[t, 0]
                    + out_r[i + 1, 1] * old_c[t, 1]
                    + out_r[i + 1, 2] * old_c[t, 2]
                    < 0
                ):
                    inside = False
                    break
            if not inside:
                out_r[i + 1, 0], out_r[i + 1, 1], out_r[i + 1, 2] = (
                    -out_r[i + 1, 0],
                    -out_r[i + 1, 1],
                    -out_r[i + 1, 2],
                )
            out_c[i, 0], out_c[i, 1], out_c[i, 2] = vx, vy, vz
            out_c[i + 1, 0], out_c[i + 1, 1], out_c[i + 1, 2] = vx, vy, vz
            k += 1
            i += 1
        i += 1
    return k


@leaf_njit(cache=True)
def _clip_in_place(
    rays: Int64Array,
    cons: Int64Array,
    m: int,
    vx: int,
    vy: int,
    vz: int,
    tmp_r: Int64Array,
    tmp_c: Int64Array,
) -> int:  # pragma: no cover - compiled
    """:func:`_clip` by a v that cuts off a vertex, written back into rays/cons; the count (≤ 0: empty)."""
    k = _clip(rays, cons, m, vx, vy, vz, tmp_r, tmp_c)
    for i in range(max(k, 0)):
        rays[i, 0], rays[i, 1], rays[i, 2] = tmp_r[i, 0], tmp_r[i, 1], tmp_r[i, 2]
        cons[i, 0], cons[i, 1], cons[i, 2] = tmp_c[i, 0], tmp_c[i, 1], tmp_c[i, 2]
    return k


@leaf_njit(cache=True)
def _witness(rays: Int64Array, cons: Int64Array, m: int, w: Int64Array) -> None:  # pragma: no cover
    """A normal inside the open cone, near its middle: the sum of the unit rays, rounded and checked.

    The sum of the integer rays is inside too, but a long ray outweighs the others and puts it near one
    side, where the next point cuts it off; the sum of unit vectors keeps a witness for many more points
    (a rod along z: a few witnesses instead of one per surfel). Rounding may leave a thin cone, so the
    rounded vector is checked exactly against the cone's edges, with the integer sum as the fallback.
    """
    fx, fy, fz = 0.0, 0.0, 0.0
    for i in range(m):
        x, y, z = float(rays[i, 0]), float(rays[i, 1]), float(rays[i, 2])
        nrm = (x * x + y * y + z * z) ** 0.5
        fx += x / nrm
        fy += y / nrm
        fz += z / nrm
    big = max(abs(fx), abs(fy), abs(fz))
    inside = big > 0.0
    if inside:
        scale = float(1 << 20) / big
        w[0], w[1], w[2] = round(fx * scale), round(fy * scale), round(fz * scale)
        for i in range(m):
            if w[0] * cons[i, 0] + w[1] * cons[i, 1] + w[2] * cons[i, 2] <= 0:
                inside = False
                break
    if not inside:
        w[0], w[1], w[2] = 0, 0, 0
        for i in range(m):
            w[0] += rays[i, 0]
            w[1] += rays[i, 1]
            w[2] += rays[i, 2]
    g = _gcd(_gcd(w[0], w[1]), w[2])
    if g > 1:
        w[0], w[1], w[2] = w[0] // g, w[1] // g, w[2] // g


@leaf_njit(cache=True)
def _cut_by_points(
    rays: Int64Array,
    cons: Int64Array,
    m: int,
    pts_in: Int64Array,
    n_in: int,
    pts_out: Int64Array,
    n_out: int,
    tmp_r: Int64Array,
    tmp_c: Int64Array,
) -> int:  # pragma: no cover - compiled
    """Cut the cone (in place) until every inner point is below every outer point at each vertex.

    Returns the new vertex count, 0 when the cone empties (or −1 past MAX_RAYS).
    """
    while True:
        found = False
        vx, vy, vz = 0, 0, 0
        for r in range(m):
            rx, ry, rz = rays[r, 0], rays[r, 1], rays[r, 2]
            hi, ihi = 0, 0
            for i in range(n_in):
                d = rx * pts_in[i, 0] + ry * pts_in[i, 1] + rz * pts_in[i, 2]
                if i == 0 or d > hi:
                    hi, ihi = d, i
            lo, ilo = 0, 0
            for i in range(n_out):
                d = rx * pts_out[i, 0] + ry * pts_out[i, 1] + rz * pts_out[i, 2]
                if i == 0 or d < lo:
                    lo, ilo = d, i
            if hi > lo:
                vx = pts_out[ilo, 0] - pts_in[ihi, 0]
                vy = pts_out[ilo, 1] - pts_in[ihi, 1]
                vz = pts_out[ilo, 2] - pts_in[ihi, 2]
                found = True
                break
        if not found:
            return m
        m = _clip_in_place(rays, cons, m, vx, vy, vz, tmp_r, tmp_c)
        if m <= 0:
            return m


@leaf_njit(cache=True)
def _start_lune(
    ex: int, ey: int, ez: int, vx: int, vy: int, vz: int, rays: Int64Array, cons: Int64Array
) -> int:  # pragma: no cover - compiled
    """The lune { n·e ≥ 0, n·v ≥ 0 } as in Cone.half_space_pair: 4 vertices, or 0 when e ∥ v."""
    wx, wy, wz = ey * vz - ez * vy, ez * vx - ex * vz, ex * vy - ey * vx
    if wx == 0 and wy == 0 and wz == 0:
        return 0
    ee = ex * ex + ey * ey + ez * ez
    ev = ex * vx + ey * vy + ez * vz
    vv = vx * vx + vy * vy + vz * vz
    _set_primitive(rays, 0, wx, wy, wz)
    _set_primitive(rays, 1, ee * vx - ev * ex, ee * vy - ev * ey, ee * vz - ev * ez)
    rays[2, 0], rays[2, 1], rays[2, 2] = -rays[0, 0], -rays[0, 1], -rays[0, 2]
    _set_primitive(rays, 3, vv * ex - ev * vx, vv * ey - ev * vy, vv * ez - ev * vz)
    for i in range(2):
        cons[i, 0], cons[i, 1], cons[i, 2] = ex, ey, ez
    for i in range(2, 4):
        cons[i, 0], cons[i, 1], cons[i, 2] = vx, vy, vz
    return 4


@njit(cache=True)
def greedy_plane_segments(
    voxel: Int64Array, dirs: Int64Array, neighbour: Int64Array
) -> tuple[Int64Array, Int64Array, Int64Array, Int64Array, Int64Array]:  # pragma: no cover - compiled
    """The greedy segmentation of surfels (voxel (n, 3), outward normal dirs (n, 3), 4 edge neighbours).

    Returns
    -------
    segment_of : (n,) the segment of each surfel.
    members, member_ptr : the surfels of segment k are members[member_ptr[k]:member_ptr[k + 1]], in the
        order they were taken.
    rays, ray_ptr : the preimage of segment k is rays[ray_ptr[k]:ray_ptr[k + 1]] (empty for a one-surfel
        segment, whose preimage is the open half-space n · e > 0).
    """
    n = voxel.shape[0]
    segment_of = np.full(n, -1, np.int64)
    queued = np.full(n, -1, np.int64)
    members = np.empty(n, np.int64)
    member_ptr = np.zeros(n + 1, np.int64)
    queue = np.empty(n, np.int64)
    pin = np.empty((n, 3), np.int64)
    pout = np.empty((n, 3), np.int64)
    rays = np.empty((MAX_RAYS + 2, 3), np.int64)
    cons = np.empty((MAX_RAYS + 2, 3), np.int64)
    tmp_r = np.empty((MAX_RAYS + 2, 3), np.int64)
    tmp_c = np.empty((MAX_RAYS + 2, 3), np.int64)
    save_r = np.empty((MAX_RAYS + 2, 3), np.int64)
    save_c = np.empty((MAX_RAYS + 2, 3), np.int64)
    w = np.zeros(3, np.int64)
    all_rays = np.empty((max(16, n), 3), np.int64)
    ray_ptr = np.zeros(n + 1, np.int64)
    n_seg = 0
    n_members = 0
    n_rays = 0
    for seed in range(n):
        if segment_of[seed] >= 0:
            continue
        sx, sy, sz = voxel[seed, 0], voxel[seed, 1], voxel[seed, 2]
        ex, ey, ez = dirs[seed, 0], dirs[seed, 1], dirs[seed, 2]
        head, tail = 0, 0
        queue[tail] = seed
        tail += 1
        queued[seed] = n_seg
        n_in, n_out, m = 0, 0, 0
        w_hi, w_lo = 0, 0
        taken = 0
        while head < tail:
            i = queue[head]
            head += 1
            px, py, pz = voxel[i, 0] - sx, voxel[i, 1] - sy, voxel[i, 2] - sz
            if abs(px) > MAX_EXTENT or abs(py) > MAX_EXTENT or abs(pz) > MAX_EXTENT:
                continue
            qx, qy, qz = px + dirs[i, 0], py + dirs[i, 1], pz + dirs[i, 2]
            ok = False
            if taken == 0:
                ok = True
            elif m == 0:
                # The second surfel: the lune of e and the first pair independent of it, cut by all four.
                pin[1, 0], pin[1, 1], pin[1, 2] = px, py, pz
                pout[1, 0], pout[1, 1], pout[1, 2] = qx, qy, qz
                k = 0
                for a in range(2):
                    for b in range(2):
                        vx = pout[b, 0] - pin[a, 0]
                        vy = pout[b, 1] - pin[a, 1]
                        vz = pout[b, 2] - pin[a, 2]
                        if k == 0 and (
                            ey * vz - ez * vy != 0 or ez * vx - ex * vz != 0 or ex * vy - ey * vx != 0
                        ):
                            k = _start_lune(ex, ey, ez, vx, vy, vz, rays, cons)
                if k > 0:
                    k = _cut_by_points(rays, cons, k, pin, 2, pout, 2, tmp_r, tmp_c)
                if k > 0:
                    m = k
                    ok = True
                    _witness(rays, cons, m, w)
                    w_hi = max(
                        w[0] * pin[0, 0] + w[1] * pin[0, 1] + w[2] * pin[0, 2],
                        w[0] * px + w[1] * py + w[2] * pz,
                    )
                    w_lo = min(
                        w[0] * pout[0, 0] + w[1] * pout[0, 1] + w[2] * pout[0, 2],
                        w[0] * qx + w[1] * qy + w[2] * qz,
                    )
            else:
                # A surfel facing away from every normal of the cone (n · e ≤ 0 at every vertex, so on the
                # whole cone) cannot be separated from its own outer voxel: refused at once, without the
                # pass over the points a cut takes (the sides of a rod beyond its segment's two).
                facing = False
                for t in range(m):
                    if rays[t, 0] * dirs[i, 0] + rays[t, 1] * dirs[i, 1] + rays[t, 2] * dirs[i, 2] > 0:
                        facing = True
                        break
                if not facing:
                    continue
                wp = w[0] * px + w[1] * py + w[2] * pz
                wq = w[0] * qx + w[1] * qy + w[2] * qz
                if max(w_hi, wp) < min(w_lo, wq):
                    w_hi, w_lo = max(w_hi, wp), min(w_lo, wq)
                    ok = True
                else:
                    pin[n_in, 0], pin[n_in, 1], pin[n_in, 2] = px, py, pz
                    pout[n_out, 0], pout[n_out, 1], pout[n_out, 2] = qx, qy, qz
                    # The cut works in place: a refused surfel must leave the cone as it was.
                    save_r[:m] = rays[:m]
                    save_c[:m] = cons[:m]
                    save_m = m
                    k = _cut_by_points(rays, cons, m, pin, n_in + 1, pout, n_out + 1, tmp_r, tmp_c)
                    if k > 0:
                        m = k
                        ok = True
                        _witness(rays, cons, m, w)
                        w_hi = w[0] * pin[0, 0] + w[1] * pin[0, 1] + w[2] * pin[0, 2]
                        for t in range(1, n_in + 1):
                            w_hi = max(w_hi, w[0] * pin[t, 0] + w[1] * pin[t, 1] + w[2] * pin[t, 2])
                        w_lo = w[0] * pout[0, 0] + w[1] * pout[0, 1] + w[2] * pout[0, 2]
                        for t in range(1, n_out + 1):
                            w_lo = min(w_lo, w[0] * pout[t, 0] + w[1] * pout[t, 1] + w[2] * pout[t, 2])
                    else:
                        m = save_m
                        rays[:m] = save_r[:m]
                        cons[:m] = save_c[:m]
            if not ok:
                continue
            pin[n_in, 0], pin[n_in, 1], pin[n_in, 2] = px, py, pz
            pout[n_out, 0], pout[n_out, 1], pout[n_out, 2] = qx, qy, qz
            n_in += 1
            n_out += 1
            taken += 1
            segment_of[i] = n_seg
            members[n_members] = i
            n_members += 1
            for t in range(4):
                j = neighbour[i, t]
                if queued[j] != n_seg and segment_of[j] < 0:
                    queued[j] = n_seg
                    queue[tail] = j
                    tail += 1
        if m > 0:
            # The preimage: the cone cut by every point taken on the witness's word.
            m = _cut_by_points(rays, cons, m, pin, n_in, pout, n_out, tmp_r, tmp_c)
            if n_rays + m > all_rays.shape[0]:
                grown = np.empty((2 * (n_rays + m), 3), np.int64)
                grown[:n_rays] = all_rays[:n_rays]
                all_rays = grown
            all_rays[n_rays : n_rays + m] = rays[:m]
            n_rays += m
        n_seg += 1
        member_ptr[n_seg] = n_members
        ray_ptr[n_seg] = n_rays
    return (
        segment_of,
        members,
        member_ptr[: n_seg + 1].copy(),
        all_rays[:n_rays].copy(),
        ray_ptr[: n_seg + 1].copy(),
    )


@leaf_njit(cache=True)
def _cut_point_plane(
    rays: Int64Array,
    cons: Int64Array,
    m: int,
    pts: Int64Array,
    n: int,
    sx: int,
    sy: int,
    sz: int,
    tmp_r: Int64Array,
    tmp_c: Int64Array,
) -> int:  # pragma: no cover - compiled
    """Cut an octant's cone (in place) until the points' width along each vertex r is at most r · s."""
    while True:
        found = False
        vx, vy, vz = 0, 0, 0
        for r in range(m):
            rx, ry, rz = rays[r, 0], rays[r, 1], rays[r, 2]
            hi, ihi, lo, ilo = 0, 0, 0, 0
            for i in range(n):
                d = rx * pts[i, 0] + ry * pts[i, 1] + rz * pts[i, 2]
                if i == 0 or d > hi:
                    hi, ihi = d, i
                if i == 0 or d < lo:
                    lo, ilo = d, i
            if hi - lo > rx * sx + ry * sy + rz * sz:
                vx = sx - (pts[ihi, 0] - pts[ilo, 0])
                vy = sy - (pts[ihi, 1] - pts[ilo, 1])
                vz = sz - (pts[ihi, 2] - pts[ilo, 2])
                found = True
                break
        if not found:
            return m
        m = _clip_in_place(rays, cons, m, vx, vy, vz, tmp_r, tmp_c)
        if m <= 0:
            return m


@njit(cache=True)
def point_plane_prefix(points: Int64Array) -> tuple[int, Int64Array, Int64Array]:  # pragma: no cover
    """How many of ``points``, taken in order, lie in one standard arithmetic plane (as PointPlane.add).

    The compiled :class:`~mrm.geometry.planes.recognition.PointPlane`: one cone per octant of normals, each
    with its witness; stops at the first point that no octant admits, or that lies farther than
    :data:`MAX_EXTENT` from the first point, or that would give a cone of more than :data:`MAX_RAYS`
    vertices. Duplicates are taken without a constraint.

    Returns
    -------
    taken : int
    rays : (8, MAX_RAYS + 2, 3) the cones of the octants, cut by every point taken (an octant with no
        admissible normal has count 0).
    counts : (8,) their vertex counts.
    """
    n = points.shape[0]
    pts = np.empty((n + 1, 3), np.int64)
    bias = np.int64(1 << 20)  # coordinates within ±(2¹⁶ + 1) packed into 21 bits each
    seen = dict()
    seen[(bias << 42) | (bias << 21) | bias] = 1  # the first point, at (0, 0, 0)
    rays = np.zeros((8, MAX_RAYS + 2, 3), np.int64)
    cons = np.zeros((8, MAX_RAYS + 2, 3), np.int64)
    m = np.zeros(8, np.int64)
    sign = np.empty((8, 3), np.int64)
    w = np.zeros((8, 3), np.int64)
    w_hi = np.zeros(8, np.int64)
    w_lo = np.zeros(8, np.int64)
    has_w = np.zeros(8, np.bool_)
    stale = np.zeros(8, np.bool_)
    tmp_r = np.empty((MAX_RAYS + 2, 3), np.int64)
    tmp_c = np.empty((MAX_RAYS + 2, 3), np.int64)
    save_r = np.empty((MAX_RAYS + 2, 3), np.int64)
    save_c = np.empty((MAX_RAYS + 2, 3), np.int64)
    dead = np.zeros(8, np.bool_)
    for o in range(8):
        sx = 1 if o & 4 == 0 else -1
        sy = 1 if o & 2 == 0 else -1
        sz = 1 if o & 1 == 0 else -1
        sign[o, 0], sign[o, 1], sign[o, 2] = sx, sy, sz
        # The closed octant: a spherical triangle whose edges lie on the coordinate planes.
        rays[o, 0, 0], rays[o, 1, 1], rays[o, 2, 2] = sx, sy, sz
        cons[o, 0, 2], cons[o, 1, 0], cons[o, 2, 1] = sz, sx, sy
        m[o] = 3
    if n == 0:
        return 0, rays, m
    x0, y0, z0 = points[0, 0], points[0, 1], points[0, 2]
    pts[0, 0], pts[0, 1], pts[0, 2] = 0, 0, 0
    taken = 1  # points taken, duplicates included
    npts = 1  # distinct points, in pts[:npts]
    for t in range(1, n):
        px, py, pz = points[t, 0] - x0, points[t, 1] - y0, points[t, 2] - z0
        if abs(px) > MAX_EXTENT or abs(py) > MAX_EXTENT or abs(pz) > MAX_EXTENT:
            break
        key = ((px + bias) << 42) | ((py + bias) << 21) | (pz + bias)
        if key in seen:
            taken += 1
            continue
        tentative = np.zeros(8, np.bool_)
        ok = -1
        for o in range(8):
            if dead[o]:
                continue
            sx, sy, sz = sign[o, 0], sign[o, 1], sign[o, 2]
            if has_w[o]:
                x = w[o, 0] * px + w[o, 1] * py + w[o, 2] * pz
                hi, lo = max(w_hi[o], x), min(w_lo[o], x)
                if hi - lo < w[o, 0] * sx + w[o, 1] * sy + w[o, 2] * sz:
                    # Taken on the witness's word: the cone is not cut by p until it is next needed.
                    w_hi[o], w_lo[o], stale[o] = hi, lo, True
                    ok = o
                    break
            if stale[o]:
                k = _cut_point_plane(rays[o], cons[o], m[o], pts, npts, sx, sy, sz, tmp_r, tmp_c)
                if k <= 0:
                    dead[o] = True  # empty without p: for good
                    continue
                m[o], stale[o] = k, False
            # Two points apart by s give the constraint 0 > 0, which no vertex check sees.
            ka = ((px - sx + bias) << 42) | ((py - sy + bias) << 21) | (pz - sz + bias)
            kb = ((px + sx + bias) << 42) | ((py + sy + bias) << 21) | (pz + sz + bias)
            if ka in seen or kb in seen:
                tentative[o] = True
                continue
            mo = m[o]
            save_r[:mo] = rays[o, :mo]
            save_c[:mo] = cons[o, :mo]
            pts[npts, 0], pts[npts, 1], pts[npts, 2] = px, py, pz
            k = _cut_point_plane(rays[o], cons[o], mo, pts, npts + 1, sx, sy, sz, tmp_r, tmp_c)
            if k <= 0:
                rays[o, :mo] = save_r[:mo]
                cons[o, :mo] = save_c[:mo]
                tentative[o] = True
                continue
            m[o] = k
            _witness(rays[o], cons[o], k, w[o])
            hi, lo = 0, 0
            for i in range(npts + 1):
                d = w[o, 0] * pts[i, 0] + w[o, 1] * pts[i, 1] + w[o, 2] * pts[i, 2]
                if i == 0 or d > hi:
                    hi = d
                if i == 0 or d < lo:
                    lo = d
            w_hi[o], w_lo[o], has_w[o] = hi, lo, True
            ok = o
            break
        if ok < 0:
            break
        for o in range(8):
            if tentative[o]:
                dead[o] = True
        for o in range(ok + 1, 8):
            if dead[o]:
                continue
            has_w[o], stale[o] = False, True
            sx, sy, sz = sign[o, 0], sign[o, 1], sign[o, 2]
            ka = ((px - sx + bias) << 42) | ((py - sy + bias) << 21) | (pz - sz + bias)
            kb = ((px + sx + bias) << 42) | ((py + sy + bias) << 21) | (pz + sz + bias)
            if ka in seen or kb in seen:
                dead[o] = True
        pts[npts, 0], pts[npts, 1], pts[npts, 2] = px, py, pz
        npts += 1
        seen[key] = 1
        taken += 1
    # Every live octant cut by all the points taken: the exact cones.
    for o in range(8):
        if dead[o]:
            m[o] = 0
        elif stale[o]:
            k = _cut_point_plane(
                rays[o], cons[o], m[o], pts, npts, sign[o, 0], sign[o, 1], sign[o, 2], tmp_r, tmp_c
            )
            m[o] = max(k, 0)
    return taken, rays, m
