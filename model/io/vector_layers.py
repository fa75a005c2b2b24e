"""Vector layers with attributes and a CRS: GeoPackage, Shapefile, FlatGeobuf, GeoJSON (ADR 0052).

Writing (:func:`write_layer`) and reading (:func:`read_layer`) go through ``pyogrio`` (GDAL's OGR) and the
CRS through ``pyproj``: the ``geo`` extra (``pip install 'mr-modeler[geo]'``), imported only here and only
when a layer is written or read.

* Coordinates are float64 as given: GeoPackage, Shapefile and FlatGeobuf store float64, and GeoJSON is
  written by :func:`mrm.io.vector_files.write_geojson`'s own encoder (``repr``), so every format reads back
  the very coordinates written (GDAL's GeoJSON writer rounds to 15 digits).
* The CRS: an EPSG code is written as the code; any other CRS as its WKT (GeoPackage, FlatGeobuf: WKT2;
  Shapefile: the ``.prj``). GeoJSON carries only a named ``crs`` (an EPSG URN, which GDAL and QGIS read),
  so a CRS without an EPSG code is **refused** for GeoJSON with a line naming the formats that keep it:
  writing the file without it would have GDAL read it as WGS 84, and reprojecting to RFC 7946's WGS 84
  would bend the exact straight edges.
* Every output is written atomically, a Shapefile's parts (``.shp .shx .dbf .prj .cpg``) as one output
  set (:func:`mrm.io.atomic.atomic_file_set`): all replaced, or none.
"""

from __future__ import annotations

import logging
import os
import re
import shutil
import tempfile
from collections.abc import Mapping, Sequence
from pathlib import Path
from typing import Any

import numpy as np
import numpy.typing as npt
import shapely
from shapely.geometry.base import BaseGeometry

from mrm.core import limits
from mrm.core.errors import FileFormatError, ParameterError
from mrm.io.atomic import atomic_file_set, atomic_open
from mrm.io.georef import geojson_crs_member
from mrm.io.reading import open_regular

log = logging.getLogger(__name__)

PathLike = str | os.PathLike[str]

#: The OGR driver of each vector layer extension.
LAYER_DRIVERS = {
    ".gpkg": "GPKG",
    ".shp": "ESRI Shapefile",
    ".fgb": "FlatGeobuf",
    ".geojson": "GeoJSON",
    ".json": "GeoJSON",
}
LAYER_EXTENSIONS = tuple(LAYER_DRIVERS)
#: The files a Shapefile is made of (written and replaced together).
SHAPEFILE_PARTS = (".shp", ".shx", ".dbf", ".prj", ".cpg")
#: A field name: a letter or _ then letters, digits, _ (no quotes, spaces or SQL); a Shapefile (dBase)
#: keeps at most 10 characters, so longer names are refused there rather than cut.
_FIELD = re.compile(r"[A-Za-z_][A-Za-z0-9_]{0,62}")
SHAPEFILE_FIELD_CHARS = 10
#: The first bytes of each binary format: no other file reaches GDAL under its name.
_MAGIC = {".gpkg": b"SQLite format 3\x00", ".fgb": b"fgb\x03", ".shp": b"\x00\x00\x27\x0a"}


def _pyogrio() -> Any:
    try:
        import pyogrio  # type: ignore[import-untyped]
    except ImportError:  # pragma: no cover - depends on the install
        raise FileFormatError(
            "vector layers (.gpkg .shp .fgb) need the geo extra: pip install 'mr-modeler[geo]' "
            "(it installs pyogrio and pyproj)"
        ) from None
    return pyogrio


def _pyproj_crs(text: str) -> Any:
    """The pyproj CRS of a CRS text (``EPSG:n`` or WKT), never read from a file or a URL."""
    try:
        from pyproj import CRS
    except ImportError:  # pragma: no cover - depends on the install
        raise FileFormatError("a CRS needs the geo extra: pip install 'mr-modeler[geo]' (pyproj)") from None
    m = re.fullmatch(r"\s*EPSG:([0-9]{1,9})\s*", text, re.IGNORECASE)
    try:
        return CRS.from_epsg(int(m.group(1))) if m is not None else CRS.from_wkt(text)
    except Exception as e:  # pyproj.exceptions.CRSError: one line
        raise FileFormatError(f"unreadable coordinate system ({str(e).splitlines()[0]})") from None


