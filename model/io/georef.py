"""Georeferenced rasters: GeoTIFF and image + world file, their transform and CRS (docs/gdal.md, ADR 0016).

MR Modeler works in **grid coordinates**: pixel (x, y) is centred on the point (x, y), y up (docs/design.md
§1). A raster of H rows whose GDAL affine transform is ``T`` (``X = a·col + b·row + c``, ``Y = d·col + e·row +
f``, with (col, row) = (0, 0) the top-left corner of the top-left pixel) is read with its bottom-left pixel at
(0, 0), so grid point (u, v) is the raster position (col, row) = (u + ½, H − ½ − v) and the world point

    (X, Y) = T · (u + ½, H − ½ − v).

In GDAL's words: the grid coordinates of an unreferenced image with origin (x0, y0) *are* world coordinates
under ``from_origin(x0 − ½, y0 + H − ½, 1, 1)``. :class:`GeoRef` holds ``T``, the raster's size and its CRS,
and maps geometries both ways (:meth:`GeoRef.to_world`, :meth:`GeoRef.to_grid`); an affine map carries
every exactness statement over (D and R commute with it as long as it is the raster's own grid).

Formats:

``.tif`` / ``.tiff``
    GeoTIFF through rasterio (the ``geo`` extra: ``pip install 'mr-modeler[geo]'``). Band 1 is read;
    non-zero samples (or those brighter than ``threshold``) are in the set, ``nodata`` samples never are.
    Written as one uint8 band (0/1) covering the georeference's whole frame, with its transform and CRS.
``.png`` / ``.pgm`` / ``.pbm`` + world file
    A world file beside the image (``name.pgw``, ``name.pngw``, ``name.wld``, …: six lines A D B E C F, where
    C, F is the *centre* of the top-left pixel) gives the transform, and ``name.prj`` (WKT) the CRS. No
    rasterio needed.
"""

from __future__ import annotations

import contextlib
import json
import logging
import math
import os
import re
import warnings
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import numpy as np

from mrm.core import limits
from mrm.core.errors import FileFormatError, MRMError, ParameterError
from mrm.core.georef import GeoRef, Transform, grid_origin, unit_grid
from mrm.core.grids import PixelSet
from mrm.core.limits import DEFAULT_PIXEL_LIMIT, check_pixel_extent, check_pixels
from mrm.core.threshold import _check_threshold, binarize
from mrm.io.atomic import atomic_file_set, atomic_open, atomic_write_bytes, atomic_write_text
from mrm.io.pixel_files import ORIGIN_KEY, parse_origin, read_pixels
from mrm.io.reading import describe_content, open_regular, read_regular

log = logging.getLogger(__name__)

PathLike = str | os.PathLike[str]

#: Extensions of GeoTIFF files.
GEOTIFF_EXTENSIONS = (".tif", ".tiff")
#: Image extensions a world file may accompany, and the world file extensions tried for each (in order).
WORLD_FILE_EXTENSIONS = {
    ".png": (".pgw", ".pngw", ".wld"),
    ".pgm": (".pgmw", ".wld"),
    ".pbm": (".pbmw", ".wld"),
    ".tif": (".tfw", ".tifw", ".wld"),
    ".tiff": (".tfw", ".tiffw", ".wld"),
}
#: A geometry covering fewer pixels than this gets a warning (wrong units? a polygon in degrees?).
FEW_PIXELS = 5


def _rasterio() -> Any:
    try:
        import rasterio
    except ImportError:  # pragma: no cover - depends on the install
        raise FileFormatError(
            "GeoTIFF needs the geo extra: pip install 'mr-modeler[geo]' (it installs rasterio)"
        ) from None
    return rasterio


