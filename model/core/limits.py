"""The limits of what a document can hold, declared once (ADR 0010).

Whatever a document can hold, its project file can hold and reopen: the same limits are checked at the edit,
operation or import that would exceed them (with a :class:`~mrm.core.errors.LimitError` or
:class:`~mrm.core.errors.SizeLimitError` naming the limit) and again by the project loader, which therefore
never refuses a file this program wrote. The costs of work whose size does not follow from the pixel count —
reconstruction (boundary length in crack steps), vector output (vertices), written files (bytes) — are
computed here from the input before the work starts.

Nothing here imports anything heavier than numpy, so every layer can use it.
"""

from __future__ import annotations

import json
from typing import Any

import numpy as np
import numpy.typing as npt

from mrm.core.errors import LimitError, ParameterError, SizeLimitError
from mrm.core.numbers import value_text

# ---------------------------------------------------------------------------------------------- the limits
#: Default maximum number of pixels of a discretization or an operation's result (a preference in the GUI,
#: ``--limit`` on the command line, ``limit=`` in the library).
DEFAULT_PIXEL_LIMIT = 200_000_000
#: Default maximum number of voxels of a voxelization or a 3D operation's result (a preference, ``--limit``,
#: ``limit=``), and of the bounding box of one voxel object: 2²⁹ (an 812³ box, 512 MB of mask).
DEFAULT_VOXEL_LIMIT = 1 << 29
#: Voxels in the bounding box of one voxel source.
MAX_OBJECT_VOXELS = DEFAULT_VOXEL_LIMIT
#: Triangles of one polyhedron (a mesh read, a reconstruction's result): about 100 bytes each in memory.
MAX_OBJECT_TRIANGLES = 20_000_000
#: Surfels (boundary squares between a voxel of the set and one outside) of a voxel set that may be
#: reconstructed; the 3D continuation costs tens of bytes per surfel.
MAX_SURFELS = 50_000_000
#: Triangles of the safety net up to which the 3D R is the compact one (its decimation, ADR 0064); beyond,
#: R is the safety net: the decimation takes about 55–90 µs per triangle today (a 20,000-triangle net,
#: about a ball of radius 30, in 1–2 s), far too slow for the desktop on bigger objects. The default of the
#: document's compact limit (``Settings.compact_limit``, ADR 0073) and of ``mrm reconstruct --compact-limit``.
MAX_COMPACT_R_TRIANGLES = 20_000
#: Surfels of a digitally convex voxel set up to which the 3D R tries the decimation beside its hull path
#: (under gauss the grown convex hull, ADR 0068; under the covers the spiked hull or the snapped core, ADRs
#: 0069–0070) and keeps the smaller: the hull paths are exact and take milliseconds, the decimation finds
#: about half the triangles on small balls but costs about a second at 20,000 surfels (a ball of radius
#: 32), and the hull is the smaller one on big balls under gauss anyway.
MAX_RIVAL_SURFELS = 20_000
#: Voxels of a label volume (four bytes each in memory).
MAX_LABEL_VOXELS = 1 << 28
#: Largest absolute coordinate of a Euclidean source. Beyond it pixel indices leave the int32 range the
#: kernels use, and float64 spacing there exceeds a millionth of a pixel, so nothing exact could follow.
COORDINATE_LIMIT = float(2**31)
#: Every pixel (x, y) of a discrete source has |x| ≤ this and |y| ≤ this (pixel files and projects alike).
PIXEL_COORDINATE_LIMIT = 2**31
#: Pixels in the bounding box of one discrete source.
MAX_OBJECT_PIXELS = DEFAULT_PIXEL_LIMIT
#: Pixels and voxels in the bounding boxes of all the grid sources (pixel and voxel sets, label maps and
#: volumes) of one document (one file) together: about 1 GB of masks at most, whatever a file claims. Masks
#: are stored bit-packed, not compressed, so their file is as big as they are (a file under 10 MB holds at
#: most 80 M pixels); labels are compressed and cost a file next to nothing (20 label maps in 5 MB took
#: 4.4 GB to load, issue 32), so a label counts :data:`LABEL_WEIGHT` times.
MAX_FILE_PIXELS = 1_000_000_000
#: What a label counts toward :data:`MAX_FILE_PIXELS`: its four bytes (int32) held, and as much again for
#: what reading and summarising it works with. Measured on projects of under 1 MB (issue 32): labels holding
#: 800 MB (weight 4) loaded at 1.05 GB and `mrm info` took 1.17 GB; at weight 8 they hold at most 500 MB
#: and `mrm info` stays under 1 GB. A label volume in a document is thus at most 125 M voxels.
LABEL_WEIGHT = 8
#: Vertices (coordinates, closing points included) of one Euclidean source.
MAX_OBJECT_VERTICES = 5_000_000
#: Longest object name, in characters.
MAX_NAME_CHARS = 10_000
#: Longest operation name in a provenance.
MAX_OPERATION_CHARS = 200
#: Largest object id (ids stay exact in every JSON reader).
MAX_ID = 2**53
#: Largest magnitude of an integer in provenance parameters.
MAX_PARAM_INT = 2**63
#: Nesting depth and JSON size of provenance parameters (free-form JSON data).
PARAMS_MAX_DEPTH = 16
PARAMS_MAX_CHARS = 1_000_000
#: Largest project file read; a document is kept :data:`FILE_BYTES_MARGIN` below it.
MAX_FILE_BYTES = 1 << 30
FILE_BYTES_MARGIN = 1 << 20
#: Boundary length (crack steps: pixel edges between a pixel of the set and one outside) of a pixel set
#: that may be reconstructed; reconstruction costs several hundred bytes per step.
MAX_CRACK_STEPS = 2_000_000
#: Labels of a label map polygonized at once (its watertight subdivision: ``mrm polygonize``,
#: :func:`mrm.polygonize`, a label map's polygons in the window): each label costs about half a millisecond of
#: assembling and exact checking whatever its size (a 693-byte PNG can hold 65,535 labels).
MAX_SUBDIVISION_LABELS = 20_000
#: Junctions (pixel corners where three labels meet, or two diagonally: the 0-cells) plus regions of a label
#: map polygonized at once. Each is a cell or a polygon of 1–3 kB, and each region one more GeoJSON Feature:
#: 120,000 keep ``mrm polygonize`` under 0.8 GB and about 20 s, where a 28 KB 2000² checkerboard has eight
#: million (ADR 0048).
MAX_SUBDIVISION_CELLS = 120_000
#: Largest file written by an export (SVG, GeoJSON, WKT, images).
MAX_OUTPUT_BYTES = 256 << 20
#: Pixels of a label map (four bytes each in memory).
MAX_LABEL_PIXELS = 50_000_000
#: Memory the cell counts of a label map's summary (``mrm info``) may take, estimated before the work at
#: :data:`LABEL_COUNT_BYTES_PER_PIXEL` a pixel and :data:`LABEL_COUNT_BYTES_PER_LINEL` a boundary linel
#: (measured: a 2000² checkerboard, 8·10⁶ linels, 690 MB; 16·10⁶ pixels of 100 blocks, 530 MB); beyond it
#: the summary leaves them out, so a small project file holding a big label map never costs gigabytes, and
#: ``mrm info`` stays under 1 GB with the interpreter and kernels (issue 32). The grids the summary already
#: holds (the map itself, or all of a project's) count against it: 4 label maps of 43·10⁶ pixels in a 0.9 MB
#: project took 1.17 GB when each map's counting had the whole budget.
MAX_LABEL_COUNT_BYTES = 640 << 20
LABEL_COUNT_BYTES_PER_PIXEL = 40
LABEL_COUNT_BYTES_PER_LINEL = 70
#: Nesting depth of geometries in WKT and GeoJSON files (a MultiPolygon in a GeometryCollection is 4).
MAX_GEOMETRY_NESTING = 32
#: Largest magnitude of a world coordinate of a georeferenced grid (a GeoTIFF's transform, a world file,
#: a project's ``georef``): the world point of every pixel a document can hold (grid coordinates within
#: ±:data:`PIXEL_COORDINATE_LIMIT`) stays within it under the grid-to-world map. Far beyond any
#: coordinate system (the Earth's circumference in nanometres is 4·10¹⁶), and far enough inside float64 that
#: squares and products of two coordinates (areas, GEOS's orientation tests) stay finite: a world file of
#: 1e308 made infinite coordinates and a GEOS exception at export (issue 32).
MAX_WORLD_COORDINATE = 1e100
#: Longest CRS text (WKT) of a georeference, in characters: a WKT2 definition is a few thousand.
MAX_CRS_CHARS = 100_000
#: Largest world file read: six numbers, a few hundred bytes at most (a 144 MB one took 3.9 GB to refuse).
MAX_WORLD_FILE_BYTES = 4096
#: Bytes of decoded samples a raster reader holds at once: one window of a GeoTIFF with its working copies,
#: and at most one of its blocks (strip or tile), which GDAL decodes whole. Beside the one-byte-per-pixel
#: mask (at most :data:`MAX_OBJECT_PIXELS`), a read then stays far under 1 GB whatever the sample type (a
#: 14 KB complex128 GeoTIFF decoded whole took 3.7 GB, issue 32).
MAX_DECODED_BYTES = 64 << 20
#: Steps of an error-bound chain (``mrm bounds``): its exact rationals grow with every step (500 steps of
#: arbitrary fractions take 2.3 s, 256 under 1 s), and real chains have a handful.
MAX_CHAIN_STEPS = 256

