"""Immutable grid sets and label grids that keep their place on the grid (docs/design.md §1, §11).

A pixel p = (x, y) ∈ Z² is centred on the Euclidean point (x, y); y points up. In memory a pixel set is an
integer origin (x0, y0) plus a boolean ``mask[row, col]`` with x = x0 + col and y = y0 + row. A voxel set is
the same with one more axis: origin (x0, y0, z0), ``mask[k, j, i]`` with (x, y, z) = (x0 + i, y0 + j, z0 + k).
One class, :class:`GridSet`, holds what does not depend on the dimension; :class:`PixelSet` and
:class:`VoxelSet` add what does. Two sets are equal when they hold the same points, whatever the extent of
their arrays; the canonical form is cropped to the bounding box (an empty set has a zero origin and an
all-zero shape). Label maps (2D) and label volumes (3D) share :class:`LabelGrid` likewise.
"""

from __future__ import annotations

import pickle
from collections.abc import Iterable, Iterator, Sequence
from typing import Any, ClassVar, Generic, Self, SupportsIndex, TypeVar, cast

import numpy as np
import numpy.typing as npt

from mrm.core.errors import ParameterError
from mrm.core.limits import DEFAULT_PIXEL_LIMIT, DEFAULT_VOXEL_LIMIT, check_pixels
from mrm.core.threshold import binarize, grey_of

BoolArray = npt.NDArray[np.bool_]
IntArray = npt.NDArray[np.int64]

#: A box of pixels (xmin, ymin, xmax, ymax), bounds included.
Box = tuple[int, int, int, int]
#: A box of voxels (xmin, ymin, zmin, xmax, ymax, zmax), bounds included.
Box3 = tuple[int, int, int, int, int, int]

_T = TypeVar("_T", bound=tuple[Any, ...])


def joint_box(boxes: Iterable[_T | None]) -> _T | None:
    """The smallest box ``(mins..., maxs...)`` holding every given box (None when there is none).

    Pixel and voxel boxes and float bounds alike (``(xmin, ymin, xmax, ymax)`` in 2D); a None among
    ``boxes`` (an empty set) is skipped.
    """
    real = [b for b in boxes if b is not None]
    if not real:
        return None
    n = len(real[0]) // 2
    lo = (min(b[d] for b in real) for d in range(n))
    hi = (max(b[n + d] for b in real) for d in range(n))
    return cast(_T, (*lo, *hi))


def dimension_of(value: object) -> int:
    """The dimension a value lives in: 3 for voxel sets, polyhedra and their exact images, else 2.

    Its class's ``ndim`` (2 for pixel sets); 2 for anything else (shapely geometries). Read from the class,
    so that knowing a polyhedron is 3D never imports the polyhedra package (the plane work must not load
    the 3D kernels).
    """
    ndim = getattr(type(value), "ndim", 2)
    return ndim if isinstance(ndim, int) else 2


def box_area(box: tuple[int, ...] | None) -> int:
    """The number of pixels or voxels of a box ``(mins..., maxs...)`` (0 for None or an empty box)."""
    if box is None:
        return 0
    n = len(box) // 2
    size = 1
    for d in range(n):
        size *= max(0, box[n + d] - box[d] + 1)
    return size


def refuse_non_finite(a: npt.NDArray[Any], what: str) -> None:
    """Refuse an array holding NaN or an infinity, which would otherwise count as "in the set" (NaN ≠ 0).

    Raises
    ------
    ParameterError
        One line: how many samples, the index of the first, and what to do.
    """
    if a.dtype.kind not in "fc" or a.size == 0:
        return
    bad = ~np.isfinite(a)
    if bad.any():
        first = tuple(int(i) for i in np.argwhere(bad)[0])
        raise ParameterError(
            f"{what} holds {int(bad.sum()):,} NaN or infinite sample(s), the first at index {first}; "
            "replace them (numpy.nan_to_num) or choose the pixels with a comparison first"
        )


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


