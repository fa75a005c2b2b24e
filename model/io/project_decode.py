"""Reading a project file's JSON into document values, checked: every decoder names the JSON path it refuses.

The file format itself (its schema, migrations, writing and the entry points that read it) is
:mod:`mrm.io.project`; this module holds the checks of its values, one ``decode_*`` per part of the schema
(a box, a pixel mask, a label map, a ring, a geometry, a source, a style, a provenance, a georeference, an
object), each raising :class:`~mrm.core.errors.FileFormatError` with the file's name and the path
(``$.objects[3].source.shape``) of the first problem it meets.
"""

from __future__ import annotations

import base64
import binascii
import json
import math
import zlib
from collections.abc import Iterable, Sequence
from typing import TYPE_CHECKING, Any, NoReturn

import numpy as np
from shapely.geometry import MultiPolygon, Polygon

from mrm.core import limits
from mrm.core.errors import FileFormatError as FileFormatError
from mrm.core.errors import MRMError
from mrm.core.georef import GeoRef
from mrm.core.grids import LabelMap, LabelVolume, PixelSet, VoxelSet
from mrm.core.limits import COORDINATE_LIMIT, PARAMS_MAX_DEPTH
from mrm.document import DocObject, Geometry, Source, Style, validate_geometry
from mrm.ops.provenance import PROVENANCE_MAX_DEPTH, Provenance

if TYPE_CHECKING:
    from mrm.geometry.polyhedra import Polyhedron

__all__ = ["Checker", "check_grid_budget", "decode_object", "decode_source"]


#: The most points of one grid source, by dimension (pixels, voxels), for masks and for label grids.
_MASK_LIMITS = {2: limits.MAX_OBJECT_PIXELS, 3: limits.MAX_OBJECT_VOXELS}
_LABEL_LIMITS = {2: limits.MAX_LABEL_PIXELS, 3: limits.MAX_LABEL_VOXELS}


class Checker:
    """Validation helpers that raise FileFormatError naming the file and the JSON path."""

    def __init__(self, name: str) -> None:
        self.name = name
        self.mask_pixels = 0  # running total of the discrete sources' bounding boxes

    def fail(self, path: str, msg: str) -> NoReturn:
        """Refuse the file: ``path`` is the JSON path of the problem."""
        raise FileFormatError(f"{self.name}: invalid project at {path}: {msg}")

    @staticmethod
    def show(v: Any) -> str:
        """A short description of a JSON value for a message (never the whole of a long value)."""
        if isinstance(v, bool):
            return "true" if v else "false"
        if v is None:
            return "null"
        if isinstance(v, dict):
            return "an object"
        if isinstance(v, list):
            return f"a list of {len(v)}"
        if isinstance(v, str):
            return repr(v if len(v) <= 40 else v[:37] + "...")
        if isinstance(v, int) and abs(v) >= 10**15:
            return f"an integer of {len(str(abs(v)))} digits"
        return repr(v)

    def obj(self, v: Any, path: str, required: Sequence[str], optional: Sequence[str] = ()) -> dict[str, Any]:
        """``v`` as a JSON object with the ``required`` keys and no key outside ``optional``."""
        if not isinstance(v, dict):
            self.fail(path, f"expected an object, got {self.show(v)}")
        for k in required:
            if k not in v:
                self.fail(path, f"missing key {k!r}")
        if len(v) > len(required):  # sets: linear in the number of keys, whatever it is
            known = {*required, *optional}
            unknown = next((k for k in v if k not in known), None)
            if unknown is not None:
                self.fail(path, f"unknown key {self.show(unknown)}")
        return v

    def list_(self, v: Any, path: str) -> list[Any]:
        """``v`` as a JSON list."""
        if not isinstance(v, list):
            self.fail(path, f"expected a list, got {self.show(v)}")
        return v

    def int_(self, v: Any, path: str, lo: int, hi: int) -> int:
        """``v`` as an integer in [lo, hi] (a boolean is no integer)."""
        if isinstance(v, bool) or not isinstance(v, int):
            self.fail(path, f"expected an integer, got {self.show(v)}")
        if not lo <= v <= hi:
            self.fail(path, f"integer {self.show(v)} out of range [{lo}, {hi}]")
        return v

    def num(self, v: Any, path: str, lo: float, hi: float) -> float:
        """``v`` as a finite number in [lo, hi], as a float (an integer beyond 2⁵³ is refused)."""
        if isinstance(v, bool) or not isinstance(v, int | float):
            self.fail(path, f"expected a number, got {self.show(v)}")
        if isinstance(v, int) and abs(v) > 2**53:
            self.fail(path, f"number {self.show(v)} is too large")
        f = float(v)
        if not (math.isfinite(f) and lo <= f <= hi):
            self.fail(path, f"number {self.show(v)} out of range [{lo:g}, {hi:g}]")
        return f

    def str_(self, v: Any, path: str, max_len: int | None = None) -> str:
        """``v`` as text of at most ``max_len`` characters (default: the name limit), surrogates removed."""
        if not isinstance(v, str):
            self.fail(path, f"expected a string, got {self.show(v)}")
        if max_len is None:
            max_len = limits.MAX_NAME_CHARS
        if len(v) > max_len:
            self.fail(path, f"string of {len(v)} characters is longer than {max_len}")
        return limits.clean_text(v)  # a JSON "\ud800" escape must not make the document unsavable

    def json_value(self, v: Any, path: str) -> None:
        """Check free-form JSON data iteratively (no recursion, whatever the nesting)."""
        stack: list[tuple[Any, str, int]] = [(v, path, 0)]
        while stack:
            x, p, d = stack.pop()
            if d > PARAMS_MAX_DEPTH:
                self.fail(p, f"nested deeper than {PARAMS_MAX_DEPTH} levels")
            if isinstance(x, dict):
                stack.extend((val, f"{p}.{k}", d + 1) for k, val in x.items())
            elif isinstance(x, list):
                stack.extend((val, f"{p}[{i}]", d + 1) for i, val in enumerate(x))
            elif isinstance(x, float) and not math.isfinite(x):
                self.fail(p, "numbers must be finite")
            elif isinstance(x, int) and not isinstance(x, bool) and abs(x) > limits.MAX_PARAM_INT:
                self.fail(p, f"number {self.show(x)} is too large")


