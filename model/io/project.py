"""Project files (``*.mrm``): one versioned JSON document, validated on load, written atomically.

Schema version 4::

    {
     "format": "mrm-project",
     "schema_version": 4,
     "generator": "MR Modeler 0.1.0",                      (optional, informative)
     "settings": {"model": "standard"},
     "selection": [2],                                      (optional; ids of selected objects)
     "autosave": {"project": "/path/x.mrm", "saved_at": "2026-..."},   (only in autosave side files)
     "objects": [
      {"id": 1, "name": "diamond",
       "style": {"fill": "#4c72b0", "stroke": "#1f2a44", "opacity": 0.6, "stroke_width": 1.5,
                 "visible": true},
       "provenance": null,
       "source": {"kind": "discrete", "origin": [-3, -3], "shape": [7, 7], "bits": "<base64>"}},
      {"id": 2, ..., "provenance": {"operation": "dss", "params": {"alpha": 2.5}, "inputs": [1],
                                    "input_contents": ["<digest>"], "input_provenance": [null]},
       "source": {"kind": "euclidean",
                  "geometry": {"type": "Polygon", "coordinates": [[[0.0, 0.0], [4.5, 0.0], ...]]}}},
      {"id": 3, ..., "georef": {"transform": [30.0, 0.0, 500000.0, 0.0, -30.0, 4200000.0],
                                "width": 64, "height": 48, "crs": "EPSG:32633", "origin": [0, 0]},
       "source": {"kind": "discrete", ...}},
      {"id": 4, ..., "source": {"kind": "labels", "origin": [0, 0], "shape": [480, 640],
                                "labels": "<base64 of zlib of int32 little-endian>"}}
     ]
    }

* Only each object's **source** representation is stored (docs/design.md §7); the others are derived on load.
* A provenance pins the content its inputs had when the result was made (``input_contents``: digests of
  :func:`mrm.document.content_digest`) and their own provenance then (``input_provenance``); each pinned
  content is stored once in the top-level ``"contents": {digest: source}`` table (optional), shared by every
  result that read it, and checked against its digest on load. Version 1 files had ids only: on load their
  provenance is pinned to the objects the file holds (the best record there is).
* ``georef`` (optional, schema 3): where the object's grid lies on the Earth, the GDAL affine
  ``transform`` (a, b, c, d, e, f, written with ``repr``: bit for bit), the raster's ``width`` and
  ``height``, its ``crs`` (``EPSG:n``, WKT or null) and the grid ``origin`` of its bottom-left pixel
  (:class:`mrm.io.georef.GeoRef`, ADR 0021). Absent for an object on a plain grid.
* A discrete source is its canonical (cropped) mask, ``np.packbits`` row-major (row 0 = lowest y, big-endian
  bit order) in base64, with its origin and shape: compact, and valid JSON.
* A label map (``kind: "labels"``, schema 4, ADR 0033) is its canonical (cropped) int32 label array,
  row-major (row 0 = lowest y), little-endian, zlib-compressed, in base64, with its origin and shape.
* A Euclidean source is GeoJSON-like: Polygon or MultiPolygon coordinates, rings closed, float coordinates
  written with ``repr`` so that every float64 comes back bit for bit. Integers (ids, origins, shapes) stay
  integers.
* Loading validates everything and names the JSON path of the first problem
  (``$.objects[3].source.shape``); files from older schema versions are upgraded by :data:`MIGRATIONS`, in
  order; a file from a newer version is refused with a message saying so.
* Saving writes a temporary file, fsyncs it and renames it over the destination
  (:func:`mrm.io.atomic.atomic_write_bytes`); the document is marked clean only then.
"""

from __future__ import annotations

import base64
import binascii
import functools
import json
import math
import os
import zlib
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, NoReturn

import numpy as np
from shapely.geometry import MultiPolygon, Polygon

from mrm.core import limits
from mrm.core.errors import FileFormatError as FileFormatError
from mrm.core.errors import MRMError
from mrm.core.georef import GeoRef
from mrm.core.grids import LabelMap, PixelSet
from mrm.core.limits import COORDINATE_LIMIT, PARAMS_MAX_DEPTH
from mrm.core.models import Model
from mrm.document import DocObject, Document, Geometry, Settings, Source, Style, validate_geometry
from mrm.io.atomic import atomic_write_bytes
from mrm.io.reading import open_regular
from mrm.ops.provenance import PROVENANCE_MAX_DEPTH, Provenance, content_digest

