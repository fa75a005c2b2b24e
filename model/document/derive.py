"""Derived representations: a lazy cache per (source, model).

For an object whose source is a Euclidean geometry E, the discrete representation is D(E); for a discrete
source A, the Euclidean one is R(A) (docs/design.md §7). Region and analytical representations always come
from the discrete one. Sources are immutable values, so a :class:`Derived` entry can be keyed by the identity
of its source and shared between threads: whatever it computes stays true for that source forever.
"""

from __future__ import annotations

import threading
from collections import OrderedDict
from collections.abc import Iterable
from typing import Any, Literal

from mrm.core.errors import Cancelled, MRMError, NotApplicableError
from mrm.core.grids import GridSet, LabelGrid, PixelSet
from mrm.core.models import Model
from mrm.core.progress import ProgressLike
from mrm.document.objects import Settings, source_dimension, source_kind
from mrm.geometry.discretize import discretize
from mrm.geometry.reconstruct import reconstruct
from mrm.geometry.reconstruct.subdivision import subdivide
from mrm.reps.analytical import analytical_of
from mrm.reps.cells import cells_of
from mrm.reps.region import region_of

Rep = Literal["discrete", "euclidean", "region", "analytical"]
#: The four representations, in the order they are usually derived.
REPS: tuple[Rep, ...] = ("discrete", "euclidean", "region", "analytical")

#: Derivations estimated below this cost (roughly, pixels touched) run in the caller's thread.
SYNC_COST = 250_000


# ---------------------------------------------------------------------------------------------- algorithms
def region_from_pixels(ps: PixelSet) -> Any:
    """The region representation of a pixel set (:func:`mrm.reps.region.region_of`).

    Also counts the pixels, which the set keeps: done here on the worker, the count costs the status bar
    and the error inspector nothing on the GUI thread (tens of milliseconds at 10⁸ pixels).
    """
    ps.count  # noqa: B018 - counted for its cache
    return region_of(ps)


#: Why a label volume has no analytical representation of its own yet.
NO_LABEL_PLANE_SEGMENTS = (
    "a label volume's faces are shared by two regions each: its digital plane segments come with its meshes"
)
#: Why a label volume has no Euclidean representation yet.
NO_LABEL_MESHES = "a label volume's meshes (one closed mesh per region) come with the compact 3D continuation"

#: Why a label map has no analytical representation of its own (the analytical view says it).
NO_LABEL_SEGMENTS = (
    "a label map's boundaries are shared by two regions each: its digital straight segments are those of "
    "each object after Edit ▸ Split into Objects"
)


