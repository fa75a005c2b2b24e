"""Triangle mesh files: OBJ, PLY, OFF and STL in, OBJ, PLY and OFF out exactly, STL out with a warning (§11).

Reading goes through ``trimesh`` without processing (``process=False``: no vertex merged, moved or dropped;
OBJ is read here, since trimesh splits its vertices by texture coordinate),
after the checks the 2-D readers make (docs/adr/0015): a regular file, at most
:data:`~mrm.core.limits.MAX_FILE_BYTES`, and the triangle count the header declares (PLY, OFF, binary STL) or
the file's size implies (OBJ, ASCII STL) within the limit, all before any decoding. The result becomes a
:class:`~mrm.geometry.polyhedra.Polyhedron`, validated exactly: an invalid mesh is refused with the file's
name and where it is wrong; :func:`~mrm.geometry.polyhedra.repair` is the user's explicit next step.

STL stores every triangle with its own three float32 corners: the corners are joined by exact equality of
their values (the format has no shared vertices; nothing is rounded or moved), in the order of first use.

Writing is exact for OBJ and OFF (``repr`` of every float64, which reads back as the same float64) and PLY
(binary little-endian doubles); STL holds float32 only, so :func:`write_mesh` returns (and logs) a warning
when a coordinate does not survive the rounding. Every write is atomic (:mod:`mrm.io.atomic`).
"""

from __future__ import annotations

import array
import io
import logging
import os
import re
from collections.abc import Callable, Iterable, Iterator
from itertools import pairwise
from pathlib import Path
from typing import Any

import numpy as np
import numpy.typing as npt

from mrm.core.errors import FileFormatError, InvalidGeometryError, MRMError
from mrm.core.limits import MAX_FILE_BYTES, check_output_bytes
from mrm.geometry.polyhedra import MAX_TRIANGLES, Polyhedron
from mrm.io.atomic import atomic_open
from mrm.io.reading import open_regular

log = logging.getLogger(__name__)

PathLike = str | os.PathLike[str]
Floats = npt.NDArray[np.float64]
Ints = npt.NDArray[np.int64]

#: Extensions read by :func:`read_mesh`.
MESH_EXTENSIONS = (".obj", ".ply", ".off", ".stl")
#: Extensions written exactly by :func:`write_mesh` (STL is written too, rounded to float32, with a warning).
EXACT_MESH_EXTENSIONS = (".obj", ".ply", ".off")
#: The bytes at the start of a PLY file read for its header; a longer header is refused.
_PLY_HEADER_BYTES = 64 * 1024
#: Fewest bytes an OFF face takes: "3 0 1 2\n".
_MIN_OFF_FACE_BYTES = 8
_PLY_SIZES = {
    "char": 1, "uchar": 1, "int8": 1, "uint8": 1, "short": 2, "ushort": 2, "int16": 2, "uint16": 2,
    "int": 4, "uint": 4, "int32": 4, "uint32": 4, "float": 4, "float32": 4, "double": 8, "float64": 8,
}  # fmt: skip


def _name(path: PathLike) -> str:
    return Path(path).name


def _extension(path: PathLike) -> str:
    ext = Path(path).suffix.lower()
    if ext not in MESH_EXTENSIONS:
        raise FileFormatError(
            f"{_name(path)}: unsupported mesh file type {ext or '(none)'!r}; use {', '.join(MESH_EXTENSIONS)}"
        )
    return ext


def _refuse_count(name: str, what: str, count: int, limit: int | None) -> None:
    if limit is not None and count > limit:
        raise FileFormatError(
            f"{name}: the file declares {count:,} {what}, more than the limit of {limit:,}; "
            "nothing was decoded"
        )


# ---------------------------------------------------------------------------------------------- headers
def _check_stl(data: bytes, name: str, limit: int | None) -> bool:
    """True for a binary STL (after checking its declared count against the size and the limit)."""
    if len(data) >= 84:
        count = int.from_bytes(data[80:84], "little")
        if len(data) == 84 + 50 * count:
            _refuse_count(name, "triangles", count, limit)
            return True
    if data[:5].lower() == b"solid" and b"facet" in data[:4096].lower():
        return False
    if len(data) < 84:
        raise FileFormatError(f"{name}: not an STL file: {len(data)} bytes, shorter than a binary STL header")
    count = int.from_bytes(data[80:84], "little")
    _refuse_count(name, "triangles", count, limit)
    raise FileFormatError(
        f"{name}: corrupt binary STL: it declares {count:,} triangles ({84 + 50 * count:,} bytes) "
        f"but the file has {len(data):,} bytes"
    )