#: The value of the "format" key.
FORMAT = "mrm-project"
#: The schema version this code writes (and the newest it reads).
SCHEMA_VERSION = 4
#: Longest CRS text accepted in a georeference (a WKT2 definition is a few thousand characters).
MAX_CRS_CHARS = 100_000
# The other limits are those of the document (mrm.core.limits, ADR 0010), so that the loader accepts every
# file the saver can write: the document refuses the edit that would exceed them. The loader reads them from
# mrm.core.limits when it runs.


@dataclass(frozen=True)
class Migration:
    """Upgrade of the JSON data of a project file by one schema version.

    Parameters
    ----------
    from_version : int
        The version it reads; it produces ``from_version + 1``.
    description : str
        What changed, for the changelog and error messages.
    apply : callable
        ``apply(data) -> data``; it may assume the input validates against ``from_version``.
    """

    from_version: int
    description: str
    apply: Callable[[dict[str, Any]], dict[str, Any]]


#: The migrations, oldest first; version ``k`` is upgraded by the entry with ``from_version == k``.
#: Schema 1 is the first version, so there is none yet. When the format changes: bump SCHEMA_VERSION, append
#: a Migration from the previous version, and add a golden file of the new version to tests/model/golden/.
MIGRATIONS: tuple[Migration, ...] = (
    Migration(
        1,
        "provenance may pin its inputs' content (input_contents, input_provenance, a top-level contents "
        "table); a version 1 file's provenance is pinned on load to the objects the file holds",
        lambda data: {**data, "schema_version": 2},
    ),
    Migration(
        2,
        "an object may carry its georeference (georef: transform, width, height, crs, origin); a version 2 "
        "file has none, so it reads unchanged",
        lambda data: {**data, "schema_version": 3},
    ),
    Migration(
        3,
        "an object's source may be a label map (kind 'labels': zlib-compressed int32 labels); a version 3 "
        "file has none, so it reads unchanged",
        lambda data: {**data, "schema_version": 4},
    ),
)


@dataclass
class Project:
    """The content of a project file, validated (what :func:`read_project` returns)."""

    objects: list[DocObject]
    settings: Settings
    selection: list[int] = field(default_factory=list)
    #: The "autosave" record of an autosave side file, else None.
    autosave: dict[str, Any] | None = None
    #: The schema version the file had before migration.
    file_version: int = SCHEMA_VERSION

    def to_document(self, path: Path | None = None, *, clean: bool = True) -> Document:
        """A new document holding this content, with an empty history."""
        doc = Document(self.settings)
        doc.reset(self.objects, self.settings, self.selection, clean=clean)
        doc.path = path
        return doc


# ============================================================================================== writing
def _encode_pixels(ps: PixelSet) -> dict[str, Any]:
    h, w = ps.shape
    bits = np.packbits(ps.mask, axis=None).tobytes() if ps.count else b""
    return {
        "kind": "discrete",
        "origin": [int(ps.origin[0]), int(ps.origin[1])],
        "shape": [h, w],
        "bits": base64.b64encode(bits).decode("ascii"),
    }


def _encode_labels(lm: LabelMap) -> dict[str, Any]:
    h, w = lm.shape
    raw = zlib.compress(lm.labels.astype("<i4", copy=False).tobytes(), 6) if lm.labels.size else b""
    return {
        "kind": "labels",
        "origin": [int(lm.origin[0]), int(lm.origin[1])],
        "shape": [h, w],
        "labels": base64.b64encode(raw).decode("ascii"),
    }


def _ring_list(coords: Any) -> list[list[float]]:
    a = np.asarray(coords, dtype=np.float64)[:, :2]
    return a.tolist()  # type: ignore[no-any-return]  # Python floats: json writes their repr


def _encode_geometry(geom: Geometry) -> dict[str, Any]:
    if geom.is_empty:
        return {"type": "Polygon", "coordinates": []}

    def poly(p: Polygon) -> list[list[list[float]]]:
        return [_ring_list(p.exterior.coords), *(_ring_list(r.coords) for r in p.interiors)]

    if isinstance(geom, MultiPolygon):
        return {"type": "MultiPolygon", "coordinates": [poly(p) for p in geom.geoms]}
    return {"type": "Polygon", "coordinates": poly(geom)}