# ---------------------------------------------------------------------------------------------- one entry
class Derived:
    """The four representations of one source under one model, each computed on first use and kept.

    Parameters
    ----------
    source : PixelSet, LabelMap or shapely Polygon / MultiPolygon
        The object's source representation (immutable). For a label map (ADR 0033) the discrete
        representation is the label map itself, the region one its cells (:func:`mrm.reps.cells.cells_of`),
        the Euclidean one its watertight gauss subdivision
        (:func:`mrm.geometry.reconstruct.subdivision.subdivide`); it has no analytical one
        (:class:`~mrm.core.errors.NotApplicableError`).
    model : str
        The discretization model.
    compact_limit : int, optional
        A voxel set's compact limit (:attr:`mrm.document.objects.Settings.compact_limit`): the most
        triangles of its safety net that R simplifies. None (other sources, or the default) means
        ``limits.MAX_COMPACT_R_TRIANGLES``. :meth:`under` takes both from a document's settings.

    Notes
    -----
    Thread-safe: each representation has its own lock, so a worker computing R(A) never blocks a caller
    asking for the discrete representation. An :class:`~mrm.core.errors.MRMError` raised by a derivation (e.g.
    a result over the pixel limit) is remembered and raised again on every request.
    """

    def __init__(self, source: Any, model: Model | str, compact_limit: int | None = None) -> None:
        self.source = source
        self.model = Model.parse(model)
        self.compact_limit = compact_limit
        self.kind: Literal["discrete", "euclidean", "labels"] = source_kind(source)
        #: 2 for plane objects, 3 for voxel sets and label volumes (docs/design.md §11).
        self.dimension = source_dimension(source)
        self._values: dict[str, Any] = {"discrete" if self.kind == "labels" else self.kind: source}
        self._errors: dict[str, MRMError] = {}
        self._locks = {r: threading.Lock() for r in REPS}
        #: How a voxel set's R was made (:class:`mrm.geometry.reconstruct.VoxelR`), once it is computed.
        self.voxel_r: Any = None

    @classmethod
    def under(cls, source: Any, settings: Settings) -> Derived:
        """A new entry of ``source`` under a document's settings (:meth:`Settings.derivation_key`)."""
        return cls(source, *settings.derivation_key(source))

    @property
    def r_note(self) -> str | None:
        """What a user is told about the R computed here when it is the safety net (exact, not compact).

        :attr:`mrm.geometry.reconstruct.VoxelR.note`; None otherwise, and until R is computed.
        """
        return None if self.voxel_r is None else self.voxel_r.note

    @property
    def r_over_limit(self) -> bool:
        """True when R is the safety net because the net is over the compact limit (a higher one helps)."""
        return self.voxel_r is not None and self.voxel_r.over_limit

    def is_ready(self, what: Rep) -> bool:
        """True when ``what`` has been computed (or failed) already."""
        return what in self._values or what in self._errors

    def peek(self, what: Rep) -> Any | None:
        """The value of ``what`` if computed, else None (never computes)."""
        return self._values.get(what)

    def get(self, what: Rep, progress: ProgressLike | None = None) -> Any:
        """Return ``what``, computing it (and what it depends on) in the calling thread if needed.

        ``progress`` may cancel the slow part of a voxel set's R (its decimation): then
        :class:`~mrm.core.errors.Cancelled` is raised and nothing is kept, so a later call computes it again.
        """
        if what in self._values:
            return self._values[what]
        if what not in REPS:
            raise ValueError(f"unknown representation {what!r}; expected one of {REPS}")
        with self._locks[what]:
            if what in self._values:
                return self._values[what]
            if what in self._errors:
                raise self._errors[what]
            try:
                value = self._compute(what, progress)
            except MRMError as e:
                if not isinstance(e, Cancelled):  # a cancel says nothing about the value: not remembered
                    self._errors[what] = e
                raise
            self._values[what] = value
            return value

    def _compute(self, what: Rep, progress: ProgressLike | None) -> Any:
        if self.dimension == 3:
            return self._compute_3d(what, progress)
        if self.kind == "labels":
            if what == "region":
                return cells_of(self.source)
            if what == "euclidean":
                # A label map is polygonized under gauss whatever the document's model: only gauss admits a
                # watertight coverage (under a cover model two parts would both claim the pixels along their
                # common edge), ADR 0033.
                return subdivide(self.source, Model.GAUSS)
            raise NotApplicableError(NO_LABEL_SEGMENTS)
        # D and R through their one entry points, which apply their limits (the pixel limit, the boundary
        # length of issue 11) before any work.
        if what == "discrete":
            return discretize(self.source, self.model)
        if what == "euclidean":
            return reconstruct(self.source, self.model)
        if what == "region":
            return region_from_pixels(self.get("discrete"))
        return analytical_of(self.get("region"))

    def _compute_3d(self, what: Rep, progress: ProgressLike | None) -> Any:
        """The representations of a voxel set, label volume or polyhedron (docs/design.md §11).

        D is the exact voxelizer, R the 3D continuation, the region representation the (6, 26) one, the
        analytical one the digital plane segments of its surfaces; a label volume's region representation is
        its cells (its plane segments and meshes come with the compact 3D continuation).
        """
        # Imported here: a document of plane objects (the desktop's first paint) never loads the 3D kernels.
        from mrm.geometry.discretize.voxels import voxelize
        from mrm.reps.cells_3d import cells_3d_of
        from mrm.reps.region_3d import region_3d_of

        if self.kind == "labels":
            if what == "region":
                return cells_3d_of(self.source.labels, self.source.origin)
            raise NotApplicableError(NO_LABEL_PLANE_SEGMENTS if what == "analytical" else NO_LABEL_MESHES)
        if what == "analytical":
            from mrm.reps.analytical_3d import analytical_3d_of

            return analytical_3d_of(self.get("region"))
        if what == "discrete":
            return voxelize(self.source, self.model)
        if what == "euclidean":
            from mrm.geometry.reconstruct import reconstruct_voxels_detailed

            r = reconstruct_voxels_detailed(self.get("discrete"), self.model, self.compact_limit, progress)
            self.voxel_r = r
            return r.polyhedron
        vs = self.get("discrete")
        vs.count  # noqa: B018 - counted for its cache, on the worker (as region_from_pixels does)
        return region_3d_of(vs.mask, vs.origin)

    def estimated_cost(self, what: Rep) -> float:
        """A rough cost of computing ``what`` now, in pixels touched (0 when ready)."""
        if self.is_ready(what):
            return 0.0
        disc = self.peek("discrete")
        if disc is not None:
            area = float(disc.mask.size if isinstance(disc, GridSet) else disc.labels.size)
        elif self.dimension == 3:  # a polyhedron: the voxels of its bounding box
            (x0, y0, z0), (x1, y1, z1) = (
                self.source.bbox if not self.source.is_empty else ((0.0, 0.0, 0.0), (0.0, 0.0, 0.0))
            )
            area = (x1 - x0 + 2.0) * (y1 - y0 + 2.0) * (z1 - z0 + 2.0)
        else:
            xmin, ymin, xmax, ymax = self.source.bounds if not self.source.is_empty else (0, 0, 0, 0)
            area = (xmax - xmin + 2.0) * (ymax - ymin + 2.0)
        own = {"discrete": area, "euclidean": 30.0 * area, "region": 2.0 * area, "analytical": 4.0 * area}[
            what
        ]
        if what in ("region", "analytical") and not self.is_ready("discrete"):
            own += area
        if what == "analytical" and not self.is_ready("region"):
            own += 2.0 * area
        return own

    def nbytes(self) -> int:
        """Approximate memory of the computed values (for cache accounting)."""
        total = 0
        values = dict(self._values)  # a snapshot: a worker may be adding a value
        for v in values.values():
            if isinstance(v, GridSet):
                total += int(v.mask.nbytes)
            elif isinstance(v, LabelGrid):
                total += int(v.labels.nbytes)
            else:
                total += 4096
        disc = values.get("discrete")
        if "region" in values and isinstance(disc, PixelSet):
            # A region may hold an int32 label image over the mask; never touch it here (it can be lazy).
            total += 4 * int(disc.mask.nbytes)
        return total