# ---------------------------------------------------------------------------------------------- opening
#: The first four bytes of a TIFF (little- and big-endian) and of a BigTIFF: nothing else reaches GDAL.
TIFF_MAGIC = (b"II*\x00", b"MM\x00*", b"II+\x00", b"MM\x00+")
#: GDAL's configuration while a GeoTIFF is read (ADR 0047): the file given and nothing else. No folder
#: listing, so no sidecar (.ovr, .msk, .aux.xml, .tfw, .tab, .imd …) is looked for; no PAM (.aux.xml read
#: or written); the georeference from the TIFF's own tags (a world file beside it is read by
#: :func:`read_georef`, bounded); no /vsicurl/ file; a block cache of the decoding budget, so that decoded
#: blocks do not pile up.
GDAL_READ_OPTIONS: dict[str, Any] = {
    "GDAL_DISABLE_READDIR_ON_OPEN": "EMPTY_DIR",
    "GDAL_PAM_ENABLED": "NO",
    "GDAL_GEOREF_SOURCES": "INTERNAL",
    "CPL_VSIL_CURL_ALLOWED_EXTENSIONS": ".mrm-none",
    "GDAL_CACHEMAX": limits.MAX_DECODED_BYTES,
}


def _fd_path(fd: int, path: PathLike) -> str:
    """A name GDAL opens that is the open file ``fd`` itself (Linux, macOS), else ``path``.

    Opening ``/proc/self/fd/N`` reopens the very file that was checked, so no rename or symlink swap between
    the check and GDAL's open can give GDAL another file; and no sidecar of the real name is ever found.
    """
    for folder in ("/proc/self/fd", "/dev/fd"):
        candidate = f"{folder}/{fd}"
        if os.path.exists(candidate):
            return candidate
    return os.fspath(path)  # pragma: no cover - Windows: the magic check still guards GDAL


@contextlib.contextmanager
def open_geotiff(path: PathLike, name: str | None = None) -> Iterator[Any]:
    """Open a GeoTIFF with rasterio, GDAL restricted to that one real TIFF file (ADR 0047).

    The file is opened first (:func:`mrm.io.reading.open_regular`: a FIFO or device is refused without
    blocking) and its first bytes must be a TIFF's or BigTIFF's: a GDAL VRT (XML) or any other format named
    ``.tif`` never reaches GDAL, whatever it points at (a local file, ``/dev/urandom``, a named pipe, a URL).
    GDAL then opens that descriptor with the GTiff driver alone and the options of
    :data:`GDAL_READ_OPTIONS`.

    Raises
    ------
    FileFormatError
        Not a TIFF, or a TIFF GDAL cannot read.
    """
    shown = os.fspath(path) if name is None else name
    rasterio = _rasterio()
    # A TIFF without georeference tags is an ordinary input here (a plain mask), not worth a warning line.
    warnings.filterwarnings("ignore", category=rasterio.errors.NotGeoreferencedWarning)
    with open_regular(path, shown) as fh:
        head = fh.read(16)
        if head[:4] not in TIFF_MAGIC:
            raise FileFormatError(
                f"{shown}: not a GeoTIFF ({describe_content(head)}); only TIFF files are read"
            )
        with rasterio.Env(**GDAL_READ_OPTIONS):
            try:
                ds = rasterio.open(_fd_path(fh.fileno(), path), driver="GTiff", sharing=False)
            except rasterio.errors.RasterioIOError as e:
                raise FileFormatError(f"{shown}: not a readable GeoTIFF ({e})") from None
            with ds:
                yield ds


# ---------------------------------------------------------------------------------------------- CRS
def _crs_text(crs: Any) -> str | None:
    """``EPSG:n`` when the CRS has a code, else its WKT (None for no CRS)."""
    if crs is None:
        return None
    epsg = crs.to_epsg()
    return f"EPSG:{epsg}" if epsg is not None else str(crs.to_wkt())


def geojson_crs_member(crs: str | None) -> dict[str, Any] | None:
    """The (pre-RFC 7946) ``crs`` member GDAL and QGIS read, e.g. ``urn:ogc:def:crs:EPSG::32633``.

    None for no CRS, or a CRS without an EPSG code (GDAL would then assume EPSG:4326; see docs/gdal.md).
    """
    if crs is None or not crs.upper().startswith("EPSG:"):
        return None
    return {"type": "name", "properties": {"name": f"urn:ogc:def:crs:EPSG::{crs.split(':', 1)[1]}"}}