def _encode_source(source: Source) -> dict[str, Any]:
    if isinstance(source, PixelSet):
        return _encode_pixels(source)
    if isinstance(source, LabelMap):
        return _encode_labels(source)
    return {"kind": "euclidean", "geometry": _encode_geometry(source)}


def _encode_style(s: Style) -> dict[str, Any]:
    return {
        "fill": s.fill,
        "stroke": s.stroke,
        "opacity": s.opacity,
        "stroke_width": s.stroke_width,
        "visible": s.visible,
    }


def object_to_json(obj: DocObject, contents: dict[str, Any] | None = None) -> dict[str, Any]:
    """One object as the project file stores it.

    ``contents`` (digest → source) collects the pinned input contents of its provenance, which the file
    stores once in its top-level ``contents`` table; without it the provenance is written unpinned.
    """
    out: dict[str, Any] = {
        "id": obj.id,
        "name": obj.name,
        "style": _encode_style(obj.style),
        "provenance": obj.provenance.to_json(contents) if obj.provenance is not None else None,
    }
    if obj.georef is not None:  # absent on a plain grid: files without georeferences stay as they were
        out["georef"] = obj.georef.as_dict()
    out["source"] = _encode_source(obj.source)
    return out


def _dump(value: Any) -> str:
    return json.dumps(value, ensure_ascii=False, allow_nan=False, separators=(", ", ": "))


@functools.lru_cache(maxsize=1)
def _generator() -> str:
    try:
        from importlib.metadata import version

        return f"MR Modeler {version('mr-modeler')}"
    except Exception:  # not installed as a distribution (running from a checkout)
        return "MR Modeler"


def dumps(doc: Document, *, autosave: dict[str, Any] | None = None) -> bytes:
    """Serialise a document to the bytes of a project file (deterministic: same document, same bytes).

    The layout puts one object per line, so files diff well and stay compact.
    """
    head: list[tuple[str, Any]] = [
        ("format", FORMAT),
        ("schema_version", SCHEMA_VERSION),
        ("generator", _generator()),
        ("settings", {"model": doc.settings.model}),
        ("selection", list(doc.selection)),
    ]
    if autosave is not None:
        head.append(("autosave", autosave))
    lines = ["{"]
    lines += [f" {_dump(k)}: {_dump(v)}," for k, v in head]
    contents: dict[str, Any] = {}
    objs = [f"  {_dump(object_to_json(o, contents))}" for o in doc.objects]
    if contents:  # each pinned input content once, shared by every result that read it
        lines.append(' "contents": {')
        lines.append(
            ",\n".join(f"  {_dump(d)}: {_dump(_encode_source(contents[d]))}" for d in sorted(contents))
        )
        lines.append(" },")
    if objs:
        lines.append(' "objects": [')
        lines.append(",\n".join(objs))
        lines.append(" ]")
    else:
        lines.append(' "objects": []')
    lines.append("}")
    return ("\n".join(lines) + "\n").encode("utf-8")


def save_project(doc: Document, path: str | os.PathLike[str], *, mark_clean: bool = True) -> None:
    """Write ``doc`` to ``path`` atomically; then (only then) set its path and mark it clean.

    If writing fails (disk full, permission, a crash) the previous file is left intact and the document stays
    modified. ``OSError`` propagates for the caller to report.
    """
    data = dumps(doc)
    atomic_write_bytes(path, data)
    doc.path = Path(path)
    if mark_clean:
        doc.history.set_clean()


# ============================================================================================== reading
_MAGIC: tuple[tuple[bytes, str], ...] = (
    (b"\x89PNG\r\n\x1a\n", "a PNG image"),
    (b"\xff\xd8\xff", "a JPEG image"),
    (b"GIF8", "a GIF image"),
    (b"II*\x00", "a TIFF image"),
    (b"MM\x00*", "a TIFF image"),
    (b"BM", "a BMP image"),
    (b"PK\x03\x04", "a ZIP archive (an .npz array file?)"),
    (b"\x93NUMPY", "a NumPy array file"),
    (b"%PDF", "a PDF document"),
    (b"\x1f\x8b", "a gzip-compressed file"),
)


def _sniff(data: bytes) -> str | None:
    for magic, what in _MAGIC:
        if data.startswith(magic):
            return what
    if len(data) >= 3 and data[:1] == b"P" and data[1:2] in b"123456" and data[2:3] in b" \t\r\n#":
        return "a Netpbm image (PBM/PGM/PPM)"
    if data.lstrip()[:5].lower() in (b"<?xml", b"<svg "):
        return "an XML/SVG document"
    return None