#: Bytes an object takes in a project file beyond its name, provenance and source (id, style, keys).
_OBJECT_OVERHEAD = 400
#: Upper bound of the bytes of one position ``[x, y], `` in a project file: two float reprs of ≤ 24
#: characters each and the punctuation.
_POSITION_BYTES = 56


# ---------------------------------------------------------------------------------------------- text
def clean_text(text: str) -> str:
    r"""``text`` with lone surrogates (which no UTF-8 file can hold) replaced by U+FFFD.

    Text read from files goes through this on the way in (JSON's ``"\ud800"`` escape gives a lone
    surrogate), so that a document never holds text it could not save.
    """
    try:
        text.encode("utf-8")
    except UnicodeEncodeError:
        # A surrogate pair spelt as two code points becomes the character it encodes; a lone one U+FFFD.
        return text.encode("utf-16-le", "surrogatepass").decode("utf-16-le", "replace")
    return text


def check_text(text: str, what: str) -> str:
    """Return ``text`` if it can be saved (valid Unicode, no lone surrogate), else raise LimitError."""
    try:
        text.encode("utf-8")
    except UnicodeEncodeError as e:
        raise LimitError(
            f"{what} holds a character that cannot be saved "
            f"(U+{ord(text[e.start]):04X} at position {e.start})"
        ) from None
    return text