def _decode_box(
    c: Checker, src: dict[str, Any], path: str, limits_by_dim: dict[int, int], what: str = "mask"
) -> tuple[tuple[int, ...], tuple[int, ...]]:
    """(origin, shape) of a grid source: two origin coordinates for pixels, three for voxels (schema 5).

    The shape is in array order ([rows, cols] or [nz, ny, nx]); both stay within the coordinate and size
    limits (``limits_by_dim`` gives the most points per dimension) and the file's total.
    """
    origin = c.list_(src["origin"], f"{path}.origin")
    if len(origin) not in (2, 3):
        c.fail(f"{path}.origin", f"expected [x0, y0] or [x0, y0, z0], got {c.show(origin)}")
    n = len(origin)
    lim = limits.PIXEL_COORDINATE_LIMIT
    o = tuple(c.int_(origin[d], f"{path}.origin[{d}]", -lim, lim) for d in range(n))
    shape = c.list_(src["shape"], f"{path}.shape")
    if len(shape) != n:
        expected = "[rows, cols]" if n == 2 else "[nz, ny, nx]"
        c.fail(f"{path}.shape", f"expected {expected} for a {n}-coordinate origin, got {c.show(shape)}")
    sh = tuple(c.int_(shape[a], f"{path}.shape[{a}]", 0, lim) for a in range(n))
    unit = "pixels" if n == 2 else "voxels"
    if all(sh) and max(o[d] + sh[n - 1 - d] - 1 for d in range(n)) > lim:
        c.fail(f"{path}.shape", f"the {what} reaches coordinates beyond ±{lim:,}")
    count = 1
    for v in sh:
        count *= v
    if count > limits_by_dim[n]:
        dims = " x ".join(str(v) for v in sh)
        c.fail(f"{path}.shape", f"a {dims} {what} holds more than the limit of {limits_by_dim[n]:,} {unit}")
    c.mask_pixels += count * (limits.LABEL_WEIGHT if what == "label map" else 1)
    if c.mask_pixels > limits.MAX_FILE_PIXELS:
        c.fail(f"{path}.shape", _too_many())
    return o, sh