class _Checker:
    """Validation helpers that raise FileFormatError naming the file and the JSON path."""

    def __init__(self, name: str) -> None:
        self.name = name
        self.mask_pixels = 0  # running total of the discrete sources' bounding boxes

    def fail(self, path: str, msg: str) -> NoReturn:
        raise FileFormatError(f"{self.name}: invalid project at {path}: {msg}")

    @staticmethod
    def show(v: Any) -> str:
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
        if not isinstance(v, list):
            self.fail(path, f"expected a list, got {self.show(v)}")
        return v

    def int_(self, v: Any, path: str, lo: int, hi: int) -> int:
        if isinstance(v, bool) or not isinstance(v, int):
            self.fail(path, f"expected an integer, got {self.show(v)}")
        if not lo <= v <= hi:
            self.fail(path, f"integer {self.show(v)} out of range [{lo}, {hi}]")
        return v

    def num(self, v: Any, path: str, lo: float, hi: float) -> float:
        if isinstance(v, bool) or not isinstance(v, int | float):
            self.fail(path, f"expected a number, got {self.show(v)}")
        if isinstance(v, int) and abs(v) > 2**53:
            self.fail(path, f"number {self.show(v)} is too large")
        f = float(v)
        if not (math.isfinite(f) and lo <= f <= hi):
            self.fail(path, f"number {self.show(v)} out of range [{lo:g}, {hi:g}]")
        return f

    def str_(self, v: Any, path: str, max_len: int | None = None) -> str:
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
    c: _Checker, src: dict[str, Any], path: str, limit: int, what: str = "mask"
) -> tuple[int, int, int, int]:
    """(x0, y0, rows, cols) of a discrete source or label map, within the coordinate and size limits."""
    origin = c.list_(src["origin"], f"{path}.origin")
    if len(origin) != 2:
        c.fail(f"{path}.origin", f"expected [x0, y0], got {c.show(origin)}")
    lim = limits.PIXEL_COORDINATE_LIMIT
    x0 = c.int_(origin[0], f"{path}.origin[0]", -lim, lim)
    y0 = c.int_(origin[1], f"{path}.origin[1]", -lim, lim)
    shape = c.list_(src["shape"], f"{path}.shape")
    if len(shape) != 2:
        c.fail(f"{path}.shape", f"expected [rows, cols], got {c.show(shape)}")
    h = c.int_(shape[0], f"{path}.shape[0]", 0, lim)
    w = c.int_(shape[1], f"{path}.shape[1]", 0, lim)
    if h and w and max(x0 + w - 1, y0 + h - 1) > lim:
        c.fail(f"{path}.shape", f"the mask reaches pixel coordinates beyond ±{lim:,}")
    if h * w > limit:
        c.fail(f"{path}.shape", f"a {h} x {w} {what} holds more than the limit of {limit:,} pixels")
    c.mask_pixels += h * w
    if c.mask_pixels > limits.MAX_FILE_PIXELS:
        c.fail(
            f"{path}.shape", f"the masks of the file hold more than {limits.MAX_FILE_PIXELS:,} pixels in all"
        )
    return x0, y0, h, w


def _decode_labels(c: _Checker, src: dict[str, Any], path: str) -> LabelMap:
    c.obj(src, path, ("kind", "origin", "shape", "labels"))
    x0, y0, h, w = _decode_box(c, src, path, limits.MAX_LABEL_PIXELS, "label map")
    text = c.str_(src["labels"], f"{path}.labels", max_len=limits.MAX_FILE_BYTES)
    try:
        packed = base64.b64decode(text, validate=True)
    except (binascii.Error, ValueError):
        c.fail(f"{path}.labels", "not valid base64")
    n = 4 * h * w
    if n == 0:
        if packed:
            c.fail(f"{path}.labels", "an empty label map has no labels")
        return LabelMap(np.zeros((0, 0), np.int32))
    # Never more than the declared size is inflated (a small file cannot claim gigabytes).
    inflate = zlib.decompressobj()
    try:
        raw = inflate.decompress(packed, n)
    except zlib.error as e:
        c.fail(f"{path}.labels", f"not valid zlib data ({e})")
    if len(raw) != n or inflate.unconsumed_tail or not inflate.eof:
        c.fail(f"{path}.labels", f"expected {n} bytes of int32 labels for a {h} x {w} map")
    labels = np.frombuffer(raw, dtype="<i4").reshape(h, w)
    if labels.size and int(labels.min()) < 0:
        c.fail(f"{path}.labels", "labels must be non-negative")
    return LabelMap(labels.astype(np.int32), (x0, y0))