def check_name(name: str) -> str:
    """Check an object name against :data:`MAX_NAME_CHARS` and :func:`check_text`."""
    if len(name) > MAX_NAME_CHARS:
        raise LimitError(
            f"an object name of {len(name):,} characters is longer than the limit of {MAX_NAME_CHARS:,}"
        )
    return check_text(name, "the object name")


def clean_name(name: str) -> str:
    """A name read from a file made acceptable: cleaned (:func:`clean_text`) and cut to the limit."""
    name = clean_text(name)
    return name if len(name) <= MAX_NAME_CHARS else name[: MAX_NAME_CHARS - 1] + "…"


def clean_json(value: Any) -> Any:
    """A JSON value read from a file with every string (keys too) passed through :func:`clean_text`.

    Iterative, so any nesting depth is fine; containers are rebuilt only where something changed.
    """
    if isinstance(value, str):
        return clean_text(value)
    if not isinstance(value, dict | list):
        return value
    out: Any = {} if isinstance(value, dict) else []
    stack: list[tuple[Any, Any]] = [(value, out)]
    while stack:
        src, dst = stack.pop()
        items = src.items() if isinstance(src, dict) else enumerate(src)
        for k, v in items:
            if isinstance(v, dict | list):
                child: Any = {} if isinstance(v, dict) else []
                stack.append((v, child))
            else:
                child = clean_text(v) if isinstance(v, str) else v
            if isinstance(dst, dict):
                dst[clean_text(str(k))] = child
            else:
                dst.append(child)
    return out