def crs_text(crs: Any) -> str | None:
    """``EPSG:n`` for a pyproj CRS with an EPSG code (exactly, no approximate match), else its WKT."""
    if crs is None:
        return None
    epsg = crs.to_epsg(min_confidence=100)
    return f"EPSG:{epsg}" if epsg is not None else str(crs.to_wkt())


def check_field_names(names: Sequence[str], path: PathLike) -> None:
    """Refuse field names a format cannot hold as they are (quotes, spaces, too long, twice)."""
    ext = Path(path).suffix.lower()
    seen: set[str] = set()
    for n in names:
        if not _FIELD.fullmatch(n):
            raise ParameterError(
                f"field name {n!r}: use letters, digits and _ (not starting with a digit), at most 63"
            )
        if ext == ".shp" and len(n) > SHAPEFILE_FIELD_CHARS:
            raise ParameterError(
                f"field name {n!r}: a Shapefile keeps at most {SHAPEFILE_FIELD_CHARS} characters"
            )
        if n.lower() in seen:
            raise ParameterError(f"field name {n!r} is given twice")
        seen.add(n.lower())


def write_layer(
    geometries: Sequence[BaseGeometry],
    fields: Mapping[str, npt.ArrayLike],
    path: PathLike,
    *,
    crs: str | None = None,
    layer: str | None = None,
) -> None:
    """Write features (a geometry and a value of each field) as a vector layer, atomically.

    Parameters
    ----------
    geometries : sequence of shapely geometries
        One per feature, in world coordinates; polygons and multipolygons are written as one layer type
        (MultiPolygon when any is multi).
    fields : mapping of str to array_like of int
        Each field's values, one per feature.
    path : str or path-like
        ``.gpkg``, ``.shp``, ``.fgb``, ``.geojson`` or ``.json``.
    crs : str, optional
        ``EPSG:n`` or WKT.
    layer : str, optional
        The layer name (GeoPackage, FlatGeobuf); default the file's stem.

    Raises
    ------
    ParameterError
        An unknown extension, a bad field name, or (GeoJSON) a CRS without an EPSG code.
    """
    p = Path(path)
    ext = p.suffix.lower()
    if ext not in LAYER_DRIVERS:
        raise ParameterError(f"{os.fspath(path)}: a vector layer is {', '.join(LAYER_EXTENSIONS)}")
    check_field_names(list(fields), p)
    columns = {k: np.asarray(v) for k, v in fields.items()}
    if LAYER_DRIVERS[ext] == "GeoJSON":
        _write_geojson_layer(geometries, columns, p, crs)
        return
    pyogrio = _pyogrio()
    geoms = np.asarray(list(geometries), dtype=object)
    multi = bool(geoms.size) and bool((shapely.get_type_id(geoms) == 6).any())
    wkt = None if crs is None else _pyproj_crs(crs)
    crs_arg = None if wkt is None else (crs_text(wkt) or "")
    limits.check_output_bytes(
        int(shapely.get_num_coordinates(geoms).sum()) * 16, f"{os.fspath(path)} (coordinates)"
    )
    p.parent.mkdir(parents=True, exist_ok=True)
    # GDAL writes a file (a Shapefile several) by name: into a private folder beside the output, then each
    # part is copied into the output set, so a failure leaves the old output as it was.
    with tempfile.TemporaryDirectory(prefix=f".{p.name}.", dir=p.parent) as tmp:
        out = Path(tmp) / f"layer{ext}"
        try:
            pyogrio.raw.write(
                str(out),
                shapely.to_wkb(geoms) if geoms.size else np.zeros(0, dtype=object),
                field_data=list(columns.values()),
                fields=list(columns),
                geometry_type="MultiPolygon" if multi else "Polygon",
                crs=crs_arg,
                driver=LAYER_DRIVERS[ext],
                layer=layer or p.stem,
                encoding="UTF-8" if ext == ".shp" else None,
            )
        except Exception as e:
            raise FileFormatError(f"{p.name}: GDAL could not write the layer ({e})") from None
        with atomic_file_set() as files:
            parts = SHAPEFILE_PARTS if ext == ".shp" else (ext,)
            for suffix in parts:
                src = out.with_suffix(suffix)
                dst = p.with_suffix(suffix)
                if src.is_file():
                    with open(src, "rb") as fin, atomic_open(dst, "wb") as fout:
                        shutil.copyfileobj(fin, fout, 1 << 20)
                else:
                    files.remove(dst)  # a .prj of an earlier CRS must not place this layer