def _check_ply(data: bytes, name: str, limit: int | None) -> None:
    head = data[:_PLY_HEADER_BYTES]
    end = head.find(b"end_header")
    if not head.startswith(b"ply") or end < 0:
        raise FileFormatError(f"{name}: not a PLY file (no 'ply' … 'end_header' header in its first 64 KB)")
    lines = head[:end].decode("ascii", "replace").splitlines()
    fmt = next((ln.split()[1] for ln in lines if ln.startswith("format ") and len(ln.split()) > 1), "")
    counts: dict[str, int] = {}
    sizes: dict[str, int] = {}
    current = ""
    for ln in lines:
        parts = ln.split()
        if len(parts) >= 3 and parts[0] == "element":
            current = parts[1]
            try:
                counts[current] = int(parts[2])
            except ValueError:
                raise FileFormatError(f"{name}: corrupt PLY header: {ln.strip()!r:.80}") from None
            if counts[current] < 0:
                raise FileFormatError(f"{name}: corrupt PLY header: {ln.strip()!r:.80}")
            sizes[current] = 0
        elif len(parts) >= 3 and parts[0] == "property" and current:
            # The least each record takes: a list holds at least its count (faces: count + 3 indices).
            if parts[1] == "list" and len(parts) >= 5:
                n = 3 if current == "face" else 0
                sizes[current] += _PLY_SIZES.get(parts[2], 1) + n * _PLY_SIZES.get(parts[3], 1)
            else:
                sizes[current] += _PLY_SIZES.get(parts[1], 1)
    _refuse_count(name, "faces", counts.get("face", 0), limit)
    _refuse_count(name, "vertices", counts.get("vertex", 0), None if limit is None else 3 * limit + 3)
    if fmt.startswith("binary"):
        need = sum(counts[k] * sizes[k] for k in counts)
        have = len(data) - (end + len(b"end_header"))
        if need > have:
            raise FileFormatError(
                f"{name}: corrupt or truncated PLY: its header declares at least {need:,} bytes of data, "
                f"the file holds {have:,}"
            )
    elif sum(counts.values()) * 2 > len(data):  # ASCII: at least a digit and a separator per element
        raise FileFormatError(f"{name}: corrupt or truncated PLY: it declares more elements than it can hold")


_OFF_COUNTS = re.compile(rb"\s*(-?\d+)\s+(-?\d+)(?:\s+(-?\d+))?")


def _check_off(data: bytes, name: str, limit: int | None) -> None:
    lines = (
        ln for ln in data[:_PLY_HEADER_BYTES].splitlines() if ln.strip() and not ln.lstrip().startswith(b"#")
    )
    first = next(lines, b"").strip()
    if not first.endswith(b"OFF"):
        raise FileFormatError(f"{name}: not an OFF file (it must start with 'OFF')")
    rest = first[: -len(b"OFF")].strip() or b""
    m = _OFF_COUNTS.match(rest) if rest else None
    if m is None:
        m = _OFF_COUNTS.match(next(lines, b""))
    if m is None:
        raise FileFormatError(f"{name}: corrupt OFF header: no vertex and face counts")
    nv, nf = int(m.group(1)), int(m.group(2))
    if nv < 0 or nf < 0:
        raise FileFormatError(f"{name}: corrupt OFF header: negative counts")
    _refuse_count(name, "faces", nf, limit)
    if nv * 6 + nf * _MIN_OFF_FACE_BYTES > len(data):
        raise FileFormatError(
            f"{name}: corrupt or truncated OFF: it declares {nv:,} vertices and {nf:,} faces, more than its "
            f"{len(data):,} bytes can hold"
        )