def _crop_bounds(mask: BoolArray) -> tuple[tuple[int, int], ...] | None:
    """Return the half-open range (lo, hi) of the True entries along each array axis, or None if none."""
    out = []
    for axis in range(mask.ndim):
        others = tuple(a for a in range(mask.ndim) if a != axis)
        idx = np.flatnonzero(mask.any(axis=others) if others else mask)
        if idx.size == 0:
            return None
        out.append((int(idx[0]), int(idx[-1]) + 1))
    return tuple(out)


def _is_whole(bounds: tuple[tuple[int, int], ...], shape: tuple[int, ...]) -> bool:
    """True when ``bounds`` (from :func:`_crop_bounds`) cover every index of ``shape``: nothing to crop."""
    return all(lo == 0 and hi == n for (lo, hi), n in zip(bounds, shape, strict=True))


def _box(origin: tuple[int, ...], shape: tuple[int, ...]) -> tuple[int, ...]:
    """(mins..., maxs...) in coordinate order of a non-empty array placed at ``origin``.

    Array axes run in the reverse order of the coordinates (``mask[row, col]`` is (x, y) = (col, row),
    ``mask[k, j, i]`` is (x, y, z) = (i, j, k)).
    """
    n = len(origin)
    return (*origin, *(origin[d] + int(shape[n - 1 - d]) - 1 for d in range(n)))


def _cell(p: object, origin: tuple[int, ...], shape: tuple[int, ...]) -> tuple[int, ...] | None:
    """The array index of point ``p`` in an array placed at ``origin``, or None when it is none of its.

    Like a Python set of integer tuples: (1.0, 2) is (1, 2), but (1.5, 2) or ("1", 2) is no point.
    """
    n = len(origin)
    if not isinstance(p, tuple) or len(p) != n:
        return None
    index = []
    for d in reversed(range(n)):
        v = p[d]
        try:
            vi = int(v)
            if vi != v:
                return None
        except (TypeError, ValueError, OverflowError):
            return None
        i = vi - origin[d]
        if not 0 <= i < shape[n - 1 - d]:
            return None
        index.append(i)
    return tuple(index)


def _slices(bounds: tuple[tuple[int, int], ...]) -> tuple[slice, ...]:
    return tuple(slice(lo, hi) for lo, hi in bounds)


def _moved(origin: tuple[int, ...], bounds: tuple[tuple[int, int], ...]) -> tuple[int, ...]:
    """The origin of the sub-array ``bounds`` (array order) of an array placed at ``origin``."""
    n = len(origin)
    return tuple(int(origin[d]) + bounds[n - 1 - d][0] for d in range(n))


def _restored(cls: type[_G], buf: Any, shape: tuple[int, ...], origin: tuple[int, ...]) -> _G:
    """Unpickle a grid set (protocol 5): its mask is the buffer itself when nothing else holds it."""
    mask = np.ndarray(shape, dtype=np.bool_, buffer=buf)
    b = _crop_bounds(mask)
    if b is None or not _is_whole(b, mask.shape):
        return cls(mask, origin)  # not canonical (not written by __reduce_ex__): the constructor's way
    # The buffer is the unpickler's (bytes read, or the receiver's memory): _frozen copies it if it belongs
    # to another array.
    return cls._canonical(_frozen(mask, fresh=True), tuple(int(v) for v in origin))


_O = TypeVar("_O", bound=tuple[int, ...])
_B = TypeVar("_B", bound=tuple[int, ...])
_G = TypeVar("_G", bound="GridSet[Any, Any]")
_S = TypeVar("_S", bound="GridSet[Any, Any]")