def read_geojson_crs(path: PathLike) -> str | None:
    """The CRS a GeoJSON file names in its ``crs`` member (``EPSG:n``), or None."""
    try:
        with open_regular(path) as fh:
            doc = json.loads(fh.read(1 << 27))
    except (ValueError, RecursionError):
        return None  # the vector reader reports a malformed file
    crs = doc.get("crs") if isinstance(doc, dict) else None
    name = crs.get("properties", {}).get("name") if isinstance(crs, dict) else None
    if not isinstance(name, str):
        return None
    code = name.rsplit(":", 1)[-1]
    if "EPSG" in name.upper() and code.isdigit():
        return f"EPSG:{code}"
    return name


#: CRS texts given to GDAL's general parser: an EPSG code or an OGC URN. Anything else is parsed as WKT only,
#: because the general parser (OSRSetFromUserInput, behind rasterio's ``CRS.from_user_input``) also reads a
#: file or fetches a URL named by the text: a ``.prj`` or a GeoJSON ``crs`` saying ``/etc/passwd`` must not.
_CRS_CODE = re.compile(r"\s*(EPSG:[0-9]{1,9}|urn:ogc:def:crs:[A-Za-z0-9.:_-]{1,120})\s*", re.IGNORECASE)


def parse_crs(text: str) -> Any:
    """The rasterio CRS of a CRS text (``EPSG:n``, an OGC URN or WKT), never read from a file or a URL.

    Raises whatever rasterio raises for a text it cannot parse.
    """
    crs = _rasterio().crs.CRS
    m = _CRS_CODE.fullmatch(text)
    return crs.from_user_input(m.group(1)) if m is not None else crs.from_wkt(text)


def same_crs(a: str | None, b: str | None) -> bool:
    """Whether two CRS texts name the same system (EPSG codes compared; WKT through rasterio if present)."""
    if a is None or b is None or a == b:
        return a == b
    try:
        return bool(parse_crs(a) == parse_crs(b))
    except Exception:  # unparsable CRS text: only equal texts are the same
        return False


# ---------------------------------------------------------------------------------------------- world files
def world_file_of(path: PathLike) -> Path | None:
    """The world file beside ``path`` (``name.pgw`` for ``name.png``, …), or None."""
    p = Path(path)
    for ext in WORLD_FILE_EXTENSIONS.get(p.suffix.lower(), ()):
        for candidate in (p.with_suffix(ext), p.with_suffix(ext.upper())):
            if candidate.is_file():
                return candidate
    return None


def parse_world_file(text: str, name: str) -> tuple[float, float, float, float, float, float]:
    """Parse a world file into GDAL's (a, b, c, d, e, f); it holds A D B E C F, C/F at a pixel's centre."""
    try:
        vals = [float(v) for v in text.split()]
    except ValueError:
        raise FileFormatError(f"{name}: a world file holds six numbers") from None
    if len(vals) != 6 or not all(math.isfinite(v) for v in vals):
        raise FileFormatError(f"{name}: a world file holds six finite numbers, found {len(vals)}")
    a, d, b, e, c, f = vals
    # C, F: the centre of the top-left pixel; GDAL's c, f: its top-left corner.
    return (a, b, c - 0.5 * a - 0.5 * b, d, e, f - 0.5 * d - 0.5 * e)


def world_file_text(transform: Transform) -> str:
    """The six lines of a world file (A D B E C F) for GDAL's transform, written with ``repr``."""
    a, b, c, d, e, f = transform
    return (
        "\n".join(repr(float(v)) for v in (a, d, b, e, c + 0.5 * a + 0.5 * b, f + 0.5 * d + 0.5 * e)) + "\n"
    )


_NETPBM_ORIGIN = re.compile(rb"#\s*mrm:origin\s+(-?\d+)\s+(-?\d+)")