# ---------------------------------------------------------------------------------------------- pixels
def check_pixel_extent(
    origin: tuple[int, ...], shape: tuple[int, ...], what: str = "the pixel set", *, limit: int | None = None
) -> None:
    """Refuse a box of pixels or voxels (origin in coordinate order, shape in array order) beyond the limits.

    Two coordinates are pixels, three are voxels; ``limit`` replaces the per-object size limit
    (:data:`MAX_OBJECT_PIXELS` or :data:`MAX_OBJECT_VOXELS`).

    Raises
    ------
    LimitError
        When a point of the box has a coordinate beyond ±:data:`PIXEL_COORDINATE_LIMIT`.
    SizeLimitError
        When the box holds more points than the limit.
    """
    n = len(origin)
    size = [int(shape[n - 1 - d]) for d in range(n)]  # coordinate order
    if 0 in size:
        return
    o = [int(v) for v in origin]
    lim = PIXEL_COORDINATE_LIMIT
    unit = "pixel" if n == 2 else "voxel"
    if min(o) < -lim or max(o[d] + size[d] - 1 for d in range(n)) > lim:
        start = ", ".join(str(v) for v in o)
        dims = " × ".join(str(v) for v in size)
        raise LimitError(
            f"{what} would reach {unit} coordinates beyond ±2^31 (its box starts at ({start}) and is "
            f"{dims}); move it closer to the origin or reduce the scale"
        )
    count = 1
    for v in size:
        count *= v
    if limit is None:
        limit = MAX_OBJECT_PIXELS if n == 2 else MAX_OBJECT_VOXELS
    check_pixels(count, limit, what, unit=f"{unit}s")


def crack_steps(mask: npt.NDArray[Any], *, rows_per_strip: int = 1024) -> int:
    """The boundary length of a mask: pixel edges (2D) or voxel faces (3D, surfels) between the set and not.

    An unset point, or the outside of the array, on the other side. For an integer label array, the edges
    between two different labels (the outside is label 0): the boundaries of a label map's subdivision.

    Linear time; works in strips along the first array axis so that it needs at most a few bytes per point
    of one strip.
    """
    m = np.asarray(mask)
    if m.dtype.kind not in "biu":
        m = m.astype(bool)
    if m.ndim not in (2, 3) or m.size == 0:
        return 0
    h = m.shape[0]
    total = 0
    for r0 in range(0, h, rows_per_strip):
        s = m[r0 : r0 + rows_per_strip]
        # Neighbours along every axis but the first, with the outside as unset on both ends.
        for axis in range(1, m.ndim):
            total += int(np.count_nonzero(np.diff(s, axis=axis)))
            total += int(np.count_nonzero(s.take(0, axis=axis))) + int(
                np.count_nonzero(s.take(-1, axis=axis))
            )
        # Along the first axis inside the strip, and to the first row of the next strip (or the outside).
        total += int(np.count_nonzero(s[1:] != s[:-1]))
        below = m[r0 + rows_per_strip] if r0 + rows_per_strip < h else np.zeros(m.shape[1:], dtype=bool)
        total += int(np.count_nonzero(s[-1] != below))
    total += int(np.count_nonzero(m[0]))  # the first row against the outside
    return total


def check_reconstruct(ps: Any, what: str | None = None) -> int:
    """Refuse to reconstruct (R) a grid set whose boundary is too long, before any work.

    A pixel set's crack steps are bounded by :data:`MAX_CRACK_STEPS`, a voxel set's surfels by
    :data:`MAX_SURFELS`.

    Returns the boundary length; call before any reconstruction work.
    """
    steps = crack_steps(ps.mask)
    if ps.mask.ndim == 3:
        if steps > MAX_SURFELS:
            raise LimitError(
                f"{what or 'the voxel set'} has a boundary of {steps:,} voxel faces, more than the "
                f"{MAX_SURFELS:,} its polyhedron may have (noise?); smooth it first, or keep it as voxels"
            )
        return steps
    if steps > MAX_CRACK_STEPS:
        raise LimitError(
            f"{what or 'the pixel set'} has a boundary of {steps:,} pixel edges, more than the "
            f"{MAX_CRACK_STEPS:,} its polygon may have (a checkerboard-like or noisy image?); simplify or "
            "smooth it first, or keep it as pixels"
        )
    return steps


