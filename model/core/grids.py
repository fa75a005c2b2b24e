"""Immutable pixel sets and label maps that keep their place on the grid (docs/design.md §1).

A pixel p = (x, y) ∈ Z² is centred on the Euclidean point (x, y); y points up. In memory a pixel set is an
integer origin (x0, y0) plus a boolean ``mask[row, col]`` with x = x0 + col and y = y0 + row. Two pixel sets
are equal when they hold the same points, whatever the extent of their arrays; the canonical form is
cropped to the bounding box (an empty set has origin (0, 0) and a 0×0 mask).
"""

from __future__ import annotations

import pickle
from collections.abc import Iterable, Iterator
from typing import Any, SupportsIndex, TypeVar, cast

import numpy as np
import numpy.typing as npt

from mrm.core.limits import DEFAULT_PIXEL_LIMIT, check_pixels
from mrm.core.threshold import binarize, grey_of

BoolArray = npt.NDArray[np.bool_]
IntArray = npt.NDArray[np.int64]

#: A box of pixels (xmin, ymin, xmax, ymax), bounds included.
Box = tuple[int, int, int, int]

_N = TypeVar("_N", int, float)


def joint_box(boxes: Iterable[tuple[_N, _N, _N, _N] | None]) -> tuple[_N, _N, _N, _N] | None:
    """The smallest box ``(xmin, ymin, xmax, ymax)`` holding every given box (None when there is none).

    Pixel boxes and float bounds alike; a None among ``boxes`` (an empty set) is skipped.
    """
    real = [b for b in boxes if b is not None]
    if not real:
        return None
    return min(b[0] for b in real), min(b[1] for b in real), max(b[2] for b in real), max(b[3] for b in real)


def box_area(box: Box | None) -> int:
    """The number of pixels of a box ``(x0, y0, x1, y1)`` (0 for None or an empty box)."""
    if box is None:
        return 0
    return max(0, box[2] - box[0] + 1) * max(0, box[3] - box[1] + 1)


def _frozen(a: npt.NDArray[Any], *, fresh: bool = False) -> npt.NDArray[Any]:
    """Return a read-only view of a private, C-contiguous copy of ``a``.

    The copy means no caller keeps a writable alias of the data (a read-only *view* of a writable array can
    still change under our feet); returning a view of a read-only base means the writeable flag cannot be
    switched back on (numpy refuses for views of read-only arrays). ``fresh=True`` skips the copy for an
    array the caller has just allocated and holds no other reference to: one that owns its data, or whose
    memory belongs to no other array (a numba kernel's result is held by numba's own ``MemInfo``; copying
    the label image a kernel painted was 300 MB more of fresh memory at 10⁸ pixels).
    """
    own = a.flags.owndata or not isinstance(a.base, np.ndarray)
    if not (fresh and own and a.flags.c_contiguous):
        a = np.array(a, order="C", copy=True)
    a.flags.writeable = False
    return a.view()


def _crop_bounds(mask: BoolArray) -> tuple[int, int, int, int] | None:
    """Return (row0, row1, col0, col1), half-open, of the True entries, or None if there are none."""
    rows = np.flatnonzero(mask.any(axis=1))
    if rows.size == 0:
        return None
    cols = np.flatnonzero(mask.any(axis=0))
    return int(rows[0]), int(rows[-1]) + 1, int(cols[0]), int(cols[-1]) + 1


def _box(origin: tuple[int, int], shape: tuple[int, ...]) -> Box:
    """(xmin, ymin, xmax, ymax) of a non-empty array placed at ``origin``."""
    x0, y0 = origin
    return (x0, y0, x0 + int(shape[1]) - 1, y0 + int(shape[0]) - 1)