class GridSet(Generic[_O, _B]):
    """A finite set of grid points in any dimension: an integer origin plus a read-only boolean mask.

    The one notion behind :class:`PixelSet` (2D) and :class:`VoxelSet` (3D) (docs/design.md §1, §11): the
    constructor crops the mask to its bounding box, so ``origin`` and ``mask`` of an instance are canonical
    and equality, hashing and serialisation never depend on how the set was built. Instances are immutable:
    the mask is a read-only array and every operation returns a new set. Coordinates are in (x, y[, z])
    order; the mask's axes are in the reverse order (``mask[row, col]``, ``mask[k, j, i]``), as numpy holds
    images and image stacks. Boxes are ``(mins..., maxs...)``, bounds included.
    """

    #: Number of coordinates of a point.
    ndim: ClassVar[int]
    #: What a point is called in messages ("pixel", "voxel").
    unit: ClassVar[str]
    #: The size limit of :meth:`union` and :meth:`symmetric_difference` (points of the joint box).
    size_limit: ClassVar[int]

    __slots__ = ("_count", "_hash", "_mask", "_origin")

    def __init__(self, mask: npt.ArrayLike, origin: Sequence[int] | None = None) -> None:
        m = np.asarray(mask)
        n = self.ndim
        if m.ndim != n:
            raise ValueError(f"a {self.unit} mask must be {n}-D, got shape {m.shape}")
        fresh = m.dtype != np.bool_
        if fresh:
            refuse_non_finite(m, f"a {self.unit} mask")
            m = m != 0
        o = tuple(int(v) for v in origin) if origin is not None else (0,) * n
        if len(o) != n:
            raise ValueError(f"a {self.unit} origin has {n} coordinates, got {o}")
        b = _crop_bounds(m)
        if b is None:
            self._mask: BoolArray = _frozen(np.zeros((0,) * n, dtype=bool), fresh=True)
            self._origin = cast(_O, (0,) * n)
        else:
            if not _is_whole(b, m.shape):
                m = m[_slices(b)]
            self._mask = _frozen(m, fresh=fresh)
            self._origin = cast(_O, _moved(o, b))
        self._hash: int | None = None
        self._count: int | None = None

    @classmethod
    def _canonical(cls, mask: BoolArray, origin: tuple[int, ...]) -> Self:
        """Wrap an already canonical, frozen mask without cropping or copying it."""
        gs = cls.__new__(cls)
        gs._mask = mask
        gs._origin = cast(_O, origin)
        gs._hash = None
        gs._count = None
        return gs

    @classmethod
    def taking_over(cls, mask: BoolArray, origin: Sequence[int]) -> Self:
        """A set taking over a boolean mask the caller has just allocated and keeps no reference to.

        The same set as ``cls(mask, origin)``, but a mask that is already canonical (its True entries
        touch every side) is frozen in place instead of copied: a 1024² result of D saves a 4 MB copy
        (2 ms). Any other mask (cropped, a view, not C-contiguous) goes through the constructor.
        """
        if mask.dtype != np.bool_ or mask.ndim != cls.ndim:
            return cls(mask, origin)
        b = _crop_bounds(mask)
        if b is None:
            return cls.empty()
        o = tuple(int(v) for v in origin)
        if _is_whole(b, mask.shape):  # _frozen copies it unless it is the caller's alone
            return cls._canonical(_frozen(mask, fresh=True), o)
        return cls(mask[_slices(b)], _moved(o, b))

    def __reduce_ex__(self, protocol: SupportsIndex) -> tuple[Any, ...]:
        # Rebuilt frozen, without the cached hash (which depends on the process's hash seed). From protocol 5
        # the mask goes as a buffer: between the window and its worker processes it travels out of band,
        # and neither side copies it (at 77 M pixels each copy was 77 MB of fresh memory, page-faulted in
        # on the cores the window shares).
        if int(protocol) >= 5 and self._mask.size:
            buf = pickle.PickleBuffer(cast(Any, self._mask))
            return (_restored, (type(self), buf, self._mask.shape, self._origin))
        return (type(self), (np.array(self._mask), self._origin))

    # ------------------------------------------------------------------ construction
    @classmethod
    def empty(cls) -> Self:
        """Return the empty set."""
        return cls(np.zeros((0,) * cls.ndim, dtype=bool))

    @classmethod
    def from_points(cls, points: npt.ArrayLike | Iterable[tuple[int, ...]]) -> Self:
        """Build a set from integer points, an (N, ndim) array of coordinates (x, y[, z])."""
        raw = np.asarray(points if isinstance(points, np.ndarray) else list(cast("Iterable[Any]", points)))
        if raw.size == 0:
            return cls.empty()
        if raw.dtype.kind not in "iu" and not (
            raw.dtype.kind == "f" and bool(np.all(np.isfinite(raw))) and np.array_equal(raw, np.floor(raw))
        ):
            # Casting would silently truncate 1.5 to 1: a point of the grid is an integer point or nothing.
            raise ValueError(f"{cls.unit} coordinates must be integers, got dtype {raw.dtype}")
        n = cls.ndim
        pts = raw.astype(np.int64).reshape(-1, n)
        lo = pts.min(axis=0)
        size = pts.max(axis=0) - lo + 1
        m = np.zeros(tuple(int(size[d]) for d in reversed(range(n))), dtype=bool)
        m[tuple(pts[:, d] - lo[d] for d in reversed(range(n)))] = True
        return cls(m, tuple(int(v) for v in lo))

    @classmethod
    def box(cls, *bounds: int) -> Self:
        """Return the full box of points with inclusive bounds ``(mins..., maxs...)`` (empty if inverted)."""
        n = cls.ndim
        if len(bounds) != 2 * n:
            raise ValueError(f"a {cls.unit} box has {2 * n} bounds, got {len(bounds)}")
        if any(bounds[n + d] < bounds[d] for d in range(n)):
            return cls.empty()
        shape = tuple(bounds[n + d] - bounds[d] + 1 for d in reversed(range(n)))
        return cls(np.ones(shape, dtype=bool), bounds[:n])

    # ------------------------------------------------------------------ basic properties
    @property
    def origin(self) -> _O:
        """The point of ``mask[0, ...]``: the lowest corner of the bounding box, in coordinate order."""
        return self._origin

    @property
    def mask(self) -> BoolArray:
        """The read-only boolean mask, cropped to the bounding box, axes in reverse coordinate order."""
        return self._mask

    @property
    def shape(self) -> _O:
        """The mask's shape (array order: (rows, cols), or (nz, ny, nx))."""
        return cast(_O, tuple(int(s) for s in self._mask.shape))

    def __len__(self) -> int:
        # Counted once (the mask is immutable): 10⁸ pixels take tens of milliseconds, and views read the
        # count at every refresh (the status bar, the inspector's chain).
        if self._count is None:
            self._count = int(np.count_nonzero(self._mask))
        return self._count

    @property
    def count(self) -> int:
        """Number of points in the set (counted once)."""
        return len(self)

    @property
    def known_count(self) -> int | None:
        """The number of points if it was counted already (:attr:`count`), else None; never counts."""
        return self._count

    def is_empty(self) -> bool:
        """True when the set holds no point."""
        return self._mask.size == 0

    def __bool__(self) -> bool:
        return not self.is_empty()

    @property
    def bbox(self) -> _B | None:
        """(mins..., maxs...), bounds included, or None for the empty set."""
        return None if self.is_empty() else cast(_B, _box(self._origin, self._mask.shape))

    def points(self) -> IntArray:
        """All points as an (N, ndim) int64 array of coordinates, sorted by the last coordinate first."""
        idx = np.nonzero(self._mask)
        n = self.ndim
        out = np.empty((idx[0].size, n), dtype=np.int64)
        for d in range(n):
            out[:, d] = idx[n - 1 - d] + self._origin[d]
        return out

    def __iter__(self) -> Iterator[_O]:
        for p in self.points():
            yield cast(_O, tuple(int(v) for v in p))

    def __contains__(self, p: object) -> bool:
        idx = _cell(p, self._origin, self._mask.shape)
        return idx is not None and bool(self._mask[idx])

    def to_array(self, box: _B) -> BoolArray:
        """Return a new writable mask over ``box`` = (mins..., maxs...), axes in array order."""
        n = self.ndim
        lo, hi = box[:n], box[n:]
        out = np.zeros(tuple(max(0, hi[d] - lo[d] + 1) for d in reversed(range(n))), dtype=bool)
        if self.is_empty() or out.size == 0:
            return out
        o = self._origin
        size = tuple(reversed(self._mask.shape))  # coordinate order
        a0 = [max(o[d], lo[d]) for d in range(n)]
        a1 = [min(o[d] + size[d], hi[d] + 1) for d in range(n)]
        if all(a0[d] < a1[d] for d in range(n)):
            dst = tuple(slice(a0[d] - lo[d], a1[d] - lo[d]) for d in reversed(range(n)))
            src = tuple(slice(a0[d] - o[d], a1[d] - o[d]) for d in reversed(range(n)))
            out[dst] = self._mask[src]
        return out

    # ------------------------------------------------------------------ equality and hashing
    def __eq__(self, other: object) -> bool:
        if not isinstance(other, GridSet) or other.ndim != self.ndim:
            return NotImplemented
        return self._origin == other._origin and np.array_equal(self._mask, other._mask)

    def __hash__(self) -> int:
        if self._hash is None:
            self._hash = hash((self._origin, self._mask.shape, np.packbits(self._mask).tobytes()))
        return self._hash

    def __repr__(self) -> str:
        return f"{type(self).__name__}({len(self)} {self.unit}s, bbox={self.bbox})"

    # ------------------------------------------------------------------ set algebra
    def _joint_box(self, other: Self) -> _B | None:
        return cast("_B | None", joint_box([self.bbox, other.bbox]))

    def _meet_box(self, box: _B) -> _B | None:
        """The part of ``box`` inside this set's bounding box, or None when they do not meet."""
        b = self.bbox
        if b is None:
            return None
        n = self.ndim
        m = (*(max(box[d], b[d]) for d in range(n)), *(min(box[n + d], b[n + d]) for d in range(n)))
        return None if any(m[n + d] < m[d] for d in range(n)) else cast(_B, m)

    def _binary(self, other: Self, op: Any, box: _B | None) -> Self:
        """Apply the element-wise ``op`` over ``box``, which must hold every point of the result."""
        n = self.ndim
        if box is None or any(box[n + d] < box[d] for d in range(n)):
            return type(self).empty()
        return type(self)(op(self.to_array(box), other.to_array(box)), box[:n])

    def _checked_joint_box(self, other: Self) -> _B | None:
        box = self._joint_box(other)
        if box is not None:
            # Two small sets far apart would need a huge mask: refuse before allocating it.
            check_pixels(
                box_area(box),
                self.size_limit,
                f"the joint bounding box of these {self.unit} sets",
                unit=f"{self.unit}s",
            )
        return box

    def union(self, other: Self) -> Self:
        """Return the points in either set.

        Raises
        ------
        SizeLimitError
            When the joint bounding box of the two sets exceeds the class's :attr:`size_limit`.
        """
        return self._binary(other, np.logical_or, self._checked_joint_box(other))

    def intersection(self, other: Self) -> Self:
        """Return the points in both sets."""
        b = other.bbox
        return self._binary(other, np.logical_and, None if b is None else self._meet_box(b))

    def difference(self, other: Self) -> Self:
        """Return the points of this set that are not in ``other``."""
        return self._binary(other, lambda a, b: a & ~b, self.bbox)

    def symmetric_difference(self, other: Self) -> Self:
        """Return the points in exactly one of the two sets (``SizeLimitError`` as for :meth:`union`)."""
        return self._binary(other, np.logical_xor, self._checked_joint_box(other))

    __or__ = union
    __and__ = intersection
    __sub__ = difference
    __xor__ = symmetric_difference

    def complement(self, box: _B) -> Self:
        """Return the points of ``box`` = (mins..., maxs...) that are not in this set."""
        return type(self)(~self.to_array(box), box[: self.ndim])

    def issubset(self, other: Self) -> bool:
        """True when every point of this set is in ``other``."""
        return self.difference(other).is_empty()

    # ------------------------------------------------------------------ geometry
    def translate(self, *offset: int) -> Self:
        """Return the set moved by the integer vector ``offset`` (one integer per coordinate)."""
        if len(offset) != self.ndim:
            raise ValueError(f"a {self.unit} set moves by {self.ndim} integers, got {len(offset)}")
        if self.is_empty():
            return self
        moved = type(self)._canonical(
            self._mask, tuple(o + int(d) for o, d in zip(self._origin, offset, strict=True))
        )
        moved._count = self._count
        return moved

    def crop(self, box: _B) -> Self:
        """Return the points of this set inside ``box`` = (mins..., maxs...)."""
        # Only the overlap with the bounding box can hold points (and a huge box costs nothing).
        m = self._meet_box(box)
        if m is None:
            return type(self).empty()
        return type(self)(self.to_array(m), m[: self.ndim])