def check_layer_crs(path: PathLike, crs: str | None) -> None:
    """Refuse, before any work, a CRS the output format cannot carry (GeoJSON: EPSG codes only)."""
    if crs is not None and LAYER_DRIVERS.get(Path(path).suffix.lower()) == "GeoJSON":
        _geojson_crs_member(Path(path), crs)


def _geojson_crs_member(p: Path, crs: str) -> dict[str, Any]:
    code = crs_text(_pyproj_crs(crs))
    member = None if code is None else geojson_crs_member(code)
    if member is None:
        raise ParameterError(
            f"{p.name}: GeoJSON names a CRS only by an EPSG code and this one has none; write .gpkg, "
            ".fgb or .shp, which keep it as WKT (or reproject the raster first: gdalwarp -t_srs)"
        )
    return member


def _write_geojson_layer(
    geometries: Sequence[BaseGeometry], columns: Mapping[str, Any], p: Path, crs: str | None
) -> None:
    """GeoJSON through our own exact encoder; a CRS without an EPSG code is refused (module docstring)."""
    from mrm.io.vector_files import write_features

    members: dict[str, Any] = {}
    if crs is not None:
        members["crs"] = _geojson_crs_member(p, crs)
    props = [{k: v[i].item() for k, v in columns.items()} for i in range(len(geometries))]
    write_features(list(geometries), props, p, members=members)


def read_layer_crs(path: PathLike) -> str | None:
    """The CRS of a vector layer (``EPSG:n``, WKT or None), from its header (:func:`read_layer`'s checks)."""
    return read_layer(path, None, geometries=False)[2]


def read_layer(
    path: PathLike, field: str | None = None, *, geometries: bool = True
) -> tuple[list[BaseGeometry], Any, str | None]:
    """Read a vector layer's geometries, one field's values (or None) and its CRS (``EPSG:n``, WKT or None).

    The file must be a regular file of the format its extension names (its first bytes checked) and at most
    :data:`mrm.io.vector_files.MAX_VECTOR_FILE_BYTES`; only the first layer is read.

    Raises
    ------
    FileFormatError
        Not a file of that format, too large, unreadable, or no field ``field``.
    """
    from mrm.io.vector_files import MAX_VECTOR_FILE_BYTES

    p = Path(path)
    ext = p.suffix.lower()
    if ext not in LAYER_DRIVERS:
        raise FileFormatError(f"{os.fspath(path)}: a vector layer is {', '.join(LAYER_EXTENSIONS)}")
    with open_regular(p, p.name) as fh:
        size = os.fstat(fh.fileno()).st_size
        head = fh.read(16)
    if size > MAX_VECTOR_FILE_BYTES:
        raise FileFormatError(f"{p.name}: {size:,} bytes, more than the {MAX_VECTOR_FILE_BYTES:,} read")
    magic = _MAGIC.get(ext)
    if magic is not None and not head.startswith(magic):
        raise FileFormatError(f"{p.name}: not a {LAYER_DRIVERS[ext]} file")
    pyogrio = _pyogrio()
    try:
        info = pyogrio.read_info(str(p))
        names = [str(n) for n in info["fields"]]
        if field is not None and field not in names:
            shown = ", ".join(names) if names else "none"
            raise FileFormatError(f"{p.name}: no field {field!r} (its fields: {shown})")
        if not geometries:
            crs_only = info.get("crs")
            return [], None, None if crs_only is None else crs_text(_pyproj_crs(crs_only))
        meta, _, wkb, data = pyogrio.raw.read(str(p), columns=[] if field is None else [field])
    except FileFormatError:
        raise
    except Exception as e:
        raise FileFormatError(f"{p.name}: unreadable vector layer ({str(e).splitlines()[0]})") from None
    geoms = list(shapely.from_wkb(wkb))
    n = int(shapely.get_num_coordinates(np.asarray(geoms, dtype=object)).sum()) if geoms else 0
    if n > limits.MAX_OBJECT_VERTICES:
        raise FileFormatError(
            f"{p.name}: {n:,} positions, more than the limit of {limits.MAX_OBJECT_VERTICES:,}"
        )
    crs = None if meta.get("crs") is None else crs_text(_pyproj_crs(meta["crs"]))
    values = None
    if field is not None:
        values = np.asarray(data[0])
        dtype = np.dtype(meta["dtypes"][0]) if meta.get("dtypes") is not None else values.dtype
        if dtype.kind not in "iuf":
            raise FileFormatError(f"{p.name}: field {field!r} holds {dtype} values; burning needs integers")
    return geoms, values, crs