def _check_obj(data: bytes, name: str, limit: int | None) -> None:
    # OBJ declares nothing: count the face lines (a k-gon becomes k − 2 triangles, at least one).
    faces = data.count(b"\nf ") + data.startswith(b"f ")
    _refuse_count(name, "faces", faces, limit)
    vertices = data.count(b"\nv ") + data.startswith(b"v ")
    _refuse_count(name, "vertices", vertices, None if limit is None else 3 * limit + 3)


# ---------------------------------------------------------------------------------------------- reading
def _read_bytes(path: PathLike, name: str) -> bytes:
    """The file's bytes, at most MAX_FILE_BYTES; the buffer is sized by the file, not by the limit.

    (``read_regular`` asks for limit + 1 bytes, which allocates a 1 GiB buffer for every small file.)
    """
    with open_regular(path, name) as fh:
        size = os.fstat(fh.fileno()).st_size
        if size > MAX_FILE_BYTES:
            raise FileFormatError(
                f"{name}: the file is {size:,} bytes, more than the {MAX_FILE_BYTES:,} accepted for a mesh"
            )
        data = fh.read(size + 1)
    if len(data) > size:
        raise FileFormatError(f"{name}: the file grew while it was read")
    return data


def _decode_obj(data: bytes, name: str) -> tuple[Floats, Ints, list[tuple[str, int]]]:
    """OBJ's ``v``, ``f`` and ``o`` lines, read here: trimesh splits a vertex per texture coordinate.

    Only the position index of ``f a/b/c`` counts; negative indices count back from the last vertex; a
    face of k > 3 vertices becomes the fan of k − 2 triangles from its first vertex (as trimesh and most
    readers do). An ``o NAME`` line starts an object: its name and its first triangle are listed (the
    regions of ``mrm polygonize``'s label meshes). Every other line (``vt``, ``vn``, ``g``, ``usemtl`` …) is
    ignored.
    """
    # Compact buffers (8 bytes a number) and a line iterator: memory stays proportional to the mesh, not
    # to Python objects per token.
    coords = array.array("d")
    faces = array.array("q")
    objects: list[tuple[str, int]] = []
    n_vertices = 0
    for number, line in enumerate(io.BytesIO(data), 1):
        parts = line.split()
        if not parts:
            continue
        if parts[0] == b"o":
            objects.append((b" ".join(parts[1:]).decode("utf-8", "replace"), len(faces) // 3))
        elif parts[0] == b"v":
            if len(parts) < 4:
                raise FileFormatError(f"{name}: line {number}: a vertex needs three coordinates")
            try:
                coords.extend((float(parts[1]), float(parts[2]), float(parts[3])))
            except ValueError:
                raise FileFormatError(f"{name}: line {number}: a vertex coordinate is not a number") from None
            n_vertices += 1
        elif parts[0] == b"f":
            if len(parts) < 4:
                raise FileFormatError(f"{name}: line {number}: a face needs at least three vertices")
            try:
                raw = [int(tok.split(b"/", 1)[0]) for tok in parts[1:]]
            except ValueError:
                raise FileFormatError(f"{name}: line {number}: malformed face {line[:80]!r}") from None
            idx = [i - 1 if i > 0 else n_vertices + i for i in raw]
            if 0 in raw or min(idx) < 0 or max(idx) >= n_vertices:
                raise FileFormatError(
                    f"{name}: line {number}: a face refers to a vertex not defined before it"
                )
            for k in range(1, len(idx) - 1):
                faces.extend((idx[0], idx[k], idx[k + 1]))
    v = np.frombuffer(coords, dtype=np.float64).reshape(-1, 3).copy()
    return v, np.frombuffer(faces, dtype=np.int64).reshape(-1, 3).copy(), objects


def _decode_off(data: bytes, name: str) -> tuple[Floats, Ints, list[tuple[str, int]]]:
    """OFF's vertices and faces, read here: trimesh fails on faces of mixed sizes.

    The header (``OFF``, then the vertex, face and edge counts, on its line or the next), the vertices'
    first three numbers, then each face's count k and k indices (a colour after them is ignored); a face
    of k > 3 vertices becomes the fan of k − 2 triangles from its first vertex, as in OBJ. ``#`` starts a
    comment. The counts were checked against the file's size before (:func:`_check_off`).
    """
    rows = (ln.split(b"#", 1)[0].split() for ln in io.BytesIO(data))
    rows = (r for r in rows if r)
    first = next(rows, [b""])
    head = first[0]
    counts = first[1:] if head.endswith(b"OFF") and len(first) > 1 else next(rows, [])
    try:
        nv, nf = int(counts[0]), int(counts[1])
        coords = [[float(x) for x in next(rows)[:3]] for _ in range(nv)]
        faces: list[int] = []
        for number in range(nf):
            row = next(rows)
            k = int(row[0])
            idx = [int(x) for x in row[1 : 1 + k]]
            if k < 3 or len(idx) < k:
                raise FileFormatError(f"{name}: face {number + 1} has fewer than three vertices")
            if min(idx) < 0 or max(idx) >= nv:
                raise FileFormatError(f"{name}: face {number + 1} refers to a vertex that does not exist")
            for j in range(1, k - 1):
                faces.extend((idx[0], idx[j], idx[j + 1]))
    except (StopIteration, IndexError):
        raise FileFormatError(
            f"{name}: truncated OFF: fewer vertices or faces than its header declares"
        ) from None
    except ValueError:
        raise FileFormatError(f"{name}: corrupt OFF: a count, coordinate or index is not a number") from None
    if any(len(c) < 3 for c in coords):
        raise FileFormatError(f"{name}: corrupt OFF: a vertex needs three coordinates")
    v = np.array(coords, np.float64).reshape(-1, 3)
    return v, np.array(faces, np.int64).reshape(-1, 3), []


def _decode(data: bytes, ext: str, name: str) -> tuple[Floats, Ints, list[tuple[str, int]]]:
    if ext == ".obj":
        return _decode_obj(data, name)
    if ext == ".off":
        return _decode_off(data, name)
    try:
        import trimesh
    except ImportError:  # pragma: no cover - depends on the installation
        raise MRMError("reading mesh files needs the trimesh package (pip install trimesh)") from None
    kind = ext[1:]
    try:
        loaded: Any = trimesh.load(io.BytesIO(data), file_type=kind, process=False, force="mesh")
        vertices = np.asarray(loaded.vertices)
        faces = np.asarray(loaded.faces)
    except MemoryError:
        raise FileFormatError(f"{name}: not enough memory to decode this {kind.upper()} file") from None
    except Exception as e:  # trimesh raises many types (ValueError, KeyError, IndexError, struct.error …)
        raise FileFormatError(f"{name}: corrupt or unreadable {kind.upper()} file: {e}") from None
    if vertices.ndim != 2 or vertices.shape[1:] != (3,) or faces.ndim != 2 or faces.shape[1:] != (3,):
        raise FileFormatError(
            f"{name}: no triangle mesh found in this {kind.upper()} file "
            f"(vertices {vertices.shape}, faces {faces.shape})"
        )
    return vertices.astype(np.float64), faces.astype(np.int64), []


def _join_equal_corners(v: Floats, t: Ints) -> tuple[Floats, Ints]:
    """STL: one vertex per distinct point (exact equality, -0.0 = 0.0), in the order of first use."""
    if v.shape[0] == 0:
        return v, t
    w = v + 0.0
    _, first, inverse = np.unique(w, axis=0, return_index=True, return_inverse=True)
    order = np.argsort(first, kind="stable")
    rank = np.empty_like(order)
    rank[order] = np.arange(order.size)
    return np.ascontiguousarray(v[first[order]]), rank[inverse.reshape(-1)][t].astype(np.int64)


def read_mesh_arrays(path: PathLike, *, limit: int | None = MAX_TRIANGLES) -> tuple[Floats, Ints]:
    """The vertices and triangles of a mesh file, as stored (STL corners joined), not validated.

    Parameters
    ----------
    path : str or path-like
        An ``.obj``, ``.ply``, ``.off`` or ``.stl`` (binary or ASCII) file.
    limit : int or None
        Most triangles accepted, checked before decoding from the header or the file's size.

    Returns
    -------
    vertices : ndarray, float64 (n, 3)
    triangles : ndarray, int64 (m, 3)

    Raises
    ------
    FileFormatError
        Unsupported extension, not a regular file, too large, a declared size beyond the limit or the file,
        corrupt content.
    """
    v, t, _ = _read(path, limit)
    return v, t


def _read(path: PathLike, limit: int | None) -> tuple[Floats, Ints, list[tuple[str, int]]]:
    # read_mesh_arrays, and an OBJ file's objects: (name, first triangle) each.
    name = _name(path)
    ext = _extension(path)
    data = _read_bytes(path, name)
    if ext == ".stl":
        binary = _check_stl(data, name, limit)
        if not binary:  # "facet normal … endfacet": two "facet" per triangle
            _refuse_count(name, "triangles", data.count(b"facet") // 2, limit)
    elif ext == ".ply":
        _check_ply(data, name, limit)
    elif ext == ".off":
        _check_off(data, name, limit)
    else:
        _check_obj(data, name, limit)
    v, t, objects = _decode(data, ext, name)
    del data
    if t.shape[0] == 0:
        raise FileFormatError(f"{name}: the file holds no triangle")
    if limit is not None and t.shape[0] > limit:
        raise FileFormatError(f"{name}: {t.shape[0]:,} triangles, more than the limit of {limit:,}")
    if ext == ".stl":
        v, t = _join_equal_corners(v, t)
    return v, t, objects


def _object_parts(v: Floats, t: Ints, objects: list[tuple[str, int]]) -> list[tuple[str, Floats, Ints]]:
    # Each OBJ object's own vertices (those its triangles use, in their order) and triangles. Triangles
    # before the first object form one named "" (none when there are none).
    starts = [(name, first) for name, first in objects]
    if not starts or starts[0][1] > 0:
        starts.insert(0, ("", 0))
    out = []
    for k, (name, first) in enumerate(starts):
        last = starts[k + 1][1] if k + 1 < len(starts) else t.shape[0]
        if last <= first:
            continue  # an object without faces
        own = t[first:last]
        used, local = np.unique(own, return_inverse=True)
        out.append((name, np.ascontiguousarray(v[used]), local.reshape(-1, 3).astype(np.int64)))
    return out


def _solid(v: Floats, t: Ints, limit: int | None, what: str) -> Polyhedron:
    try:
        return Polyhedron(v, t, limit=limit)
    except InvalidGeometryError as e:
        raise InvalidGeometryError(f"{what}: {e}") from None


def read_mesh(
    path: PathLike, *, limit: int | None = MAX_TRIANGLES, object_name: str | None = None
) -> Polyhedron:
    """Read a mesh file as a :class:`~mrm.geometry.polyhedra.Polyhedron`, validated exactly.

    Parameters
    ----------
    path : str or path-like
        An ``.obj``, ``.ply``, ``.off`` or ``.stl`` file.
    limit : int or None
        Most triangles accepted.
    object_name : str or None
        The name of one object (``o NAME``) of an OBJ file to read alone: the regions of a label volume's
        meshes (``mrm polygonize``) share their common faces, so the file as a whole is no solid.

    Raises
    ------
    FileFormatError
        The file cannot be read (see :func:`read_mesh_arrays`), or holds no object of that name.
    InvalidGeometryError
        The mesh is not the boundary of a solid (open, non-manifold, self-intersecting, inverted, NaN or
        infinite coordinates, zero-area triangles …): the message starts with the file's name and says
        where (and, for an OBJ file of several objects, how to read one). Nothing is repaired:
        :func:`mrm.geometry.polyhedra.repair` does it on request.
    """
    name = _name(path)
    v, t, objects = _read(path, limit)
    if object_name is not None:
        parts = {n: (pv, pt) for n, pv, pt in _object_parts(v, t, objects)}
        if object_name not in parts:
            held = ", ".join(repr(n) for n in parts if n) or "none"
            raise FileFormatError(f"{name}: no object named {object_name!r}; the file's objects: {held}")
        return _solid(*parts[object_name], limit, f"{name}, object {object_name!r}")
    try:
        return _solid(v, t, limit, name)
    except InvalidGeometryError as e:
        if len(objects) < 2:
            raise
        names = [n for n, _ in objects]
        shown = ", ".join(repr(n) for n in names[:4]) + (", …" if len(names) > 4 else "")
        raise InvalidGeometryError(
            f"{e} — the file holds {len(names)} objects ({shown}), which may be solids apart (a label "
            "volume's regions share their faces): read one with object_name=NAME (--object NAME), or all "
            "with read_mesh_objects"
        ) from None


def read_mesh_objects(path: PathLike, *, limit: int | None = MAX_TRIANGLES) -> list[tuple[str, Polyhedron]]:
    """Every object of a mesh file as its own polyhedron, validated exactly: (name, polyhedron) each.

    An OBJ file's objects (``o NAME`` lines, as ``mrm polygonize`` writes a label volume's regions) in the
    file's order; any other file, or an OBJ without ``o`` lines, is one object named "".

    Raises
    ------
    FileFormatError, InvalidGeometryError
        As :func:`read_mesh`; the message names the object that is no solid.
    """
    name = _name(path)
    v, t, objects = _read(path, limit)
    return [
        (n, _solid(pv, pt, limit, f"{name}, object {n!r}" if n else name))
        for n, pv, pt in _object_parts(v, t, objects)
    ]


# ---------------------------------------------------------------------------------------------- writing
def _as_polygons(t: Ints) -> tuple[Ints, Ints]:
    # Triangles as the polygon list (ptr, indices) the writers take.
    return np.arange(0, 3 * t.shape[0] + 1, 3, dtype=np.int64), t.reshape(-1)


def _used_only(v: Floats, idx: Ints) -> tuple[Floats, Ints]:
    # The vertices the indices use, and the indices into them: a vertex inside a face is in no polygon. A
    # mask, not np.unique: its hash took 2.5 s on 10⁷ indices, holding the GIL (the desktop froze meanwhile).
    used = np.zeros(v.shape[0], np.bool_)
    used[idx] = True
    if used.all():
        return v, idx
    return v[used], (np.cumsum(used) - 1)[idx]


#: Rows turned into Python lists at a time when a file's text is made: one ``tolist`` of a whole big array
#: holds the GIL for half a second (the desktop writes files on a worker; its window would freeze).
_ROWS = 1 << 16


def _rows(a: npt.NDArray[Any]) -> Iterator[list[Any]]:
    # The rows of a, as lists, a chunk at a time.
    for k in range(0, a.shape[0], _ROWS):
        yield a[k : k + _ROWS].tolist()


def _vertex_text(v: Floats, head: str) -> Iterator[str]:
    # The vertex lines, a chunk at a time. repr() is the shortest string that reads back as the same float64
    # (the 2-D vector files do the same).
    for rows in _rows(v):
        yield "".join(f"{head}{x!r} {y!r} {z!r}\n" for x, y, z in rows)


def _face_text(ptr: Ints, idx: Ints, head: Callable[[int], str], first: int) -> Iterator[str]:
    # One line per polygon idx[ptr[k]:ptr[k + 1]]: head, then its vertex numbers counted from first; a chunk
    # of polygons at a time. Plain lists, not one array per polygon: a label volume's mesh has millions.
    for k in range(0, ptr.size - 1, _ROWS):
        stop = min(k + _ROWS, ptr.size - 1)
        a0 = int(ptr[k])
        vals = (idx[a0 : int(ptr[stop])] + first).tolist()
        bounds = (ptr[k : stop + 1] - a0).tolist()
        yield "".join(head(b - a) + " ".join(map(str, vals[a:b])) + "\n" for a, b in pairwise(bounds))


def _obj_faces(ptr: Ints, idx: Ints) -> Iterator[str]:
    # OBJ's face lines (vertex numbers from 1); triangles alone by a quicker way (a fifth less time).
    if idx.size == 3 * (ptr.size - 1):
        for rows in _rows(idx.reshape(-1, 3)):
            yield "".join(f"f {a + 1} {b + 1} {c + 1}\n" for a, b, c in rows)
    else:
        yield from _face_text(ptr, idx, lambda _n: "f ", 1)


def _text_parts(v: Floats, ptr: Ints, idx: Ints, ext: str) -> Iterator[str]:
    # An OBJ or OFF file's text, a chunk at a time: a big mesh's text is hundreds of megabytes, and one join,
    # concatenation or encoding of it holds the GIL for a second (the desktop writes files on a worker).
    # Polygon k is idx[ptr[k]:ptr[k + 1]].
    if ext == ".obj":
        yield "# written by MR Modeler: exact float64 coordinates\n"
        yield from _vertex_text(v, "v ")
        yield from _obj_faces(ptr, idx)
    else:
        yield f"OFF\n{v.shape[0]} {ptr.size - 1} 0\n"
        yield from _vertex_text(v, "")
        yield from _face_text(ptr, idx, lambda n: f"{n} ", 0)  # each face: its vertex count, its indices


def _ply_bytes(v: Floats, ptr: Ints, idx: Ints) -> bytes:
    # Each face: its vertex count (uchar, or uint when a polygon has more than 255) and its indices (int).
    n_poly = ptr.size - 1
    sizes = np.diff(ptr)
    wide = n_poly > 0 and int(sizes.max()) > 255
    count = "uint" if wide else "uchar"
    head = (
        "ply\nformat binary_little_endian 1.0\ncomment written by MR Modeler: exact float64 coordinates\n"
        f"element vertex {v.shape[0]}\nproperty double x\nproperty double y\nproperty double z\n"
        f"element face {n_poly}\nproperty list {count} int vertex_indices\nend_header\n"
    )
    c = 4 if wide else 1
    out = np.zeros(c * n_poly + 4 * idx.size, np.uint8)
    starts = c * np.arange(n_poly) + 4 * ptr[:-1]  # polygon k's count, then its indices
    counts = sizes.astype("<u4" if wide else "u1").view(np.uint8).reshape(n_poly, c)
    out[starts[:, None] + np.arange(c)] = counts
    polygon = np.repeat(np.arange(n_poly), sizes)
    at = 4 * np.arange(idx.size) + c * (polygon + 1)
    out[at[:, None] + np.arange(4)] = idx.astype("<i4").view(np.uint8).reshape(-1, 4)
    return head.encode("ascii") + v.astype("<f8").tobytes() + out.tobytes()


def _stl_bytes(v: Floats, t: Ints) -> bytes:
    corners = v[t]  # (m, 3, 3)
    n = np.cross(corners[:, 1] - corners[:, 0], corners[:, 2] - corners[:, 0])
    norm = np.linalg.norm(n, axis=1, keepdims=True)
    n = np.divide(n, norm, out=np.zeros_like(n), where=norm > 0)
    rec = np.zeros(t.shape[0], dtype=[("n", "<f4", (3,)), ("c", "<f4", (3, 3)), ("a", "<u2")])
    rec["n"] = n
    rec["c"] = corners
    header = b"MR Modeler binary STL (float32 coordinates)".ljust(80, b" ")
    return header + np.uint32(t.shape[0]).tobytes() + rec.tobytes()


def stl_rounding_warning(vertices: Floats, name: str) -> str | None:
    """The warning for writing ``vertices`` to STL, or None when float32 holds every coordinate exactly."""
    with np.errstate(over="ignore"):
        rounded = vertices.astype(np.float32).astype(np.float64)
    moved = ~(rounded == vertices).all(axis=1)
    if not moved.any():
        return None
    with np.errstate(invalid="ignore"):
        worst = float(np.nanmax(np.abs(rounded - vertices)))
    return (
        f"{name}: STL keeps float32 coordinates only: {int(moved.sum()):,} of {vertices.shape[0]:,} vertices "
        f"were rounded (by up to {worst:.3g}); the file may not be a valid solid any more. "
        "Write OBJ, PLY or OFF to keep the coordinates exactly"
    )


def write_mesh(poly: Polyhedron, path: PathLike, *, triangles: bool = False) -> str | None:
    """Write a polyhedron to ``path`` (OBJ, PLY, OFF exactly; STL rounded to float32), atomically.

    OBJ and OFF get one polygon per face where a polygon can hold it
    (:attr:`~mrm.geometry.polyhedra.Polyhedron.polygons`: read back, its fan of triangles covers the face
    exactly), the face's triangles otherwise; a vertex inside a face is then left out. ``triangles=True``
    writes every triangle instead. PLY is written as triangles: trimesh, which reads it here (and in most
    Python tools), cannot read a binary PLY whose faces have mixed sizes. STL holds triangles only.

    Returns
    -------
    str or None
        A warning for the user when the file does not hold the coordinates exactly (STL), else None. It is
        also logged; the command line prints it, the GUI shows it.

    Raises
    ------
    FileFormatError
        For an unsupported extension.
    LimitError
        When the file would exceed :data:`~mrm.core.limits.MAX_OUTPUT_BYTES`.
    """
    name = _name(path)
    ext = _extension(path)
    v, t = poly.vertices, poly.triangles
    per_tri = {".obj": 30, ".off": 30, ".ply": 13, ".stl": 50}[ext]
    check_output_bytes(v.shape[0] * 75 + t.shape[0] * per_tri, f"{name}")
    warning = None
    if triangles or ext in (".stl", ".ply"):
        ptr, idx = _as_polygons(t)
    else:
        ptr, idx = poly.polygons
        v, idx = _used_only(v, idx)
    if ext == ".ply":
        parts: Iterable[bytes] = [_ply_bytes(v, ptr, idx)]
    elif ext == ".stl":
        if t.shape[0] >= 2**32:
            raise FileFormatError(f"{name}: binary STL holds fewer than 2³² triangles")
        warning = stl_rounding_warning(v, name)
        parts = [_stl_bytes(v, t)]
    else:
        parts = (text.encode("ascii") for text in _text_parts(v, ptr, idx, ext))
    with atomic_open(path, "wb") as fh:
        for part in parts:
            fh.write(part)
    if warning is not None:
        log.warning("%s", warning)
    return warning


def write_label_meshes(
    vertices: Floats,
    objects: list[tuple[str, str, Ints]],
    path: PathLike,
    polygons: list[tuple[Ints, Ints]] | None = None,
) -> None:
    """Write several meshes on one vertex list to an OBJ file, one object per mesh, exactly and atomically.

    The label-volume polygonization (:mod:`mrm.geometry.reconstruct.polygonize_3d`) writes its regions this
    way: each region is an ``o`` object (``objects``: its name, its group — the regions of one label share
    one ``g`` group — and its triangles, indices into ``vertices``), so a face shared by two regions is the
    same vertex numbers in both, reversed (as polygons too: ``LabelMeshes.polygons`` cuts a face where the
    region on its other side changes). Coordinates are written with ``repr`` (they read back as the
    same float64). Each object alone is a closed mesh; the file as a whole is not one solid (shared faces
    appear twice), so :func:`read_mesh` refuses it whole: read an object with ``object=NAME``, or all of them
    with :func:`read_mesh_objects`. ``polygons`` (one (ptr, indices) per object,
    ``LabelMeshes.polygons``) writes each object's faces as polygons instead of its triangles; a vertex no
    polygon uses is left out.

    Raises
    ------
    FileFormatError
        For an extension other than ``.obj``.
    LimitError
        When the file would exceed :data:`~mrm.core.limits.MAX_OUTPUT_BYTES`.
    """
    name = _name(path)
    if _extension(path) != ".obj":
        raise FileFormatError(f"{name}: several meshes on one vertex list are written to OBJ (.obj) only")
    n_tri = sum(int(t.shape[0]) for _, _, t in objects)
    check_output_bytes(vertices.shape[0] * 75 + n_tri * 30, name)
    faces = polygons or [_as_polygons(t) for _, _, t in objects]
    if polygons is not None:  # leave out the vertices inside faces
        vertices, every = _used_only(vertices, np.concatenate([idx for _, idx in faces]))
        cuts = np.cumsum([idx.size for _, idx in faces])[:-1]
        faces = [(ptr, idx) for (ptr, _), idx in zip(faces, np.split(every, cuts), strict=True)]
    with atomic_open(path, "wb") as fh:
        fh.write(b"# written by MR Modeler: exact float64 coordinates, one object per region\n")
        for text in _vertex_text(vertices, "v "):
            fh.write(text.encode("ascii"))
        for (obj, group, _), (ptr, idx) in zip(objects, faces, strict=True):
            fh.write(f"o {obj}\ng {group}\n".encode("ascii"))
            for text in _obj_faces(ptr, idx):
                fh.write(text.encode("ascii"))


__all__ = [
    "EXACT_MESH_EXTENSIONS",
    "MESH_EXTENSIONS",
    "read_mesh",
    "read_mesh_arrays",
    "read_mesh_objects",
    "stl_rounding_warning",
    "write_label_meshes",
    "write_mesh",
]