def _cell(p: object, origin: tuple[int, int], shape: tuple[int, ...]) -> tuple[int, int] | None:
    """(row, col) of pixel ``p`` = (x, y) in an array placed at ``origin``, or None when it is none of its.

    Like a Python set of integer tuples: (1.0, 2) is (1, 2), but (1.5, 2) or ("1", 2) is no pixel.
    """
    if not isinstance(p, tuple) or len(p) != 2:
        return None
    x, y = p
    try:
        xi, yi = int(x), int(y)
        if xi != x or yi != y:
            return None
    except (TypeError, ValueError, OverflowError):
        return None
    r, c = yi - origin[1], xi - origin[0]
    return (r, c) if 0 <= r < shape[0] and 0 <= c < shape[1] else None


def _restored(buf: Any, shape: tuple[int, int], origin: tuple[int, int]) -> PixelSet:
    """Unpickle a :class:`PixelSet` (protocol 5): its mask is the buffer itself when nothing else holds it."""
    mask = np.ndarray(shape, dtype=np.bool_, buffer=buf)
    if _crop_bounds(mask) != (0, shape[0], 0, shape[1]):
        return PixelSet(mask, origin)  # not canonical (not written by __reduce_ex__): the constructor's way
    # The buffer is the unpickler's (bytes read, or the receiver's memory): _frozen copies it if it belongs
    # to another array.
    return PixelSet._canonical(_frozen(mask, fresh=True), (int(origin[0]), int(origin[1])))


