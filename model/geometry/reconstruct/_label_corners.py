"""The table of pointel repairs of the 3D label-volume polygonization (:mod:`.polygonize_3d`), and its search.

The polygonization cuts every voxel into 4 × 4 × 4 *quarter cells* (side ¼). A quarter cell whose closure
reaches no side of its voxel is a *core* cell (the eight around the centre); one touching one side is a
*face* cell, two sides an *edge* cell (it lies along a linel), three sides a *corner* cell (at a pointel).
By default every quarter cell belongs to its voxel's region; then each region's solid is its voxels, and
its boundary is the staircase, which is not a 2-manifold where a region meets itself only along a linel or
at a pointel. Two rules move a few edge and corner cells to a neighbouring voxel's region so that every
region's boundary is a 2-manifold (with the (6, 26) topology: a region's voxels that meet only along an
edge or at a corner are kept apart):

* **linel rule** (:func:`linel_sources`): around a linel, if two diagonal voxels carry the same non-zero
  region and the other two carry others, those two voxels' edge cells along the linel go to the voxel across
  the axis c = (b + 1) mod 3 (b the linel's axis); the diagonal (0, 0)–(1, 1) is tried before (1, 0)–(0, 1),
  so of a checkerboard of two regions the first pair is cut and the second joined;
* **pointel rule** (this table): the eight corner cells around a pointel take the regions of the voxels
  given by the pointel's entry, found by :func:`search_entry` — the fewest changed corner cells (each taking
  the region of another voxel of the 2 × 2 × 2 block), in a fixed order, such that around every lattice
  point of the quarter grid within ¼ of the pointel each non-zero region and its complement are both
  face-connected (the condition for the boundary to be a 2-manifold there), an entry that keeps the
  topology first. Region 0 (the background) is not meshed and may stay pinched.

A pointel's *pattern* is the partition of its eight voxels by region (positions p + (dx, dy, dz) numbered
dx + 2·dy + 4·dz, blocks numbered by first position: a restricted growth string) and which block, if any, is
the background. The table lists the patterns whose entry is not the identity: 15,298 of the 21,147
(Bell(9)). Of the 21,147 entries 18,989 also keep the (6, 26) topology of their eight voxels
(:func:`keeps_topology`); the other 2,158 have no such entry of up to four changes (for instance two regions
both pinched, one of which must be joined) and take the first 2-manifold one. ``tests/model/
test_polygonize_3d.py`` checks the whole table against the condition above, and samples against the search.
Regenerate with ``python -m mrm.geometry.reconstruct._label_corners`` (about six minutes).
"""

from __future__ import annotations

import base64
import itertools
import zlib
from functools import cache

import numpy as np
import numpy.typing as npt

from mrm.geometry._jit import njit

Int64Array = npt.NDArray[np.int64]
UInt8Array = npt.NDArray[np.uint8]

#: Quarter cells of a pointel's neighbourhood: offsets (i, j, k) in −2 … 1 per axis, cell [i/4, (i+1)/4] from
#: the pointel; index (k + 2)·16 + (j + 2)·4 + (i + 2).
_CELLS = np.array([(i, j, k) for k in range(-2, 2) for j in range(-2, 2) for i in range(-2, 2)], np.int64)


def _position(d: tuple[int, ...] | list[int]) -> int:
    return int(d[0]) + 2 * int(d[1]) + 4 * int(d[2])


@njit(cache=True)
def linel_source(g0: int, g1: int, g2: int, g3: int, background: int, q: int) -> int:  # pragma: no cover
    """The linel rule: the quadrant whose region quadrant ``q``'s edge cells take.

    ``g0 … g3`` are the regions of the voxels at (e_c, e_d) = (0, 0), (1, 0), (0, 1), (1, 1) across a linel
    along axis b (c = (b + 1) mod 3, d = (b + 2) mod 3); quadrant q = e_c + 2·e_d; ``background`` is never
    cut apart. Compiled: the polygonization's kernels call it, the table's search too.
    """
    if g0 != background and g0 == g3 and g0 != g1 and g0 != g2:
        return 1 if q == 0 else (2 if q == 3 else q)  # across c: (0, 0) -> (1, 0), (1, 1) -> (0, 1)
    if g1 != background and g1 == g2 and g1 != g0 and g1 != g3:
        return 0 if q == 1 else (3 if q == 2 else q)  # across c: (1, 0) -> (0, 0), (0, 1) -> (1, 1)
    return q


def linel_sources(g: tuple[int, int, int, int], background: int) -> tuple[int, int, int, int]:
    """:func:`linel_source` of the four quadrants."""
    return tuple(linel_source(g[0], g[1], g[2], g[3], background, q) for q in range(4))  # type: ignore[return-value]


def _default_cells(g: tuple[int, ...], background: int) -> list[int]:
    """The region of each of the 64 quarter cells around a pointel under the linel rule, corners unchanged."""
    out = []
    for c in _CELLS.tolist():
        d = [0 if x < 0 else 1 for x in c]
        outer = [x in (-1, 0) for x in c]
        if sum(outer) == 2:
            b = outer.index(False)
            ca, da = (b + 1) % 3, (b + 2) % 3

            def vox(ec: int, ed: int, d: list[int] = d, ca: int = ca, da: int = da) -> int:
                e = list(d)
                e[ca], e[da] = ec, ed
                return g[_position(e)]

            quads = (vox(0, 0), vox(1, 0), vox(0, 1), vox(1, 1))
            src = linel_sources(quads, background)[d[ca] + 2 * d[da]]
            out.append(quads[src])
        else:
            out.append(g[_position(d)])
    return out


def _blocks() -> Int64Array:
    # The 27 lattice points within ¼ of the pointel (offsets −1, 0, 1 quarters), each with its 8 cells in the
    # bit order dx + 2·dy + 4·dz.
    rows = []
    for w in itertools.product((-1, 0, 1), repeat=3):
        cells = []
        for dz, dy, dx in itertools.product((0, 1), repeat=3):
            i, j, k = w[2] - 1 + dx, w[1] - 1 + dy, w[0] - 1 + dz
            cells.append((k + 2) * 16 + (j + 2) * 4 + (i + 2))
        rows.append(cells)
    return np.array(rows, np.int64)


BLOCKS = _blocks()


def _face_connected(bits: int) -> bool:
    cells = [i for i in range(8) if bits >> i & 1]
    if not cells:
        return True
    seen = {cells[0]}
    todo = [cells[0]]
    while todo:
        p = todo.pop()
        for b in (1, 2, 4):
            q = p ^ b
            if bits >> q & 1 and q not in seen:
                seen.add(q)
                todo.append(q)
    return len(seen) == len(cells)


#: MANIFOLD[s]: the boundary of the cells of subset s (bits dx + 2·dy + 4·dz) of a 2 × 2 × 2 block is a
#: 2-manifold at the block's centre (s and its complement both face-connected, or s empty or full).
MANIFOLD = np.array([_face_connected(s) and _face_connected(255 ^ s) for s in range(256)], np.bool_)


def cells_valid(regions: npt.ArrayLike, background: int) -> npt.NDArray[np.bool_]:
    """Whether each assignment of the 64 cells (rows of ``regions``) is a 2-manifold for each non-zero region.

    ``regions`` is (n, 64); each row is checked at the 27 lattice points within ¼ of the pointel.
    """
    r = np.asarray(regions, np.int64)
    vals = r[:, BLOCKS]  # (n, 27, 8)
    ok = np.ones(r.shape[0], np.bool_)
    weights = (1 << np.arange(8)).astype(np.int64)
    for slot in range(8):
        region = vals[:, :, slot : slot + 1]
        bits = ((vals == region) * weights).sum(axis=2)
        good = MANIFOLD[bits] | (region[:, :, 0] == background)
        ok &= good.all(axis=1)
    return ok


def _corner_indices() -> list[int]:
    # The cell index of each position's corner cell: offsets (d − 1) per axis.
    return [
        ((d[2] - 1) + 2) * 16 + ((d[1] - 1) + 2) * 4 + ((d[0] - 1) + 2)
        for d in ([p & 1, p >> 1 & 1, p >> 2 & 1] for p in range(8))
    ]


CORNERS = _corner_indices()


def _cell_components(cells: list[int], member: list[bool]) -> list[int]:
    # Face-connected components of the member cells of the 4 × 4 × 4 block (−1 for the others).
    comp = [-1] * 64
    n = 0
    for start in range(64):
        if not member[start] or comp[start] >= 0:
            continue
        comp[start] = n
        todo = [start]
        while todo:
            c = todo.pop()
            i, j, k = c % 4, c // 4 % 4, c // 16
            for di, dj, dk in ((1, 0, 0), (-1, 0, 0), (0, 1, 0), (0, -1, 0), (0, 0, 1), (0, 0, -1)):
                a, b, e = i + di, j + dj, k + dk
                if 0 <= a < 4 and 0 <= b < 4 and 0 <= e < 4:
                    q = e * 16 + b * 4 + a
                    if member[q] and comp[q] < 0:
                        comp[q] = n
                        todo.append(q)
        n += 1
    return comp


#: The cell of each position's voxel nearest its centre (a core cell): offsets −2 or 1 per axis.
_CORES = [
    ((2 if p >> 2 & 1 else -1) + 1) * 16 + ((2 if p >> 1 & 1 else -1) + 1) * 4 + ((2 if p & 1 else -1) + 1)
    for p in range(8)
]


def keeps_topology(cells: list[int], g: tuple[int, ...], background: int) -> bool:
    """Whether the cells keep the (6, 26) topology of the eight voxels around the pointel, region by region.

    For each non-zero region R: two of its voxels have their core cells in one face-connected set of R's cells
    exactly when they are 6-connected through R's voxels of the block, and the other cells (if any) are
    face-connected, as the other voxels are 26-connected.
    """
    for region in set(g) - {background}:
        mine = [p for p in range(8) if g[p] == region]
        vcomp = {p: p for p in mine}
        changed = True
        while changed:  # 6-components of R's voxels in the block (positions differing by one bit)
            changed = False
            for p in mine:
                for b in (1, 2, 4):
                    q = p ^ b
                    if q in vcomp and vcomp[q] != vcomp[p]:
                        low = min(vcomp[p], vcomp[q])
                        vcomp[p] = vcomp[q] = low
                        changed = True
        comp = _cell_components(cells, [c == region for c in cells])
        pairs = {(vcomp[p], comp[_CORES[p]]) for p in mine}
        if len({a for a, _ in pairs}) != len(pairs) or len({b for _, b in pairs}) != len(pairs):
            return False
        if len(pairs) != max(comp) + 1:  # a piece of R holding no core of R
            return False
        if len(mine) < 8:
            other = _cell_components(cells, [c != region for c in cells])
            if max(other) != 0:
                return False
    return True


def search_entry(g: tuple[int, ...], background: int) -> tuple[int, ...]:
    """The pointel rule's entry for the regions ``g`` of the eight voxels: the source position of each corner.

    The fewest corner cells change (each to the region of a face neighbour, then of an edge neighbour, then
    of the opposite voxel, in the 2 × 2 × 2 block); among as many, the first in the order of positions and
    candidates. An entry that also :func:`keeps_topology` is preferred (the search looks for one first,
    among entries of up to four changes); the patterns with none (two regions both pinched, where one must be
    joined) take the first 2-manifold one. Raises RuntimeError if there is none (never, for the 21,147
    patterns).
    """
    base = _default_cells(g, background)
    options: list[list[int]] = []
    for p in range(8):
        cand = [p ^ b for b in (1, 2, 4)] + [p ^ b for b in (6, 5, 3)] + [p ^ 7]
        seen = {g[p]}
        opts = []
        for q in cand:
            if g[q] not in seen:
                seen.add(g[q])
                opts.append(q)
        options.append(opts)
    for topology in (True, False):
        if cells_valid([base], background)[0] and (not topology or keeps_topology(base, g, background)):
            return tuple(range(8))
        for k in range(1, 5 if topology else 9):
            for chosen in itertools.combinations(range(8), k):
                combos = list(itertools.product(*[options[p] for p in chosen]))
                if not combos:
                    continue
                rows = np.array([base] * len(combos), np.int64)
                for col, p in enumerate(chosen):
                    rows[:, CORNERS[p]] = [g[c[col]] for c in combos]
                for at in np.flatnonzero(cells_valid(rows, background)).tolist():
                    if topology and not keeps_topology(rows[at].tolist(), g, background):
                        continue
                    entry = list(range(8))
                    for col, p in enumerate(chosen):
                        entry[p] = combos[at][col]
                    return tuple(entry)
    raise RuntimeError(f"no pointel entry for {g} (background {background})")


def patterns() -> list[tuple[tuple[int, ...], int]]:
    """Every pattern: a restricted growth string of length 8 and its background block (−1: none)."""
    out: list[tuple[int, ...]] = []

    def grow(prefix: list[int], top: int) -> None:
        if len(prefix) == 8:
            out.append(tuple(prefix))
            return
        for v in range(top + 2):
            grow([*prefix, v], max(top, v))

    grow([0], 0)
    return [(g, bg) for g in out for bg in (-1, *range(max(g) + 1))]


def pattern_key(g: tuple[int, ...], background: int) -> int:
    """The table's key of a pattern: its digits in base 8, then the background block + 1 (0: none)."""
    return sum(int(v) << (3 * i) for i, v in enumerate(g)) + ((background + 1) << 24)


def _encode(keys: list[int], entries: list[tuple[int, ...]]) -> str:
    k = np.array(keys, "<i8").tobytes()
    e = np.array(entries, np.uint8).tobytes()
    return base64.b64encode(zlib.compress(k + e, 9)).decode("ascii")


@cache
def table() -> tuple[Int64Array, UInt8Array]:
    """The sorted keys (:func:`pattern_key`) of the non-identity patterns and their entries (n, 8) uint8."""
    raw = zlib.decompress(base64.b64decode(_TABLE))
    n = len(raw) // 16
    keys = np.frombuffer(raw[: 8 * n], "<i8").astype(np.int64)
    entries = np.frombuffer(raw[8 * n :], np.uint8).reshape(n, 8).copy()
    return keys, entries


def generate() -> str:
    """Search every pattern (minutes) and return the encoded table."""
    keys, entries = [], []
    for g, bg in patterns():
        e = search_entry(g, bg)
        if e != tuple(range(8)):
            keys.append(pattern_key(g, bg))
            entries.append(e)
    order = np.argsort(keys)
    return _encode([keys[i] for i in order], [entries[i] for i in order])