class PixelSet(GridSet[tuple[int, int], Box]):
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
    immutable: the mask is a read-only array and every operation returns a new set. Everything but the
    image conversions and the quarter turns is :class:`GridSet`'s, shared with :class:`VoxelSet`.
    """

    ndim = 2
    unit = "pixel"
    size_limit = DEFAULT_PIXEL_LIMIT
    __slots__ = ()

    def __init__(self, mask: npt.ArrayLike, origin: Sequence[int] = (0, 0)) -> None:
        super().__init__(mask, origin)

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
        refuse_non_finite(a, "the image")
        if a.ndim == 3 and a.shape[2] in (3, 4):
            a = grey_of(a)
        if a.ndim != 2:
            raise ParameterError(f"an image must be 2-D (or H×W×3, H×W×4 for colour), got shape {a.shape}")
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


class VoxelSet(GridSet[tuple[int, int, int], Box3]):
    """A finite set of voxels: an integer origin plus a read-only boolean mask, always canonical (§11).

    Parameters
    ----------
    mask : array_like of bool, shape (nz, ny, nx)
        ``mask[k, j, i]`` is True when voxel (x0 + i, y0 + j, z0 + k) belongs to the set: numpy's (z, y, x)
        order of image stacks.
    origin : tuple of int
        (x0, y0, z0), the voxel of ``mask[0, 0, 0]``.

    Notes
    -----
    The same value as :class:`PixelSet` with one more axis (:class:`GridSet` holds both): canonical crop,
    equality by points, immutable, the voxel limit on unions.
    """

    ndim = 3
    unit = "voxel"
    size_limit = DEFAULT_VOXEL_LIMIT
    __slots__ = ()

    def __init__(self, mask: npt.ArrayLike, origin: Sequence[int] = (0, 0, 0)) -> None:
        super().__init__(mask, origin)

    def rotate90(self, k: int = 1, axis: int = 2, center: tuple[int, int, int] = (0, 0, 0)) -> VoxelSet:
        """Rotate by k·90° counter-clockwise about the axis ``axis`` (0 = x, 1 = y, 2 = z) through ``center``.

        Quarter turns about a voxel centre map voxels to voxels exactly (a permutation of coordinates with
        signs).
        """
        k %= 4
        if k == 0 or self.is_empty():
            return self
        if axis not in (0, 1, 2):
            raise ValueError(f"the axis of a quarter turn is 0, 1 or 2 (x, y or z), got {axis!r}")
        a, b = [(1, 2), (2, 0), (0, 1)][axis]  # the plane turned, counter-clockwise seen from +axis
        pts = self.points() - np.asarray(center, dtype=np.int64)
        for _ in range(k):
            pts[:, a], pts[:, b] = -pts[:, b].copy(), pts[:, a].copy()
        return VoxelSet.from_points(pts + np.asarray(center, dtype=np.int64))


class LabelGrid(Generic[_O, _B, _S]):
    """An immutable integer label grid with an origin, any dimension (docs/design.md §1, §11); 0 = background.

    The one notion behind :class:`LabelMap` (2D) and :class:`LabelVolume` (3D). The array is cropped to the
    bounding box of the non-zero labels and stored read-only as int32, so equality and hashing depend only on
    content. Axes are in array order (the reverse of the coordinates), as for :class:`GridSet`.
    """

    #: The grid set of one label (PixelSet, VoxelSet).
    set_type: ClassVar[type[GridSet[Any, Any]]]

    __slots__ = ("_hash", "_labels", "_origin")

    def __init__(self, labels: npt.ArrayLike, origin: Sequence[int] | None = None) -> None:
        a = np.asarray(labels)
        n = self.set_type.ndim
        what = self.what
        if a.ndim != n:
            raise ValueError(f"a {what} must be {n}-D, got shape {a.shape}")
        if a.dtype.kind not in "biu":
            raise ValueError(f"labels must be integers, got dtype {a.dtype}")
        if a.size and (a.min() < 0 or a.max() > np.iinfo(np.int32).max):
            raise ValueError("labels must be non-negative 32-bit integers")
        o = tuple(int(v) for v in origin) if origin is not None else (0,) * n
        converted = a.astype(np.int32, copy=False)
        fresh = converted is not a
        b = _crop_bounds(converted != 0)
        if b is None:
            self._labels = _frozen(np.zeros((0,) * n, dtype=np.int32), fresh=True)
            self._origin = cast(_O, (0,) * n)
        else:
            if not _is_whole(b, converted.shape):
                converted = converted[_slices(b)]
            self._labels = _frozen(converted, fresh=fresh)
            self._origin = cast(_O, _moved(o, b))
        self._hash: int | None = None

    #: What the grid is called in messages.
    what: ClassVar[str] = "label grid"

    def __reduce__(self) -> tuple[Any, ...]:
        return (type(self), (np.array(self._labels), self._origin))

    @classmethod
    def from_sets(cls, parts: Iterable[_S]) -> Self:
        """Label the i-th set with i + 1; the sets must be pairwise disjoint."""
        parts = list(parts)
        n = cls.set_type.ndim
        box = joint_box(p.bbox for p in parts)
        if box is None:
            return cls(np.zeros((0,) * n, dtype=np.int32))
        out = np.zeros(tuple(box[n + d] - box[d] + 1 for d in reversed(range(n))), dtype=np.int32)
        for i, p in enumerate(parts, start=1):
            b = p.bbox
            if b is None:
                continue
            # each set written over its own box, by masked copies (no index arrays)
            sub = out[tuple(slice(b[d] - box[d], b[n + d] - box[d] + 1) for d in reversed(range(n)))]
            if np.logical_and(sub != 0, p.mask).any():
                raise ValueError(f"the {cls.set_type.unit} sets of a {cls.what} must be disjoint")
            np.copyto(sub, i, where=p.mask)
        return cls(out, box[:n])

    @classmethod
    def taking_over(cls, labels: npt.NDArray[np.int32], origin: Sequence[int]) -> Self:
        """A grid taking over a fresh int32 array of non-negative labels the caller keeps no reference to.

        The same grid as ``cls(labels, origin)``, but an array already cropped (its non-zero labels touch
        every side) is frozen in place instead of copied: loading a 50 M-pixel label map saves 200 MB (as
        :meth:`GridSet.taking_over` does for masks). Any other array goes through the constructor.
        """
        if labels.dtype != np.int32 or labels.ndim != cls.set_type.ndim:
            return cls(labels, origin)
        b = _crop_bounds(labels != 0)
        if b is None or not _is_whole(b, labels.shape):
            return cls(labels, origin)
        return cls._canonical(labels, origin)

    @classmethod
    def _canonical(cls, labels: npt.NDArray[np.int32], origin: Sequence[int]) -> Self:
        """Take a fresh int32 array of non-negative labels whose non-zero labels touch every side.

        No check, crop or copy: for builders that know it (the array is frozen here, so the caller must
        hold no other reference to it).
        """
        lm = cls.__new__(cls)
        lm._labels = _frozen(labels, fresh=True)
        lm._origin = cast(_O, tuple(int(v) for v in origin))
        lm._hash = None
        return lm

    @property
    def origin(self) -> _O:
        """The point of ``labels[0, ...]``, in coordinate order."""
        return self._origin

    @property
    def labels(self) -> npt.NDArray[np.int32]:
        """The read-only int32 array, axes in array order."""
        return self._labels

    @property
    def shape(self) -> _O:
        """The shape of the label array (array order)."""
        return cast(_O, tuple(int(s) for s in self._labels.shape))

    def is_empty(self) -> bool:
        """True when no point carries a non-zero label."""
        return self._labels.size == 0

    def label_at(self, p: tuple[int, ...]) -> int:
        """The label of point ``p`` (coordinates): 0 outside the grid, on its background, or for no point."""
        idx = _cell(p, self._origin, self._labels.shape)
        return 0 if idx is None else int(self._labels[idx])

    def __contains__(self, p: object) -> bool:
        """True when point ``p`` carries a non-zero label."""
        return self.label_at(p) != 0  # type: ignore[arg-type]

    @property
    def bbox(self) -> _B | None:
        """(mins..., maxs...) of the labelled points, bounds included, or None when empty."""
        return None if self.is_empty() else cast(_B, _box(self._origin, self._labels.shape))

    def label_values(self) -> list[int]:
        """The distinct non-zero labels, sorted."""
        v = np.unique(self._labels)
        return [int(x) for x in v if x != 0]

    def _set(self, mask: BoolArray) -> _S:
        return cast(_S, self.set_type(mask, self._origin))

    def __eq__(self, other: object) -> bool:
        if not isinstance(other, LabelGrid) or other.set_type is not self.set_type:
            return NotImplemented
        return self._origin == other._origin and np.array_equal(self._labels, other._labels)

    def __hash__(self) -> int:
        if self._hash is None:
            self._hash = hash((self._origin, self._labels.shape, self._labels.tobytes()))
        return self._hash

    def __repr__(self) -> str:
        return (
            f"{type(self).__name__}(labels={self.label_values()}, origin={self._origin}, shape={self.shape})"
        )


class LabelMap(LabelGrid[tuple[int, int], Box, PixelSet]):
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
    read-only as int32, so equality and hashing depend only on content (:class:`LabelGrid`).
    """

    set_type = PixelSet
    what = "label map"
    __slots__ = ()

    def __init__(self, labels: npt.ArrayLike, origin: Sequence[int] = (0, 0)) -> None:
        super().__init__(labels, origin)

    @classmethod
    def from_pixel_sets(cls, parts: Iterable[PixelSet]) -> LabelMap:
        """Label the i-th set with i + 1; the sets must be pairwise disjoint."""
        return cls.from_sets(parts)

    def pixel_set(self, label: int) -> PixelSet:
        """Return the pixels carrying ``label``."""
        return self._set(self._labels == label)

    def support(self) -> PixelSet:
        """Return the pixels with a non-zero label."""
        return self._set(self._labels != 0)


class LabelVolume(LabelGrid[tuple[int, int, int], Box3, VoxelSet]):
    """An immutable integer label volume with an origin (docs/design.md §11); label 0 is the background.

    Parameters
    ----------
    labels : array_like of int, shape (nz, ny, nx)
        ``labels[k, j, i]`` is the label of voxel (x0 + i, y0 + j, z0 + k).
    origin : tuple of int
        (x0, y0, z0).
    """

    set_type = VoxelSet
    what = "label volume"
    __slots__ = ()

    def __init__(self, labels: npt.ArrayLike, origin: Sequence[int] = (0, 0, 0)) -> None:
        super().__init__(labels, origin)

    def voxel_set(self, label: int) -> VoxelSet:
        """Return the voxels carrying ``label``."""
        return self._set(self._labels == label)

    def support(self) -> VoxelSet:
        """Return the voxels with a non-zero label."""
        return self._set(self._labels != 0)