class PixelSet:
    """A finite set of pixels: an integer origin plus a read-only boolean mask, always canonical.

    Parameters
    ----------
    mask : array_like of bool, shape (rows, cols)
        ``mask[row, col]`` is True when pixel (x0 + col, y0 + row) belongs to the set.
    origin : tuple of int
        (x0, y0), the pixel of ``mask[0, 0]``.

    Notes
    -----
    The constructor crops the mask to its bounding box, so ``origin`` and ``mask`` of an instance are
    canonical and equality, hashing and serialisation never depend on how the set was built. Instances are
    immutable: the mask is a read-only array and every operation returns a new set.
    """

    __slots__ = ("_count", "_hash", "_mask", "_origin")

    def __init__(self, mask: npt.ArrayLike, origin: tuple[int, int] = (0, 0)) -> None:
        m = np.asarray(mask)
        if m.ndim != 2:
            raise ValueError(f"a pixel mask must be 2-D, got shape {m.shape}")
        fresh = m.dtype != np.bool_
        if fresh:
            m = m != 0
        x0, y0 = (int(origin[0]), int(origin[1]))
        b = _crop_bounds(m)
        if b is None:
            self._mask: BoolArray = _frozen(np.zeros((0, 0), dtype=bool), fresh=True)
            self._origin = (0, 0)
        else:
            r0, r1, c0, c1 = b
            if (r0, r1, c0, c1) != (0, m.shape[0], 0, m.shape[1]):
                m = m[r0:r1, c0:c1]
            self._mask = _frozen(m, fresh=fresh)
            self._origin = (x0 + c0, y0 + r0)
        self._hash: int | None = None
        self._count: int | None = None

    @classmethod
    def _canonical(cls, mask: BoolArray, origin: tuple[int, int]) -> PixelSet:
        """Wrap an already canonical, frozen mask without cropping or copying it."""
        ps = cls.__new__(cls)
        ps._mask = mask
        ps._origin = origin
        ps._hash = None
        ps._count = None
        return ps

    @classmethod
    def taking_over(cls, mask: BoolArray, origin: tuple[int, int]) -> PixelSet:
        """A set taking over a boolean mask the caller has just allocated and keeps no reference to.

        The same set as ``PixelSet(mask, origin)``, but a mask that is already canonical (its True entries
        touch all four sides) is frozen in place instead of copied: a 1024² result of D saves a 4 MB copy
        (2 ms). Any other mask (cropped, a view, not C-contiguous) goes through the constructor.
        """
        if mask.dtype != np.bool_ or mask.ndim != 2:
            return cls(mask, origin)
        b = _crop_bounds(mask)
        if b is None:
            return cls.empty()
        if b == (0, mask.shape[0], 0, mask.shape[1]):  # _frozen copies it unless it is the caller's alone
            return cls._canonical(_frozen(mask, fresh=True), (int(origin[0]), int(origin[1])))
        r0, r1, c0, c1 = b
        return cls(mask[r0:r1, c0:c1], (int(origin[0]) + c0, int(origin[1]) + r0))

    def __reduce_ex__(self, protocol: SupportsIndex) -> tuple[Any, ...]:
        # Rebuilt frozen, without the cached hash (which depends on the process's hash seed). From protocol 5
        # the mask goes as a buffer: between the window and its worker processes it travels out of band,
        # and neither side copies it (at 77 M pixels each copy was 77 MB of fresh memory, page-faulted in
        # on the cores the window shares).
        if int(protocol) >= 5 and self._mask.size:
            return (_restored, (pickle.PickleBuffer(cast(Any, self._mask)), self._mask.shape, self._origin))
        return (PixelSet, (np.array(self._mask), self._origin))

    # ------------------------------------------------------------------ construction
    @classmethod
    def empty(cls) -> PixelSet:
        """Return the empty pixel set."""
        return cls(np.zeros((0, 0), dtype=bool))

    @classmethod
    def from_image(
        cls,
        image: npt.ArrayLike,
        origin: tuple[int, int] = (0, 0),
        *,
        threshold: float | None = None,
        invert: bool = False,
    ) -> PixelSet:
        """Build a set from an image array as numpy, Pillow and matplotlib hold it: **row 0 at the top**.

        Parameters
        ----------
        image : array_like, shape (H, W) or (H, W, 3|4)
            A boolean mask, a grey image or a colour image (colour is read as its luminance).
        origin : tuple of int
            The pixel (x0, y0) of the image's **bottom-left** sample (last row, column 0), as the
            ``mrm:origin`` of an image file: image row r is y = y0 + H − 1 − r, column c is x = x0 + c.
        threshold : float, optional
            Grey and colour images: samples brighter than it are in the set (default: Otsu's threshold;
            boolean images and images holding only 0 and one other value keep their non-zero samples; float
            images, read as values in [0, 1], are cut at 0.5).
        invert : bool
            Take the dark samples instead (black-on-white drawings, potrace's convention).

        Returns
        -------
        PixelSet
            The same set :func:`mrm.io.pixel_files.read_pixels` gives for that image saved as a PNG.

        Examples
        --------
        >>> import numpy as np
        >>> img = np.array([[1, 0],
        ...                 [1, 1]], dtype=bool)   # an L: the top row holds one pixel
        >>> ps = PixelSet.from_image(img)
        >>> sorted(ps)
        [(0, 0), (0, 1), (1, 0)]
        >>> bool((ps.to_image() == img).all())
        True
        """
        a = np.asarray(image)
        if a.ndim == 3 and a.shape[2] in (3, 4):
            a = grey_of(a)
        if a.ndim != 2:
            raise ValueError(f"an image must be 2-D (or H×W×3, H×W×4 for colour), got shape {a.shape}")
        if a.dtype == np.bool_:
            rows = a
        elif a.dtype.kind == "f":
            # Float images (matplotlib's imread, skimage) hold values in [0, 1]: cut at the middle.
            rows = a > (0.5 if threshold is None else threshold)
        else:
            rows = binarize(a, threshold)
        if invert:
            rows = ~rows
        return cls(rows[::-1], origin)

    def to_image(self, box: Box | None = None) -> BoolArray:
        """Return the set as a boolean image with **row 0 at the top** (the inverse of :meth:`from_image`).

        Parameters
        ----------
        box : (xmin, ymin, xmax, ymax), optional
            The pixels the image covers (default: the bounding box; the empty set gives a 0×0 image). Its
            bottom-left pixel (xmin, ymin) is the ``origin`` that gives the set back through
            :meth:`from_image`.
        """
        if box is None:
            return np.ascontiguousarray(self._mask[::-1])
        return np.ascontiguousarray(self.to_array(box)[::-1])

    @classmethod
    def from_points(cls, points: npt.ArrayLike | Iterable[tuple[int, int]]) -> PixelSet:
        """Build a set from integer points, an (N, 2) array of (x, y)."""
        raw = np.asarray(points if isinstance(points, np.ndarray) else list(cast("Iterable[Any]", points)))
        if raw.size == 0:
            return cls.empty()
        if raw.dtype.kind not in "iu" and not (
            raw.dtype.kind == "f" and bool(np.all(np.isfinite(raw))) and np.array_equal(raw, np.floor(raw))
        ):
            # Casting would silently truncate 1.5 to 1: a pixel is an integer point or nothing.
            raise ValueError(f"pixel coordinates must be integers, got dtype {raw.dtype}")
        pts = raw.astype(np.int64).reshape(-1, 2)
        x0, y0 = int(pts[:, 0].min()), int(pts[:, 1].min())
        w = int(pts[:, 0].max()) - x0 + 1
        h = int(pts[:, 1].max()) - y0 + 1
        m = np.zeros((h, w), dtype=bool)
        m[pts[:, 1] - y0, pts[:, 0] - x0] = True
        return cls(m, (x0, y0))

    @classmethod
    def box(cls, xmin: int, ymin: int, xmax: int, ymax: int) -> PixelSet:
        """Return the full rectangle of pixels with the given inclusive bounds (empty if inverted)."""
        if xmax < xmin or ymax < ymin:
            return cls.empty()
        return cls(np.ones((ymax - ymin + 1, xmax - xmin + 1), dtype=bool), (xmin, ymin))

    # ------------------------------------------------------------------ basic properties
    @property
    def origin(self) -> tuple[int, int]:
        """(x0, y0): the pixel of ``mask[0, 0]`` (the bottom-left of the bounding box)."""
        return self._origin

    @property
    def mask(self) -> BoolArray:
        """The read-only boolean mask, cropped to the bounding box, indexed ``[row, col]``."""
        return self._mask

    @property
    def shape(self) -> tuple[int, int]:
        """(rows, cols) of the mask, i.e. (height, width) of the bounding box."""
        return (int(self._mask.shape[0]), int(self._mask.shape[1]))

    def __len__(self) -> int:
        # Counted once (the mask is immutable): 10⁸ pixels take tens of milliseconds, and views read the
        # count at every refresh (the status bar, the inspector's chain).
        if self._count is None:
            self._count = int(np.count_nonzero(self._mask))
        return self._count

    @property
    def count(self) -> int:
        """Number of pixels in the set (counted once)."""
        return len(self)

    @property
    def known_count(self) -> int | None:
        """The number of pixels if it was counted already (:attr:`count`), else None; never counts."""
        return self._count

    def is_empty(self) -> bool:
        """True when the set holds no pixel."""
        return self._mask.size == 0

    def __bool__(self) -> bool:
        return not self.is_empty()

    @property
    def bbox(self) -> Box | None:
        """(xmin, ymin, xmax, ymax), bounds included, or None for the empty set."""
        return None if self.is_empty() else _box(self._origin, self._mask.shape)

    def points(self) -> IntArray:
        """All pixels as an (N, 2) int64 array of (x, y), sorted by y then x."""
        rows, cols = np.nonzero(self._mask)
        out = np.empty((rows.size, 2), dtype=np.int64)
        out[:, 0] = cols + self._origin[0]
        out[:, 1] = rows + self._origin[1]
        return out

    def __iter__(self) -> Iterator[tuple[int, int]]:
        for x, y in self.points():
            yield (int(x), int(y))

    def __contains__(self, p: object) -> bool:
        rc = _cell(p, self._origin, self._mask.shape)
        return rc is not None and bool(self._mask[rc])

    def to_array(self, box: Box) -> BoolArray:
        """Return a new writable mask over ``box`` = (xmin, ymin, xmax, ymax), indexed ``[row, col]``."""
        xmin, ymin, xmax, ymax = box
        out = np.zeros((max(0, ymax - ymin + 1), max(0, xmax - xmin + 1)), dtype=bool)
        if self.is_empty() or out.size == 0:
            return out
        h, w = self.shape
        x0, y0 = self._origin
        # Overlap of [x0, x0+w) with [xmin, xmax+1) and likewise in y.
        ox0, ox1 = max(x0, xmin), min(x0 + w, xmax + 1)
        oy0, oy1 = max(y0, ymin), min(y0 + h, ymax + 1)
        if ox0 < ox1 and oy0 < oy1:
            out[oy0 - ymin : oy1 - ymin, ox0 - xmin : ox1 - xmin] = self._mask[
                oy0 - y0 : oy1 - y0, ox0 - x0 : ox1 - x0
            ]
        return out

    # ------------------------------------------------------------------ equality and hashing
    def __eq__(self, other: object) -> bool:
        if not isinstance(other, PixelSet):
            return NotImplemented
        return self._origin == other._origin and np.array_equal(self._mask, other._mask)

    def __hash__(self) -> int:
        if self._hash is None:
            self._hash = hash((self._origin, self._mask.shape, np.packbits(self._mask).tobytes()))
        return self._hash

    def __repr__(self) -> str:
        return f"PixelSet({len(self)} pixels, bbox={self.bbox})"

    # ------------------------------------------------------------------ set algebra
    def _joint_box(self, other: PixelSet) -> Box | None:
        return joint_box([self.bbox, other.bbox])

    def _binary(self, other: PixelSet, op: Any, box: Box | None) -> PixelSet:
        """Apply the element-wise ``op`` over ``box``, which must hold every pixel of the result."""
        if box is None or box[2] < box[0] or box[3] < box[1]:
            return PixelSet.empty()
        return PixelSet(op(self.to_array(box), other.to_array(box)), (box[0], box[1]))

    def _checked_joint_box(self, other: PixelSet) -> Box | None:
        box = self._joint_box(other)
        if box is not None:
            # Two small sets far apart would need a huge mask: refuse before allocating it.
            check_pixels(box_area(box), DEFAULT_PIXEL_LIMIT, "the joint bounding box of these pixel sets")
        return box

    def union(self, other: PixelSet) -> PixelSet:
        """Return the pixels in either set.

        Raises
        ------
        SizeLimitError
            When the joint bounding box of the two sets exceeds ``DEFAULT_PIXEL_LIMIT`` pixels.
        """
        return self._binary(other, np.logical_or, self._checked_joint_box(other))

    def intersection(self, other: PixelSet) -> PixelSet:
        """Return the pixels in both sets."""
        a, b = self.bbox, other.bbox
        if a is None or b is None:
            return PixelSet.empty()
        box = (max(a[0], b[0]), max(a[1], b[1]), min(a[2], b[2]), min(a[3], b[3]))
        return self._binary(other, np.logical_and, box)

    def difference(self, other: PixelSet) -> PixelSet:
        """Return the pixels of this set that are not in ``other``."""
        return self._binary(other, lambda a, b: a & ~b, self.bbox)

    def symmetric_difference(self, other: PixelSet) -> PixelSet:
        """Return the pixels in exactly one of the two sets (``SizeLimitError`` as for :meth:`union`)."""
        return self._binary(other, np.logical_xor, self._checked_joint_box(other))

    __or__ = union
    __and__ = intersection
    __sub__ = difference
    __xor__ = symmetric_difference

    def complement(self, box: Box) -> PixelSet:
        """Return the pixels of ``box`` = (xmin, ymin, xmax, ymax) that are not in this set."""
        return PixelSet(~self.to_array(box), (box[0], box[1]))

    def issubset(self, other: PixelSet) -> bool:
        """True when every pixel of this set is in ``other``."""
        return self.difference(other).is_empty()

    # ------------------------------------------------------------------ geometry
    def translate(self, dx: int, dy: int) -> PixelSet:
        """Return the set moved by the integer vector (dx, dy)."""
        if self.is_empty():
            return self
        moved = PixelSet._canonical(self._mask, (self._origin[0] + int(dx), self._origin[1] + int(dy)))
        moved._count = self._count
        return moved

    def crop(self, box: Box) -> PixelSet:
        """Return the pixels of this set inside ``box`` = (xmin, ymin, xmax, ymax)."""
        b = self.bbox
        if b is None:
            return PixelSet.empty()
        # Only the overlap with the bounding box can hold pixels (and a huge box costs nothing).
        box = (max(box[0], b[0]), max(box[1], b[1]), min(box[2], b[2]), min(box[3], b[3]))
        if box[2] < box[0] or box[3] < box[1]:
            return PixelSet.empty()
        return PixelSet(self.to_array(box), (box[0], box[1]))

    def rotate90(self, k: int = 1, center: tuple[int, int] = (0, 0)) -> PixelSet:
        """Rotate by k·90° counter-clockwise (y up) about the pixel centre ``center``.

        The rotation (x, y) ↦ (cx − (y − cy), cy + (x − cx)) maps pixels to pixels exactly.
        """
        k %= 4
        if k == 0 or self.is_empty():
            return self
        pts = self.points()
        cx, cy = int(center[0]), int(center[1])
        x, y = pts[:, 0] - cx, pts[:, 1] - cy
        for _ in range(k):
            x, y = -y, x
        return PixelSet.from_points(np.stack([x + cx, y + cy], axis=1))

    def flip_x(self, axis: int = 0) -> PixelSet:
        """Mirror about the vertical line x = ``axis`` (a pixel column): (x, y) ↦ (2·axis − x, y)."""
        if self.is_empty():
            return self
        x0, y0 = self._origin
        w = self.shape[1]
        return PixelSet(self._mask[:, ::-1], (2 * axis - (x0 + w - 1), y0))

    def flip_y(self, axis: int = 0) -> PixelSet:
        """Mirror about the horizontal line y = ``axis`` (a pixel row): (x, y) ↦ (x, 2·axis − y)."""
        if self.is_empty():
            return self
        x0, y0 = self._origin
        h = self.shape[0]
        return PixelSet(self._mask[::-1, :], (x0, 2 * axis - (y0 + h - 1)))


