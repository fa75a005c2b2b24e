"""Classified rasters: a band of a GeoTIFF as a label map, and a label map written as a georeferenced raster.

A classified GeoTIFF (land cover, a segmentation) holds one class value per pixel. :func:`read_label_raster`
reads band ``N`` through the checked opener :func:`mrm.io.georef.open_geotiff` (ADR 0047), a window of whole
blocks at a time, and gives a :class:`~mrm.core.grids.LabelMap` placed where :func:`mrm.io.georef.read_georef`
places the raster, with the class values it stands for:

* the *background* — no region — is the band's nodata pixels (the file's nodata, or ``nodata=`` given) and
  the pixels a ``mask`` leaves out; every other value is a class, 0 included, as ``gdal_polygonize`` does;
* class values are integers (a float band is accepted when every class value is an integer);
* a LabelMap keeps 0 for the background, so class value ``values[k - 1]`` is stored as label ``k``.

:func:`write_label_raster` writes a label image on a georeference: a GeoTIFF (the smallest integer type that
holds the labels) or a PNG + world file (+ ``.prj`` and GDAL's ``.aux.xml``), atomically.
"""

from __future__ import annotations

import logging
import os
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np
import numpy.typing as npt

from mrm.core import limits
from mrm.core.errors import FileFormatError, ParameterError
from mrm.core.georef import GeoRef, grid_origin
from mrm.core.grids import LabelMap
from mrm.core.limits import check_pixels
from mrm.io.atomic import atomic_file_set, atomic_open, atomic_write_bytes
from mrm.io.georef import (
    GEOTIFF_EXTENSIONS,
    _georef_of,
    _rasterio,
    _windows,
    open_geotiff,
    parse_crs,
    read_pixels_georef,
    write_world_file,
)

log = logging.getLogger(__name__)

PathLike = str | os.PathLike[str]


@dataclass(frozen=True)
class LabelRaster:
    """A classified band read as a label map.

    Attributes
    ----------
    labels : LabelMap
        Label ``k`` (1, 2, …) is the class ``values[k - 1]``; 0 is the background (nodata, masked out).
    values : numpy.ndarray of int64
        The class values, increasing.
    georef : GeoRef or None
        The raster's transform, size and CRS (None for a TIFF without georeference).
    """

    labels: LabelMap
    values: npt.NDArray[np.int64]
    georef: GeoRef | None


def _class_values(band: npt.NDArray[Any], valid: npt.NDArray[np.bool_], name: str) -> npt.NDArray[Any]:
    """The samples as integers (a float band's as int64), refusing non-integer or huge class values."""
    if band.dtype.kind == "f":
        v = band[valid]
        bad = ~np.isfinite(v) | (v != np.round(v)) | (np.abs(v) >= 2**31)
        if bad.any():
            raise FileFormatError(
                f"{name}: a classified band holds integer class values; found {float(v[bad][0])!r} "
                "(give --nodata for the value that means no data)"
            )
        return np.where(valid, band, 0).astype(np.int64)  # nodata (NaN) never cast
    if band.dtype.kind not in "iub":
        raise FileFormatError(f"{name}: a classified band holds integers, not {band.dtype}")
    return band


#: Rows of pixels numbered at a time (their int64 working copies stay within a few megabytes).
_STRIP_PIXELS = 1 << 20