def check_compact_limit(n: object) -> int:
    """A compact limit (``Settings.compact_limit``, ``--compact-limit``) as an int.

    Raises
    ------
    ParameterError
        Unless ``n`` is a whole number of triangles from 1 to :data:`MAX_OBJECT_TRIANGLES` (no polyhedron, so
        no safety net, has more).
    """
    if isinstance(n, bool) or not isinstance(n, int | np.integer) or not 1 <= n <= MAX_OBJECT_TRIANGLES:
        raise ParameterError(
            f"the compact limit is a whole number of triangles from 1 to {MAX_OBJECT_TRIANGLES:,}, not {n!r}"
        )
    return int(n)


def label_junctions(labels: npt.NDArray[np.integer[Any]], *, rows_per_strip: int = 1024) -> int:
    """The junctions of a label array: pixel corners where three labels meet, or two diagonally.

    The outside is label 0. A corner is one exactly when at least three of the four pixel edges that meet
    there separate different labels. Linear time, in strips of rows (a few bytes per pixel of one strip).
    """
    lab = np.asarray(labels)
    if lab.ndim != 2 or lab.size == 0:
        return 0
    h, w = lab.shape
    zero = np.zeros((1, w), dtype=lab.dtype)
    total = 0
    for i0 in range(0, h + 1, rows_per_strip):
        i1 = min(i0 + rows_per_strip, h + 1)  # corner rows i0 … i1 − 1, each between pixel rows i − 1 and i
        rows = lab[max(i0 - 1, 0) : min(i1, h)]
        if i0 == 0:
            rows = np.vstack([zero, rows])
        if i1 == h + 1:
            rows = np.vstack([rows, zero])
        p = np.pad(rows, ((0, 0), (1, 1)))
        a, b, c, d = p[:-1, :-1], p[:-1, 1:], p[1:, :-1], p[1:, 1:]
        sides = (a != b).astype(np.uint8)
        sides += c != d
        sides += a != c
        sides += b != d
        total += int(np.count_nonzero(sides >= 3))
    return total


def check_subdivision(
    labels: npt.NDArray[np.integer[Any]], n_labels: int, n_regions: int, what: str | None = None
) -> int:
    """Refuse to polygonize a label map whose subdivision would cost too much, before any of the work.

    ``n_labels`` and ``n_regions`` count its distinct non-zero labels and its regions (4-connected
    components of one label). Checked: the labels against :data:`MAX_SUBDIVISION_LABELS`, the boundary
    length (edges between different labels) against :data:`MAX_CRACK_STEPS`, which also bounds the
    vertices and the size of any file written from the polygons, and the junctions plus regions against
    :data:`MAX_SUBDIVISION_CELLS`.

    Returns the boundary length.

    Raises
    ------
    LimitError
        Naming the count that is too large and its limit.
    """
    name = what or "the label map"
    if n_labels > MAX_SUBDIVISION_LABELS:
        raise LimitError(
            f"{name} has {n_labels:,} labels, more than the {MAX_SUBDIVISION_LABELS:,} that may be "
            "polygonized at once; merge labels, or split it into smaller maps"
        )
    steps = crack_steps(labels)
    if steps > MAX_CRACK_STEPS:
        raise LimitError(
            f"{name} has boundaries of {steps:,} pixel edges, more than the {MAX_CRACK_STEPS:,} its polygons "
            "may have (a checkerboard-like or noisy image?); smooth it first, or keep it as a label map"
        )
    junctions = label_junctions(labels)
    if junctions + n_regions > MAX_SUBDIVISION_CELLS:
        raise LimitError(
            f"{name} has {n_regions:,} regions and {junctions:,} corners where three labels meet, "
            f"{junctions + n_regions:,} pieces, more than the {MAX_SUBDIVISION_CELLS:,} that may be "
            "polygonized at once (a checkerboard-like or noisy image?); smooth it first, or keep it as a "
            "label map"
        )
    return steps