def _too_many() -> str:
    return (
        f"the masks of the file hold more than {limits.MAX_FILE_PIXELS:,} pixels and voxels in all (label "
        f"maps included, a label counting as {limits.LABEL_WEIGHT})"
    )


def check_grid_budget(c: Checker, sources: Iterable[tuple[Any, str]]) -> None:
    """Refuse a file whose grid sources, by their declared shapes, exceed the file's budget, before decoding.

    ``sources`` are the raw JSON sources with their paths. Malformed shapes are skipped: the decoder names
    them. The decoder counts again as it goes (:func:`_decode_box`); counting first means a file of many
    compressed label maps is refused before the first is inflated, not after gigabytes of them.
    """
    total = 0
    lim = limits.PIXEL_COORDINATE_LIMIT
    for src, path in sources:
        if not isinstance(src, dict) or src.get("kind") not in ("discrete", "labels"):
            continue
        shape = src.get("shape")
        if (
            not isinstance(shape, list)
            or len(shape) not in (2, 3)
            or not all(type(v) is int and 0 <= v <= lim for v in shape)
        ):
            continue
        count = 1
        for v in shape:
            count *= v
        labels = src["kind"] == "labels"
        if count > (_LABEL_LIMITS if labels else _MASK_LIMITS)[len(shape)]:
            continue  # one object over its own limit: the decoder says so
        total += count * (limits.LABEL_WEIGHT if labels else 1)
        if total > limits.MAX_FILE_PIXELS:
            c.fail(f"{path}.shape", _too_many())


#: Bytes inflated per step while a label map is decoded straight into its array.
_INFLATE_CHUNK = 1 << 24


def _decode_labels(c: Checker, src: dict[str, Any], path: str) -> LabelMap | LabelVolume:
    c.obj(src, path, ("kind", "origin", "shape", "labels"))
    origin, shape = _decode_box(c, src, path, _LABEL_LIMITS, "label map")
    grid = LabelMap if len(origin) == 2 else LabelVolume
    text = c.str_(src["labels"], f"{path}.labels", max_len=limits.MAX_FILE_BYTES)
    try:
        packed = base64.b64decode(text, validate=True)
    except (binascii.Error, ValueError):
        c.fail(f"{path}.labels", "not valid base64")
    count = int(np.prod(shape, dtype=np.int64))
    n = 4 * count
    dims = " x ".join(str(v) for v in shape)
    if n == 0:
        if packed:
            c.fail(f"{path}.labels", "an empty label map has no labels")
        return grid(np.zeros((0,) * len(shape), np.int32))
    # Never more than the declared size is inflated (a small file cannot claim gigabytes), straight into the
    # array the grid then takes over: one copy of the labels in memory, not three.
    labels = np.empty(shape, dtype="<i4")
    out = memoryview(labels).cast("B")  # type: ignore[arg-type]  # numpy arrays are buffers
    inflate = zlib.decompressobj()
    pos, tail = 0, packed
    try:
        while pos < n:
            piece = inflate.decompress(tail, min(_INFLATE_CHUNK, n - pos))
            if not piece:
                break
            out[pos : pos + len(piece)] = piece
            pos += len(piece)
            tail = inflate.unconsumed_tail
        extra = inflate.decompress(tail, 1) if pos == n and not inflate.eof else b""
    except zlib.error as e:
        c.fail(f"{path}.labels", f"not valid zlib data ({e})")
    del out
    if pos != n or extra or inflate.unconsumed_tail or not inflate.eof:
        c.fail(f"{path}.labels", f"expected {n} bytes of int32 labels for a {dims} map")
    if labels.size and int(labels.min()) < 0:
        c.fail(f"{path}.labels", "labels must be non-negative")
    return grid.taking_over(labels, origin) if labels.dtype == np.int32 else grid(labels, origin)


