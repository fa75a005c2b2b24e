"""Project files (``*.mrm``): one versioned JSON document, validated on load, written atomically.

Schema version 6::

    {
     "format": "mrm-project",
     "schema_version": 6,
     "generator": "MR Modeler 0.1.0",                      (optional, informative)
     "settings": {"model": "standard", "compact_limit": 20000},   (compact_limit optional, schema 6)
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
                                "labels": "<base64 of zlib of int32 little-endian>"}},
      {"id": 5, ..., "source": {"kind": "discrete", "origin": [-4, -4, -4], "shape": [9, 9, 9],
                                "bits": "<base64>"}},
      {"id": 6, ..., "source": {"kind": "polyhedron", "vertices": [[0.0, 0.0, 2.5], ...],
                                "triangles": [[0, 2, 1], ...]}}
     ]
    }

* Only each object's **source** representation is stored (docs/design.md §7); the others are derived on load.
* A provenance pins the content its inputs had when the result was made (``input_contents``: digests of
  :func:`mrm.ops.provenance.content_digest`) and their own provenance then (``input_provenance``); each pinned
  content is stored once in the top-level ``"contents": {digest: source}`` table (optional), shared by every
  result that read it, and checked against its digest on load. Version 1 files had ids only: on load their
  provenance is pinned to the objects the file holds (the best record there is).
* ``georef`` (optional, schema 3): where the object's grid lies on the Earth, the GDAL affine
  ``transform`` (a, b, c, d, e, f, written with ``repr``: bit for bit), the raster's ``width`` and
  ``height``, its ``crs`` (``EPSG:n``, WKT or null) and the grid ``origin`` of its bottom-left pixel
  (:class:`mrm.core.georef.GeoRef`, ADR 0021). Absent for an object on a plain grid.
* A discrete source is its canonical (cropped) mask, ``np.packbits`` row-major (row 0 = lowest y, big-endian
  bit order) in base64, with its origin and shape: compact, and valid JSON.
* A label map (``kind: "labels"``, schema 4, ADR 0033) is its canonical (cropped) int32 label array,
  row-major (row 0 = lowest y), little-endian, zlib-compressed, in base64, with its origin and shape.
* A voxel set or label volume (schema 5, docs/design.md §11) is stored as a pixel set or label map is, with
  three origin coordinates [x0, y0, z0] and the shape [nz, ny, nx] of its ``mask[k, j, i]``: the number of
  origin coordinates is the dimension. A polyhedron (``kind: "polyhedron"``, schema 5) is its float64
  vertices (``repr``, bit for bit) and its outward triangles as vertex indices; it is validated exactly on
  load (:class:`mrm.geometry.polyhedra.Polyhedron`).
* ``settings.compact_limit`` (schema 6, ADR 0073): the most triangles of a voxel set's safety net that its R
  simplifies (:attr:`mrm.document.Settings.compact_limit`); absent in older files, which get the default.
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
import functools
import json
import os
import zlib
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np
from shapely.geometry import MultiPolygon, Polygon

from mrm.core import limits
from mrm.core.errors import FileFormatError as FileFormatError
from mrm.core.grids import GridSet, LabelGrid
from mrm.core.models import Model
from mrm.document import DocObject, Document, Geometry, Settings, Source, Style
from mrm.document.objects import is_polyhedron
from mrm.io.atomic import atomic_write_bytes
from mrm.io.project_decode import Checker, check_grid_budget, decode_object, decode_source
from mrm.io.reading import open_regular
from mrm.ops.provenance import PROVENANCE_MAX_DEPTH, Provenance, content_digest

#: The value of the "format" key.
FORMAT = "mrm-project"
#: The schema version this code writes (and the newest it reads).
SCHEMA_VERSION = 6
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
    Migration(
        4,
        "a discrete source or label map may be a voxel set or label volume (origin [x0, y0, z0], shape "
        "[nz, ny, nx]), and a source may be a polyhedron (kind 'polyhedron'); a version 4 file has none, so "
        "it reads unchanged",
        lambda data: {**data, "schema_version": 5},
    ),
    Migration(
        5,
        "the settings may hold the compact limit of the voxel objects' R (compact_limit); a version 5 file "
        "has none, so it reads unchanged with the default limit",
        lambda data: {**data, "schema_version": 6},
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
def _encode_pixels(ps: GridSet[Any, Any]) -> dict[str, Any]:
    bits = np.packbits(ps.mask, axis=None).tobytes() if ps.count else b""
    return {
        "kind": "discrete",
        "origin": [int(v) for v in ps.origin],
        "shape": [int(v) for v in ps.shape],
        "bits": base64.b64encode(bits).decode("ascii"),
    }


def _encode_labels(lm: LabelGrid[Any, Any, Any]) -> dict[str, Any]:
    raw = zlib.compress(lm.labels.astype("<i4", copy=False).tobytes(), 6) if lm.labels.size else b""
    return {
        "kind": "labels",
        "origin": [int(v) for v in lm.origin],
        "shape": [int(v) for v in lm.shape],
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
    if isinstance(source, GridSet):
        return _encode_pixels(source)
    if isinstance(source, LabelGrid):
        return _encode_labels(source)
    if is_polyhedron(source):
        # Python floats: json writes their repr, so every float64 comes back bit for bit
        return {
            "kind": "polyhedron",
            "vertices": source.vertices.tolist(),
            "triangles": source.triangles.tolist(),
        }
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
        ("settings", {"model": doc.settings.model, "compact_limit": doc.settings.compact_limit}),
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


def migrate(
    data: dict[str, Any],
    name: str = "project",
    migrations: Sequence[Migration] = MIGRATIONS,
    current: int = SCHEMA_VERSION,
) -> dict[str, Any]:
    """Upgrade the JSON data of a project file to schema ``current``, applying ``migrations`` in order."""
    c = Checker(name)
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
    c = Checker(name)
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
    st = c.obj(raw["settings"], "$.settings", ("model",), ("compact_limit",))
    model = c.str_(st["model"], "$.settings.model", 40)
    if model not in Model.names():
        c.fail(
            "$.settings.model", f"unknown model {c.show(model)}; expected one of {', '.join(Model.names())}"
        )
    compact_limit = (
        c.int_(st["compact_limit"], "$.settings.compact_limit", 1, limits.MAX_OBJECT_TRIANGLES)
        if "compact_limit" in st
        else limits.MAX_COMPACT_R_TRIANGLES
    )
    settings = Settings(model=Model(model), compact_limit=compact_limit)
    objs_raw = c.list_(raw["objects"], "$.objects")
    table_raw = raw.get("contents")
    check_grid_budget(
        c,
        [
            (src, f"$.contents[{key!r}]")
            for key, src in (table_raw if isinstance(table_raw, dict) else {}).items()
        ]
        + [
            (o.get("source"), f"$.objects[{i}].source") for i, o in enumerate(objs_raw) if isinstance(o, dict)
        ],
    )
    contents: dict[str, Source] = {}
    if "contents" in raw:  # the pinned input contents of the provenance records, each stored once
        keys = tuple(raw["contents"]) if isinstance(raw["contents"], dict) else ()
        table = c.obj(raw["contents"], "$.contents", (), keys)
        for key, src in table.items():
            c.str_(key, "$.contents", 64)
            value = decode_source(c, src, f"$.contents[{key!r}]")
            if content_digest(value) != key:  # a digest names its content: a file cannot make it lie
                c.fail(f"$.contents[{key!r}]", "the content does not match its digest")
            contents[key] = value
    objects: list[DocObject] = []
    seen: dict[int, int] = {}
    for i, o in enumerate(objs_raw):
        obj = decode_object(c, o, f"$.objects[{i}]", contents)
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
    visiting: list[int] = []  # the objects being pinned, each an input of the one before
    cyclic: set[int] = set()

    def pinned(oid: int, depth: int) -> DocObject:
        if oid in done:
            return done[oid]
        obj = by_id[oid]
        if oid in visiting:
            # A cycle of ids (a hand-made file: a result's inputs exist before it): no object on it records
            # what its inputs were, so none is pinned, and its account says so (issue 32: a half-pinned
            # cycle made `mrm account` fail on a record without content).
            cyclic.update(visiting[visiting.index(oid) :])
            return obj
        visiting.append(oid)
        prov = obj.provenance
        if (
            prov is not None
            and not prov.pinned
            and prov.inputs
            and depth < PROVENANCE_MAX_DEPTH
            and all(i in by_id and i != oid for i in prov.inputs)
        ):
            ins = [pinned(i, depth + 1) for i in prov.inputs]
            if oid not in cyclic:
                obj = obj.with_(provenance=Provenance.of_inputs(prov.operation, prov.params, ins))
        visiting.pop()
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