def image_frame(path: PathLike) -> tuple[int, int, int, int]:
    """The box (xmin, ymin, xmax, ymax) of every pixel of an image file, from its header.

    The pixel readers place an image's bottom-left pixel at its ``mrm:origin`` (PNG text, Netpbm comment),
    a GeoTIFF's at :func:`grid_origin`, else at (0, 0); this is the frame they place it in. ``--invert`` and
    the georeference of a world file need it, which the (cropped) pixel set has lost. NPZ files hold sets,
    not pictures: refused.
    """
    from PIL import Image

    ext = Path(path).suffix.lower()
    if ext in GEOTIFF_EXTENSIONS:
        with open_geotiff(path, Path(path).name) as ds:
            georef = _georef_of(ds, Path(path))
            if georef is not None:
                return georef.frame
            return 0, 0, int(ds.width) - 1, int(ds.height) - 1
    if ext not in (".png", ".pbm", ".pgm"):
        raise ParameterError(f"{os.fspath(path)}: --invert applies to images (PNG, Netpbm, GeoTIFF) only")
    name = Path(path).name
    with open_regular(path, name) as fh, Image.open(fh) as im:  # reads the header only
        width, height = im.size
        text = getattr(im, "text", {}) if ext == ".png" else {}
        origin = parse_origin(text[ORIGIN_KEY], name) if ORIGIN_KEY in text else (0, 0)
    if ext != ".png":
        with open_regular(path, name) as fh:
            m = _NETPBM_ORIGIN.search(fh.read(4096))
        if m is not None:
            origin = (int(m.group(1)), int(m.group(2)))
    return origin[0], origin[1], origin[0] + width - 1, origin[1] + height - 1


def read_georef(path: PathLike) -> GeoRef | None:
    """The georeference of a raster: a GeoTIFF's own, or an image's world file (+ ``.prj``); else None.

    Its ``origin`` is where the pixel readers (:func:`mrm.io.pixel_files.read_pixels`) put the raster's
    bottom-left pixel, so that ``read_georef(p).to_world`` maps what ``read_pixels(p)`` gives. A GeoTIFF
    without georeference tags takes its world file's transform, as GDAL would. Every georeference is within
    the limits of :mod:`mrm.core.limits` (world coordinates, CRS length), so what imports also saves and
    reopens; a world file or ``.prj`` beyond them is refused with a message naming it.
    """
    p = Path(path)
    if p.suffix.lower() in GEOTIFF_EXTENSIONS:
        with open_geotiff(p, p.name) as ds:
            return _georef_of(ds, p)
    if world_file_of(p) is None:
        return None
    return _world_file_georef(p, image_frame(p), None)


def _georef_of(ds: Any, p: Path) -> GeoRef | None:
    """The georeference of an open GeoTIFF (its tags, else a world file beside it), or None."""
    t = ds.transform
    if t.is_identity:  # no georeference tags: a world file beside it, or none (a plain TIFF)
        return _world_file_georef(p, (0, 0, int(ds.width) - 1, int(ds.height) - 1), _tiff_crs(ds, p))
    g = _georef(p.name, (t.a, t.b, t.c, t.d, t.e, t.f), int(ds.width), int(ds.height), _tiff_crs(ds, p))
    origin = grid_origin(g)
    return g if origin == (0, 0) else GeoRef(g.transform, g.width, g.height, g.crs, origin)


def _tiff_crs(ds: Any, p: Path) -> str | None:
    try:
        return _crs_text(ds.crs)
    except Exception as e:  # a CRS GDAL read but PROJ cannot express
        raise FileFormatError(f"{p.name}: unreadable coordinate system ({e})") from None


def _georef(
    name: str,
    transform: Transform,
    width: int,
    height: int,
    crs: str | None,
    origin: tuple[int, int] = (0, 0),
) -> GeoRef:
    """A GeoRef read from file ``name``; a refusal (limits, a singular transform) names the file."""
    try:
        return GeoRef(transform, width, height, crs, origin)
    except MRMError as e:
        raise type(e)(f"{name}: {e}") from None