def _decode_bits(c: Checker, src: dict[str, Any], path: str) -> PixelSet | VoxelSet:
    c.obj(src, path, ("kind", "origin", "shape", "bits"))
    origin, shape = _decode_box(c, src, path, _MASK_LIMITS)
    grid = PixelSet if len(origin) == 2 else VoxelSet
    bits = c.str_(src["bits"], f"{path}.bits", max_len=limits.MAX_FILE_BYTES)
    n = int(np.prod(shape, dtype=np.int64))
    nbytes = (n + 7) // 8
    dims = " x ".join(str(v) for v in shape)
    if len(bits) != 4 * ((nbytes + 2) // 3):
        c.fail(
            f"{path}.bits",
            f"expected {nbytes} bytes of base64 for a {dims} mask, got {len(bits)} characters",
        )
    try:
        raw = base64.b64decode(bits, validate=True)
    except (binascii.Error, ValueError):
        c.fail(f"{path}.bits", "not valid base64")
    if len(raw) != nbytes:
        c.fail(f"{path}.bits", f"expected {nbytes} bytes for a {dims} mask, got {len(raw)}")
    if n == 0:
        return grid.empty()
    mask = np.unpackbits(np.frombuffer(raw, dtype=np.uint8), count=n).reshape(shape).view(bool)
    return grid(mask, origin)


def _decode_ring(c: Checker, ring: Any, path: str) -> np.ndarray[Any, np.dtype[np.float64]]:
    c.list_(ring, path)
    if len(ring) < 4:
        c.fail(path, f"a ring needs at least 4 positions (closed), got {len(ring)}")
    for k, pt in enumerate(ring):
        if type(pt) is not list or len(pt) != 2:
            c.fail(f"{path}[{k}]", f"expected a position [x, y], got {c.show(pt)}")
        for j in (0, 1):
            v = pt[j]
            tv = type(v)
            if tv is float:
                if not (-COORDINATE_LIMIT <= v <= COORDINATE_LIMIT):  # also catches NaN and infinities
                    c.fail(f"{path}[{k}][{j}]", f"coordinate {c.show(v)} outside ±{COORDINATE_LIMIT:.0f}")
            elif tv is int:
                if not -COORDINATE_LIMIT <= v <= COORDINATE_LIMIT:
                    c.fail(f"{path}[{k}][{j}]", f"coordinate {c.show(v)} outside ±{COORDINATE_LIMIT:.0f}")
            else:
                c.fail(f"{path}[{k}][{j}]", f"expected a number, got {c.show(v)}")
    a = np.array(ring, dtype=np.float64)
    if not np.array_equal(a[0], a[-1]):
        c.fail(path, "the ring is not closed (its last position must repeat the first)")
    return a


def _decode_geometry(c: Checker, g: Any, path: str) -> Geometry:
    c.obj(g, path, ("type", "coordinates"))
    kind = g["type"]
    coords = c.list_(g["coordinates"], f"{path}.coordinates")
    if kind == "Polygon":
        if not coords:
            return Polygon()
        polys = [coords]
        cpaths = [f"{path}.coordinates"]
    elif kind == "MultiPolygon":
        polys = coords
        cpaths = [f"{path}.coordinates[{i}]" for i in range(len(coords))]
        if not polys:
            return Polygon()
    else:
        c.fail(f"{path}.type", f"expected 'Polygon' or 'MultiPolygon', got {c.show(kind)}")
    built = []
    for rings, p in zip(polys, cpaths, strict=True):
        c.list_(rings, p)
        if not rings:
            c.fail(p, "a polygon needs an exterior ring")
        rs = [_decode_ring(c, r, f"{p}[{i}]") for i, r in enumerate(rings)]
        built.append(Polygon(rs[0], rs[1:]))
    geom: Geometry = MultiPolygon(built) if kind == "MultiPolygon" else built[0]
    try:
        return validate_geometry(geom)
    except MRMError as e:
        c.fail(path, str(e))


def _decode_polyhedron(c: Checker, src: dict[str, Any], path: str) -> Polyhedron:
    from mrm.geometry.polyhedra import Polyhedron  # only for a file that holds one (its kernels are many)

    c.obj(src, path, ("kind", "vertices", "triangles"))
    verts = c.list_(src["vertices"], f"{path}.vertices")
    tris = c.list_(src["triangles"], f"{path}.triangles")
    if len(tris) > limits.MAX_OBJECT_TRIANGLES:
        c.fail(f"{path}.triangles", f"more than the limit of {limits.MAX_OBJECT_TRIANGLES:,} triangles")
    if len(verts) > limits.MAX_OBJECT_VERTICES:
        c.fail(f"{path}.vertices", f"more than the limit of {limits.MAX_OBJECT_VERTICES:,} vertices")
    for k, pt in enumerate(verts):
        if type(pt) is not list or len(pt) != 3:
            c.fail(f"{path}.vertices[{k}]", f"expected a position [x, y, z], got {c.show(pt)}")
        for j, v in enumerate(pt):
            if type(v) not in (int, float) or not -COORDINATE_LIMIT <= v <= COORDINATE_LIMIT:
                c.fail(
                    f"{path}.vertices[{k}][{j}]",
                    f"expected a number within ±{COORDINATE_LIMIT:.0f}, got {c.show(v)}",
                )
    n = len(verts)
    for k, tri in enumerate(tris):
        if type(tri) is not list or len(tri) != 3 or any(type(i) is not int or not 0 <= i < n for i in tri):
            c.fail(f"{path}.triangles[{k}]", f"expected three vertex indices in [0, {n}), got {c.show(tri)}")
    try:
        return Polyhedron(
            np.array(verts, dtype=np.float64).reshape(-1, 3), np.array(tris, dtype=np.int64).reshape(-1, 3)
        )
    except MRMError as e:
        c.fail(path, str(e))


def decode_source(c: Checker, src: Any, path: str) -> Source:
    """An object's source (pixels, labels, a geometry or a polyhedron) at ``path``, checked."""
    c.obj(src, path, ("kind",), ("origin", "shape", "bits", "geometry", "labels", "vertices", "triangles"))
    kind = src["kind"]
    if kind == "polyhedron":
        return _decode_polyhedron(c, src, path)
    if kind == "discrete":
        return _decode_bits(c, src, path)
    if kind == "labels":
        return _decode_labels(c, src, path)
    if kind == "euclidean":
        c.obj(src, path, ("kind", "geometry"))
        return _decode_geometry(c, src["geometry"], f"{path}.geometry")
    c.fail(f"{path}.kind", f"expected 'discrete', 'labels', 'euclidean' or 'polyhedron', got {c.show(kind)}")


def _decode_style(c: Checker, s: Any, path: str) -> Style:
    c.obj(s, path, ("fill", "stroke", "opacity", "stroke_width", "visible"))
    fill = c.str_(s["fill"], f"{path}.fill", 9)
    stroke = c.str_(s["stroke"], f"{path}.stroke", 9)
    opacity = c.num(s["opacity"], f"{path}.opacity", 0.0, 1.0)
    width = c.num(s["stroke_width"], f"{path}.stroke_width", 0.0, 100.0)
    if not isinstance(s["visible"], bool):
        c.fail(f"{path}.visible", f"expected true or false, got {c.show(s['visible'])}")
    try:
        return Style(fill=fill, stroke=stroke, opacity=opacity, stroke_width=width, visible=s["visible"])
    except MRMError as e:
        c.fail(path, str(e))


def _decode_provenance(
    c: Checker, p: Any, path: str, contents: dict[str, Source] | None = None, depth: int = 0
) -> Provenance | None:
    if p is None:
        return None
    if depth > PROVENANCE_MAX_DEPTH:
        c.fail(path, f"a provenance chain is longer than {PROVENANCE_MAX_DEPTH} operations")
    c.obj(p, path, ("operation", "params", "inputs"), ("input_contents", "input_provenance"))
    op = c.str_(p["operation"], f"{path}.operation", 200)
    if not op:
        c.fail(f"{path}.operation", "empty operation name")
    params = c.obj(
        p["params"], f"{path}.params", (), tuple(p["params"]) if isinstance(p["params"], dict) else ()
    )
    # The size first (one C-speed dump), so that a huge parameter set is refused before the per-value checks.
    try:
        size = len(json.dumps(params))
    except (RecursionError, ValueError):
        c.fail(f"{path}.params", f"nested deeper than {PARAMS_MAX_DEPTH} levels")
    if size > limits.PARAMS_MAX_CHARS:
        c.fail(f"{path}.params", f"the parameters are larger than {limits.PARAMS_MAX_CHARS:,} characters")
    c.json_value(params, f"{path}.params")
    params = limits.clean_json(params)
    inputs = c.list_(p["inputs"], f"{path}.inputs")
    # 0 names an input that was an intermediate result of a re-run, never an object of the document.
    ids = [c.int_(v, f"{path}.inputs[{i}]", 0, 2**53) for i, v in enumerate(inputs)]
    sources: list[Source] = []
    parents: list[Provenance | None] = []
    digests: list[str] = []
    if "input_contents" in p:
        refs = c.list_(p["input_contents"], f"{path}.input_contents")
        if len(refs) != len(ids):
            c.fail(f"{path}.input_contents", f"expected {len(ids)} digests (one per input), got {len(refs)}")
        for i, d in enumerate(refs):
            key = c.str_(d, f"{path}.input_contents[{i}]", 64)
            if contents is None or key not in contents:
                c.fail(f"{path}.input_contents[{i}]", f"no content {c.show(key)} in $.contents")
            sources.append(contents[key])
            digests.append(key)
        ups = c.list_(p.get("input_provenance", [None] * len(ids)), f"{path}.input_provenance")
        if len(ups) != len(ids):
            c.fail(f"{path}.input_provenance", f"expected {len(ids)} records (one per input), got {len(ups)}")
        parents = [
            _decode_provenance(c, u, f"{path}.input_provenance[{i}]", contents, depth + 1)
            for i, u in enumerate(ups)
        ]
    elif "input_provenance" in p:
        c.fail(f"{path}.input_provenance", "given without input_contents")
    try:
        return Provenance(op, params, tuple(ids), tuple(sources), tuple(parents), tuple(digests))
    except MRMError as e:
        c.fail(path, str(e))


def _decode_georef(c: Checker, g: Any, path: str) -> GeoRef | None:
    if g is None:
        return None
    c.obj(g, path, ("transform", "width", "height", "crs"), ("origin",))
    t = c.list_(g["transform"], f"{path}.transform")
    if len(t) != 6:
        c.fail(f"{path}.transform", f"expected six numbers [a, b, c, d, e, f], got {c.show(t)}")
    # Any finite number here; GeoRef applies the limits of every georeference (limits.check_transform).
    transform = tuple(c.num(v, f"{path}.transform[{i}]", -math.inf, math.inf) for i, v in enumerate(t))
    lim = limits.PIXEL_COORDINATE_LIMIT
    width = c.int_(g["width"], f"{path}.width", 1, 2 * lim)
    height = c.int_(g["height"], f"{path}.height", 1, 2 * lim)
    origin = c.list_(g.get("origin", [0, 0]), f"{path}.origin")
    if len(origin) != 2:
        c.fail(f"{path}.origin", f"expected [x0, y0], got {c.show(origin)}")
    x0 = c.int_(origin[0], f"{path}.origin[0]", -lim, lim)
    y0 = c.int_(origin[1], f"{path}.origin[1]", -lim, lim)
    crs = None if g["crs"] is None else c.str_(g["crs"], f"{path}.crs", limits.MAX_CRS_CHARS)
    try:
        return GeoRef(transform, width, height, crs, (x0, y0))  # type: ignore[arg-type]
    except MRMError as e:
        c.fail(path, str(e))


def decode_object(c: Checker, o: Any, path: str, contents: dict[str, Source] | None = None) -> DocObject:
    """One object of ``$.objects`` (``contents``: the file's table of pinned input contents), checked."""
    c.obj(o, path, ("id", "name", "style", "provenance", "source"), ("georef",))
    oid = c.int_(o["id"], f"{path}.id", 1, 2**53)
    name = c.str_(o["name"], f"{path}.name")
    style = _decode_style(c, o["style"], f"{path}.style")
    prov = _decode_provenance(c, o["provenance"], f"{path}.provenance", contents)
    georef = _decode_georef(c, o.get("georef"), f"{path}.georef")
    source = decode_source(c, o["source"], f"{path}.source")
    return DocObject(id=oid, name=name, source=source, style=style, provenance=prov, georef=georef)