class LabelMap:
    """An immutable integer label image with an origin (docs/design.md §1); label 0 is the background.

    Parameters
    ----------
    labels : array_like of int, shape (rows, cols)
        ``labels[row, col]`` is the label of pixel (x0 + col, y0 + row).
    origin : tuple of int
        (x0, y0).

    Notes
    -----
    Like :class:`PixelSet`, the array is cropped to the bounding box of the non-zero labels and stored
    read-only as int32, so equality and hashing depend only on content.
    """

    __slots__ = ("_hash", "_labels", "_origin")

    def __init__(self, labels: npt.ArrayLike, origin: tuple[int, int] = (0, 0)) -> None:
        a = np.asarray(labels)
        if a.ndim != 2:
            raise ValueError(f"a label map must be 2-D, got shape {a.shape}")
        if a.dtype.kind not in "biu":
            raise ValueError(f"labels must be integers, got dtype {a.dtype}")
        if a.size and (a.min() < 0 or a.max() > np.iinfo(np.int32).max):
            raise ValueError("labels must be non-negative 32-bit integers")
        converted = a.astype(np.int32, copy=False)
        fresh = converted is not a
        b = _crop_bounds(converted != 0)
        if b is None:
            self._labels = _frozen(np.zeros((0, 0), dtype=np.int32), fresh=True)
            self._origin = (0, 0)
        else:
            r0, r1, c0, c1 = b
            if (r0, r1, c0, c1) != (0, converted.shape[0], 0, converted.shape[1]):
                converted = converted[r0:r1, c0:c1]
            self._labels = _frozen(converted, fresh=fresh)
            self._origin = (int(origin[0]) + c0, int(origin[1]) + r0)
        self._hash: int | None = None

    def __reduce__(self) -> tuple[Any, ...]:
        return (LabelMap, (np.array(self._labels), self._origin))

    @classmethod
    def from_pixel_sets(cls, parts: Iterable[PixelSet]) -> LabelMap:
        """Label the i-th set with i + 1; the sets must be pairwise disjoint."""
        parts = list(parts)
        boxes = [p.bbox for p in parts if p.bbox is not None]
        if not boxes:
            return cls(np.zeros((0, 0), dtype=np.int32))
        box = (
            min(b[0] for b in boxes),
            min(b[1] for b in boxes),
            max(b[2] for b in boxes),
            max(b[3] for b in boxes),
        )
        out = np.zeros((box[3] - box[1] + 1, box[2] - box[0] + 1), dtype=np.int32)
        for i, p in enumerate(parts, start=1):
            b = p.bbox
            if b is None:
                continue
            # each set written over its own box, by masked copies (no index arrays)
            sub = out[b[1] - box[1] : b[3] - box[1] + 1, b[0] - box[0] : b[2] - box[0] + 1]
            if np.logical_and(sub != 0, p.mask).any():
                raise ValueError("the pixel sets of a label map must be disjoint")
            np.copyto(sub, i, where=p.mask)
        return cls(out, (box[0], box[1]))

    @classmethod
    def _canonical(cls, labels: npt.NDArray[np.int32], origin: tuple[int, int]) -> LabelMap:
        """Take a fresh int32 array of non-negative labels whose non-zero labels touch all four sides.

        No check, crop or copy: for builders that know it (the array is frozen here, so the caller must
        hold no other reference to it).
        """
        lm = cls.__new__(cls)
        lm._labels = _frozen(labels, fresh=True)
        lm._origin = (int(origin[0]), int(origin[1]))
        lm._hash = None
        return lm

    @property
    def origin(self) -> tuple[int, int]:
        """(x0, y0) of ``labels[0, 0]``."""
        return self._origin

    @property
    def labels(self) -> npt.NDArray[np.int32]:
        """The read-only int32 array, indexed ``[row, col]``."""
        return self._labels

    @property
    def shape(self) -> tuple[int, int]:
        """(rows, cols) of the label array."""
        return (int(self._labels.shape[0]), int(self._labels.shape[1]))

    def is_empty(self) -> bool:
        """True when no pixel carries a non-zero label."""
        return self._labels.size == 0

    def label_at(self, p: tuple[int, int]) -> int:
        """The label of pixel ``p`` = (x, y): 0 outside the map, on its background, or for no pixel."""
        rc = _cell(p, self._origin, self._labels.shape)
        return 0 if rc is None else int(self._labels[rc])

    def __contains__(self, p: object) -> bool:
        """True when pixel ``p`` = (x, y) carries a non-zero label."""
        return self.label_at(p) != 0  # type: ignore[arg-type]

    @property
    def bbox(self) -> Box | None:
        """(xmin, ymin, xmax, ymax) of the labelled pixels, bounds included, or None when empty."""
        return None if self.is_empty() else _box(self._origin, self._labels.shape)

    def label_values(self) -> list[int]:
        """The distinct non-zero labels, sorted."""
        v = np.unique(self._labels)
        return [int(x) for x in v if x != 0]

    def pixel_set(self, label: int) -> PixelSet:
        """Return the pixels carrying ``label``."""
        return PixelSet(self._labels == label, self._origin)

    def support(self) -> PixelSet:
        """Return the pixels with a non-zero label."""
        return PixelSet(self._labels != 0, self._origin)

    def __eq__(self, other: object) -> bool:
        if not isinstance(other, LabelMap):
            return NotImplemented
        return self._origin == other._origin and np.array_equal(self._labels, other._labels)

    def __hash__(self) -> int:
        if self._hash is None:
            self._hash = hash((self._origin, self._labels.shape, self._labels.tobytes()))
        return self._hash

    def __repr__(self) -> str:
        return f"LabelMap(labels={self.label_values()}, origin={self._origin}, shape={self.shape})"