def read_label_raster(
    path: PathLike,
    *,
    band: int = 1,
    nodata: float | None = None,
    mask: PathLike | None = None,
    limit: int = limits.MAX_LABEL_PIXELS,
) -> LabelRaster:
    """Read band ``band`` of a classified GeoTIFF as a label map (see the module docstring).

    The band is decoded a window of whole blocks at a time (ADR 0047) into an array of its own integer type
    (int64 for a float band); the peak is about 6 bytes per pixel beyond that array (the int32 labels, the
    validity mask).

    Parameters
    ----------
    path : str or path-like
        A GeoTIFF.
    band : int
        The band to read, from 1.
    nodata : float, optional
        The value of the pixels that are no region; default: the band's own nodata, if any.
    mask : str or path-like, optional
        A pixel file of the raster's size (a GeoTIFF on the same grid, or a PNG, PGM, PBM): its zero
        pixels are no region (``gdal_polygonize -mask``).
    limit : int
        Rasters with more pixels are refused from their header.

    Returns
    -------
    LabelRaster

    Raises
    ------
    FileFormatError
        Not a TIFF, non-integer class values, more classes than a subdivision takes, a mask of another
        size or grid.
    ParameterError
        A band the raster does not have, a ``nodata`` value the band's type cannot hold.
    """
    rasterio = _rasterio()
    p = Path(path)
    name = p.name
    with open_geotiff(p, name) as ds:
        width, height = int(ds.width), int(ds.height)
        if not isinstance(band, int) or isinstance(band, bool) or not 1 <= band <= int(ds.count):
            raise ParameterError(f"{name}: no band {band}; the raster has {ds.count} (bands count from 1)")
        check_pixels(width * height, limit, f"{name}: the raster")
        georef = _georef_of(ds, p)
        dtype = np.dtype(ds.dtypes[band - 1])
        if nodata is None:
            nodata = ds.nodatavals[band - 1]
        else:
            _check_nodata(nodata, dtype, name)
        store = dtype if dtype.kind in "iub" else np.dtype(np.int64)
        rows = np.zeros((height, width), dtype=store)  # top row first, as the band
        valid = np.zeros((height, width), dtype=bool)
        found: list[npt.NDArray[np.int64]] = []
        try:
            for win in _windows(ds, name, band):
                data = ds.read(band, window=win)
                r0, c0 = int(win.row_off), int(win.col_off)
                r1, c1 = r0 + data.shape[0], c0 + data.shape[1]
                if nodata is None:
                    ok = np.ones(data.shape, dtype=bool)
                elif data.dtype.kind == "f" and np.isnan(nodata):
                    ok = ~np.isnan(data)
                else:
                    ok = data != nodata
                valid[r0:r1, c0:c1] = ok
                ints = _class_values(data, ok, name)
                rows[r0:r1, c0:c1] = ints
                found.append(_distinct(ints[ok]))
                del data, ok, ints
        except rasterio.errors.RasterioError as e:
            raise FileFormatError(f"{name}: corrupt GeoTIFF ({e})") from None
    if mask is not None:
        valid &= mask_rows(mask, (height, width), georef, name)
    values = np.unique(np.concatenate(found)) if found else np.zeros(0, np.int64)
    if values.size > limits.MAX_SUBDIVISION_LABELS:
        raise FileFormatError(
            f"{name}: {values.size:,} class values, more than the {limits.MAX_SUBDIVISION_LABELS:,} a "
            "polygonization takes: is it a classified raster (or give --nodata / --mask)?"
        )
    labels = np.zeros((height, width), dtype=np.int32)  # bottom row first, as a LabelMap holds it
    step = max(1, _STRIP_PIXELS // max(1, width))
    for r0 in range(0, height, step):
        r1 = min(height, r0 + step)
        k = np.searchsorted(values, rows[r0:r1]).astype(np.int32) + 1
        k[~valid[r0:r1]] = 0
        labels[height - r1 : height - r0] = k[::-1]
    del rows, valid
    if mask is not None:  # a mask may leave some class with no pixel: keep only the values still present
        present = _present(labels, values.size)
        if not present[1:].all():
            renumber = np.cumsum(present).astype(np.int32) - 1
            labels = renumber[labels]
            values = values[present[1:]]
    lm = LabelMap.taking_over(labels, grid_origin(georef))
    return LabelRaster(lm, values.astype(np.int64), georef)


def _distinct(v: npt.NDArray[Any]) -> npt.NDArray[np.int64]:
    """The distinct values of valid samples, a million at a time (8/16-bit types: a table of seen values)."""
    v = v.ravel()
    small = v.dtype.itemsize <= 2 and v.dtype.kind in "iub"
    lo = int(np.iinfo(v.dtype).min) if small and v.dtype.kind == "i" else 0
    seen = np.zeros(1 << (8 * v.dtype.itemsize), dtype=bool) if small else None
    out = np.zeros(0, np.int64)
    for i in range(0, v.size, _STRIP_PIXELS):
        chunk = v[i : i + _STRIP_PIXELS].astype(np.int64)
        if seen is not None:
            seen[chunk - lo] = True
        else:
            out = np.union1d(out, chunk)
    return (np.flatnonzero(seen).astype(np.int64) + lo) if seen is not None else out


def _present(labels: npt.NDArray[np.int32], n: int) -> npt.NDArray[np.bool_]:
    """Which of the labels 0..n occur, a strip at a time (no full-size int64 copy)."""
    present = np.zeros(n + 1, dtype=bool)
    flat = labels.ravel()
    for i in range(0, flat.size, _STRIP_PIXELS):
        present[flat[i : i + _STRIP_PIXELS]] = True
    return present


def _check_nodata(nodata: float, dtype: np.dtype[Any], name: str) -> None:
    """Refuse a nodata value the band's type cannot hold (it would silently match nothing)."""
    if dtype.kind == "f":
        return
    info = np.iinfo(dtype) if dtype.kind in "iu" else np.iinfo(np.uint8)
    if nodata != nodata or nodata != int(nodata) or not (info.min <= nodata <= info.max):
        raise ParameterError(
            f"{name}: --nodata {nodata:g} is not a value of the band's type {dtype} "
            f"(integers from {info.min} to {info.max})"
        )


def mask_rows(
    mask: PathLike, shape: tuple[int, int], georef: GeoRef | None, name: str
) -> npt.NDArray[np.bool_]:
    """The mask file's pixels as rows (top first) of the raster's shape: True where a region may be.

    The mask's size (and, for a georeferenced mask, its transform) is checked from its header before any
    pixel is decoded.
    """
    from mrm.io.georef import image_frame, read_georef

    mname = Path(mask).name
    if Path(mask).suffix.lower() not in (*GEOTIFF_EXTENSIONS, ".png", ".pgm", ".pbm"):
        raise ParameterError(
            f"{os.fspath(mask)}: a mask is an image (.tif .png .pgm .pbm) of the input's size"
        )
    h, w = shape
    mgeo = read_georef(mask)
    if mgeo is not None:
        if (mgeo.width, mgeo.height) != (w, h) or (
            georef is not None and tuple(mgeo.transform) != tuple(georef.transform)
        ):
            raise FileFormatError(
                f"{mname}: the mask is not on the grid of {name} ({mgeo.width}×{mgeo.height} pixels, "
                f"transform {tuple(mgeo.transform)})"
            )
        x0, y0 = mgeo.origin
    else:
        x0, y0, x1, y1 = image_frame(mask)
        if (x1 - x0 + 1, y1 - y0 + 1) != (w, h):
            raise FileFormatError(
                f"{mname}: the mask has {x1 - x0 + 1}×{y1 - y0 + 1} pixels, the raster {name} {w}×{h}"
            )
    ps, _ = read_pixels_georef(mask, limit=h * w)
    return ps.to_image((x0, y0, x0 + w - 1, y0 + h - 1))


# ---------------------------------------------------------------------------------------------- writing
#: Label raster types, smallest first: a label image is written in the first that holds its range.
_LABEL_DTYPES = ("uint8", "uint16", "int16", "uint32", "int32")


def label_dtype(lo: int, hi: int) -> str:
    """The smallest GeoTIFF sample type holding every label from ``lo`` to ``hi``."""
    for dt in _LABEL_DTYPES:
        info = np.iinfo(dt)
        if info.min <= lo and hi <= info.max:
            return dt
    raise ParameterError(f"labels from {lo} to {hi} do not fit in a 32-bit raster")


def write_label_raster(rows: npt.NDArray[Any], path: PathLike, georef: GeoRef) -> None:
    """Write a label image (``rows``: top row first, ``georef``'s size) as GeoTIFF or PNG + world file.

    A GeoTIFF gets the smallest integer type holding the labels (:func:`label_dtype`), deflate-compressed;
    a PNG 8 or 16-bit grey (labels from 0 to 65535), with its world file, ``.prj`` and ``.aux.xml``
    (:func:`mrm.io.georef.write_world_file`). Each is one output set (ADR 0049).
    """
    p = Path(path)
    ext = p.suffix.lower()
    lo, hi = (int(rows.min()), int(rows.max())) if rows.size else (0, 0)
    if ext in GEOTIFF_EXTENSIONS:
        rasterio = _rasterio()
        profile = {
            "driver": "GTiff",
            "width": georef.width,
            "height": georef.height,
            "count": 1,
            "dtype": label_dtype(lo, hi),
            "transform": rasterio.Affine(*georef.transform),
            "crs": None if georef.crs is None else parse_crs(georef.crs),
            "compress": "deflate",
            "tiled": True,
        }
        with rasterio.io.MemoryFile() as mem:
            with mem.open(**profile) as ds:
                ds.write(rows.astype(profile["dtype"]), 1)
            data = mem.read()
        with atomic_file_set() as files:
            with atomic_open(p, "wb") as fh:
                fh.write(data)
            files.remove(f"{os.fspath(p)}.aux.xml")
        return
    if ext != ".png":
        raise ParameterError(f"{os.fspath(path)}: a georeferenced label raster is written as .tif or .png")
    if lo < 0 or hi > 65535:
        raise ParameterError(
            f"{p.name}: labels from {lo} to {hi} do not fit in a PNG (0 to 65535); write a .tif"
        )
    import io

    from PIL import Image

    buf = io.BytesIO()
    Image.fromarray(np.ascontiguousarray(rows).astype(np.uint8 if hi <= 255 else np.uint16)).save(buf, "PNG")
    with atomic_file_set():
        atomic_write_bytes(p, buf.getvalue())
        write_world_file(p, georef)