def _world_file_georef(p: Path, frame: tuple[int, int, int, int], crs: str | None) -> GeoRef | None:
    """The georeference of image ``p`` (pixels in ``frame``) from its world file and CRS, or None.

    The CRS is GDAL's: the PAM file ``name.png.aux.xml`` (:func:`read_pam_srs`), else a ``.prj`` (what MR
    Modeler wrote before it wrote the PAM file; GDAL ignores it). Every file is read bounded
    (:data:`~mrm.core.limits.MAX_WORLD_FILE_BYTES`, the CRS limit) and only when it is a regular file.
    """
    wf = world_file_of(p)
    if wf is None:
        return None
    raw = read_regular(wf, limits.MAX_WORLD_FILE_BYTES, "a world file", wf.name)
    transform = parse_world_file(raw.decode("ascii", errors="replace"), wf.name)
    prj = p.with_suffix(".prj")
    aux = pam_file_of(p)
    source = p.name  # the file a refusal names: where the CRS text came from
    if crs is None and aux.is_file():  # GDAL's place for an image's CRS (it ignores a .prj beside a PNG)
        crs, source = read_pam_srs(aux), aux.name
    if crs is None and prj.is_file():
        # UTF-8 takes at most 4 bytes a character: a longer file cannot hold a CRS within the limit.
        text = read_regular(prj, 4 * limits.MAX_CRS_CHARS, "a CRS (.prj)", prj.name)
        crs, source = text.decode("utf-8", errors="replace").strip() or None, prj.name
    if crs is not None:
        try:
            limits.check_crs_text(crs, f"{source}: the CRS")
            crs = _crs_text(parse_crs(crs))
        except MRMError:
            raise
        except Exception:  # no rasterio, or a WKT it cannot parse: keep the text as it is
            log.debug("kept the CRS text of %s as it is", p.name)
    x0, y0, x1, y1 = frame
    return _georef(wf.name, transform, x1 - x0 + 1, y1 - y0 + 1, crs, (x0, y0))


def write_world_file(path: PathLike, georef: GeoRef) -> Path:
    """Write the world file (and ``.prj`` for a CRS) beside the image ``path``; returns the world file.

    One output set (:func:`mrm.io.atomic.atomic_file_set`, joining the caller's, which holds the image): a
    ``.prj`` left from an earlier georeference is removed when this one has no CRS, so the image never reads
    back with a CRS that is not its own.
    """
    p = Path(path)
    wf = p.with_suffix(WORLD_FILE_EXTENSIONS.get(p.suffix.lower(), (".wld",))[0])
    prj = p.with_suffix(".prj")
    aux = pam_file_of(p)
    with atomic_file_set() as files:
        atomic_write_text(wf, world_file_text(georef.transform))
        if georef.crs is None:
            files.remove(prj)
            files.remove(aux)
        else:
            text = georef.crs
            try:
                text = parse_crs(georef.crs).to_wkt()
            except Exception:  # no rasterio: EPSG codes are written as they are
                log.debug("wrote the CRS of %s as text", p.name)
            atomic_write_text(prj, text + "\n")
            # GDAL (and so rasterio, QGIS) reads an image's CRS from its PAM file, never from the .prj.
            atomic_write_text(aux, pam_text(text))
    return wf


# ------------------------------------------------------------------------------------------ PAM (.aux.xml)
#: The largest ``.aux.xml`` read: a CRS within its limit (4 bytes a character at most) and some markup.
MAX_PAM_BYTES = 4 * limits.MAX_CRS_CHARS + (64 << 10)
_XML_DECLARATIONS = re.compile(rb"<!\s*(DOCTYPE|ENTITY|ELEMENT|ATTLIST)", re.IGNORECASE)


def pam_file_of(path: PathLike) -> Path:
    """GDAL's PAM side file of an image: ``name.png.aux.xml``."""
    p = Path(path)
    return p.with_name(p.name + ".aux.xml")


def pam_text(crs_wkt: str) -> str:
    """The ``.aux.xml`` GDAL reads an image's CRS from: ``<PAMDataset><SRS>WKT</SRS></PAMDataset>``."""
    from xml.sax.saxutils import escape

    return f"<PAMDataset>\n  <SRS>{escape(crs_wkt)}</SRS>\n</PAMDataset>\n"