# The encoded table (generate() wrote it): zlib of the int64 keys then the uint8 entries, in base64.
_TABLE = (
    "eNo03cGPc2mVH/6bV29bBtGosCpeZOUuGasb0ehiVe4iqwvqvjqMYAQomUVWgGhEIxgBSlibkikdEIxMyePFrBzLsRKUjEzJ"
    "8R+QhZdZ/TJ/zy9Sf06y+Og533Me3/vcW37rfXskovns/yXj7WeO7z6zZzDZTPSxZzArv5czmOVU30wfg8nmQR97BrPyuZzB"
    "LBdsuTT3aI7BLDsO+lb6mGye5OVaH/uNNZPNi5zBrPpWnVnu5Hs5k81BzmByfJQzmOWJZ77qv+hnllfe9DX/6rM+Jps3n9kz"
    "OX6rzmCWI313+hhMNhN97BnMyu/lDGY5lc/kTDYPcgaT47mcwSwXbLk092iOwSw7DlzpX+tnPnPDF/tv9TOY5U6+lzPZHOQM"
    "JsdHOYNZnnjmq/6LfmZ55a2eyxvnx5bLN87tjXNTLzsOvH3muHnrPX3rPfVF+OYzx8xav9XPLEfyOzmTzUTOYFb9Xp1ZTuUz"
    "OZPNg5zBrPr8rfdQziwXbLk096ifWXYcfP5KP3sGk82TPvYMZuVrOYNZPqtvrNm8mGfPYFa+lTOY5U7fXh+Dyeagjz2DWflR"
    "zmCWJ575au5ijsEsr7zpb97xvfuO9/kd7/M73ud3vM/6GMzK38oZzHKk707OZDORs2cwK7+XM5jlVN9MzmTzIGfPYFY+lzOY"
    "5YItl+YezTGYZceBKz6ZX5tnMMtnbvhibmuOwSx3+vZyJpuDnD2DWflRzmCWJ575au5ijsEsr7zV+zLyPLlgy+XIeY+c98h5"
    "y8uOA2/m/t///+x9H3vfx973sfedb8fea/0c36kzmGwm+tgzmJXfyxnMcqpvJmeyeZAzmFWf25/BLBdsuTT3aI7BLDsOrmNl"
    "jj2DyeZJH3sGs/K1nMEsn+UbOZPNi33YM5iVb+UMZrmT7+VMNgf7sGcwKz/KGczyxDNfzV3MMZjllTf9zed8n3/O+/057/fn"
    "vN+f837rYzArfytnMMuR/e70s2cw2Uz0sWcwK7+XM5jlVH1mzebBPHsGs/K5nMEsF2y5NPdojsEsOw5c8cn82jyDWT5zwxdz"
    "W3MMZrlT31uzOZhnz2BWfpQzmOWJZ76au5hjMMsrb/W+fN7z44Itl593zp93zp93zvKy48Abmy94b7/gff2Cz+UdJ/ruv+A9"
    "088sp/pmciabBzmDWfW5/RnMcsGWS3OP+pllx4ErPplb+zwGs3zmhi/mtuYYzHIn38uZbA72Yc9gVn6UM5jliWe+mruYYzDL"
    "K2/6m3d9/73r++9d78e7vv/e9f2nj8Gs/K2cwSxH+u70MZhsJvrYM5iV38sZzHKqPrNm82CePYNZ+VzOYJYLtlyaezTHYJYd"
    "B674ZH5tnsEsn7nhi7mtOQaz3Onb62Mw2Rz0sWcwKz/KGczyxDNfzV3MMZjllbd6b77oeXLBlssvOvcvOvcvOnd52XHgrfa9"
    "sy9bLu/se2c/9bLjwGfueOKZr/a73Ll/+zLLK28cfcl1csGWyy+5zi+5/y+5XnnZceCKT+bX5hnM8pkbvpjbmmMwy5363prN"
    "wTx7BrPyo5zBLE8889XcxRyDWV5542jinLlgy+XEOU+c88Q5y8uOA2+1vrfm8K+tOZr6fC7Ycjn1+VOfP/X58rLjwFv5b3zf"
    "z3zfz3zfz3zfz3yPyxnMcuQ/GNzpZ89gspnoY89gVn4vZzDLqb6ZPgaTzYM+9gxm5XM5g1ku2HJp7tEcg1l2HPSt9DHZr9XZ"
    "b6yZ7F/Umey36sxyJ9/LmewP6kyOj3IGszzxzFf9F/3M8sqb/Zv3vHfvee/e897xzXveP30MZjl6z/unnz2DyWaijz2DWfm9"
    "nMEsp/pm+hjMqj+oMzmeyxnMcsGWS3OP5hjMsuPAlbm1OQazfOaGL+a25hjMcqdvr4/BrPpBncnxUc5gliee+WruYo7BLK+8"
    "1Xvy4LlxwZbLB+f74HwfnK+87DjwZq6Ze4/n3uO591edWY7kd3ImxxN1Jsf36sxyKp/JmRw/qDM5ns+9h3JmuWDLpblH/cyy"
    "4yBfWTPW3Kgzttyrlwefd3SdDGZ54ll+sb6ab77s+XzZ8+GbL3tOX/Y9o49ZjvTdyZkcT9SZHN/bl8Esp/pmcmb5IJ/bh8Es"
    "F2y5NPdojsEsOw5cmVvrZ5bP3PBF/1Y/s9zJ93JmeZAfXSeDWZ541n/RxyyvvNVzWzhnLtgunM/CuaiXHQfe9Dfv+3Prfe/T"
    "+96n971HcgazHL3vzyv97BlMNhN97BnMyu/lDGY51TfTx2By/KDO5HhujsEsF2y5NPdojsEsOw76VvqYHK/ljFpvrJnsX9Q5"
    "3qozar23ZnJ8lDOYZ/lFzmBe5c0H3pMPvCcfeE8+8O8oH/h3FH0MZuVv5QxmObLfnX72DCabiT72DGbl93IGs5zqm+ljMDme"
    "yxnMcsGWS3OP5hjMsuPAlbm1OQazfOaGL+a25hjMcqdvr4/B5PgoZzDLE8/6L/oZzPLKWz3vrzh/Lth+xbl9xbl9xbnJy44D"
    "b2y+6n37qvftq963r3rfOOIdJ+buzTGY5VTfTB+DyfGDOpPjuTkGs1yw5dLcozkGs+w4cKV/rZ/5zI18K2fu1PfqzPLgeo76"
    "GMzyxLO+iz7mlTf7NR/6nvnQ98yHnifffOi56mMwy9GHvkf0s2cw2Uz0sWcwK7+XM5jlVN9MH4NZPuib62MwywVbLs09mmMw"
    "y44DV3wyvzbPYJbP3PDF3NYcg1nu9O31MZhsDvrYM5iVH+UMZnniWf9FP4NZXnmr9+RrnhsXbL/mnL/mnL/mnOVlx4E3jlr7"
    "csGWy9b+rf1b+8vLjgNPPJu7mGNeOfq6z+eCLZdf9/lf9/lf9/nysuPAlbm1OQazfOaGL+a25hjMcqdvr4/BLA/6jvoYzPLE"
    "s/6LfgazvPLG0dI5csGWy6VzXDrHpXOUlx0H3mr9yH+rzlHnc7lg2/m8zud1Pk9edhx4K/+d79ne92zve7b3Pcs36m+tR73v"
    "0973qXkGk81EH3sGs/J7OYNZTvXN9DGYbB70sWcwK5/LGcxywZZLc4/mGMyy46BvpY/J5knOrPVaP/NZfaPOZPMiZzCrvlVn"
    "ljv3s9fHYLI56GPPYFZ+lDOY5Ylnvuq/6GeWV97q/fyG9/Mb3k++UX9rPfqG9/Ib3ks5k81EH3sGs/J7OYNZTuUzOZP9gzqT"
    "/VydWS7Ycqn/UT+z7DhwxSf9a+tnbvji/rb2ZzDLnb69PgaTzUEfewaz8qOcwSxPPPNV/0U/s7zyVs//m54LF2y5/Kbz/Kbz"
    "VC87Drx90/fkR96/j7x/H/n77kf+vqte67f6meVIfidnspnIGcyq36szy6l89pH3UR+TzYM+9gxm5XM5g1ku2HJp7lE/s+w4"
    "uI6VfvYMJpsnfewZzMrXcgazfFbfWLN5Mc+ewaz11nqnf6+fwWRz0Meewaz8KGcwyxPPfDV3Mcdgllfe9Dcfe38/9v5+7P39"
    "2PurXuu3+pnlSH4nZ7KZyBnMqt+rM8upfCZnsnmQM2s9188sF2y51P+on1l2HLjik7m1OWb5zA1f9G/1M8udfP+x90cfk81B"
    "H3sGs/KjnMEsTzzz1dxFP7O88lbPe/B8uGDL5eBcB+eqXnYceNP//97Ez97H8D5avw3vV/jzW53JZqKPPYNZ+b2cwSyn+mZy"
    "JscP6kyO5+rMcsGWS/2P+pllx8F1rvQx2TzJy7U+9htrJpsXOaPWW2v2e2smm4O8POpjntUv6sxrPd9veb7f8ny/5fl+y/NV"
    "Z7KZ6GPPYFZ+L2cwy6n6zJoxt26tH607rtTX1s/c8MXnb30+g1nu1PfWjKP1iWf1i/WVt7qPv3G9f+N6rTs23/b9/W3nbD3i"
    "HSffdm7fdm76meVU30wfg8nmQR97BrPyuZzBLBdsuTT3qJ9Zdhy44pPPWZtjPnPDF31bfcydz93LGUw2B33sGczKj3IGszzx"
    "zFf9F/3MK2/qzXc8d775juduPfqOn7Pv+DmTM9lM9LFnMCu/lzOY5VR9Zl0+qM+tywVbLvU9WnccuOKT61m7HgazfOaGL+a2"
    "5hjMcqdvr4/BZHPQx57BrPwoZzDLE8981XexvvJWz/VvnTcXbLn8W+do3XHgjaPv2ocLtlx+18/fd+2nXnYc+MwdTzzz9bve"
    "a/sxr7xx9D3XxQVbLr/neqw7DlzxSd/a+pkbvnzP+/A974N+ZrnTt9fHYLI56GPPYFZ+lDOY5Ylnvuq7WF954+j7zosLtlx+"
    "33P8vr/3ft/5ycuOA2+1/vfWHP6DNUd/5/O5YMvl3/k8644Db+V/9H32A99jP/A9xckPfA/9wPeQPmY51TfTx2CyedDHnsGs"
    "fC5nMMsFWy7NPZpjMMuOA1f61/qZG77It3JmuZPv5Uw2BzmDyfFRzmCWJ575au5ijsEsr7zpa37oz68fet5880N/7/yh/56n"
    "j1mO9N3pYzDZTPSxZzArv5czmOVUPpMz2T+oMzmeyxnMcsGWS3OP5hjMsuPAlb619YYv9tvaj8Esd/K9nMn+oM7k+ChnMMsT"
    "z3zVf9HPLK+81bn/yDmx5fJHzulHzulHzkledhx4Y/Nj79uPvW8/9p6plyPecaL/Xj+znMpnciabBzmDWfX5j70vcma5YMul"
    "uUdzDGbZceCKT+bX5hnM8pkbvujbmt+bZzDZHPSxZzArP8oZzPLEM1/NXcwxmOWVN/3NJ75/PvE+fOLfwT7x72DqtX77ie8j"
    "c8xypO9OzmQzkTOYVb+3P4NZTvXN5Ew2D3Jmref2ZTDLBVsuzT2aYzDLjgNXfDK/Nscsn7nhi/6tfma5k+/lTDYHObPWR9fP"
    "YJYnnvlq7qKfWV55q+f9E8+FC7Zc/sQ5/sQ5/sQ5ysuOA2/mmp96P3/q/fyp9/Cn3kM5x3fqDCabiT72DGbl93IGs5zqm8mZ"
    "HD+oMzme25fBLBdsuTT3aI7BLDsO+lb6mGye5ByvrRm13lgz2bzIGRxv1Rm13lsz2RzkHB+tGcwzX/Vd9DGY5VVf86nfrz71"
    "/nzq/fnU99unvt/0MZiVv5UzmOXIfnf62TOYbCb62DOYld/LGcxyqj6z5nhujsEsWy71P+pnMMuOA1fm1uYYzA1f9G31MZjl"
    "Tn1vzfHRHIN5ll/kjEudy8/cJ5c/c58/c58/c5/ysmPzc8/5554bJz/3XH7uuehjllN9MzmT4wd1Jsdz+zKY5YItl+Ye9TPL"
    "jgNX9l/rZ27Ut+rs99ZMNgc5k+OjOoNZnnjWd9FXNr9w/nzzCz9/v/Dz9wvPRV6O9N3pYzDZTPSxZzArv5czmOVUfWZdPpif"
    "m2cwywVbLs09mmMwy44DV/rW1hu+2G9rPwaz3KnvrcuD+aN5BrM88Sy/1Pn8vftk+/fux3r6SzlbLn/pHH7pHH5pTl52HHji"
    "ma/2udiHwSyvHP3KdXHBlstfua5fua5fuS552XHgSt/aesMX+23tx2CWO/W9dXkwfzTPYJYnnuUX69Gv3S8XbLn8tfv9tfv9"
    "tfuVlx2H/8T/bN/f2Jctl7+x72/s+xv7ysuON05X9mPL5cp+K/ut7CcvOw7c8cQzX+1zsQ+zvPLG0W9dHxdsufyt6/ut6/ut"
    "65OXHQeu9K2tn7nhi3239mUwy518L2eyP6gzOT7KGczyxDNf9V/0M8srb3VeT86LLZdPzunJOamXHQfeOFrblwu2XK49h7V9"
    "1cuOA5954pmv9rms3a/9mOWVN45+5/q4YMvl71zf79z/71ynvOw4cMUn82tzzPKZG77o3+pnljv5Xs5kc5Aza310/QxmeeKZ"
    "r+Yu+pnllTeOnp0jF2y5fHaOz85Pvew48Fb7pf3Ycpn2S88l7SsvOw48m7uYYzCvvHH0e9fBlsvf+/zf+/zf+3x52XHgytza"
    "HIP5zA1f9G/1M5jlTn1vzfHRHIN54lnfRR+DeeWtzuEPzuEP7v8P7v8P7l/e8cbmj34//KNz5R0nf/T73R/9fqefWU71zeRM"
    "jh/UmRzP7ctglgu2XJp71M8sOw5c2X+tn/nMjXwrZ+7U9+pMNgc5k+OjOoNZnnjWd9HHvPKm3vzJc+KbP/n9/k9+v/+T5ycv"
    "R/ru9DGYbCb62DOYld/LGcxyqj6zLh/Mz80zmOWCLZfmHs0xmGXHgSs+mV+bZzDLZ274Ym5rjsEsd/r2+hhMNgd97BnMyo9y"
    "BrM88Sy/WF95q+f+D54HF2z/wflZdxx4q7mNObZcbjyPjX3Uy44DTzxvvOfmmFeO/uxzuWDL5Z997p+9B3/2+fKy48CVvrX1"
    "Mzd8se/WvgxmuVPfW5cH80fzDGZ54ll+sb7yVvf/4v7ZvrhP647D1hyHf7TmdGcftjv7WHe8lf9kn701h/9izenBvmy5PHgu"
    "B5+jXnYceKv10ZrDf7Xm6ORzuWDL5cl7cfK56mXHgbda/zf+d3VO/2L/v9j3L+7rL/aXdxz+h3kO/9Oao3+2Lxds/9l+1h0H"
    "3mrubI4tl2fXd7aPetlx4Inns59Dc8wrR3/1uVyw5fKvPvevzuWvPl9edhy40re2fuaGL/bd2pfBLHfqe+vyYP5onsEsTzzL"
    "L9ZX3jh6dQ5csOXy1Tm8OodX5yAvOw4X/i+fw+nV/myv9rHuePvfvPH/2O//4/9V5/Rf7Mv2X+xr3fGm3nz2P4ARbz9zfPeZ"
    "PYPJZqKPPYNZ+b2cwSyn6jPr8sH83DyDWS7UH607/St1Nk/q5VrOfmPN5kWdUeutNfu9NZPNQc7k+KjOYJYn+UXOvFo3/+qz"
    "dfnmM8dvP7NnMMuRvjt9DCabiT72DGbl93IGs5yqz6zLB/Nz8wxmuWDLpblHcwxm2XGQr62fueGL/bb2YzDLnfreujyYP5pn"
    "MMuT+sX6ylud0xv3+8b9WHefOW7eeu5vPXf/gzNvPnPMrPVb/cxyJL+TM9lM5Axm1e/VmeVUPpMz2TzImbWev/X8zTHLBVsu"
    "zT3qZ5YdB5+70s+ewWTzpI89g1n5Ws5gls/qG/u+mGPPYNZ6q2+vj8Fkc9DHnsGs/ChnMMsTz3w1dzHHYJZX3vQ373gv3/Fe"
    "vuO9fMd7qV7rt+/4fjLHLEf67uRMNhM5g1n1e/szmOVU30zOZPMgZ9Z6bl8Gs1yw5dLcozkGs+w4cMUn82tzzPKZG77o3+pn"
    "ljv5Xs5kc5Aza310/QxmeeKZr+Yu+pnllbd63iPPhQu2XI6c48j5qZcdB970NWPv29j7Nva+qd+pM5hsJvrYM5iV38sZzHKq"
    "PtM/18/g+FGdwezUV+psntQ5Xlszar2xZvOizuB4q86o9d6azUGd46M1g+OLOoN5lTef+yxnMNm8+ZzvD30MZuVv5QxmObLf"
    "nX72DCabiT72DGbl93IGs5yqz/TP9TOYZcul/kf9DGbZcdC/1s9gPnPDF/1b/QxmuVPf6z/qZzBP8oucwbzyVufyeff3eff3"
    "eff3efdl/fYLnh/vOPmC8/+C8/+C85eXU/WZdflgfm6ewSwX6o/WHQdzaznzWX2rztyp79WZbA5yJsdHdQazPMkvcuaVN/Xm"
    "XT9XfPOun5t3/dy867zl5UjfnT4Gk81EH3sGs/J7OYNZTtVn1uWD+bl5BrNcsOXS3KM5BrPsOHDFJ/Nr8wxm+cwNX8xtzTGY"
    "5U7fXh+Dyeagjz2DWflRzmCWJ/WL9ZW3et5f9By4+KLzsu448Fb9d/rv9Ft3PN15T+XMK0dfsg8XbLn8kuf4Jc/xSz5HXnYc"
    "5GvrZ274Yr+t/RjMcqe+ty4P5o/mGczypH6xvvLG0cR9c8GWy4n7nrjvifuWlx2Hf21/Tqf2nZqz7nib+nN45s/hme+Lme+L"
    "me8JOYNZjvwPjd7pZ89gspnoY89gVn4vZzDLqb6ZPgazfNA318dglgu2+h/1M5hlx0HfSh/7tTX7jTX7F2v2W2v2e2tmeXB9"
    "R30MZnmSX+TMq/nmPc/9Pc/9Pc+db97z/PUxmOXoPc9fP3sGk81EH3sGs/J7OYNZTvXN9DGY5YO+uT4Gs1yw5dLcozkGs+w4"
    "cGVubY7BLJ+54Yu5rTkGs9zp2+tjMMuDvqM+BrM88az/op/BLK+81fN/8Dy4YPvg/B6c34Pzk5cdB97MNXPv5dx7Ofc+qjPL"
    "kfxOzuR4os7k+F6dWU7lMzmzfJDP594rfcxywVb/oz5m2XGQr7jmhlvu9ZcH+x9dD4NZntQv1ldzzZed95edN9982bl/2feA"
    "PmY50ncnZ3I8UWdyfG9fBrOc6pvJmeWDfG4fBrNcsOXS3KM5BrPsOHBlbq2fWT5zwxf9W/3Mciffy5nlQX50nQxmeeJZ/0Uf"
    "s7zyVs9t4Zy5YLtwPgvnol52HHjT37zvz5X3vU/ve5/e9x7JGcxy9L4/T/SzZzDZTPSxZzArv5czmOVU30wfg8nxXM5glgu2"
    "+h/1M5hlx0HfSh/Ha3VGrTfW7F+sOd6qM2q9t+b4qM7g+KLOYF7lzQee8wee8wee8wf+/eYD/36jj8Gs/K2cwSxH9rvTz57B"
    "ZDPRx57BrPxezmCWU30zfQwmx3M5g1ku2HJp7tEcg1l2HLgytzbHYJbP3PDF3NYcg1nu9O31MZgcH+UMZnniWf9FP4NZXnmr"
    "5/0V588F2684t684t684N3nZceCNzVe9b1/1vn3V+/ZV7xtHvOPE3L05BrOc6pvpYzDLB31zfQxmuWCr/1E/g1l2HPSt9TGf"
    "1bfqzJ36Xp1ZHnz+UR+DWZ7kFznzypt9mg99b3zoe+NDz4dvPvSc9DGY5ehD3wv62TOYbCb62DOYld/LGcxyqm+mj8EsH/TN"
    "9TGY5YItl+YezTGYZceBKz6ZX5tnMMtnbvhibmuOwSx3+vb6GEw2B33sGczKj3IGszzxrP+in8Esr7zVe/I1z40Ltl9zzl9z"
    "zl9zzvKy48AbR619uWDb2re1b2tfedlx4En/RT/zytHXfR4XbLn8us/9us/9us+Vlx0HrsytzTGY5TM3fDG3Ncdgljt9e30M"
    "ZnnQd9THYJYnnvVf9DOY5ZU3jpbOkQu2XC6d49I5Lp2jvOw48FbrR/5bdY46n8sF287ndT6v83nysuPAW/nvfI/2vkf5pve9"
    "aT3qfU/2viflTDYTfewZzMrv5QxmOdU308dgsnnQx57BrHwuZzDLBVsu9T1adxzss5Iz2TzJmbVe62c+q2/UmWxe5Axm1bfq"
    "zJ373MsZTDYHfewZzMqPcgazPPHMV/0X/cwrb+rNN7xnfPMN75n16Bves294z+RMNhN97BnMyu/lDGY5VZ9Zlw/qc+tywZZL"
    "fY/WHQeu+KRvbf3MDV9c79b1MpjlTt9eH4PJ5qCPPYNZ+VHOYJYnnvmq72J95a2e3zedKxdsufym87LuOPD2Tb/nfeR9+cj7"
    "8pG/F37k74XqtX6rn1mO5HdyJpuJnMGs+r06s5zKZx/5ftLHZPOgjz2DWflczmCWC7ZcmnvUzyw7Dq5jpZ89g8nmSR97BrPy"
    "tZzBLJ/VN9ZsXsyzZzBrvbXe6d/rZzDZHPSxZzArP8oZzPLEM1/NXcwxmOWVN/3Nx97fj72/H3t/P/b+qtf6rX5mOZLfyZls"
    "JnIGs+r36sxyKp/JmWwe5Mxaz/UzywVbLvU/6meWHQeu+GRubY5ZPnPDF/1b/cxyJ99/7P3Rx2Rz0Meewaz8KGcwyxPPfDV3"
    "0c8sr7zV8x48Hy7Ycjk418G5qpcdB970NeH9Cu9T+PNVnclmoo89g1n5vZzBLKfqM875KO/Mr9TZPKmXazn7jTWbF3VGrbfW"
    "7PfWbA7q5VHO/mLNvFo333Ke33Ke33Ke6kw2E33sGczK7+UMZjlVn3HOR3lnvbZ+5oYvPmfrcxjMcqe+51H9ZH2xvvJW1/c3"
    "rudvXA+bb/u++7Zzsx7xjpNvO4dvOwf9zHKqb6aPwWTzoI89g1n5XM5glgu2XOp7tO44cMUn+671M5+54Yu+rT7mzvXt5Qwm"
    "m4M+9gxm5Uc5g1meeOar/ot+5pU39eY7njPffMdzth59x8/Jd/ycyJlsJvrYM5iV38sZzHKqPrMuH9Tn1uWCLZf6Hq07Dlzx"
    "yfWsXQ+DWT5zwxdzW3MMZrnTt9fHYLI56GPPYFZ+lDOY5Ylnvuq7WF95q+f6t86bC7Zc/q1ztO448MbRd+3DBVsuv2sf644D"
    "n7njiWe+ftd7bB/mlTeOvuc6uGDL5fdch3XHgSs+6VtbP3PDl+95/t/z/PUzy52+vT4Gk81BH3sGs/KjnMEsTzzzVd/F+sob"
    "R993Xlyw5fL7fl/5vn+f+r7zk5cdB95q/e+tOfwHa47+zudzwZbLv/N51h0H3sr/6PvqB76POPmB75sf+L75ge8beTlVn1mX"
    "D+bn5hnMcsGWS3OP5hjMspOv5ey31uz31kw2BzmT46M6g1meeOaruYs5BrO8qjc/9OcF3/zQ34N+6L/b/NDzkJcjfXf6GEw2"
    "E33sGczK7+UMZjlVn1mXD+bn5hnMcsGWS3OP5hjMsuMgX1tv+GKfrX0YzHKnvrcuD+aP5hnM8qR+qfP4kftiy+WP3NeP3NeP"
    "3Je87Nj82HP/sef+Y89bvRzxjhP99/qZ5VQ+kzPZPMiZtZ7/2HM0xywXbLk092iOwSw7DlzxyfzaPINZPvNFvjW3N8dgsjno"
    "Y89gVn6UM5jliWe+mruYYzDLK2/6m0/83H/i+X/i30M+8e8h6rV++4nvAXPMcqTvTs5kM5EzmFW/tz+DWU71zeRMNg9yZq3n"
    "9mUwywVbLs09mmMwy44DV3wyvzbHLJ+54Yv+rX5muZPv5Uw2Bzmz1kfXz2CWJ575au6in1leeavn/RPPhQu2XP7EOf7EOf7E"
    "OcrLjgNv+pqfeu9+6r37qfdO/U6dwWQz0ceewaz8Xs5gllP1mf65fgaz5VLfoz4Gs+zkKzmbJ3WO19aMWm+s2byoMzjeqjNq"
    "vbdmc1Dn+GjNYJ75qu+ij8Esr/qaT/3fiXzq+X7qe+dT3zuf+t7Rx2BW/lbOYJYj+93pZ89gspnoY89gVn4vZzDLqfpM/1w/"
    "g1m2XOp/1M9glh0H/Wv9DOaGL/q2+hjMcqe+13/Uz+D4os641H3/zP1w+TP38zP38zP3Iy879bc/9zw4+bnz/rnz/rnzlpdT"
    "9Zl1+WB+bp7BLBfqj/rW1uy31uz31kw2BzmT46M6g1me5Bd52fzCzwXf/MJ7/wvv/S+cm7wc6bvTx2Cymehjz2BWfi9nMMup"
    "+sy6fDA/N89glgu2XJp7NMdglh0H+dp6wxf7bO3DYJY79b11eTB/NM9glif1S53H37uvv3fd1tNfqrPl8pfu95fu95fm5GXH"
    "E898NX8xz2CWV45+5Xq4YMvlr1zPr1zPr1yPvOw4yNfWG77YZ2sfBrPcqe+ty4P5o3kGszypX6xHv3Z/XLDl8tfu79fu79fu"
    "T152HP6z/X5jP7Zc/sZ+v7Hfb+wnLzveOF3Zb6XfuuPA08pz1ce88sbRb+3LBVsuf+s6f+s6f+tz5WXHQb62fuaGL/bb2o/B"
    "LHfqe+vyYP5onsEsT+oX6ytvdb9P7vfJ/Vh3vHG01s8FWy7XzmdtH/Wy48Bnnnjmq30ua8/NfszyyhtHv3N9XLDl8neu73ee"
    "3+9cp7zsOHDFJ/Nrc8zymRu+6N/qZ5Y7+V7OZHOQM2t9dP0MZnnima/mLvqZ5ZU3jp6dIxdsuXx2js/OT73sOPBW+6W5dP5p"
    "Ps1x0HfRx2BeeePo9/Zny+Xvfd7vfd7vfZ687DjoX+tnMJ+54Yv+rX4Gs9yp7/Uf9TOYJ/lFzmBeeav7/YP7+4P7+4P7+4P7"
    "4k397R+dF+84+aPfU/7o95Q/+j1FXk7VZ9blg/m5eQazXKg/WncczK3lzGf1rTpzp75XZ7I5yJkcH9UZzPIkv8iZV97Umz/5"
    "vZJv/uT3yj/5vfJPzltejvTd6WMw2Uz0sWcwK7+XM5jlVH1mXT6Yn5tnMMsFWy7NPZpjMMuOA1d8Mr82z2CWz9zwxdzWHINZ"
    "7vTt9TGYbA762DOYlR/lDGZ5Ur9YX3mr5/0PngMX/+C8rDsOvFX/Rv9Gv3XH08Z7KmdeOfqzfbhgy+WfPcc/e45/9jnysuMg"
    "X1s/c8MX+23tx2CWO/W9dXkwfzTPYJYn9Yv1lbe63xf3++J+rDsOW/0c/tGa0535nXnrjrfyn8z/F2tOD+YP5q07Dkf9HP6r"
    "NUcn+3DBlsuT53ayv3rZceCt1v/dmtO/2Ocvnv9f7PcX+3D4H+Y4/E9rjv7Zflz8s32sOw68Vf9Z/1m/dcfT2fstZ145+qt9"
    "uGDL5V/d31/d3199jrzsOMjX1s/c8MV+W/sxmOVOfW9dHswfzTOY5Un9Yn3ljaNX980FWy5f3fer+3513/Ky4/C/7M/p1b5X"
    "c9Ydbzf+H/P/15rTfzH/L+atO97Um+bNZ39+fub47jN7BpPNRB97BrPyezmDWU71zfQxmGwe9LFnMCufyxnMcsGWS3OP5hjM"
    "suOgb6WPyeZJXq650c9k8yJnMKu+VWeWO/lezmRzkDOYHB/lDGZ54pmv+i/6meWVN33Nv/qsj8nmzWf2TI7fqjOY5Uh+J2ey"
    "mcgZTI7v5QxmOZXP5Ew2D3IGk+O5nMEsF2y5NPdojsEsOw5c6V9bP3PDF/nWfsxyJ9/LmWwOcgaT46OcwSxPPPNV/0U/s7zy"
    "Vs/hjfNiy+Ub5/TGOamXHQfePnPcvPUevvUevvUefua4fMs7/Uw2EzmDWfV7dWY5lc/kTDYPcgaz6vO33is5s1yw5dLco35m"
    "2XHw+Sv97BlMNk/62DOYla/lDGb5rL6xZvNinj2DWflWzmCWO/W9NZuDefYMZuVHOYNZnnjmq7mLOQazvPKmv3nH9+Q73s93"
    "vJ/veD/f8X7qYzArfytnMMuR+p01m4l59gxm5fdyBrOcqs+s2TyYZ89gVj6XM5jlgi2X5h7NMZhlx4ErPplfm2cwy2du+GJu"
    "a47BLHfqe2s2B/PsGczKj3IGszzxzFdzF3MMZnnlrd6LkefHBVsuR8555JxHzlledhx4M/f/3tzP3uux93rsvR57r/l27P3V"
    "z/GdNZPNRM5gVv3efgxmOdU3kzPZPMgZzKrP7c9glgu2XJp7NMdglh0H17Eyx57BZPOkjz2DWflazmCWz+obazYv5tkzmJVv"
    "5QxmuVPfW7M5mGfPYFZ+lDOY5Ylnvpq7mGMwyytv+pvP+V7+nPf3c97fz3l/P+f91cdgVv5WzmCWI/vd6WfPYLKZ6GPPYFZ+"
    "L2cwy6n6zJrNg3n2DGblczmDWS7Ycmnu0RyDWXYcuOKT+bV5BrN85oYv5rbmGMxyp763ZnMwz57BrPwoZzDLE898NXcxx2CW"
    "V97qffm858cFWy4/75w/75w/75zlZceBNzZf8N5+wefxjhP5/Re8V+rlVD6TM9k8yBnMqs+/4L2SM8sFWy7NPepnlh0Hrvhk"
    "bu3zGMzymRu+mNuaYzDLnfrems3BPHsGs/KjnMEsTzzz1dzFHINZXnnT37zre+5d33Pveg/e9T33ru85fQxm5W/lDGY5Ur+z"
    "ZjMxz57BrPxezmCWU/WZNZsH8+wZzMrncgazXLDl0tyjOQaz7DhwxSfza/MMZvnMDV/Mbc0xmOVO314fg8nmoI89g1n5Uc5g"
    "liee+WruYo7BLK+81XvyRc+TC7ZcftG5f9G5f9G5y8uOA2+175192XJ5Z987+6mXHQc+c8cTz3y13+XO/duXWV554+hLrpML"
    "tlx+yXV+yf1/yfXKy44DV3wyvzbPYJbP3PDF3NYcg1nu1PfWbA7m2TOYlR/lDGZ54pmv5i7mGMzyyhtHE+fMBVsuJ8554pwn"
    "zlledhx4q/W9NYd/bc3R1OdzwZbLqc+f+vypz5eXHQfeyn/j+33m+33m+33m+33m986Z3zv1MZhsJvrYM5iV38sZzHKqb6aP"
    "wWTzoI89g1n5XM5glgu2XJp7NMdglh0HfSt9TPYbdSb7F3Um+606s9zJ93Im+4M6k+OjnMEsTzzzVf9FP7O88lbvzXvem/e8"
    "N3zznj/33/Pnvj5mOZLfyZnsJ+pMju/lDGY5lc/kTPYP6kyO53IGs1yw5dLcozkGs+w4cMVnbvhin619mOVOvpcz2R/UmRwf"
    "5QxmeeKZr/ov+pnllbc67wfnw5bLB+fy4FzUy44Dbw++l+beq7n3au57SJ3J8USdyfG9OrOcymdyJscP6kyO53Pvh5xZLthy"
    "ae5RP7PsOMhX1oyNNWNvXR7sf3RdDGZ54pnXOt8vO1+++bKf2y/7uf2yn1t5OVK/sy4n5u/NM5jlVH1mXT6Yn5tnMMsFWy7N"
    "PZpjMMuOA1d85oY783vr8uBzjj6HwSxPPPPKW13/wvWzW3jv3/dc3vdc3vc83vc85BzfWTM5nqgzOb63D4NZTvXN5EyOH9SZ"
    "HM/ty2CWC7Zcmns0x2CWHQf5yprjtXlGudHH8VYfo9zr4/ioj8E8yy9yBvMqbz7w5+IHnuMHnuMH/r78gb8v62MwK38rZzDL"
    "kf3u9LNnMNlM9LFnMCu/lzOY5VR9Zs3x3ByDWbZc6n/Uz2CWHQeuzK3NMZjP3Ojb6mMwd9Z7a46P+hnME8/6LvoYzCtvdb9f"
    "cZ9fcZ9fcZ9fcX9svup58o6Tr3oeX/Uc1MupfCZncvygzuR4/lXPSc4sF2y5NPeon1l2HLjiMzfcmd9blwf7H10Xg1meeOaV"
    "N/3Nh86Tbz70c/Shn6MP/RzJy5H6nXU5MX9vnsEsp+oz6/LB/Nw8g1ku2HJp7tEcg1l2HLjik/m1eQazfOaGL+a25hjMcqdv"
    "r4/BZHPQx57BrPwoZzDLE8+88lbP72ueAxds2XHgrfpb/Wy5bJ1/69zVy44DTzzzytHXfQ4XbLn8us/5uuf8dZ8nLzsOXPGZ"
    "G+7M763Lg885+hwGszzxzCtvHC3dDxdsuVy6n6X7WbofedlxeOS/9TlcdPZlx1vnz9fen6+9n/vezz3fcNT787H356M5BpPN"
    "RB97BrPyezmDWU71zfQxmGwe9LFnMCufyxnMcsGWS3OP5hjMsuOgb6WPWT7xWd9GH5P9izqT/VadWe5c514fg8nmoI89g1n5"
    "Uc5gliee+ar/op9ZXnmr9+0b3rdveN/4hqNveL/0MdlP1Jns79WZ5VQ+kzPZP6gz2c/VmeWCLZf6H/Uzy44DV3ziMzd8sd/W"
    "fsxy9w3PWx+Dyeagjz2DWflRzmCWJ575qv+in1leeavn+U3PgQu2XH7T+X3T+amXHQfevun76yPv0UfeI77h6CPfV/qYHE/U"
    "mRzfqzPLqXz2kfdJH5PNgz72DGblczmDWS7YcmnuUT+z7DjIV9blE5/lG+vyhTufs3d9DCabgz72DGblRzmDWZ545iuvvNVz"
    "/thz5huOPvZ8rcsJp/KZdfnAORdsuWTHgSs+8ZkbvnD3sXP82Dm6Diabgz72DGblRzmDWZ545iuvvNV5Dc6FC7ZcsuPA2+Dn"
    "LjyP8DzCz5k6k+OJOpPje3VmOZXP5EyOH9SZHM/VmeWCLZf6H/Uzy46DfGXN2Fgz9tblmdc6p285p285H2vGzLps2XHFZ264"
    "M7+3Lk8888pb7f839mfzbT9PHPGOk297Xt/2vNTLqXz2bd+L+phsHvSxZzArn8sZzHLBlktzj/qZZceBKz7xmRu+cGffveth"
    "MNkc9LFnMCs/yhnM8sQzX3nlzVzzHc+Nbzj6jvfLupxwKp9Zlw+cc8GWS3YcuOLTd/w9+Tv+nuxzmOUzN3wxtzXHYJY7fXt9"
    "DCabgz72DGblRzmDWZ545iuvvNV5/61z5YItl+w48MbRd81zwZbL73qvv+u9Vi87Dnzmjiee+corbxx9z3VwwZZLdhy44hOf"
    "ueELd9/z/L7n+X3P85OzOehjz2BWfpQzmOWJZ77yyhtH33ffXLDl8vvO//t+P/2+5yAvOw681frfW3P4D9Yc/Z3P54Itl+w4"
    "8Fb+R98DP/DzzskPfF//wN+LfuB7W15O9c30MZhsHvSxZzArn8sZzHLBlktzj+YYzLLjwBU3fDG/Nc8sd/K9nMn+oM7k+Chn"
    "MMsTz3w1dzHHYJZX3vQ1P/S9/kPPk29+6N9df+jfXfUxy5H8Ts5kP1FncnwvZzDLqXwmZ7J/UGdyPJczmOWCLZfmHs0xmGXH"
    "gStu+GJ+a55Z7uR7OZP9QZ3J8VHOYJYnnvmq/6KfWV55q3P+kXNhy+WPnMuPnMuPnIu87DjwxubH3gNOfuy5/9jzVi+n8pmc"
    "yfGDOpPj+Y89bzmzXLDl0tyjOQaz7DhwxY3+vXV5sO/RvgxmeeKZr+Yu5hjM8qrefOJ8+eYTP6ef+Dn9xM+pvByp31mXE/P3"
    "5hnMcqo+sy4fzM/NM5jlgi2X5h7NMZhlx4ErbvTvrcuDfY/2ZTDLE891fT9xfVz+xPX9xPX9xPXJy05f81PP56eez089l596"
    "LnKO76yZHE/UmRzf24fBLKf6ZnImxw/qTI7n9mUwywVbLs09mmMwy46DfGXN8do8o9zo43irj1Hu9XF81Mdgnvmq76KPwSyv"
    "+ppP/fn4qef6qef6qf/+/6n//q+Pwaz8rZzBLEf2u9PPnsFkM9HHnsGs/F7OYJZT9Zk1x3NzDGbZcqn/UT+DWXYcuDK3Nsdg"
    "buRbOaPc6+P4qI/BPMsvcsal7uNn7uNn7uNn7uNn7kNedmx+7nlw8nPn/XPnrF5O5TM5k+MHdSbH8597DnJmuWDLpblH/cyy"
    "48AVN/r31uXBfkfXwWCWJ57lzS+cE9/8ws/BL/wc/MLPgbwcqd9ZlxPz9+YZzHKqPrMuH8zPzTOY5YItl+YezTGYZceBK270"
    "763Lg32P9mUwyxPPdX1/7/o4/aU6Wy5/6bp/6bp/6brlZceBJ575ap+LfRjM8srRr1wXF2y5/JXr+pXr+pXrkpcdB6640b+3"
    "Lg/2PdqXwSxPPHP0a9fLBVsuf+16f+16f+165WXH4T/xP9vvN/bj8jf2+439fmM/ednxxunKfmy5XNlvZb+V/eRlx4E7nnjm"
    "q30u9mGWV944+q3r44Itl791fb91fb91ffKy48AVn7nhi3229mGWO/lezmR/UGdyfJQzmOWJZ77qv+hnllfe6nyenA9bLp+c"
    "y5NzUS87DrxxurYfWy7XznttP/Wy48ATz7zyxtHvfB4XbLn8nc/7nfv4nc+Vlx0HrvjMDXfm99blweccfQ6DWZ545pW3uv5n"
    "18+ON05TH1su032m+0z3KS87Djybu5hjMK+8cfR718GWy9/7/N/7/N/7fHnZceDK3Nocg/nMjb6tPgZzZ7235vion8E88azv"
    "oo/BvPJW9/sH9/kH9/kH9/kH98cbmz86N95x8ke/L/zR7wnq5VQ+kzM5flBncjz/o98f5MxywZZLc4/6mWXHgSs+c8Od+b11"
    "ebD/0XUxmOWJZ15509/8yXnyzZ/8vvYnv6/9ye9r8nKkfmddTszfm2cwy6n6zLp8MD83z2CWC7Zcmns0x2CWHQeu+GR+bZ7B"
    "LJ+54Yu5rTkGs9zp2+tjMNkc9LFnMCs/yhnM8sQzr7zV8/sHz4ELtuw48Fb9G/1sudw4/41zVy87DjzxzCtHf/Y5XLDl8s8+"
    "58+e8599nrzsOHDFZ264M7+3Lg8+5+hzGMzyxDOvvNX1v7h+dhy2+jj8ozUXO3PseCv/ydzemsN/seb0YD+2XB6c38H5qZcd"
    "B95qfeR/VefiZH92HP4b/7t+tn/xHP/iOv7iOv5insP/MMfhf1pz9M/ukwu27DjwVv1n/Wy5PLuus+tRLzsOPPHMK0d/9Tlc"
    "sOXyrz7nr+7/rz5PXnYcuOIzN9yZ31uXB59z9DkMZnnimVfeOHp1P1yw5fLV/by6n1f3Iy87Dhf+L5/DxfX/Z+9+fpw37sOP"
    "U6REbYzEWC+2OvS0WWyIxEgMmtjy0JNiJMQkSALbaHPoKTFiIzGSwDb69VleyMLHRhLIgqpDT6qgCq3RBvJC1R+QA485Jf57"
    "vs+u3h+JokiR1Orx8zj26YWZ+cyQHP4QOaJGtIshxn/CP1PvL/hX8tH7lPoYYvypznfqrD7PVsopnq08OV/ZRoOitoi7IA4N"
    "ClqXxGEbDYqWX1GOBkX10MeAetfUQ4Oihhhhh/gu8Sh9HFA+pBxFHVE+phwFrQnlaFA0f0o+ijrDOd4SvyAeRV1iTJxVW8Wh"
    "oGWvbKt14vDklHw0KGidEYdtNChafk45GhS1RfkF5ShoXVKOBkXzr8hHUT30MSD+mngUNcQIO8R3iUfpYR8HbOeQeDQo6ojy"
    "MeUoaE0oR4Oi+VPyUdQZzvGW+AXxKOoSY+1/m/5CHwOb/rLpL/LVECOM0aqvtFee1OscV+SrLp7iGfHnxKOoLcovKEdB65Jy"
    "NCiaf0U+iuqhjwHx18SjqCFG2MEb6nXrHDfUR1F72McB9YbUQ4OijogbE4cGBa0JcdhGg6LlU8rRoKgznOMt9RbUQ4OiLjEm"
    "3mpwHWpwHWpwnDS4Dq08wTYaFC2vU44GRXWJO6UcBa0zyrGNBkXLzylHg6K2iLugHAWtS8qxjQZFy68oR4OieuhjQL1r6qFB"
    "UUOMsIM31O9SHw2K2sM+Dqg3pB4aFHVE3JhyFLQmlGMbDYqWTylHg6LOcI631FtQDw2KusRYjxeX/Yke+hi49LdLf7v0N+Vq"
    "iBHG1LNOON5PON5PON5PON6xThyenJ7wuUs+ClpnxGEbDYqWn1OOBkVtEXdBOQpal5SjQdH8K/JRVA99DIi/Jh5FDTFiuR3i"
    "sY0GBa0b4rCNBkXLu5SjQVF7lPcpR0FrQDvYRoOi5UPK0aCoI8rHlKOgNaEdbKNB0fIp5WhQ1BnO8ZZ6C+qhQVGXGBNvfYXr"
    "9lc4jr/CcfwVjuOvcBwThwZFy+uUo0FRXeJOiUODgtYZcdhGg6Ll55SjQVFb5F+QRuuS+thGg6LlV5SjQVE99DGg3jX10KCo"
    "IUbYwRvqd6mPBkXtYR8H1BtSDw2KOiJ/TBqtCfWxjQZFy6eUo0FRZzjHW+otqIcGRV1irMfJM+w/9NDH4Bn6+Rn6+Rn6mXI1"
    "xAhjtL7K8fpVjtOvslw8xTPizr/KcUY8itoi7oJyFLQuKUeDovlX5KOoHvoYEH9NPIoaYoQdvKFel+1Ag6L2sI8D6g2phwZF"
    "HVE+phwFrQntYBsNipZPKUeDos5wjrfUW1APDYq6xJh462tc777G9e5rHBdf43r3Na53xKFB0fI65WhQVJe4U+LQoKB1Rhy2"
    "0aBo+TnlaFDUFvkXpNG6pD620aBo+RXlaFBUD30MqHdNPTQoaogRdvCG+l3qo0FRe9jHAfWG1EODoo6IGxOHBgWtCXHYRoOi"
    "5VPK0aCoM5zjLfUW1EODoi4x1uPmWfYneuhj8Cz9/iz9/iz9TrkaYoSxtntKu+hjcEq7p7RHvhpihD0c4QzneEt7i1O2n3ZR"
    "1CXG6D7HeqKHPgbPsZ7Psf3Psb6UqyFG2MEb6nepjwZF7WEfB9QbUg8Nijoif0warQn1sY0GRcunlKNBUWc4x1vqLaiHBkVd"
    "YozuGf2MHvoYnNHPZ/TzGf1MuRpihLGmz0lj9Hek0W2xfPTQx6DF8lssv8XyKVdDjDBW/57r+gXX6wuu1xdcry+4XqOLp3hG"
    "vXPqoUFRW8RdEIcGBa1L4rCNBkXLryhHg6J66GNAvWvqoUFRQ4ywQ3yXeJQ+DigfUo6ijigfU46C7Qn5KNieko+iznCOt8Qv"
    "iEdRlxiz/dbX+Vz/Op/rX2f/f539TzkaFNVdaZ0Sj200KGidEYdtNChafk45GhS1RdwFcWhQNP+SfBQ8uaIcDYrqoY8B9a6p"
    "hwZFDTHCDvW61EODovawjwPqDamHBkUdETcmDg2K5k/IR8GTKeVoUNQZzvGWegvqoUFRlxjrcXLJfkMPfQwu6d9L+veS/qVc"
    "DTHCGK0rjtcrjtMrjlN08RTPiD8nHkVtUX5BOQqeXJKPgidX5KOoHvoYEH9NPIoaYoQd4rqk+6SHOCYfzZT0nPSC9JLlWt/g"
    "fP8G/fcN+o98FNWl/JRyFDw5Ix8FT87JR1FblF9QjoInV+SjqB76xF0Th6KGGGGH+C7xKGoP+zggfkg8ijqifEw5Cp5MyUdR"
    "ZzgnbkEcirrEWPvfo9/QQ9+jHzz6gXw1xAhj4q1vct3/JsfBNzkOvslxQDkaFNX9Jtd94rGNBgWtM+KwjQZFy88pR4Oitoi7"
    "IA4NCp5cko+CJ1fUQ4OieuhjQL1r6qFBUUOMiOsQh4LtLvnY7pNGwfaAfGwPSWN7TBoF21PyUebkL8hHWbJd1rc4Dr7FcfAt"
    "joNvcRxQjgZFdb/FcUA8ttGgoHVGHLbRoGj5OeVoUNQWcRfEoUHBkyvK0aCoHvrEXxOPBkUNMcIO9brUQ4Oi9rCPA+oNqYcG"
    "RR0RNyYODQqeTClHg6LOcE78gng0KOoSY93Pz9Pv6KH/PP32PP32PP1GuRpihDFa3+Y4+zbH2bc5zr7NcYYunuIZ9c6phwZF"
    "bRF3QRwaFDy5JB8FT66ohwZF9dDHgHrX1EODooYYYYf4LvEoPexTPqQcZUT+mHwUbE/JR5nhnPIF5ShLjNkO6ztcH77D9eE7"
    "7LfvsN8oR4Oiut/h+kA8ttGgoHVGHLbRoGj5OeVoUNQWcRfEoUHBkyvK0aCoHvrEXxOPBkUNMcIO3lC/S300KGoP+zig3pB6"
    "aFDUEXFj4tCgoDUhDttoULR8SjkaFHWGc+IXxKNBUZcY63HxAvsJPfRfoJ9foJ9foJ8pV0OMMEbXp1300MfAp32f9n3ap1wN"
    "McI58QviUZbovshy0UP/RZb3Ist7keVRroYYYYd6XeqhQVF72McB9YbUQ4OijogbE4cGBU+mlKNBUWc4J35BPBoUdYkxugH9"
    "hh76GAT0X0D/BfQf5WqIEcaavsZ/IB/dkOWih37I8kKWF7I8ytUQI4zVf+S62ea62ea62ea6Sbre5rrY5rpIPBoUtM6IwzYa"
    "FC0/pxwNitoi7oI4NChoXRKHbTQoWn5FORoU1UMfA+pdUw8NihpiRFyHOBS0bihXu8Rhu08aBa0B5WhQNH9IPoo6onxMOQpa"
    "E8rRoGj+lHwUdYZzvCV+QTyKusRYj7Pvcpx9l+OMdP27HF/f5fgiHwWtM+KwjQZFy88pR4Oitii/oBwF25fko2D7inwU1UMf"
    "A+KviUdRQ4ywQ1yXdA/7OGC7hrSLBkUdUT6mHAXbE/JRsD0lH0Wd4RxviV8Qj6IuMdZ+fon+QR+Dl+ifl+gf8tUQI4xf4nr1"
    "PY6f73H8fI/vdb/H97rka7pOPIrqUn5KOQpaZ5SjQdH8c/JR1BblF5SjoHVJORoUzb8iH0X10MeA+GviUdQQI5bbIR7baFDQ"
    "uiEO22hQtLxLORoUtUd+nzRaA+pjGw2KpofEjYlDg4LWhDhso0HR8inlaFDUGc7xlnoL6qFBUZcYE299n+Pz+xyf3+f4/D7H"
    "J/marhOPorqUn1KOgtYZ5WhQNP+cfBS1RfkF5ShoXVKOoukr4lFUD30MiL8mHkUNMcIO3lCvSz0UtYd9HBA/JB5FHVE+phwF"
    "rQnlKJqeEo+iznCOt8QviEdRlxjr/ozof/TQxyCi3yL6jXw1xAhj4i3D8WY43kjXDceP4fOUfBS0zojDNhoULT+nHA2K2iLu"
    "gnIUPLkkHwVPrshHUT30MSD+mngUNcSI9ewQh4LWDeVqlzhs90mjoDWgHI2mh6SxPSaNgtaEcnVKHMqc/AX5KEvdvz9g//6A"
    "/fsD9u8P2L/ko6B1Rhy20aBo+TnlaFDUFvkXpNFckfZJX5MOsUN+l3QP+zhg+UOWjwZFHZE/Jo1mSnqGc/IXpJcY63b8kPX9"
    "IetLOkTrR/Tvjzhv8RTPfkR//Yj+Ih5FbRF3QTkKnlySj4InV+SjqB76GBB/TTyKGmKEHda3SzxKD/uUDylHGZE/Jh8FrQnl"
    "6pQ4lBnOKV9QjrLEmHzrx+yHH7MfSLs/5nj/Mcc75ShonRGHbTQoWn5OORoUtUX+BWk0V6Q99Mm/Jh1ihB28YbldlosGRe1h"
    "HwfUG1IPDYo6Im5MHBoUtCbEYRsNipZPKUeDos5wTvmC9BJj3W8/oT/RQ/8n9BvpECOMtd7L1EMfg5c5/l+mHfLVECOcv8zx"
    "RzzKEluv0P4rtEc6xA75XdI97OPgFfbTK+wn4lHUEflj0mimpGc4J39Beokxuq+y3uihj8Gr9M+rPGe9ynZRroYY/RPt/zPt"
    "/pT2fko90iHGaP2M8/RnnId49jPOs59xnhGHoraIuyAODQpal8RhGw2Kll9RjgZF9dDHgHrX1EODooYYYYf4LvEofRxQPqQc"
    "RR1RPqYcBa0J5WhQNH9KPoo6wznesn0L6qFBUZcYE2f9nOvxz9nPpOs/5zr8c67D5KOgdUYcttGgaPk55WhQ1BblF5SjYPuS"
    "fBRsX5GPonroY8B6XFMPDYoaYoQd4rqk+zigvSHtoUFRR5SPKUfB9oR8FGxPyUdRZzjHW+IXxKOoS4y1n1+jf9DH4DX65zX6"
    "5zX6h3I1xAhjtH7B8+4veN79BccR+aqLp3hG/DnxKGqL8gvKUdC6pBwNiuZfkY+ieuhjQPz1L9h+6qGoIUbYwRvqd6mPBkXt"
    "YR8HxA2pP6Y+GhS0JsRhGw2Klk8pR4OiznCOt9RbUA8NirrEmHjrda4fr3McvM44yOuMg5Cv6TrxKKpL+SnlKGidUY4GRfPP"
    "yUdRW5RfUI6C1iXlKJq+Ih5F9dDHgPjr1zluqIeihhhhB2+o36UeitrDPg6IHxKPoo4oH1OOgtaEchRNT4lHUWc4x1viF8Sj"
    "qEuMdb++wX5AD30M3qD/3qD/3qD/KFdDjDCmnvVLjr9fcvyRrv+S4+mXfH6Rj4LWGXHYRoOi5eeUo0FRW8RdUI6CJ5fko+DJ"
    "Ffkoqoc+BsRfsx5oUNQQI+I6xKGgdUO52iUO233SKGgNKEej6SFpbI9Jo6A1oVydEocyx1u2d0EcGhR1qfv/V+z/X7H/f8X+"
    "/xX7n3wUtM6IwzYaFC0/pxwNitoi/4I0mivSPga0d017aFDUEDuUd0n3cUA7Q9pBg6KOyB+TRjMlPSe90O14k/XF4E3W903W"
    "903Wl3I1ROvX9P+v6Wc8+zX9+Gv6kTgUtUXcBeUoeHJJPgqeXJGPonroY0D8NfEoaogRdljfLvEoffKH5GN7TBoFrQnl6pQ4"
    "lDn5C/JV6zf062/o199wXP+G45p8FLTOiMM2GhQtP6ccDYraIv+CNJor0j7pa9Id0l3SfRywvCHLQ4Oijsgfk0YzJT0nvdD1"
    "+y3r8VvWg3TrLfY/+hi8xf5/i+P5LepRroYY4Rxvqb+gPhoUdYmtt1k+Bm+z/LdZ/tssn3I1xA7lXdJ9HNDOkHbQoKgj8sek"
    "0UxJz0kvSLvvsN7ooY/BO6z/O6z/O6w/5WqI0b/S3ru0g8G7tPMu7bxLO5SrIcbY6rBe6GPQob0O7XVoj3I1xAhHOMM53tLO"
    "gnZQ1CXG2HqP9UIfg/dYn/dYH/LVECPsENcl3cM+Dt5jv9MuGhR1RPmYchRsT8hHwfaUfBR1hnO8JX5BPIq6xBhbN/QP+hjc"
    "0D839A/5aogRxuh2aRc99DHocjx0aZd8NcQIezjDOd7SzqLL9tIeirrEGN33WT/00MfgfdbvfdaPfDXECDt4Q70u9VDUHvZx"
    "QPyQeBR1RPmYchS0JpSjaHpKPIo6wzneEr8gHkVdYoxuj35DD30MevRbj34jXw0xwljbE9pDHwOhPaE98tUQI5wLxwHxKEuM"
    "sfUBy/mAdkmHGGGH8i7pHvZx8AH77wPOd+JR1BH5Y9JopqRnOCd/QXqJMbY+ZL0/ZL1Jhxij9TvuR37HfsNTPPsd9xe/4/6C"
    "eBS1RdwF5Sh4ckk+Cp5ckY+ieuhjQPw18ShqiBF2WN8u8Sg97FM+pBxlRP6YfBS0JpSrU+JQZjinfEE5yhJj8q3fsx9+z34g"
    "7f6e+8Pfc39IOQpaZ8RhGw2Klp9TjgZFbZF/QRrNFWkPffKvSYcYYQdvWG6X5aJBUXvYxwH1htRDg6KOiBsThwYFrQlx2EaD"
    "ouVTytGgqDOcU74gvcRY99sf6E/00P8D/UY6xAhjrdenHvoY9Dn++7RDvhpihPM+xx/xKEtsfUT7H9Ee6RA75HdJ97CPg4/Y"
    "Tx+xn4hHUUfkj0mjmZKe4Zz8BeklxtgasL4D1pd0iNGQeIz+jTS2RtQfUZ90iLH679Qfk8boP0hja8J+Qh+DCfdBE5ZDvhpi"
    "hLGmp6Qx+k/S6M5YLnroYzDj+JixXPLVECOMNf1fpP+b9j+m3Y9ph3SI0f8Qj9H/kkb3j7SDHvp/pD3SIUYYa7059dDHYM72"
    "zWmHfDXECOdzjn/iUZbY+oT2P6E90iF2yO+S7mEfB59w/H/C8U88ijoif0wazZT0DOfkL0gvMUb3lvVGD30MbumfW46/W7aL"
    "cjXEaEH7/0e7S9pbUo90iPGfMMY/085fSP+Vdj6lnU9ph3SI8ac6X3V9tR3oY7Dy5HplGw2KGmKEI5zhHG9pZ0E7KOoSY3Rr"
    "K1vooY9BjfWrsX411o9yNcQIO8R3iUfp44B2h8ShQVFHlI8pR0FrQjkaFDyZUo4GRZ3hHG+JXxCPoi4x1n6z6Tf0MbDpL5v+"
    "Il8NMcIY3Trtooc+BnX2R512yVdDjLCHI5zhHG9pb1Fnu2kXRV1ijG6D9UQPfQwarGeDfmiwvpSrIUbYwRvqd6mPBkXtYR8H"
    "1BtSDw2KOiJuTDkKWhPKsY0GRcunlKNBUWc4x1vqLaiHBkVdYoyuS3+jhz4GLv3t0t8u/U25GmKEsbZ7QrvoY3BCuye0e0K7"
    "lKshRtjDEc5wjre0u6BdNCjqEmN0v8L6ooc+Bl9hfb/C+n6F9aVcDTHCDt5Qv0t9NChqD/s4oN6QemhQ1BH5Y9JoTaiPbTQo"
    "Wj6lHA2KOsM53lJvQT00KOoSY3SfoZ/RQx+DZ+jnZ+jnZ+hnytUQI4zR+uqqfn2lQTnFM8rPV7bRoKgt4i4oR0HrknI0KJp/"
    "RftoUFQPfQyod008ihpihB28oV6X5aFBUXvYxwH1htRDg6KOKB9TjoLWhHawjQZFy6eUo0FRZzjHW+otqIcGRV1iTLz1tVU8"
    "GhS07JUn2EaDouV1ytGgqC5xp8ShQUHrjDhso0HR8nPK0aCoLfIvSKN1SX1so0HR8ivK0aCoHvoYUO+aemhQ1BAj7OAN9bvU"
    "R4Oi9rCPA+oNqYcGRR2RPyaN1oT62EaDouVTytGgqDOc4y31FtRDg6IuMdbj5Fn2H3roY/As/fws/fws/Uy5GmKEsbZ7Srvo"
    "Y3BKu6e0R74aYoQ9HOEM53hLe4tTtp92UdQlxug+x3qihz4Gz7Gez7H9z7G+lKshRtjBG+p3qY8GRe1hHwfUG1IPDYo6In9M"
    "Gq0J9bGNBkXLp5SjQVFnOMdb6i2ohwZFXWKM7hn9jB76GJzRz2f08xn9TLkaYoSxps9JY/R3pNFtsXz00MegxfJbLL/F8ilX"
    "Q4wwVv+e5VywHPTQx+CC5VywnAuWQ7kaYoQjnOEcb2lnQTso6hJjdL/O+qGHPgZfZ/2+zvp9nfWjXA0xwg71utRDg6L2sI8D"
    "6g2phwZFHRE3Jg4NiuZPyEfBkynlaFDUGc7xlnoL6qFBUZcYo3tJ/6KHPgaX9O8l/XtJ/1KuhhhhjO4V7aOHPgZXtH9Fu+Sr"
    "IUY4wznxC9LuN1gOeuhj8A2W8w224xssj3I1xAg71OsSj6L2sI8D4ofEo6gjyseUo6gTyqesJxoUdYZz4hfEoahLjNH16Cf0"
    "0PfoH49+IV8NMcIY3W/SHnroY/BN2v0m/f5N2qdcDTHCOfUW1EOD4n6L5aKHPgbfYrnfYrnfYrmUqyFG2KFel3poUNQe9nFA"
    "vSH10KCoI+LGxKFBwZMp5WhQ1BnOiV8QjwZFXWKM7vP0H3roP0+/PU+/PU+/Ua6GGGGM1re53/829/vf5n7/29zvo4uneEa9"
    "c+qhQVFbxF0QhwYFTy7JR8GTK+qhQVE99DGg3jX10KCoIUbYIb5LPEqf/CH52B6TRlEnLH9KHBoUdYZz4hbE4Yn1HZ7jvsNz"
    "3HfYX2h/h/1GHBoU1V1pnRKPbTQoaJ0Rh200KFp+TjkaFLVF3AVxaFDUS+KuiEODonroY0C9a+qhQVFDjLBDvS710KCoPezj"
    "gHpD6qFBUUfEjYlDg6JOiJsShwZFneGc+AXxaFDUJca6/19gf6CH/gv03wv03wv0H+VqiBHG6Pq0ix76GPi079O+T/uUqyFG"
    "OMM59RbUQ3FfZLnooY/Biyz3RZb7IsulXA0xwg71utRDg6L2sI8D6g2phwZFHRE3Jg4NijohbkocGhR1hnPiF8SjQVGXGKMb"
    "0I/ooY9BQD8G9GNAP1KuhhhhrOlr/Afy0Q1ZLnrohywvZHkhy6NcDTHCWP1H2m/TPnroY9BmOW2W02Y5lKshRtjDEc5wjre0"
    "t6A9FHWJMbrfZT3RQx+D77J+32X9yFdDjLCDN8R3Sfewj4PvcrzSPhoUdUTcmDg0KGhNiMM2GhQtn1KOBkWd4RxviV8Qj6Iu"
    "MUb3JfoTPfQxeIn+fIn+JF8NMcIY3e/RLnroY/A9jqfv0S75aogR9nCEM5zjLe0tvsf20y6KusQY3e+znuihj8H3Wc/vs57k"
    "qyFG2MEb6nWph6L2sI8D4ofEo6gjysff57giDgWtCXHYRoOi5VPK0aCoM5zjLfUWxKOoS4zRjehX9NDHIKJfI/qVfDXECGNt"
    "z9Ae+hgY2jO0R74aYoRzw3FCPErrB7T7A9oh3SHdJd3HwQ/Ybz/gukAcijoif0wazZT0nPSCdOuHrMcPWQ/S1o+4j/0R962k"
    "XTzFsx9xv/kj7jeJR1FbxF0QhwYFrUvisI0GRcuvKEeDonroY0C9a+JR1BAj7OANy+lSD6WHfRwQNyQOZcRyx5SjQUFrQhy2"
    "0aBo+ZRyNCjqDOd4S/yCeJQlxuRbP2a/o/1j9jtp98c8n/yY5xPKUdA6Iw7baFC0/JxyNChqi/wL0uol+VekVQ99DIi7Jh1i"
    "hB28Ia5Luod9HLC+Q9YXDYo6Im5MHBoUtCbEYRsNipZPKUeDos5wjrfELUgvMdb99xP6FT30MfgJ/UU6xAhjdF+mHfTQx+Bl"
    "zrOXaY98NcQIezjCGc7x9mWOX9pDWWKM7iusF3roY/AK60M6xAg7eENcl3QP+zh4hePhFY4H4lHUEXFj4tCgoDUhDttoULR8"
    "SjkaFHWGc7wlbkF6iTG6r9Jf6KGPwavsx1e5L3uV/qNcDTHCWNP/RBqjfyaN7k9ZPnroY/BTlkc6xAhj9V+4bv2M69XPuB7h"
    "2c+43vyM6w1xKGqLuAvi0KCgdUkcttGgaPkV5WhQVA99DKh3TT00KGqIEXaI7xKP0scB5UPKUdQR5WPKUdCaUI4GBU+mlKNB"
    "UWc4x1viF8SjqEuMibN+zufTz9nPaP+c8bWfM75GHIrqEndKHBoUtM6IwzYaFC0/pxwNitqi/IJyFGxfko+CJ1eUo0FRPfQx"
    "oN419dCgqCFG2CGuS7qPA9ob0h4aFHVE+ZhyFGxPyEfBkynlaFDUGc7xlvgF8SjqEmPt99foJ/QxeI3+eY3+IV8NMcIYrV9w"
    "nP2C4+wXHF/kqy6e4hnx58SjqC3KLyhHQeuScjQomn/1C44TylFUD30MqHdNPIoaYoQdvKFel+WhQVF72McBcUPqj6mPBgWt"
    "CXHYRoOi5VPK0aCoM5zjLfUW1EODoi4xJt56nevN6xwHr/Ne1uu8l0W+puuvc/2hHorqEndKOQpaZ5SjQdH8c9pHg6K2iLug"
    "HAWtS8pRNH1Fu2hQVA99DKh3TT00KGqIEXbwhvpd6qGoPezjgPgh8SjqiPIx5ShoTShH0fSU9UeDos5wjrfUWxCPoi4x1v39"
    "BvsFPfQxeIN+fIP+I18NMcKYeOuXHJe/5Lj8JcffLzn+KMeTU/LRoKB1Rhy20aBo+TnlaFDUFnEXlKPgySX5KHhyRbtoUFQP"
    "fQyod009NChqiBFxHeJQ0LqhHE+6pNFouk8aBa0B5WjwZEg+Gk2PSaOgNaEcT6ak0aDMKV9QjgZPrF9xv/QrjpNfcZz8iuvX"
    "r7h+EYcGRcvrlKNBUV3aOyUe22hQ0DojDttoULT8nHI0KGqL/AvSeHJFPTQoqo8B8dfEo0FRQ4ywQ70u9dCg9HFA3JA4NCjq"
    "iPwxaTyZUg8NypzyBeVoFtovb7Kdb7J9b7J9b7J9lFu/Zn/+mv2DZ7+m/39N/xOHoraIu6AcBU8uyUfBkyvaRYOieuhjQL1r"
    "4lHUECPs0H6XeJQ++UPysT0mjYLWhHIUPJmSjwZFneGcuAVxqvUb+h/t33Ce/Ybz7DfsF8pVl7hT4tCgoHVGHLbRoGj5OeVo"
    "UNQW+Rek1UvqX1EfDYrqoY8B9a6phwZFDTHCDnFd0n0c0N6Q9tCgqCPyx6TVCfWn1EeDos5wTvlC++e3bCf6v2V7SLfeohx9"
    "DN6iH94innw1xAhnOH+L44l6KO7bLA899DF4m+W9Tb+/zXIpV0OMsENcl3QfB7Q3pD00KOqI/DFpdUL9KfXRoKgznFO+IO2+"
    "w/aihz4G77C977C977C9lKshRv+K/49236Vd9N+lPukYWx3i0Megw/I7LL9DfcrVECMc4QzneEs7C9pBUZcYo/se64ce+hi8"
    "x/q9x/q9x/pRroYYYYe4Luk+DmhvSHtoUNQR5WPKUbA9IR8FT6aUo0FRZzjHW+IXxKOoS4y1n27oJ/QxuKF/bugf8tUQI4zR"
    "7dIueuhj0KX/u7RLvhpihD2c4RxvaWfRZXtpD0VdYozu+6wfeuhj8D7r9z7b/z7rSbkaYoQdvKF+l3ooag/7OCB+SDyKOqJ8"
    "TDkKWhPKUTQ9Zf3RoKgznOMt9RbEo6hLjNHt0Y/ooY9Bj37s0X/kqyFGGGt7QnvoYyC0J+wXoV3K1RAjnFNvQT00KDG6H7B8"
    "9DH4gOV+wHI/YLmUqyFG2KFel3poUPo4IG5IHBoUdUT+mDSeTKmHBmVO+YJyNCixbu+HbO+HbOeHbOeHbCflMVq/4/7sd9x3"
    "4dnvuK/6HfdVxKGoLeIuKEfBk0vyUfDkinbRoKge+hhQ75p4FDXECDu03yUepU/+kHxsj0mjoDWhHAVPpuSjQVFnOCduQRxK"
    "TNr6PfsB7d9z//x77p9/z/6hXHWJOyUODQpaZ8RhGw2Klp9TjgZFbZF/QVq9pP4V9dGgqB76GFDvmnpoUNQQI+wQ1yXdxwHt"
    "DWkPDYo6In9MWp1Qf0p9NCjqDOeUL0jH2k9/YHvR/wPbRTrGVp849DHo0y996pGvhhjhDOd9jjPqobgfsTz00MfgI5b3Efvh"
    "I5ZLuRpihB3iuqT7OKC9Ie2hQVFH5I9JqxPqT6mPBkWd4ZzyhW7ngO1Ef8D2kI6G7AeM/o00tkbUR39EfdKx+u/UH5PG6D9I"
    "Y2tCe+hjMKG/J7RPvhpihLGmp6Qx+k/S6M5YLnroYzBjf89YLvlqiBHGmv4v/G/a/5h2P6a9j9mej2mX8uh/8H+p90fWC/0/"
    "Ek+6NaccfQzmLGdOPPlqiBHOcD7nvKAeivsJy0MPfQw+YXmfsF2fsFzK1RAj7BDXJd3HAe0NaQ8Nijoif0xanVB/Sn00KOoM"
    "55QvSLu3bC966GNwy/besr23bC/laojRAv+Pdpe0i/6S+qTjP2FMvb/gX6n/KfXR/5T6pONPdZ6kxiqNUY00tuyVHvoYrGxf"
    "rzQoaogRxpquk8aoQRpdl+Wihz4GK0+uXZbvsnzK1RAjjDV9Qhqjr5BG9xmWjx76GDzD8p9h+c+wfMrVECOMNf1V0hh9jTS6"
    "z7J89NDH4FmW/yzLf5blU66GGGGs7Z7SLvoYnNLuKe2Rr4YYYQ9HOMM53tLeYmUbDYq6xBjd51hP9NDH4DnW8zm2/znWl3I1"
    "xAg7eEP9LvXRoKg97OOAekPqoUFRR+SPSaM1oT620aBo+ZRyNCjqDOd4S70F9dCgqEuM0T2jn9FDH4Mz+vmMfj6jnylXQ4ww"
    "1vQ5aYz+jjS6LZaPHvoYtFh+i+W3WD7laogRxurfk39BGqOvk0b3kvVAD30MLlmPS9bjkvWgXA0xwljTV/gN8tH1WC566Hss"
    "z2M55KshRhhr+pv4LfLRfZ7loIf+8yznebbreZZHuRpihLGmv00ao++QRvcFlose+i+w3BdY7gssl3I1xAhjdH3aRQ99DHza"
    "92nfp33K1RAjnOGcegvqoSzRfZHlo4c+Bi+y/BdZ/ossn3I1xAg71OtSDw2K2sM+Dqg3pB4aFHVE3Jg4NCjqhLgpcWhQ1BnO"
    "iV8QjwZFXWKMbkA/ood+QP8F9F9A/1GuhhhhrOlr/Afy0Q1ZHnrohywvZHkhy6NcDTHCWP1H8tukMfouaXRfYvnooY/BSyz/"
    "JZZPvhpihLGmv0cao++TRjdiueihj0HE9kcsl3w1xAhjTRvSP6D9H9LuD2mHdIjRj4jH6Mek0f0J7aCHPgY/oV3SIUYYo/sy"
    "7aCHPgYvs70v0x75aogR9nCEM5zj7csc97SHssQY3VdYL/TQx+AV1od0iBF28Ia4Luke9nHwCteDV7geEI+ijogbE4cGBa0J"
    "cdhGg6LlU8rRoKgznOMtcQvSS4zRfZX+Qg99DF6lv0iHGGGs6X8ijdE/k0b3pywHPfQx+CnLIR1ihLH6L+T/jDRGPyeNrddY"
    "DvoYvMZx+RrXgddYLuVqiBHGmv4FaYxeJ43uGywfPfQxeIPlv8Hy32D5lKshRhhr+pf4K5bzJu1j8Cbtv0n7b9I+5WqI0a/x"
    "N7T3W9Yb/d9Sn3TrLcrRx+AtlvsWy32LepSrIUY4wzne0s6CdtCgqEt032a90EMfg7dZr7dZr7dZL8rVECPsENcl3ccB7Q1p"
    "Dw2KOiJ/TFqdUH9KfTQo6gznlC90O99hO9HH4B228x228x22k3I1xOhf8f/R7ru0iz4G79Luu7T7Lu1SroYYY6tDe+hj0KG9"
    "Du11aI9yNcQIRzjDOd7SzoJ2UNQlxui+x/qhhz4G77F+77F+77F+lKshRtghrku6h30c0O6QdtGgqCPKx5SjYHtCPgqeTClH"
    "g6LOcI63xC+IR1GXGGt/3dBf6GNwQz/d0E/kqyFGGKPbpV300Megy37o0i75aogR9nCGc7ylnUWX7aU9FHWJMbrvs37ooY/B"
    "+6zf+2z/+6wn5WqIEXbwhvpd6qGoPezjgPgh8SjqiPIx5ShoTShH0fSU9UeDos5wjrfUWxCPoi4xRrdHP6KHPgY9+rFH/5Gv"
    "hhhhrO0J7aGPgdCesF+EdilXQ4xwTr0F9dCgLNH9gOWjj8EHLPcDlvsBy6VcDTHCDvW61EOD0sM+DogfEo8GRR2RPyaNJ1Pq"
    "oUGZ4Zy4BXFoUJYYaz98SD98yPZ/yPZ/yPZTHqL1uwbf29OfeIpnK0/OV7bRoKgt4i4oR8GTS/JR8OSKdtGgqB76GFDvmngU"
    "NcQIO7TfJR6lh33Kh5SjjMgfk4+C1oRyFDyZko8GRZ3hnLgFcShLjMm3fs9+QnvlSX1lGw2K6hJ3ShwaFLTOiMM2GhQtP6cc"
    "DYraIv+CtHpJ/Svqo0FRPfQxoN419dCgqCFG2MEb6nepjwZF7WEfB9QbUg8NijoibkwcGhS0JsRhGw2Klk8pR4OiznBO+YL0"
    "EmPd739gf6CH/h/oP9IhRhhrvT710Megz/7o0w75aogRznDe5zinHsoS3Y9YLnroY/ARy/2I4+Ajlk+5GmKEHeK6pHvYxwHt"
    "DmkXDYo6In9MWp1Qf0p9NCjqDOeUL0gvMdbtH7D96A/YTtIhRkP8N+pja0R99EfUJx1ijNGYNEb/QRpbE9pDH4MJ+2FC++Sr"
    "IUYYa3pKGqP/JI3ujOWihz4GM46DGcslXw0xwljT/4X/TT62Pqb9j2n3Y7brY9qnPMTof6iP0f+SRvePtIse+n+kPdIhRhhr"
    "vTn10MdgzvrNaYd8NcQIZzifc95RD2WJ7icsFz30MfiE5X5Cv3zC8ilXQ4ywQ1yXdA/7OKDdIe2iQVFH5I9JqxPqT6mPBkWd"
    "4ZzyBeklxrr9t2w/+rdsJ+kQowX+H/WxtaQ++kvqkw4x/hPG+Gfa+wv+lXxsfUq76H9Ku6RDjFXb5ft+fAafxTOX7ydJY/R3"
    "pNFtuXw/6fL9pMv3ky7fT7p8P+ny/aTL95Mu30+6fD9J+xirf4+X6OHz+AIG1L/GfyAf3ZD1RA/9kPULWb+Q9aNcDTHCWP1H"
    "fAkj/Am+Sr1/Io3RP5NG96esH3roY/BT1ot0iBHG6r/ga/gGcf+K/4/lvMty0MfgXfrjXfrjXZZLuRpifIM9/BD/wPKGpDH6"
    "N9LYGrEe6I9YHukQY/XfaWdMGqP/II2tCe2ij8GE7ZqwHPLVECOMNT0ljdF/kkZ3xnLRQx+DGf06Y7nkqyFGGGv6v/C/ycfW"
    "x7T/Me1+zHZ9TPuUhxj9D/Ux+l/S6P6RdtFD/4+0RzrECGOtN6ce+hjMWb857ZCvhhjhDOcrH30euXweuXwesb6fsFz00Mfg"
    "E5b7Cf3yCcunXA0xwg5xXdI97OOAdoe0iwZFHZE/Jq1OqD+lPhoUdYZzyheklxije0s/oIc+Brf0wy39cEs/UK6GGC3w/1gO"
    "tpa0j/6SdkiHGP8JY/wz7f0F/0o+tj6lXfQ/pV3S4af6OdDkeov/gv+Of8IY/9xkufhX8rH1aZPlNlluk+U2WS7xK2s126k3"
    "3KZqWdtpO1W+jqvZdpm4suV5cZquO+XiHq2X00hYYz3tiuuZXl4ttb1WzcnuFyflXX59E5/bn8TbTs56OfvXO70+dkG7dmo/"
    "WjWrVq/QX3Vntbz6bj9sHxeN7PXc7Sdne32cxPFY3+1HPU4z16+e3K7VcZDZf8Qlyy3H2uovx3H2H28l+zdRvpXetFtDJ7Ne"
    "vW7Xk+v9KL6WjN9z/NnJ/WDr+ZFa7/R22/b2cXDwdjdWNhp2Y+u4KjjO95x/Of1XuZ291z1Nb45LZ3M+N5obrVS8VfY8TZ83"
    "efllrs/13HbX5db6fMjsRz3OHx1nW/XW53lqf6+PDyf7upu4/m656rdHz2ZZ1tP9uynfrr/p/4zPJa2n21vLKd9pP+dzbrO8"
    "etH2ENfc5G/2z+o6c7c+Wf3i3O83Z93viXp3Oizfud8PdTcZ92g77VR8c6f/t66jef1/r7OKW+3XBvmN9fVS21kdF87u8e5u"
    "9XNt67xJ9rOzdT7qftLlpo/L/OM+o/8Ty1nHOevy2v7jv87nWn1Vr36/vXWtp9fh+io/cX4468+7zXFhN1L96K7T6uo8stfX"
    "58bW59+6XqORff6l+6XRaGQc57v90rg/LhpNa3VdbnC+uHqdbjS2PzeTnx+b/tysX+71wd7eHi1/tJqHtdtIXf+d7eMu73qb"
    "cR3X/muWuq9bXzedrevd7nVDy1f3U5bllLrvLf58sDPvD+q1su2n6iXvJzLvb3ev53uuf43UdaSx9/qyPg6bzZzyvOv6ut28"
    "+wdrc/9aS/SnW3S/nLccvZ7nLUf3c9n9sKl3f32pP7rOVNoPB32eZl/37Z3ypJbuH2edbmzfN9+l1/vRTnzurfP1Pryu1/e7"
    "+xCraTWb63acu/3ouPs+x/d+Tmd8ztvZnzeb4zdrve7r1evJuFq9tl0vp7/t++Nlcx1N5rvp++7Nedi4j3cffW64GdfNI/TH"
    "/Xrp9bzw/jdVr55fb6t/i59LS7e7//ptZY877F7fND7v/jrvfqXovtytJZd/t+UucStrtX3rVfQ8k398OSm3j7v842QV7+Q8"
    "n+9e/9yS17/150htVf7oM/qR7srE9Sm7P9Lrt2f8wN5//XPv+73U/ewqXdv6fHJtd52u3Xm/vrWd5z6ue4+2UNd/fZ43qN+4"
    "3/7VceDqej06Puru5vzQ8/w+zs06ztyS53m6/1fXvU3/u/S79r+7t57ex+6OK2z2X6OR/zmSUX5/XV1d91bPMbbN/Z/z6Hlh"
    "9XnyqC+czf2l466vv+nPoeT+TuQ7aTfr7zjr6/qjvrhfH/vRY1ji+KnVWF6tXnid3Xvertb3/jzU+9Li475Eu5nXxf33g8Xj"
    "lbnPX4een8nz5NHZ4aavl0XHXWo8y90Zz9p7f+Nkfg67OeNc7mY9iz5vDz4Pt56fEsftUY4HPR8254uTOm/tzPNDxwsScfb6"
    "vqbE80L+533R8VO4Xbv3ZRnjbrVNe7XMcTmL63t6HG77+YxxmPX+c1frYbv7xq12+jfZjuWk29v6vNwan3qUcT9O06zvPE+l"
    "4lb30XXGKZp6v9FcjS/UH/Xmfft6v91c9WdT71t5fl6Pk9c39ZxVu3XUdO5zcc5z8/ZxeVffyjkOrC33PH8l2qvvjOvlfU9x"
    "166b/T2Fzf18Yjn1wu8pEsdNI3Ff5W72Q+p7i+3n+8bm+4rt8QHuHzbHTYN042480G5kHX/ulqvtvGt/db9hsbz769j9cl2u"
    "e43keZA6f2r6/JXXv6nvAR49p22N12zO+zrPS+n+uHuOre/UWz8f6zheY3vcKnUeN9b5ifGeu36yt/uzse4Ha9UPtvYP/XFw"
    "P6zHyRur8THLamT1w+rzvplz3VqPm7s79ZzteF3vg9vNGQ/L+16irFvnRz1j/NU+rL3NuEzqup8aZ0iMz22NQya+j6vtHL/1"
    "Et9TpJ4ji76v0e9DNvcjTtZz7c73jenve/OWu9HJ/n40/X1o+jqT146V8blcP7zd1Hhabjt2qh0dTy+/XZa1tR6NvP7auU6U"
    "Ox5zzo/NuLmTug6sl29lHY+Fy3X2L1e3s8T6Z/dDTZ9jt65zje24ZtX7pcZdfIPvb9zN52Ej735pR2tz3736XHIS44WJ+6Xs"
    "63SjlnOd2FwXM8d73N3Pq9T3f+n7nnS9ne818+6P9t8npcdX0vdB1etnxxe3lzhu6tvXWe3/nfvRfTrpcWFn+77X2hofXt//"
    "pI+DTX7J48lJteM468/7rfbyP/e3nyPW/bI+H6zk+aDjIhW226pbie3fXLfsvc8rievIVn9Y998XN3L7zdm/vYnrSenlV4nP"
    "up4l16d0e1bB9b34ec/euu4d6fpj515/WA93NY63vr9lvRLjwrabuI7VUvcpVm3re2M393vTgvM6/3vOvOuFmxOnz1WrccTN"
    "+WfVyi0n776efna13bLPUdwHFF5HnNX9fuF1ZOc5qqbXkWrPUe7W95S725F6/mE77sdiDtl+1b4fx9z+fm7rer4aV928n7F5"
    "Pyl1Xdl/PU5eVxLtb23/Znxpz+fF+nPGvr8u3m1nc3O837VvWbqe9d37n7zzfes9kWby+rG6XtJfpduzUtdpK/O5wNXnjoPP"
    "Z8fO+dzO+7zerK/LfnrYcVTq+bvM51L54yfj/HlUlnOfvT5/Gnr/uvc+u8rnUz35+bQ6Lu16xvfd+84nPY6t3ef3rf7N/Vx0"
    "nAOPy53tyH4/MefzYjcuY/xx6/tvm/HHvLj7++faZpxyb3l2XHO9nPvP2Tr3Uc7qupI1Dmsnxlfzy5tNOzm+e798x9n5Xqmx"
    "GQfV9dukNT7vc3R7PL7o/n2rf9fuvt9r1ZrJ8Sg3b9y0lrkfm+vx2EQ/2en7ZzcxjrHbn9ZWuY4/bvXnzvfszYxx1e33kgvH"
    "la3c7/n39lt6vHTn+20rNQ5tZb/XvXU8rvt/9/3SzXh28r3f5vq97cT+2nlPbH28leqndD/svpe/fX3N3j579Z5p6nyxs46T"
    "jPsle89xsipvNDKPk0b17a9tjSut3wvMPe7K9Wct570Ra/29RfJ7reZuv+eOzyW+R0u4835gU9+bcAreC0+229z+3Qrfi7q1"
    "xPls7b7fu/2ck319XOevPq/v3hi2t9YvZ/xUP4fqjpP6PUv2e9GJ9Vt/jiTjst/zbmZ8Dif3S/2uP5up72ftrPe/9H3OR+eF"
    "lX2flf0+ybr/EtfN9Hrf369u4nLa2W5v/R5x6e29W29rs935x+Fhx2/++9p2xvP07nlUdry56nqur6s548a5y0/f396/V1e6"
    "no771kovJ+99JJ4jtz537Yzn0OzzdHN+brd39+5/tX5I9UfCxkHtOdnfC+Q+92/fF+VdJzPv4/b9/sba875B9vU4e9yY/D3v"
    "69rb30ttXxeLfg+45/uhvfeLRe8XF73Pvue9y8zlFj9/FnxflXo/bv1cmbN/c74f2Nq/jRK/o8r/nVbu8bj1+7cKy9/7OzEr"
    "//0Be9/3i7txbm3f/fDmeHRKnhebz7lH9w377ic292/bcdxPb8bVkuXp91433xO5ta31zD1vUvdn6e3PPb7d1H14/vOWXmfd"
    "1PuijaznosT2uZt6O89FG7ev47vjqQWu99/+/V7iPdSC84z1zThe3K3j0tn7PvTOc0beOHLu7yXdzfszeb8zyBg35P1R5265"
    "ln6v1Nwen8nML76/KxgnrnZ/l98Piefd+u775cX1i86HjW6l88/d/9xZ+ri2ss9byyl5nKTr550Pqzi3sTn/y12/U98fZLw/"
    "/pDjYef+je8Tirc3sd06zthM9Xu9yvlibb+flnGc7d1vVtnjMWN/1/PvGzbjb0cbJ3zQ+5P3/dGsN7fen6w3U+tZ8j3Qtc19"
    "38vbWeNH+b9zqSfGu5rJ9yHt+vY4X857kc3mXb3mvdnvRSbHdZLHt9Nw7n9/7GT8vizj+TmxvL3fAzYz7z/zxvcau+MyWeN7"
    "zUc2m5v7s/T8BU3GXfaM79XKvWe6il/3Z2q+gc17eo5Ta7jJ33ff9/P980Vt9T3z6vcGtfu4Ws75ou3ZO/enOeN7jp23fXaV"
    "7btf19z3aJs7v4OvF/zeK2NehpzjjnFEJ/t3jTvnh50aRyjzvmG9zPibnRqv4/crjI/lnX/3x+HdetyNSyXimoxTafn6fUWb"
    "du9+D3M3LvBoux99cq/7o574fbTN+5X29n62d8aP9o4jpcevs34Psjt+1+R7iOLxO2sT10hcb611fzjWeryn2cyav2H//VUq"
    "Pr2fm3r9SY8vWdvfC6evR+vv0bKPC71+5I2H3f1+Nef9wE37zT3tJ/u30nrrcp3UvDiPrnx344VW8vqzqqfXkftxS+suLuN7"
    "4JLn0877POXf+3WS8wkcsr8aWe9JllzvonHL5HwN9+N1BeNySXPGMbPHpQs+Fw8dJys730DmOFlz7zhZLeu6ljVe5taS4wF2"
    "jedpe3Ndsxu1Wvr3slXHzXZ+/9E8bPzs0Hb2r0fG9cvW5wLGD5pu3vWtuft7x0T/l3sv835/Jq7bd8dZvbn/9/3N3ffut65/"
    "eh3fp6XLvfsFSHP9+/7NdbBo/oSd86K2vz933LlvT50/mcvJGA9Mv4fSLDUemdN+4XZatlNqO/U6nhGXfb/z0PHz1ThC7nuP"
    "qevC3bleT40bVhxHr/iec9H4t1sw/p13/m//biN3eXnjd5Wff1Ljepvfs5cd18s/XptZ+9t1yq3v9nN++Xp532/sPOdUHYc/"
    "cDty9qe193emGctz8j7ntsfFnd3PNzdnvpm8cSZ3y93yvPG1VL3c68dqfa11/FO9f3I+p2oF43W1fb/n3f89S+H3VY2CeZGS"
    "40/7x7923z+r8fmd/j10/vN43vtX6flEnJx5LFO/40yNC9Tric+x+/VpNvV8qO3/nq3aOEbquf5o4xhO5XEMezNekT2OUbGd"
    "7eMqdZ6s9wfjDPr+Yu7vGLn/1vGB7fcpmpv65ccH7K3n8Iz3Bbbfwyj7XL15TrWqPWfaFZ8zi+a/O/A502pWfM5Mvn9e/Pu+"
    "8u1t3R+UeE+hlrzvre8+r9n1zM+l3PshO/N94eT9fPr5o773+aOWmB+s8P58z/f2RffpdpX79Ixxsb1x2+/hVaqXed++NR9r"
    "pft35yj378nn+tVxodf5yu/B2O4Rf690vPv58r9fajzo/t6qHfl7+4L7e6v5sPt7q3bY/f2m/np/NwvmEcy4TtibcYZy3++v"
    "xxlKzQ9V/LukWmJ8Pz1u3XTX4xn73u9pZLw3uXO85Y8L2o28+XYe8P5Z6d8DWmV/F1h0HOx/b+zh711VfZ4o2f8Fz39W6vNy"
    "9zktfb1wit5Ly/heuZk739Ix7z+zvi9MfI9g1x/TfUvm/BN578UVfz7b2df7xH3Hgedh/cvz8Mmdh3ue8wvnp90Z/97zvkKF"
    "831v/oHtWrWc3+8V7Ycjv0+7538NSo3TZL7f9rDfx1V6z7n88sqN8xa//+w4xxnndbafs488zlt9fa1ayX4td93Je1+84vXm"
    "8OMzff9dal6CPfMx2TnjCA/83jn3vYJq36sX/x6o2vfqu7/DKfk5n/N7sMzxpqP8Hiz7vZb834Htf+9l63ffj+G9F+sB43LZ"
    "++Hw/Z313ktuu0d67+Xh651+78U5eDzyQcd5xfHI452fVvPA9bbL/F7v0Pv6PdfZ5pHva0p9L1+4PoX5RfcV+98bKb6fqVq/"
    "aLnF47YF98vl3yupP+S9kvTvNI77XkmJ/V6rNw7arvT7N/uPH+uwcerKx23xcV2uvaf9fq30vMRF8+g9bNy48nxXDx4vflzP"
    "CVbzYc8Jpfsjd7y4XmaewZzx4sT140HjxTvz/Bx5vDjzeN4zPlU0LlX43FJ43GePM/3NP+/lfR4dOK5UOD5QNN5TOP9quflZ"
    "jzafZlE7OfNpbtbPKTOPl5v7nFl1/qvS40FOznyrzoHjSuvrl/ug8aO8fjtwPvnHPQ/iZt65Q7cjPQ+iUzDPde78dW79kOPH"
    "Sc2/9sD56yoe9zvz11Ve74J55A4+jx6zue9ZVh7Pyp2Hu7F3/OrA59jC+Ucqzvv+eZ/vvez6lT+/S873fuD87dXjC4+zzPne"
    "Sy/PKTdf0uHjLgXn+2d/P7F/vurC+4mK618+vuR9ZtX7ibL1DnyeLZqP9G90vvbc+X4L5mvf6Zeq87WXPZ7y7ysOmq+98vHv"
    "VDz+S87XfvD5dOj1qep92Xp+52M9j1iNA9f7yONTuc8b1lHGow5+7ni65l8//LkjdX9x6PzrVsX5oo88//qm/YrjVun5163s"
    "+ddLnwcl518/+LzKfv/dfXzjB/vnWz/8uPkCP69mzLde+fzJmW995z76cT4n10u8N1U4b1v18fxy46fZ89lufqfmHHl+K2d9"
    "HJaeH+oo74dVfW+s2vyASR/H/IAlnitqpeZ/ewzHWZn5AQvfL7NK9nvZ48TKvL5WmffN/WzPC+5jCrd3/7xrlfvrMc0LXfZ9"
    "oCrzQmfPp+LwP57HmS953Z5V1E/r46SRNa/7/vfD6kef1zx/frWne17zRH88VfOaP47j90HrufN7i9LHp7V3XLVkvUPnNX9c"
    "5+l6nvTK27N/XvMH9+vT8l5+7vtsT+o9+wOX87T357HfXyhqv1YQX3i/V+0+qFZ72p4PnAf6ebuvL9kPT+i+vlY79n19Rnml"
    "eYzT8yE/3fN+5/dDuXm/Dz5PHvrcULQeB87z/QSf96yn/nkvY57v6udH9jzf1oHzfFfaX3V37/3tZ/r7w4PnaXroONOhvy88"
    "cL6vL+DvDx80j9mTPi7z/5fzsOPVOnie2yf+O8IHzadb/fdyW/MpP8nf+R11fusvf+e3mj/s0PmtP8fnzzHnt37w+fj5/b3f"
    "gfPqfu5+B3j4vNNf/j5w6/eBR51veue8+Ix+z5peXtXj/2m5j3pi9+tln8u/nAckczz4ab0PP/b9+UOf7/aMo/xNPAft+f3d"
    "IfM355+PD5u3uczv+BolrzeNKuNjFX5v6T7lv7dsNCr04xHno2hkzINsPaZ5kB8y74j1BZt35Nj7uZ49TlBtvt2K8xtbx57f"
    "+CmcL+Kg/nzar0Ofg3kjHja++8WbN8L9gs4bsW9+4aJ5hb+cN+IxzROYe59f8T5o9zmi2jyFFefxffB8Xznz91b+HCo5b++X"
    "86L8jc6Lkrufqs2rkvv/szn56Xmb8+LKlufF2SWXl/gfm/Tzr53zf7xV13Prex2d/3lnngMn27x207/7z5tnvGp/5bWb/r8f"
    "u7E9H3hRP+1Zn739s/N7LyfnPW3H3nu/uLte9YJ+3G5/+3+Mkv/H5BynP1Pt7847X6u4XrVaah71zHkgqu6nx3bcOAcfN3aZ"
    "87Ds8ZeeZ333/2uK/vcwO76WG+eUur7lzf++W389f30ta97+jP+HLLs+O9/r7xs33P6faX7vfwQz/zfzgLjy/VzUvpP8Pa5L"
    "f7vp/3+r1fb87+f+9drb78n/XXFL9fd6/oVaIr+h632frm3ijtAftX3XzeO376aue27F9XJ3rpsVj2P7wOPPfrzHn1t74PFn"
    "J+OLrhfVt/ew627+/4ccdh22cj5Xinx87RfW+6yuy3biOtE44nU5uf8aZfvlM2i/qF7J63KJ/t753WKq3yu8B1JLSb6TNiPO"
    "Xo+fr34P+Shd32nvCPuhtv96Unm9avXadr2c/s47fu0Djxv7MR+X9gOPy/z+PcLxnn99zotzDrr/fvh9bq124PrYD/j8bzx9"
    "n/+1o33+fzb3n/frW3t895/12uO9/6zVDrv/rKXqZ7wnuP/zwy7zOZBxXb+/ruZ/nrglP0+czfewj/rifn1s175vn+t0rcby"
    "avWHHY/1esb16jjHeS3//+gOfl5+HPfNm+e09HXyy+eeoz/31FPPr4eeZ7Xy9/2fyXPXvv87zp1fd/v9nRrfI9USv+fIidv8"
    "32b6/eSM8j1xq/+vvf/+o164PHvTTuJ/l2mnSXlzE5fYnrLred/OJj6//9bLTZj+P63072f2Pwel26vv1LMz7/Oa+8bvM//n"
    "tOT1KLGcZq3svM2p9ztS23X3eZ3VT87e7UqPN2X0V+2g/toZn6/zfFJ2fZq1/PWv3v9HPw6cg4+DvPH4g46nsv9bmvifWDv7"
    "f9dtp8z3lg/9H/c94+yZ/2Nb4r6h1PhW4f/C5rwfm///fe5B5+0h6/Ow+tvf+1dfrlUrM55o1Sr+D+9Of+f9/mj7+/edcqvg"
    "/xUffj7Uku+T7B3XSLfbLGi3WWq8M31eFK2Pvb8fi/5Xuuz/T5eLK7F8Z+f/y5qZ/2tW/PuuZnP3/deHjQtW/11ZznLL9lvi"
    "+aPqcvb/D9wD91OF9X/Q8Vc2fuv4r/C5cfzPr2btwM8v+8leTw/9HLNqD/scO7T+9nu6h3+OJd7ra1Y/zx9wfSgzblT9Pd2d"
    "36Gu3tPN3O/J9xgLf/ebd/4/9H7NqfT/FJ/f+5Xs/XfQ8dPc9/yYe5+a/bux4v+vPNL4xd321kuMC+TG6fjF3fX5frzGcbLH"
    "1+/q2Ylxnfzy5jpusz3l1vP+Pcmt+NK/z8h47nT3PafnPPdl/Y7Qvm/vzrztT8St5k3PjLO3xjPdRNzm/C1av1otPX/Yk+qf"
    "VHs5/8du5bRXS/+PzgO3f3ueq/Lt1WtPYH83qm9vrZb1PeRDj59a7nvVbi33OKp2X5fzebUp13kX9X1nt7Zq161t92cqbj2u"
    "ofM0Zpdvx+n6Fq+fmzMult0v+Z9vTuH7cg+ajy4nbnc98j6vD9ue/HKr4L4ivR7p5efdd1q1z7YfV/P65a9H/jwJ5frfecLj"
    "iQ9r7/GPIx42TnJo/aLn76L1Lz6fyl53PtvrYuJ4rbR+tdzz13nKr4N5902f9XUwrVur9Pur9XOOe+jvUB/L/Ljl90P2vLjF"
    "11Gn4PcPGx/2ef/A63rh+fA3+DlY33Zdr9LxmT2vba3qfMRV9lc9871B+/P3fkD+c3u2zUO+533s3/enn5uynqeyzPnev/mF"
    "+N6/oeWOU9uZJ0qfZ5PvvdXu47Lf629+nt77KPpd6YOOp4z7wLL3vY/9e3y3lryPK3r+3bj//vnw7+9L/Q9wxjyEn/fv+ffO"
    "z5aYJzJzfrbHsB/qx9gvX4Dv+1PnT43zx14/b5U4f57E9/1l5yXdmd/uy+//M7//P+o8rxW/bz/Wex4POC6eus+1KuvxOD/P"
    "vpjvoTklf0d1vM+nvO+9H3Z/89D7kvzn+Kfz8z7/e/BDtj/v984PuM/beu48zvvtx3m/t5H/vdoh71M3tZ3a39j71I0jv0/d"
    "ONL7Lm7B+xmNx/Tei/uE3ntplNjeY77fWvG+N/P/BB7ynmWj8fl6z7JxWH89be9bNg993/LJnhdf3Pct3S/o+5aNPf267zxs"
    "fPm+5dF+H5K8T8+cB7Xw8zn5fUUz9/enx/49V9X3PTPut6t+7pSb//TL94b/pt8bzk9Xe+84/bvEY89f+tD5UutO2fkEC+vt"
    "HR/OG08omn80r17RvKZ1Z1WvXnLexD3xD5qXda2VM59qI/t6mzU/ZiNjuy3H2krbR5oPtuxxsSfeLtVPm/k+q22nnT3P6BG2"
    "0z4w3i41n27V/sr7n82c+cDz3gPLPb9S9ez6/nnqVv1d35wv6eNus3/Kxdu7/dbY2d7teSoaGf1RdV6tvP8d3X5fvJ5qr7n9"
    "Pc2j/O24+no+j9XvJDbt5Fmi3qP+sVPxzZ33iu7On/LzsNgNzo/N/GaaTmvlXq+25pNJ97PO35teTiPneClaTvp4SB+P6eXk"
    "HpeNivUaqfc5tvq5RD+ujm97vdy8fmlknxePvV/qu9ffUvX0vLW3t+fo/e0cON+nVfI+IuN3GY2982tu/w/Bsef9LH8/5pT6"
    "HNk3zp8x72R6vs5G8fxszr7yvHmH1u3mfV6ml+PmtlduOXrdLlpO2fvFEvWON+/nPp2c/Iz/ZWhsXz8aid9DrXUTn3+J+7DN"
    "fnCcrfvT4v1Xbf7Xssd/iXqZ32dU6Mf7ecJy7kvz+8N+8HyflberYr2tecKKn78OW5+d67NV9B5A0fXVeVzXV/vA+IJ5P3Ov"
    "jwXzfq7inZzryWdwvbMfeL2zP+PrnZ28Tz3keucWnN9uxv3J035+F80HWst6T6rOc5u96g/bpj+cu3kK78ffHvVF4nrn7J8P"
    "tNE4aH7prXJ9HkrPP/qg/knMB5r+n5Ej9Lt97Pu3kvMyV74feVzX/8f1Oet+Xj9n61vnS6n5QDOP+1r5543P5HM+/b5Czv+l"
    "bd2PWsn2bDfVjrv+vby19b8ia7fHX9bvHa1+X1/i9zsreQ5dj0szPlW/22ref3KS7zPVS9erp+rnfT+z+72YlZ5vIe85J3F8"
    "1ffMB8r67Z13uF4m3s4ej2w0Evmu1cj7Pzhnaxwp6//1Gsn93iDduP9dSCPr+dVNzdeQaKdB/zXulusyHtHg+G9kPBetj7tG"
    "wfyqVqqfVuOZrp05ftEsXy813lG6HxP17/qpbD/c1XOfxn7IGQ9M7r9j9G+6/SLX8+bYlevp9xO1rO8Dt/4Prb5nHJ36hfGp"
    "cfT0vJA733fVU+thZad35pe0co7Tkq7vx62c4+qB7T0gzq60fU615VvOgevlVIuznCP3g+rabsb1IuO6vv9zPzW+2tj8Dnh1"
    "naolnmMr/A7KXf9e2tL2UvcN2de7Ri3n/Kylzjdrfb+efd2qJeerLFNv53ytOl9U+r0Dq+T/YDl74/Lr7/2/16LPf7fo8z+9"
    "//iexa1yHGS1s863Cj//Kx3HFeL3X1fy6m1/3+SW3k7nSNvpVNzOPdef5Poc3G95FtTfuZ486etFfb1eh10v7MJ5C+1S53HF"
    "8764vaNdH+wndH2wGxnjiAdcH+wDj/OV9v3/4GT8jzfv4Vqrcbh1vrN5H+Tg60T6/bq77a1XfM+u5HqW7hc9zzbbt+4n9tPD"
    "+tnKvD92j/V5Xvpz9FjXxy/S50o91W913luqcjze9Z+VcX/sFN+3H+3zrL7n8yz3upo1vrX1f4d75qWtF8yHU688b85D/8dn"
    "M59sxu8Iq9Ur+786Rb+n3fTn2ubO/6g3a82999+743H1vP/zSaxP3jhes2Acr1kmvuA95pz7rVR/JMaHdr7nc7PeV7VS45tW"
    "9vuqh/7fUX3v/7U3y8TbZf5PQ7e79HY1H/Y/Tvu/V2hWjM98T+Og/sn9n51m9v9XFb2vunWcZc9PsvV+1t3Ieta8uLnnXXO7"
    "3fv9UndzzzudH7twXI52CuObO+NyW9cxa/f/aDfnV725E5dZP1luZZdv+q1g3hjLbub+nib3Pdnjr6+dFb+/nr33eGs88Pi0"
    "Ct7bt3a+J7ErjzPn/B6gynpuvx/arD7eWbJe4r7HrjKeeITttA/cTvux9JtV8L9jVu7vYDKvc3nzPOT+76LlHHU+4b2fp/VS"
    "8dXGC3Lvw5yCeYLTvx+rWj97ueXHP/Pul3LfP7Lrleb12uzfxt7feRR8n5J/PO6cRyWXX+p+oOx6VF3fneOw8Hxwjn0+2Aee"
    "D0cdt6t6XB8+jleUfuzH+3GOt6Lf3VvZv5+3m5v3Te5/525pejOusJVvredfK/M+XHWtPfMD5G1/8j0UK+f3vFbledwP+jwo"
    "e3393FzHkvuluXc+leL92Mx/Dt2zHtvz3CXfP/jcjfMcPj9y2fernsT4TPb8tnc/HHCazr1V5kv+2xun2Tf/b8Mpmk96uz8q"
    "j9M8+fGnot/DP6h/1su3Sz/fpa7vFcZZmqlxluYRxlnszTjLo317H5/8/zPnLk28ze+O7Z33oJqVxx/2zivyGY6DZP3eOft/"
    "ITJ+5/cFHwdJnid6f5r6vivTiuMhTsXxkCc97lP6fbkH9d8XaFxk3zyorlNuHtTP0/hI3nysqXlX989X/hSOm5R4fyR/fvyM"
    "8/CxjOcceX2rj6c88fHFUvNffWbjgp/X8cAncLwW3Ec+6Dr60OvS5+b83zPeUDRf9N55pB/eD1vP5cd5j+M47zs0jvT9d+OY"
    "7wfYT8/7AY0jvx/QyLq/TX4f3iz1vXmznniuO+b3w40jfw/Y+IJ8f9p4TN+fNo40vlzyvjrz+MwaV208ZePNx1jvz/P3Z+7n"
    "5Puzxt/Y92eNL/j3Z42M8a0q3581vvz+7OD3AHbnrU79f1L562HO/NWp3+se+T3J9PcLZd8jeuj7SFW/R6ztmxf7y++P/2a/"
    "Py7Mr/g99OOaf9quPm9z5vHiODv/H5T5P7HreXrrjw7TjP+JTc8zlv6dSuX5jHPmbbYL5jNO/6+QzndwNydEzv+2HjTfc9G8"
    "0lXnjU4fT+v9Uq84z7CT/b8Cq/nTnEPm292OXy3f0fVT7+Z8WR139VXc6jip63vUetzU/397V7YdOQpD2fn/P56ibHYJJMCp"
    "pKfSDz7pGGywEGi5VybqtQo3xueRjfyqMx5ZIr+utZbEI2tluM8G+9bez1E3X6295ew9DluMa4mXt14/iUf29ZpH+lVMXtW4"
    "nqr1P+BNotY/DFVSgpyY6zqt36hL3igL8kapVI+pxoGheTMIP9fFo5e/c/X3Vp/leXrzANmOn2ufF7TcJ22UN/o8X+3MpB2D"
    "H4vV74wH8xy/sJvwX6Y6IFVdYHfzeQD1PZd5iZk8mBNeNi7vryPyYOoSX/z6u3PXc5yr697pVZ49TeP9dcmuGfNepnmTFS/z"
    "9f2u32VxH+JXCAx6BQ+mxXh/XXyvu/+4LuL6Dv9j3PX7YP4H37md/2u/zPLoZCO3w3Yv/exm5zMmH6Fe4v3V6tR8vPdXV+gX"
    "mjzS+JN7fXem30Gd2CV9gs3T/nqM389pppyZT8mZe1DO7JNyVvFe6lXeS1J9aQnV231KzvG6ThePoefzRgK8k0AdNcPhd6zO"
    "EZHvIc9HUzc32VHhXGpivNJmu662X7h8j1yewhlfo7zPu2id3eSnCudTG8ZjkfoUv4OncNJ/vBb+CxovYGcna5jnT2jwGu1c"
    "0clJZX8WPBlNP0SeQDKPHnLN9qzWkJ/y9but4rVCH3nuqX6m/DNh/zE9v8jMzkXjZRCPSuGvSH7FyL9T8qiUPLyi8Ufa1k88"
    "51FreGgufp99Hjfy8zn3Q1eED2a5PyaP8lF+M4Xym+nMA+lyfqm53ytIorOVXcDjT+r9eUt5ffO6l6ker4Pqj8/z/BpeM+cc"
    "rB/v58T9sNWPU94lffH0TvnNxGWvxf1Shh0vnDev/TTz/eoh72+2D7Fx1OeBvD/M2iHjF6RzBEVfbPE+Bs8VvG+kcVuT+8H1"
    "/bLeONdfOS59bB3O1kW+umI8f10u7CfkwjRyscZrBvKKqW6eH5RH07eLcXeV96E770Lrrn4ImBd63Zfvr+3vqt/Onwrlh2rQ"
    "7xrXTYEX7erDwfF/uD9s/4j9hvgKJV/Uag34E1XKT1CFHWvh+wqcWnufSnGcklcfnk/e+FP8ZrM/2fnFq7i8jXmllT0L2EOd"
    "HXvbY+X3sm8/kunqbY7zS8t+DN2emtgVWR9e9Rao7aI9JMnPwfzU9zki50FdeDAgz96W+hDFiV3fK8Rgl+YBuJ7o7xQeZXZ+"
    "/K14DJHiQwN9BeCBKXmjJY4j9+PCv0oPNfeluFQ8B1d4ENfiQK773vED0+etzvVVM/6pXSEmdkiNPynjPvc5RXV1TWRZ36Q9"
    "/9/n/HSt111v72hSfdTZdyfEkyZ5qvf7AvLigHWJxTW7/RGz8wRmH47Hme0AQVx3ehrfo/FTa/g+Ad9HH2+j51bbA/vw3jrr"
    "r0vyC4zvKw+T7xntBd+0L+2JaZ6hRvCR/O+19P54vudRvhtFrCemcj8y813c9oq/88h8vm8BD9e+70G+G9PgzsyEr6PU9693"
    "Dbyi7yuYZ0jF6ekxL7GXEx4cD+I2EF4cSeTFCfzOvsRLNXmb/sY1aK0x/phxfKoax5uf1cN5liFO57u8tNjO3O2wuPSz/Dj0"
    "8QWbgSYnPJ6c3X4K/prn+XEMnR/n4hf3oZ0v74tyEuTPl/FAKh8x6Gd/nh8njWfKjyNavKa840w+4YiSvb2EAx3jJL33MK5S"
    "1HUoWv2T/F6wPLx+Jjw5wiNxy9y/Z/RPfu/43Ns/4U2hDzjj1R/hzbF2ddyI33abP+dwfxhP92T/W+XRyftG5aen8X/4IR5U"
    "QnqM4HeR5fsbvB2TT6eLB/o1Xp3VfsbvMe8f5X+QQ5ymhHBDhV4O8mT8GHdU4Tdv/Z5xnqrCe2LXhPMMGUf+rYeC7i1woFj9"
    "euz8Jw2MD834Ncr4MBzc/RzAP9fGhTzJP4f0Px2nIM/HQzw/TsK4bw2uc1es1ybP/EN8P26C98bXGy9PwG3aLY2/zbP9bbhc"
    "eoK/DX1fIWl5FpNx4vbJpv+b/j7g90Tyb3D+ol15Jua1CGp+yx+fd2SfWcDDNvXpNem7tjxGZ/w2Dsnn5flH7BjHOvYTGNxP"
    "IP9RP4E97CewI9wqldeouNa8Rvv2rCXl8fLtOvERu85+zK6zD9l19rC944h2ggX06s452do/cE7GeJ6m+9K/d252f+Hc3O0z"
    "h8/P7t87P7tffo6zxPOW/Z6nP2rHOJAvlff9cH4l/WjcpudX0j/in23lkrrPcO2R77r4N+1M9PcVOxWTkz3eHjWPu2Z+HmVq"
    "Ppo2b5nN32Kb99dTPK46zOeB85ZVVyPzukz5Eza+v3z9LOKOFXJdxderh/D1CsbXay6+vuFxaHkg2Ph6tcTjoNp5Ps3j4I7I"
    "w0F8u2LyOTz/fNPom+I8kfTNafw1om863IzexgGD/pBqPAZ+ziLOFH6eafdNIfL4fMv7bG+8EwcXpEb1dxP+bhWnptq62tT6"
    "rafwajd+lItX04t4NX0Ex2gTz7BWPJxXh/Pfxo1N1oF+/nnVub3Al1X6zFT2utWreCYpoXzoDoeU5PNej9t4F2FHeBc6T6gm"
    "5eVK+el88/rcsJ5vLuRevnnbHss3v+7j55u3+PWn880vXPl8vM24yfne8HxL6vfZeY7pcaoc/8WJ+ow7fowTddpG/gyQdzvz"
    "b/thXZkNP8eJumrLdYEG671ph87H9b4i3f/X/IQrdYAo3/1EfaGNuHxRX8jvxOUVkV+65tma5u97OcrfX6435Ef1hjbi83qZ"
    "J19t+oMVi1eamh/vW7tiOz5f59dj8Xl23nWdt/3T9Yf2866FX61DdMivP6ybsBGfV5T84SI+CtYBWIjPt3m/ipIfuhCnV5w4"
    "PVpPAMtXxewRZrvz9Y548Xvfxe+9XK17ZB6pe7Qbz5/Vl8W+CzeuH+Xwp/Jihd+L68d54cbNWvvpt9RbckQcga7qkKRridvy"
    "LuX7D+uigPVmGnkj15thx00VL24K+l834qdCjuKn5+rVcO0G4vzP45ZqiPcltgfrjdLin4frOWn9k+eSbn8X7H1Ywfr9u+6+"
    "647R/sn1jNZh+yXxSUgfTNbxj8Y1bBPXANbHj/pXKXkwh/1FEv+7suO8N2WZckvMf/vuR9/96P+zH53Lr2vqGv6ufQv1K7T+"
    "8If2y/8At9Tpbg=="
)

if __name__ == "__main__":  # pragma: no cover
    print(generate())