class DerivationCache:
    """The :class:`Derived` entries of a document: those of its current objects plus a few recent ones.

    Parameters
    ----------
    keep_recent : int
        How many entries of sources no longer in the document are kept (so that undoing a recent edit finds
        R(A) already computed). Entries of current objects are always kept.
    recent_bytes : int
        The kept entries of old sources hold at most about this much memory (painting on a large object
        replaces its source at every dab; its old versions must not pile up here).
    """

    def __init__(self, keep_recent: int = 16, recent_bytes: int = 64 * 2**20) -> None:
        self.keep_recent = int(keep_recent)
        self.recent_bytes = int(recent_bytes)
        # Keyed by (id of the source, model, compact limit or None): see Settings.derivation_key.
        self._live: dict[tuple[int, str, int | None], Derived] = {}
        self._recent: OrderedDict[tuple[int, str, int | None], Derived] = OrderedDict()
        self._lock = threading.Lock()

    def __len__(self) -> int:
        return len(self._live) + len(self._recent)

    def entry(self, source: Any, model: str, compact_limit: int | None = None) -> Derived:
        """The entry of ``source`` under ``model`` (and a voxel set's compact limit), made if needed."""
        key = (id(source), str(model), compact_limit)
        with self._lock:
            e = self._live.get(key)
            if e is None or e.source is not source:
                e = self._recent.pop(key, None)
                if e is None or e.source is not source:
                    e = Derived(source, model, compact_limit)
                self._live[key] = e
            return e

    def entry_under(self, source: Any, settings: Settings) -> Derived:
        """The entry of ``source`` under a document's settings (:meth:`Settings.derivation_key`)."""
        return self.entry(source, *settings.derivation_key(source))

    def retain(self, live: Iterable[tuple[Any, ...]]) -> None:
        """Declare the entries in use; the others move to the bounded recent list.

        Each is (source, model) or (source, model, compact limit), as :meth:`entry` takes them.
        """
        with self._lock:
            keep: dict[tuple[int, str, int | None], Derived] = {}
            for source, model, *rest in live:
                key = (id(source), str(model), rest[0] if rest else None)
                e = self._live.pop(key, None) or self._recent.pop(key, None)
                if e is not None and e.source is source:
                    keep[key] = e
            for key, e in self._live.items():
                self._recent[key] = e
                self._recent.move_to_end(key)
            while len(self._recent) > self.keep_recent:
                self._recent.popitem(last=False)
            total = sum(e.nbytes() for e in self._recent.values())
            while self._recent and total > self.recent_bytes:
                _, e = self._recent.popitem(last=False)
                total -= e.nbytes()
            self._live = keep

    def clear(self) -> None:
        """Forget every entry."""
        with self._lock:
            self._live.clear()
            self._recent.clear()