def read_pam_srs(path: PathLike) -> str | None:
    """The CRS text (``<SRS>``) of a GDAL PAM file, or None when it names none.

    Our own bounded reader: at most :data:`MAX_PAM_BYTES`, a regular file only, and no document type
    declaration (so no entity expands: a "billion laughs" file or an external entity is refused unread).

    Raises
    ------
    FileFormatError
        Too large, a declaration, not XML, or not a ``PAMDataset``.
    """
    import xml.etree.ElementTree as ET

    p = Path(path)
    raw = read_regular(p, MAX_PAM_BYTES, "a GDAL side file (.aux.xml)", p.name)
    if _XML_DECLARATIONS.search(raw):
        raise FileFormatError(f"{p.name}: an .aux.xml with a document type declaration is not read")
    try:
        root = ET.fromstring(raw)
    except ET.ParseError as e:
        raise FileFormatError(f"{p.name}: not a GDAL .aux.xml ({e})") from None
    if root.tag != "PAMDataset":
        raise FileFormatError(f"{p.name}: not a GDAL .aux.xml (its root is <{root.tag[:40]}>)")
    srs = root.find("SRS")
    text = None if srs is None or srs.text is None else srs.text.strip()
    return text or None


# ---------------------------------------------------------------------------------------------- GeoTIFF
def read_raster(
    path: PathLike,
    *,
    threshold: float | None = None,
    limit: int = DEFAULT_PIXEL_LIMIT,
) -> tuple[PixelSet, GeoRef | None]:
    """Read band 1 of a GeoTIFF as a pixel set and its georeference.

    The band is decoded a window of whole blocks at a time (at most
    :data:`~mrm.core.limits.MAX_DECODED_BYTES` of samples and working copies), straight into the mask: the
    peak is about one byte per pixel whatever the sample type (ADR 0047).

    Parameters
    ----------
    path : str or path-like
    threshold : float, optional
        Samples greater than it are in the set; by default every non-zero sample is.
    limit : int
        Rasters with more pixels are refused from their header.

    Returns
    -------
    pixels : PixelSet
        Placed where :func:`read_georef` says (its ``origin``: (0, 0), or (x0, y0) for a unit grid).
    georef : GeoRef or None
        None for a TIFF without georeference.

    Raises
    ------
    FileFormatError
        Not a TIFF (a VRT or any other file named ``.tif``), unreadable, or stored in blocks larger than the
        decoding budget.
    SizeLimitError
        More pixels than ``limit``.
    """
    rasterio = _rasterio()
    p = Path(path)
    name = p.name
    if threshold is not None:
        _check_threshold(threshold)
    with open_geotiff(p, name) as ds:
        width, height = int(ds.width), int(ds.height)
        check_pixels(width * height, limit, f"{name}: the raster")
        georef = _georef_of(ds, p)
        nodata = ds.nodata
        mask = np.zeros((height, width), dtype=bool)  # bottom row first, as a PixelSet holds it
        try:
            for win in _windows(ds, name):
                band = ds.read(1, window=win)
                r0, c0, c1 = int(win.row_off), int(win.col_off), int(win.col_off + win.width)
                # The working copies of a few rows at a time, within the budget too.
                step = max(1, limits.MAX_DECODED_BYTES // (_WORKING_BYTES * band.shape[1]))
                for k in range(0, band.shape[0], step):
                    rows = _in_set(band[k : k + step], nodata, threshold)
                    top = r0 + k  # image row of rows[0]; row r is mask row height − 1 − r
                    mask[height - top - rows.shape[0] : height - top, c0:c1] = rows[::-1]
                del band
        except rasterio.errors.RasterioError as e:
            raise FileFormatError(f"{name}: corrupt GeoTIFF ({e})") from None
        except MemoryError:
            raise FileFormatError(f"{name}: not enough memory to decode this GeoTIFF") from None
    ps = PixelSet.taking_over(mask, (0, 0))
    dx, dy = grid_origin(georef)
    return (ps.translate(dx, dy) if (dx, dy) != (0, 0) else ps), georef


#: Bytes of working copies per sample while samples are turned into mask rows (the validity mask, the
#: comparison, int64 copies for an integer threshold): they are made a few rows at a time, within the budget.
_WORKING_BYTES = 24


def _windows(ds: Any, name: str, band: int = 1) -> Iterator[Any]:
    """Windows of band ``band`` covering the raster, each whole blocks of at most the decoding budget.

    Refuses a raster stored in blocks (strips or tiles, which GDAL decodes whole) of more than
    :data:`~mrm.core.limits.MAX_DECODED_BYTES`, before any is decoded.
    """
    from rasterio.windows import Window

    budget = limits.MAX_DECODED_BYTES
    width, height = int(ds.width), int(ds.height)
    bh, bw = (int(v) for v in ds.block_shapes[band - 1])
    bh, bw = max(1, min(bh, height)), max(1, min(bw, width))
    itemsize = np.dtype(ds.dtypes[band - 1]).itemsize
    # A pixel-interleaved block holds every band's sample of its pixels.
    interleaved = ds.count > 1 and getattr(ds.interleaving, "name", "") == "pixel"
    block_bytes = bh * bw * itemsize * (ds.count if interleaved else 1)
    if block_bytes > budget:
        raise FileFormatError(
            f"{name}: the TIFF stores its samples in blocks of {bh}×{bw} pixels ({block_bytes:,} bytes "
            f"decoded each), more than the {budget:,} read at once; rewrite it tiled or in strips "
            "(gdal_translate -co TILED=YES)"
        )
    if bh * width * itemsize <= budget:  # whole rows of blocks
        rows = bh * max(1, budget // (bh * width * itemsize))
        for r0 in range(0, height, rows):
            yield Window(0, r0, width, min(rows, height - r0))
        return
    cols = bw * max(1, budget // (bh * bw * itemsize))  # one row of blocks, a few blocks at a time
    for r0 in range(0, height, bh):
        for c0 in range(0, width, cols):
            yield Window(c0, r0, min(cols, width - c0), min(bh, height - r0))


def _in_set(band: Any, nodata: float | None, threshold: float | None) -> Any:
    """The mask rows (top first) of a window of samples: non-zero, or above ``threshold``; never nodata."""
    valid = np.ones(band.shape, dtype=bool) if nodata is None else band != nodata
    if band.dtype.kind == "f":
        valid &= np.isfinite(band)
        return (band > (0.0 if threshold is None else threshold)) & valid
    if threshold is None:
        return (band != 0) & valid
    if band.dtype.kind == "c":  # a threshold compares the real part
        return (band.real > threshold) & np.isfinite(band.real) & valid
    grey = np.where(valid, band, 0).astype(np.int64)
    return binarize(np.clip(grey, 0, None), threshold) & valid


def write_raster(ps: PixelSet, path: PathLike, georef: GeoRef) -> None:
    """Write the pixels of ``georef``'s frame as a one-band uint8 GeoTIFF (1 = in the set), atomically.

    Pixels outside the frame are not written; :func:`write_georeferenced` grows the frame to hold them.
    """
    rasterio = _rasterio()

    image = ps.to_image(georef.frame).astype(np.uint8)
    profile = {
        "driver": "GTiff",
        "width": georef.width,
        "height": georef.height,
        "count": 1,
        "dtype": "uint8",
        "transform": rasterio.Affine(*georef.transform),
        # Parsed by our own reader: rasterio's from_user_input would also read a file a CRS text names.
        "crs": None if georef.crs is None else parse_crs(georef.crs),
        "compress": "deflate",
        "nbits": 1,
    }
    with rasterio.io.MemoryFile() as mem:
        with mem.open(**profile) as ds:
            ds.write(image, 1)
        data = mem.read()
    # GDAL reads ``name.tif.aux.xml`` before the file's own georeference: one left from the old file would
    # place the new one (GDAL's own Create deletes it too). The TIFF and that removal are one output set.
    with atomic_file_set() as files:
        with atomic_open(path, "wb") as fh:
            fh.write(data)
        files.remove(f"{os.fspath(path)}.aux.xml")


def few_pixels_warning(ps: PixelSet, geom: Any, what: str) -> str | None:
    """A warning when a geometry with area covers fewer than :data:`FEW_PIXELS` pixels, else None."""
    if len(ps) >= FEW_PIXELS or getattr(geom, "is_empty", True):
        return None
    return (
        f"{what} covers only {len(ps)} pixel{'s' if len(ps) != 1 else ''}: are its coordinates in other "
        "units than the pixel grid (degrees?)? Give --resolution (world units per pixel) or --like RASTER"
    )


def read_pixels_tif(
    path: PathLike, *, threshold: float | None = None, limit: int = DEFAULT_PIXEL_LIMIT
) -> PixelSet:
    """:func:`mrm.io.pixel_files.read_pixels` for a GeoTIFF: band 1, placed by :func:`grid_origin`."""
    return read_raster(path, threshold=threshold, limit=limit)[0]


def read_pixels_georef(
    path: PathLike, *, threshold: float | None = None, limit: int = DEFAULT_PIXEL_LIMIT
) -> tuple[PixelSet, GeoRef | None]:
    """A pixel file's pixels (:func:`mrm.io.pixel_files.read_pixels`) and its georeference, if it has one.

    What an import keeps on the object (``DocObject.georef``): the GeoTIFF's transform and CRS, or the world
    file's, consistent with where the pixels were placed.
    """
    if Path(path).suffix.lower() in GEOTIFF_EXTENSIONS:
        return read_raster(path, threshold=threshold, limit=limit)
    ps = read_pixels(path, threshold=threshold, limit=limit)
    georef = read_georef(path) if Path(path).suffix.lower() in WORLD_FILE_EXTENSIONS else None
    return ps, georef


#: The pixel files a georeferenced result may be written to: a GeoTIFF, or an image with a world file.
GEOREFERENCED_EXTENSIONS = (".tif", ".tiff", ".png")


def write_georeferenced(ps: PixelSet, path: PathLike, georef: GeoRef) -> GeoRef:
    """Write ``ps`` on ``georef``'s grid: a GeoTIFF, or a PNG + world file (+ ``.prj``); atomically.

    The frame is the georeference's, grown to hold every pixel of ``ps`` (:meth:`GeoRef.covering`), so an
    object read from a raster and written back unchanged gets the raster's transform and size back. Returns
    the georeference written.
    """
    ext = Path(path).suffix.lower()
    if ext not in GEOREFERENCED_EXTENSIONS:
        raise ParameterError(
            f"{os.fspath(path)}: a georeferenced result is written as .tif or .png (+ world file)"
        )

    grid = georef.covering(ps.bbox)
    check_pixel_extent((grid.frame[0], grid.frame[1]), (grid.height, grid.width), f"{Path(path).name}")
    if ext in GEOTIFF_EXTENSIONS:
        write_raster(ps, path, grid)
        return grid
    import io

    from PIL import Image

    buf = io.BytesIO()
    Image.fromarray(ps.to_image(grid.frame)).save(buf, format="PNG")  # the world file's top-left pixel
    # The PNG, its world file and .prj are one output set: a full disk never leaves the new picture placed
    # by the old world file (issue 32).
    with atomic_file_set():
        atomic_write_bytes(path, buf.getvalue())
        # The PNG carries no mrm:origin: it reads back at (0, 0) with the world file placing it.
        write_world_file(path, grid)
    return grid


def georef_summary(georef: GeoRef | None) -> dict[str, Any]:
    """The ``crs`` and ``transform`` keys of a georeferenced result's ``--json`` summary (or none)."""
    if georef is None:
        return {}
    return {"crs": georef.crs, "transform": list(georef.transform)}


def geojson_members(georef: GeoRef | None, world_geom: Any) -> dict[str, Any]:
    """The FeatureCollection members of a georeferenced result: ``crs`` (EPSG URN) and ``bbox``."""
    if georef is None:
        return {}
    members: dict[str, Any] = {}
    crs = geojson_crs_member(georef.crs)
    if crs is not None:
        members["crs"] = crs
    if not world_geom.is_empty:
        members["bbox"] = list(world_geom.bounds)
    return members


def write_pixels_tif(ps: PixelSet, path: PathLike) -> None:
    """:func:`mrm.io.pixel_files.write_pixels` for a GeoTIFF: the bounding box on its :func:`unit_grid`."""
    # The grid's pixel (0, 0) is the set's origin (x0, y0): unit_grid maps it to the world point (x0, y0).
    x0, y0 = ps.origin
    write_raster(ps.translate(-x0, -y0), path, unit_grid(ps))