def _decode_bits(c: _Checker, src: dict[str, Any], path: str) -> PixelSet:
    c.obj(src, path, ("kind", "origin", "shape", "bits"))
    x0, y0, h, w = _decode_box(c, src, path, limits.MAX_OBJECT_PIXELS)
    bits = c.str_(src["bits"], f"{path}.bits", max_len=limits.MAX_FILE_BYTES)
    n = h * w
    nbytes = (n + 7) // 8
    if len(bits) != 4 * ((nbytes + 2) // 3):
        c.fail(
            f"{path}.bits",
            f"expected {nbytes} bytes of base64 for a {h} x {w} mask, got {len(bits)} characters",
        )
    try:
        raw = base64.b64decode(bits, validate=True)
    except (binascii.Error, ValueError):
        c.fail(f"{path}.bits", "not valid base64")
    if len(raw) != nbytes:
        c.fail(f"{path}.bits", f"expected {nbytes} bytes for a {h} x {w} mask, got {len(raw)}")
    if n == 0:
        return PixelSet.empty()
    mask = np.unpackbits(np.frombuffer(raw, dtype=np.uint8), count=n).reshape(h, w).view(bool)
    return PixelSet(mask, (x0, y0))


def _decode_ring(c: _Checker, ring: Any, path: str) -> np.ndarray[Any, np.dtype[np.float64]]:
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


def _decode_geometry(c: _Checker, g: Any, path: str) -> Geometry:
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


def _decode_source(c: _Checker, src: Any, path: str) -> Source:
    c.obj(src, path, ("kind",), ("origin", "shape", "bits", "geometry", "labels"))
    kind = src["kind"]
    if kind == "discrete":
        return _decode_bits(c, src, path)
    if kind == "labels":
        return _decode_labels(c, src, path)
    if kind == "euclidean":
        c.obj(src, path, ("kind", "geometry"))
        return _decode_geometry(c, src["geometry"], f"{path}.geometry")
    c.fail(f"{path}.kind", f"expected 'discrete', 'labels' or 'euclidean', got {c.show(kind)}")


def _decode_style(c: _Checker, s: Any, path: str) -> Style:
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
    c: _Checker, p: Any, path: str, contents: dict[str, Source] | None = None, depth: int = 0
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


def _decode_georef(c: _Checker, g: Any, path: str) -> GeoRef | None:
    if g is None:
        return None
    c.obj(g, path, ("transform", "width", "height", "crs"), ("origin",))
    t = c.list_(g["transform"], f"{path}.transform")
    if len(t) != 6:
        c.fail(f"{path}.transform", f"expected six numbers [a, b, c, d, e, f], got {c.show(t)}")
    big = float(2**1000)  # any finite float64; only NaN, infinities and huge integers are refused
    transform = tuple(c.num(v, f"{path}.transform[{i}]", -big, big) for i, v in enumerate(t))
    lim = limits.PIXEL_COORDINATE_LIMIT
    width = c.int_(g["width"], f"{path}.width", 1, 2 * lim)
    height = c.int_(g["height"], f"{path}.height", 1, 2 * lim)
    origin = c.list_(g.get("origin", [0, 0]), f"{path}.origin")
    if len(origin) != 2:
        c.fail(f"{path}.origin", f"expected [x0, y0], got {c.show(origin)}")
    x0 = c.int_(origin[0], f"{path}.origin[0]", -lim, lim)
    y0 = c.int_(origin[1], f"{path}.origin[1]", -lim, lim)
    crs = None if g["crs"] is None else c.str_(g["crs"], f"{path}.crs", MAX_CRS_CHARS)
    try:
        return GeoRef(transform, width, height, crs, (x0, y0))  # type: ignore[arg-type]
    except MRMError as e:
        c.fail(path, str(e))


def _decode_object(c: _Checker, o: Any, path: str, contents: dict[str, Source] | None = None) -> DocObject:
    c.obj(o, path, ("id", "name", "style", "provenance", "source"), ("georef",))
    oid = c.int_(o["id"], f"{path}.id", 1, 2**53)
    name = c.str_(o["name"], f"{path}.name")
    style = _decode_style(c, o["style"], f"{path}.style")
    prov = _decode_provenance(c, o["provenance"], f"{path}.provenance", contents)
    georef = _decode_georef(c, o.get("georef"), f"{path}.georef")
    source = _decode_source(c, o["source"], f"{path}.source")
    return DocObject(id=oid, name=name, source=source, style=style, provenance=prov, georef=georef)


def migrate(
    data: dict[str, Any],
    name: str = "project",
    migrations: Sequence[Migration] = MIGRATIONS,
    current: int = SCHEMA_VERSION,
) -> dict[str, Any]:
    """Upgrade the JSON data of a project file to schema ``current``, applying ``migrations`` in order."""
    c = _Checker(name)
    version = (
        c.int_(data.get("schema_version"), "$.schema_version", 1, 2**31) if "schema_version" in data else 0
    )
    if version == 0:
        c.fail("$", "missing key 'schema_version'")
    if version > current:
        raise FileFormatError(
            f"{name}: this project was written by a newer version of MR Modeler (schema {version}); "
            f"this version reads schema {current} and older. Update MR Modeler to open it."
        )
    for m in migrations:
        if m.from_version == version and version < current:
            data = m.apply(data)
            version += 1
            data["schema_version"] = version
    if version != current:
        raise FileFormatError(f"{name}: no migration from project schema {version} to {current}")
    return data


def parse_project(
    data: bytes,
    name: str = "project",
    *,
    migrations: Sequence[Migration] = MIGRATIONS,
    current: int = SCHEMA_VERSION,
) -> Project:
    """Parse and validate the bytes of a project file.

    Raises
    ------
    FileFormatError
        With a message naming the file and, for content errors, the JSON path of the problem.
    """
    if not data.strip():
        raise FileFormatError(f"{name}: the file is empty")
    what = _sniff(data)
    if what is not None:
        raise FileFormatError(
            f"{name}: this is {what}, not an MR Modeler project; import it as a file instead of opening it"
        )
    try:
        text = data.decode("utf-8-sig")
    except UnicodeDecodeError as e:
        raise FileFormatError(
            f"{name}: not an MR Modeler project (not UTF-8 text: invalid byte at offset {e.start})"
        ) from None

    def refuse_constant(s: str) -> Any:
        raise ValueError(f"{s} is not a valid number in a project file")

    try:
        raw = json.loads(text, parse_constant=refuse_constant)
    except json.JSONDecodeError as e:
        # An error at the very end, or a string that never closes, means the text stops mid-document.
        if e.pos >= len(text.rstrip()) - 1 or e.msg.startswith("Unterminated string"):
            raise FileFormatError(
                f"{name}: the file ends unexpectedly at line {e.lineno} (truncated or incompletely written)"
            ) from None
        raise FileFormatError(
            f"{name}: not valid JSON: {e.msg} (line {e.lineno}, column {e.colno})"
        ) from None
    except RecursionError:
        raise FileFormatError(f"{name}: the JSON is nested too deeply to be a project file") from None
    except ValueError as e:  # NaN/Infinity literals; integers with thousands of digits
        raise FileFormatError(f"{name}: unreadable number: {e}") from None
    c = _Checker(name)
    if not isinstance(raw, dict):
        raise FileFormatError(f"{name}: not an MR Modeler project (the JSON is {c.show(raw)}, not an object)")
    if raw.get("format") != FORMAT:
        if "format" not in raw:
            raise FileFormatError(f"{name}: not an MR Modeler project (no 'format' key)")
        raise FileFormatError(
            f"{name}: not an MR Modeler project (format is {c.show(raw['format'])}, expected {FORMAT!r})"
        )
    file_version = (
        c.int_(raw["schema_version"], "$.schema_version", 1, 2**31) if "schema_version" in raw else 0
    )
    raw = migrate(raw, name, migrations, current)
    c.obj(
        raw,
        "$",
        ("format", "schema_version", "settings", "objects"),
        ("generator", "selection", "autosave", "contents"),
    )
    if "generator" in raw:
        c.str_(raw["generator"], "$.generator", 200)
    st = c.obj(raw["settings"], "$.settings", ("model",))
    model = c.str_(st["model"], "$.settings.model", 40)
    if model not in Model.names():
        c.fail(
            "$.settings.model", f"unknown model {c.show(model)}; expected one of {', '.join(Model.names())}"
        )
    settings = Settings(model=Model(model))
    contents: dict[str, Source] = {}
    if "contents" in raw:  # the pinned input contents of the provenance records, each stored once
        keys = tuple(raw["contents"]) if isinstance(raw["contents"], dict) else ()
        table = c.obj(raw["contents"], "$.contents", (), keys)
        for key, src in table.items():
            c.str_(key, "$.contents", 64)
            value = _decode_source(c, src, f"$.contents[{key!r}]")
            if content_digest(value) != key:  # a digest names its content: a file cannot make it lie
                c.fail(f"$.contents[{key!r}]", "the content does not match its digest")
            contents[key] = value
    objs_raw = c.list_(raw["objects"], "$.objects")
    objects: list[DocObject] = []
    seen: dict[int, int] = {}
    for i, o in enumerate(objs_raw):
        obj = _decode_object(c, o, f"$.objects[{i}]", contents)
        if obj.id in seen:
            c.fail(f"$.objects[{i}].id", f"id {obj.id} is already used by $.objects[{seen[obj.id]}]")
        seen[obj.id] = i
        objects.append(obj)
    if file_version < 2:  # written before provenance pinned its inputs
        objects = _pin_legacy_provenance(objects)
    selection: list[int] = []
    if "selection" in raw:
        sel = c.list_(raw["selection"], "$.selection")
        for i, v in enumerate(sel):
            sid = c.int_(v, f"$.selection[{i}]", 1, 2**53)
            if sid not in seen:
                c.fail(f"$.selection[{i}]", f"no object has id {sid}")
            selection.append(sid)
    autosave = None
    if "autosave" in raw:
        a = c.obj(raw["autosave"], "$.autosave", ("project", "saved_at"))
        if a["project"] is not None:
            c.str_(a["project"], "$.autosave.project", 4096)
        c.str_(a["saved_at"], "$.autosave.saved_at", 100)
        autosave = dict(a)
    return Project(objects, settings, selection, autosave, file_version)


def _pin_legacy_provenance(objects: list[DocObject]) -> list[DocObject]:
    """Pin the inputs of provenance written before pinning existed, from the objects of the same file.

    An older file recorded only input ids; the best record of what those inputs were is what the file holds
    for them (the results were saved with them). Inputs the file no longer holds stay unpinned, and the
    account of such a result says so instead of guessing.
    """
    by_id = {o.id: o for o in objects}
    done: dict[int, DocObject] = {}
    visiting: set[int] = set()

    def pinned(oid: int, depth: int) -> DocObject:
        if oid in done:
            return done[oid]
        obj = by_id[oid]
        if oid in visiting:  # a cycle of ids in a hand-made file: leave it unpinned
            return obj
        visiting.add(oid)
        prov = obj.provenance
        if (
            prov is not None
            and not prov.pinned
            and prov.inputs
            and depth < PROVENANCE_MAX_DEPTH
            and all(i in by_id and i != oid for i in prov.inputs)
        ):
            ins = [pinned(i, depth + 1) for i in prov.inputs]
            obj = obj.with_(provenance=Provenance.of_inputs(prov.operation, prov.params, ins))
        visiting.discard(oid)
        done[oid] = obj
        return obj

    return [pinned(o.id, 0) for o in objects]


def read_project(path: str | os.PathLike[str], **kw: Any) -> Project:
    """Read and validate a project file (see :func:`parse_project`)."""
    p = Path(path)
    name = p.name
    with open_regular(p, name) as fh:  # a FIFO or device is refused, never waited on
        size = os.fstat(fh.fileno()).st_size
        if size > limits.MAX_FILE_BYTES:
            raise FileFormatError(
                f"{name}: the file is {size:,} bytes, larger than the limit of {limits.MAX_FILE_BYTES:,}"
            )
        data = fh.read(limits.MAX_FILE_BYTES + 1)
    if len(data) > limits.MAX_FILE_BYTES:
        raise FileFormatError(f"{name}: the file is larger than the limit of {limits.MAX_FILE_BYTES:,} bytes")
    return parse_project(data, name, **kw)


def load_project(path: str | os.PathLike[str]) -> Document:
    """Open a project file as a new document (clean, empty history, ``doc.path`` set).

    An open document is never touched: on any error nothing is created and the caller keeps what it had.
    """
    return read_project(path).to_document(Path(path))


def loads(data: bytes, name: str = "project") -> Document:
    """Build a document from the bytes of a project file."""
    return parse_project(data, name).to_document()