def check_pixels(estimated: int, limit: int | None, what: str, *, unit: str = "pixels") -> None:
    """The one size check: refuse work whose result would cover more than ``limit`` pixels, before any of it.

    ``estimated`` is an upper bound of the pixels the work would make (an operation's
    :attr:`~mrm.ops.registry.OperationSpec.estimate`, a discretization's box); None lifts the limit.
    ``unit`` names what is counted in the message ("voxels" in 3D).

    Raises
    ------
    SizeLimitError
        With the size the result would have had and the limit, for the message.
    ParameterError
        When ``limit`` is neither None nor a non-negative integer.
    """
    if limit is None:
        return
    if isinstance(limit, bool) or not isinstance(limit, int) or limit < 0:
        raise ParameterError(
            f"the {unit[:-1]} limit must be a non-negative integer or None, got {value_text(limit)}"
        )
    if estimated > limit:
        raise SizeLimitError(int(estimated), int(limit), what, unit)


# ---------------------------------------------------------------------------------------------- georeference
def check_transform(
    transform: tuple[float, ...], grid_map: tuple[float, ...], what: str = "the raster's transform"
) -> None:
    """Refuse a georeference whose pixels could lie beyond :data:`MAX_WORLD_COORDINATE` in the world.

    ``grid_map`` is its map from grid coordinates to the world, ``[A, B, D, E, X0, Y0]`` (X = A·u + B·v + X0,
    Y = D·u + E·v + Y0); ``transform`` is GDAL's (a, b, c, d, e, f), for the message. Every pixel corner a
    document can hold has |u|, |v| ≤ :data:`PIXEL_COORDINATE_LIMIT` + 1, so its world point is within
    ``|X0| + reach·(|A| + |B|)`` (and likewise for Y): a property of the map, the same for every frame on it
    (an object grown or moved on its raster's grid keeps it). The inverse map (world to grid) must be finite
    too. Import, operations and the project loader all build georeferences through
    :class:`mrm.core.georef.GeoRef`, which calls this: what imports also saves and reopens.

    Raises
    ------
    LimitError
        When a world coordinate could exceed the limit, or the pixels are too small to invert the map.
    """
    A, B, D, E, X0, Y0 = (float(v) for v in grid_map)
    reach = float(PIXEL_COORDINATE_LIMIT + 1)
    worst = max(abs(X0) + reach * (abs(A) + abs(B)), abs(Y0) + reach * (abs(D) + abs(E)))
    a, b, _c, d, e, _f = (float(v) for v in transform)
    shown = ", ".join(f"{float(v):.6g}" for v in transform)
    if not worst <= MAX_WORLD_COORDINATE:  # NaN fails too
        raise LimitError(
            f"{what} ({shown}) would put pixels at world coordinates beyond ±{MAX_WORLD_COORDINATE:.0e}, "
            "the limit of a georeference"
        )
    det = a * e - b * d
    with np.errstate(all="ignore"):
        inverse = np.array([e, b, d, a]) / det if det else np.array([np.inf])
    if not np.isfinite(inverse).all():
        raise LimitError(f"{what} ({shown}) has pixels too small (area {det:.3g}) to map back to the grid")


def check_crs_text(crs: str, what: str = "the CRS") -> str:
    """Refuse a CRS text longer than :data:`MAX_CRS_CHARS` characters (or one that cannot be saved)."""
    if len(crs) > MAX_CRS_CHARS:
        raise LimitError(
            f"{what} is a text of {len(crs):,} characters, longer than the limit of {MAX_CRS_CHARS:,}"
        )
    return check_text(crs, what)


# ---------------------------------------------------------------------------------------------- output
def check_output_bytes(estimate: int, what: str) -> None:
    """Refuse a file whose estimated size exceeds :data:`MAX_OUTPUT_BYTES`, before it is built."""
    if estimate > MAX_OUTPUT_BYTES:
        raise LimitError(
            f"{what} would be about {estimate / 2**20:,.0f} MB, more than the limit of "
            f"{MAX_OUTPUT_BYTES / 2**20:,.0f} MB"
        )


def check_vertices(n: int, what: str = "the polygon") -> None:
    """Refuse a Euclidean shape with more than :data:`MAX_OBJECT_VERTICES` vertices."""
    if n > MAX_OBJECT_VERTICES:
        raise LimitError(f"{what} has {n:,} vertices, more than the limit of {MAX_OBJECT_VERTICES:,}")


def check_chain_steps(n: int) -> None:
    """Refuse an error-bound chain of more than :data:`MAX_CHAIN_STEPS` steps, before any arithmetic."""
    if n > MAX_CHAIN_STEPS:
        raise LimitError(f"the chain has {n:,} steps, more than the limit of {MAX_CHAIN_STEPS:,}")


# ---------------------------------------------------------------------------------------------- parameters
def check_param_int(v: int, what: str = "a provenance parameter") -> int:
    """Refuse an integer parameter beyond ±:data:`MAX_PARAM_INT`."""
    if abs(v) > MAX_PARAM_INT:
        digits = len(str(abs(v))) if abs(v) < 10**4000 else "thousands of"
        raise LimitError(f"{what} is an integer of {digits} digits, beyond the limit of ±2^63")
    return v


# ---------------------------------------------------------------------------------------------- file cost
def json_bytes(value: Any) -> int:
    """Upper bound of the UTF-8 bytes of ``value`` in a project file (its ASCII-escaped JSON length)."""
    return len(json.dumps(value, allow_nan=False))


def source_file_bytes(kind: str, *, pixels: int = 0, coordinates: int = 0, rings: int = 0) -> int:
    """Upper bound of the bytes a source takes in a project file.

    A discrete source is its packed mask in base64 (exact) plus its origin and shape; a label map its
    zlib-compressed int32 labels in base64 (zlib's worst case: the raw bytes and 5 bytes per 16 KB block); a
    Euclidean source at most :data:`_POSITION_BYTES` per coordinate plus brackets per ring.
    """
    if kind == "discrete":
        return 4 * (((pixels + 7) // 8 + 2) // 3) + 120
    if kind == "labels":
        raw = 4 * pixels
        return 4 * ((raw + 5 * (raw // 16_384 + 1) + 6 + 2) // 3) + 160
    return _POSITION_BYTES * coordinates + 8 * rings + 120


def object_file_bytes(name_bytes: int, provenance_bytes: int, source_bytes: int) -> int:
    """Upper bound of the bytes of one object's line in a project file (selection entry included)."""
    return _OBJECT_OVERHEAD + name_bytes + provenance_bytes + source_bytes + 20


def check_document_totals(pixels: int, nbytes: int) -> None:
    """Refuse a document whose discrete sources or file size would exceed the per-file limits."""
    check_pixels(
        pixels,
        MAX_FILE_PIXELS,
        f"the pixel objects of the document together (a label counts as {LABEL_WEIGHT} pixels)",
    )
    if nbytes > MAX_FILE_BYTES - FILE_BYTES_MARGIN:
        raise LimitError(
            f"the document would need a project file of about {nbytes / 2**20:,.0f} MB, more than the limit "
            f"of {(MAX_FILE_BYTES - FILE_BYTES_MARGIN) / 2**20:,.0f} MB; remove or simplify objects"
        )


__all__ = [name for name in dir() if name.isupper() and not name.startswith("_")] + [
    "check_chain_steps",
    "check_crs_text",
    "check_pixels",
    "check_document_totals",
    "check_name",
    "check_output_bytes",
    "check_param_int",
    "check_pixel_extent",
    "check_reconstruct",
    "check_subdivision",
    "check_text",
    "check_transform",
    "check_vertices",
    "clean_json",
    "clean_name",
    "clean_text",
    "crack_steps",
    "json_bytes",
    "label_junctions",
    "object_file_bytes",
    "source_file_bytes",
]
