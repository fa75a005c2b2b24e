"""The shared model: an ordered list of objects, each with one source representation (DESIGN §7).

An object (:class:`DocObject`) is an immutable value: an id, a name, a :class:`Style`, an optional
:class:`Provenance`, and its **source** — either a Euclidean geometry (shapely Polygon / MultiPolygon, always
valid) or a discrete :class:`~mrm.core.grids.PixelSet`. The other representations are *derived* from the
source under the document's discretization model and cached by :mod:`mrm.derive`:

* Euclidean source E: discrete = D(E), Euclidean = E;
* discrete source A: discrete = A, Euclidean = R(A);

so D(Euclidean) = discrete holds for every object at every moment (D(R(A)) = A is R's contract).

The :class:`Document` is changed only through the commands of :mod:`mrm.commands`, pushed on its single
:class:`~mrm.history.History`. Views subscribe to coarse, batched :class:`Changes` and never mutate the
model themselves. Nothing here imports Qt.
"""

from __future__ import annotations

import json
import math
import re
import threading
import weakref
from collections.abc import Callable, Iterable, Iterator, Mapping, Sequence
from contextlib import contextmanager
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import Any, Literal, TypeAlias

import numpy as np
import shapely
from shapely.geometry import MultiPolygon, Polygon

from mrm.core import limits
from mrm.core.errors import InvalidGeometryError, LimitError, ParameterError, SizeLimitError
from mrm.core.grids import LabelMap, PixelSet

# Declared once in mrm.core.limits; re-exported here for the modules that imported them from this one.
from mrm.core.limits import COORDINATE_LIMIT as COORDINATE_LIMIT
from mrm.core.limits import PARAMS_MAX_CHARS as PARAMS_MAX_CHARS
from mrm.core.limits import PARAMS_MAX_DEPTH as PARAMS_MAX_DEPTH
from mrm.derive import DerivationCache, Derived
from mrm.history import Command, History
from mrm.io.georef import GeoRef, result_georef

#: A Euclidean source: a valid shapely Polygon or MultiPolygon (possibly empty).
Geometry: TypeAlias = Polygon | MultiPolygon
#: What an object's source can be: pixels, polygons, or a label map (ADR 0033).
Source: TypeAlias = PixelSet | Polygon | MultiPolygon | LabelMap
SourceKind = Literal["euclidean", "discrete", "labels"]

#: The discretization models (DESIGN §2).
MODELS = ("standard", "supercover", "gauss")

_COLOR_RE = re.compile(r"^#[0-9a-fA-F]{6}([0-9a-fA-F]{2})?$")

#: Fill colours given to new objects in turn (a colour-blind-safe palette).
PALETTE = ("#4c72b0", "#dd8452", "#55a868", "#c44e52", "#8172b3", "#937860", "#da8bc3", "#8c8c8c")


# ---------------------------------------------------------------------------------------------- geometry
_VALIDATED: weakref.WeakValueDictionary[int, Any] = weakref.WeakValueDictionary()
_VALIDATED_LOCK = threading.Lock()


def validate_geometry(geom: object) -> Geometry:
    """Return ``geom`` if it can be a Euclidean source, else raise :class:`InvalidGeometryError`.

    A Euclidean source is a 2-D shapely Polygon or MultiPolygon, valid in the OGC sense (DESIGN §6), with
    finite coordinates of magnitude at most :data:`COORDINATE_LIMIT`. An empty geometry of any type becomes
    the empty Polygon. Coordinates are never altered.
    """
    if not isinstance(geom, shapely.Geometry):
        raise InvalidGeometryError(f"expected a polygon, got {type(geom).__name__}")
    with _VALIDATED_LOCK:
        if _VALIDATED.get(id(geom)) is geom:
            return geom
    if geom.is_empty:
        return Polygon()
    if not isinstance(geom, Polygon | MultiPolygon):
        raise InvalidGeometryError(f"an object's Euclidean shape must be a polygon, got a {geom.geom_type}")
    if shapely.has_z(geom):
        raise InvalidGeometryError("the polygon has 3-D coordinates; only plane (x, y) coordinates are used")
    coords = shapely.get_coordinates(geom)
    if not np.isfinite(coords).all():
        raise InvalidGeometryError("the polygon has NaN or infinite coordinates")
    if coords.size and float(np.abs(coords).max()) > COORDINATE_LIMIT:
        raise InvalidGeometryError(
            f"the polygon has a coordinate of magnitude {float(np.abs(coords).max()):.3g}, "
            f"beyond the limit of {COORDINATE_LIMIT:.0f}"
        )
    if not shapely.is_valid(geom):
        raise InvalidGeometryError(f"invalid polygon: {shapely.is_valid_reason(geom)}")
    with _VALIDATED_LOCK:
        _VALIDATED[id(geom)] = geom
    return geom


def _source_cost(source: Source) -> tuple[int, int]:
    """(pixels of the mask box, bytes in a file) of a source; refuses one beyond the per-object limits."""
    if isinstance(source, PixelSet):
        limits.check_pixel_extent(source.origin, source.shape, "the pixel object")
        n = source.shape[0] * source.shape[1]
        return n, limits.source_file_bytes("discrete", pixels=n)
    if isinstance(source, LabelMap):
        limits.check_pixel_extent(source.origin, source.shape, "the label map")
        n = source.shape[0] * source.shape[1]
        if n > limits.MAX_LABEL_PIXELS:
            raise SizeLimitError(n, limits.MAX_LABEL_PIXELS, "the label map")
        return n, limits.source_file_bytes("labels", pixels=n)
    n = int(shapely.get_num_coordinates(source))
    limits.check_vertices(n, "the polygon object")
    parts = shapely.get_parts(source)
    rings = int(parts.size + shapely.get_num_interior_rings(parts).sum()) if parts.size else 0
    return 0, limits.source_file_bytes("euclidean", coordinates=n, rings=rings)


def source_kind(source: Source) -> SourceKind:
    """'discrete' for a pixel set, 'euclidean' for a geometry, 'labels' for a label map."""
    if isinstance(source, PixelSet):
        return "discrete"
    return "labels" if isinstance(source, LabelMap) else "euclidean"


def validate_source(source: object) -> Source:
    """Return ``source`` checked: a pixel set, a label map, or a geometry :func:`validate_geometry` takes."""
    if isinstance(source, PixelSet | LabelMap):
        return source
    return validate_geometry(source)


# ---------------------------------------------------------------------------------------------- values
def _check_color(value: object, what: str) -> str:
    if not isinstance(value, str) or not _COLOR_RE.match(value):
        raise ParameterError(f"{what} must be a colour '#rrggbb' or '#rrggbbaa', got {value!r}")
    return value.lower()


@dataclass(frozen=True)
class Style:
    """How an object is drawn in every view.

    Parameters
    ----------
    fill : str
        Fill colour, ``'#rrggbb'`` or ``'#rrggbbaa'``.
    stroke : str
        Outline colour, same form.
    opacity : float
        Fill opacity in [0, 1].
    stroke_width : float
        Outline width in screen pixels, ≥ 0.
    visible : bool
        Whether the object is drawn at all.
    """

    fill: str = PALETTE[0]
    stroke: str = "#1f2a44"
    opacity: float = 0.6
    stroke_width: float = 1.5
    visible: bool = True

    def __post_init__(self) -> None:
        object.__setattr__(self, "fill", _check_color(self.fill, "fill"))
        object.__setattr__(self, "stroke", _check_color(self.stroke, "stroke"))
        for name, hi in (("opacity", 1.0), ("stroke_width", 100.0)):
            v = getattr(self, name)
            if isinstance(v, bool) or not isinstance(v, int | float) or not (0.0 <= float(v) <= hi):
                raise ParameterError(f"{name} must be a number in [0, {hi:g}], got {v!r}")
            object.__setattr__(self, name, float(v) + 0.0)  # + 0.0 turns -0.0 into 0.0
        if not isinstance(self.visible, bool):
            raise ParameterError(f"visible must be true or false, got {self.visible!r}")

    @classmethod
    def for_index(cls, i: int) -> Style:
        """A default style whose fill colour cycles through :data:`PALETTE`."""
        return cls(fill=PALETTE[i % len(PALETTE)])


def _freeze_json(value: Any, depth: int = 0) -> Any:
    """Return a checked deep copy of a JSON value (dict/list/str/int/float/bool/None); tuples become lists."""
    if depth > PARAMS_MAX_DEPTH:
        raise ParameterError(f"provenance parameters are nested deeper than {PARAMS_MAX_DEPTH} levels")
    if value is None or isinstance(value, bool):
        return value
    if isinstance(value, str):
        return limits.check_text(value, "a provenance parameter")
    if isinstance(value, int):
        return limits.check_param_int(int(value))
    if isinstance(value, float):
        if not math.isfinite(value):
            raise ParameterError("provenance parameters must be finite numbers")
        return float(value)
    if isinstance(value, np.integer):
        return limits.check_param_int(int(value))
    if isinstance(value, np.floating):
        return _freeze_json(float(value), depth)
    if isinstance(value, list | tuple):
        return [_freeze_json(v, depth + 1) for v in value]
    if isinstance(value, Mapping):
        out = {}
        for k, v in value.items():
            if not isinstance(k, str):
                raise ParameterError(f"provenance parameter names must be strings, got {k!r}")
            limits.check_text(k, "a provenance parameter name")
            out[k] = _freeze_json(v, depth + 1)
        return out
    raise ParameterError(f"provenance parameters must be JSON data, got {type(value).__name__}")


def content_digest(source: Any) -> str:
    """A digest of an object's source representation: equal digests mean equal content.

    A pixel set is hashed through its canonical (cropped) mask and origin, a geometry through its WKB
    (float64 coordinates bit for bit), so the digest names the content, not the object that holds it.
    """
    import hashlib

    h = hashlib.sha256()
    if isinstance(source, PixelSet):
        h.update(b"discrete:")
        h.update(np.asarray([*source.origin, *source.shape], dtype=np.int64).tobytes())
        h.update(np.packbits(source.mask, axis=None).tobytes())
    elif isinstance(source, LabelMap):
        h.update(b"labels:")
        h.update(np.asarray([*source.origin, *source.shape], dtype=np.int64).tobytes())
        h.update(source.labels.astype("<i4", copy=False).tobytes())
    else:
        h.update(b"euclidean:")
        h.update(shapely.to_wkb(source, byte_order=1))
    return h.hexdigest()[:32]


#: Longest chain of pinned provenance records accepted (a project file nests them).
PROVENANCE_MAX_DEPTH = 512


@dataclass(frozen=True)
class Provenance:
    """How an object was produced: the operation, its parameters and its inputs *as they were then*.

    Parameters
    ----------
    operation : str
        The operation's name (as in :mod:`mrm.ops`).
    params : Mapping
        Its parameters as JSON data (copied and checked; treat as read-only).
    inputs : sequence of int
        Ids of the objects it read (they may since have been edited or removed).
    sources : sequence of Source, optional
        The content of each input at the moment the result was made (pinned: editing or deleting the
        input object never changes it). Empty for provenance that predates pinning.
    parents : sequence of Provenance or None, optional
        The provenance each input had at that moment (None for a drawn or imported input), so the whole
        chain that led to the result is pinned too.

    Notes
    -----
    ``digests`` (one per pinned source, :func:`content_digest`) is computed once; equality compares
    digests, never the sources themselves. A project file stores each pinned content once, by digest,
    shared between every result that read it (:mod:`mrm.io.project`).
    """

    operation: str
    params: Mapping[str, Any] = field(default_factory=dict)
    inputs: tuple[int, ...] = ()
    sources: tuple[Any, ...] = field(default=(), compare=False, repr=False)
    parents: tuple[Provenance | None, ...] = ()
    digests: tuple[str, ...] = ()

    def __post_init__(self) -> None:
        if not isinstance(self.operation, str) or not self.operation:
            raise ParameterError("a provenance needs an operation name")
        if len(self.operation) > limits.MAX_OPERATION_CHARS:
            raise LimitError(f"an operation name is longer than {limits.MAX_OPERATION_CHARS} characters")
        limits.check_text(self.operation, "the operation name")
        if not isinstance(self.params, Mapping):
            raise ParameterError("provenance parameters must be a mapping of names to values")
        params = _freeze_json(self.params)
        if len(json.dumps(params)) > PARAMS_MAX_CHARS:
            raise ParameterError("provenance parameters are too large")
        object.__setattr__(self, "params", params)
        ins = tuple(self.inputs)
        if not all(isinstance(i, int) and not isinstance(i, bool) for i in ins):
            raise ParameterError("provenance inputs must be object ids (integers)")
        # 0 stands for an input that is no object of a document (a file given to the CLI, a chain's
        # intermediate result): its content is pinned all the same. The project loader takes the same range.
        if not all(0 <= i <= limits.MAX_ID for i in ins):
            raise LimitError(f"provenance inputs must be object ids in [0, 2^53], got {list(ins)[:5]}")
        object.__setattr__(self, "inputs", ins)
        sources = tuple(self.sources)
        if sources and len(sources) != len(ins):
            raise ParameterError(f"a provenance pins {len(sources)} input contents for {len(ins)} inputs")
        for s in sources:
            if not isinstance(s, PixelSet | Polygon | MultiPolygon):
                raise ParameterError(f"a pinned input content must be a source, got {type(s).__name__}")
        object.__setattr__(self, "sources", sources)
        parents = tuple(self.parents) if self.parents else (None,) * len(sources)
        if len(parents) != len(sources):
            raise ParameterError("a provenance needs one parent record per pinned input")
        if not all(p is None or isinstance(p, Provenance) for p in parents):
            raise ParameterError("a provenance's parents must be provenance records or None")
        depth = 1 + max((p.depth for p in parents if p is not None), default=0)
        if depth > PROVENANCE_MAX_DEPTH:
            raise ParameterError(f"a provenance chain is longer than {PROVENANCE_MAX_DEPTH} operations")
        object.__setattr__(self, "parents", parents)
        object.__setattr__(self, "_depth", depth)
        digests = tuple(self.digests) or tuple(content_digest(s) for s in sources)
        if len(digests) != len(sources):
            raise ParameterError("a provenance needs one digest per pinned input content")
        object.__setattr__(self, "digests", digests)

    @property
    def depth(self) -> int:
        """How many operations the pinned chain holds (this one included)."""
        return int(self.__dict__["_depth"])

    @property
    def pinned(self) -> bool:
        """True when the inputs' content at creation is recorded."""
        return bool(self.sources)

    @classmethod
    def of_inputs(cls, operation: str, params: Mapping[str, Any], inputs: Sequence[DocObject]) -> Provenance:
        """The provenance of a result made from ``inputs`` now: their ids, content and provenance pinned."""
        return cls(
            operation,
            params,
            tuple(o.id for o in inputs),
            tuple(o.source for o in inputs),
            tuple(o.provenance for o in inputs),
        )

    @classmethod
    def from_json(cls, data: Mapping[str, Any]) -> Provenance:
        """Build from ``{"operation": name, "params": {...}, "inputs": [ids]}`` (what operations produce)."""
        if not isinstance(data, Mapping) or "operation" not in data:
            raise ParameterError("a provenance is a mapping with 'operation', 'params' and 'inputs'")
        return cls(str(data["operation"]), data.get("params", {}), tuple(data.get("inputs", ())))

    def to_json(self, contents: dict[str, Any] | None = None) -> dict[str, Any]:
        """The provenance as the project file stores it.

        With ``contents`` (digest → source, filled in here) the pinned inputs are written as their digests
        plus their parents' records; the caller stores each content once.
        """
        out: dict[str, Any] = {
            "operation": self.operation,
            "params": _freeze_json(self.params),
            "inputs": list(self.inputs),
        }
        if contents is not None and self.sources:
            for d, s in zip(self.digests, self.sources, strict=True):
                contents.setdefault(d, s)
            out["input_contents"] = list(self.digests)
            out["input_provenance"] = [None if p is None else p.to_json(contents) for p in self.parents]
        return out


@dataclass(frozen=True, eq=True)
class DocObject:
    """One object of a document: an immutable value (edits make new objects).

    Parameters
    ----------
    id : int
        Unique within the document, never reused (an undo may bring a removed object back).
    name : str
        Shown in the object list; need not be unique.
    source : PixelSet or Polygon or MultiPolygon
        The source representation (DESIGN §7).
    style : Style
        How it is drawn.
    provenance : Provenance or None
        The operation that produced it, if any.
    georef : GeoRef or None
        Where its grid lies on the Earth (the affine transform and CRS of the raster it came from, or of
        its inputs' grid: :func:`mrm.io.georef.result_georef`); None for a plain grid (ADR 0016, 0021).
    """

    id: int
    name: str
    source: Source
    style: Style = field(default_factory=Style)
    provenance: Provenance | None = None
    georef: GeoRef | None = None

    __hash__ = None  # type: ignore[assignment]  # a value with a dict inside; compare, don't hash

    def __post_init__(self) -> None:
        if isinstance(self.id, bool) or not isinstance(self.id, int) or not 1 <= self.id <= limits.MAX_ID:
            raise ParameterError(f"object ids are integers in [1, 2^53], got {self.id!r}")
        if not isinstance(self.name, str):
            raise ParameterError(f"an object name must be text, got {type(self.name).__name__}")
        limits.check_name(self.name)
        object.__setattr__(self, "source", validate_source(self.source))
        if not isinstance(self.style, Style):
            raise ParameterError("style must be a Style")
        if self.provenance is not None and not isinstance(self.provenance, Provenance):
            raise ParameterError("provenance must be a Provenance or None")
        if self.georef is not None:
            if not isinstance(self.georef, GeoRef):
                raise ParameterError("georef must be a GeoRef or None")
            if self.georef.crs is not None:
                limits.check_text(self.georef.crs, "the CRS")
        # The object's share of the per-file limits, checked by the document before it is inserted.
        pixels, source_bytes = _source_cost(self.source)
        prov_bytes = limits.json_bytes(self.provenance.to_json()) if self.provenance is not None else 4
        if self.georef is not None:  # counted with the provenance: both are small records beside the source
            prov_bytes += limits.json_bytes(self.georef.as_dict()) + 12
        object.__setattr__(self, "_mask_pixels", pixels)
        object.__setattr__(
            self,
            "_file_bytes",
            limits.object_file_bytes(limits.json_bytes(self.name), prov_bytes, source_bytes),
        )

    @property
    def mask_pixels(self) -> int:
        """Pixels of the bounding box of a discrete source (0 for a Euclidean one), as files count them."""
        return int(self.__dict__["_mask_pixels"])

    @property
    def file_bytes(self) -> int:
        """Upper bound of the bytes this object takes in a project file."""
        return int(self.__dict__["_file_bytes"])

    @property
    def kind(self) -> SourceKind:
        """'discrete', 'euclidean' or 'labels' (a label map, ADR 0033): which representation is the source."""
        return source_kind(self.source)

    def with_(self, **changes: Any) -> DocObject:
        """Return a copy with some fields replaced."""
        return replace(self, **changes)


@dataclass(frozen=True)
class Settings:
    """Document-wide settings saved in the project file.

    Parameters
    ----------
    model : str
        The discretization model D (and its associated continuation R): 'standard', 'supercover' or 'gauss'.
    """

    model: str = "standard"

    def __post_init__(self) -> None:
        if self.model not in MODELS:
            raise ParameterError(
                f"unknown discretization model {self.model!r}; choose one of {', '.join(MODELS)}"
            )


# ---------------------------------------------------------------------------------------------- events
@dataclass(frozen=True)
class Changes:
    """What changed in one batch of edits; delivered to every subscriber once per batch.

    Attributes
    ----------
    revision : int
        The document revision after the batch.
    inserted, removed : tuple of int
        Ids of objects that appeared / disappeared (net over the batch).
    changed : Mapping[int, frozenset[str]]
        For objects present before and after: which aspects changed, among 'source', 'name', 'style',
        'provenance', 'georef' and 'derived' (the derived representations changed although the source did
        not, e.g. after a change of the discretization model).
    reordered : bool
        The order of the objects present before and after changed.
    selection, settings, reset : bool
        The selection changed / the settings changed / the whole document was replaced (views rebuild).
    """

    revision: int
    inserted: tuple[int, ...] = ()
    removed: tuple[int, ...] = ()
    changed: Mapping[int, frozenset[str]] = field(default_factory=dict)
    reordered: bool = False
    selection: bool = False
    settings: bool = False
    reset: bool = False


class _Pending:
    def __init__(self, order: list[int], selection: tuple[int, ...], settings: Settings) -> None:
        self.order = order
        self.selection = selection
        self.settings = settings
        self.changed: dict[int, set[str]] = {}
        self.reset = False
        self.touched = False


# ---------------------------------------------------------------------------------------------- document
class Document:
    """An ordered collection of objects with settings, a selection, one history and change events.

    Parameters
    ----------
    settings : Settings, optional
        Initial settings (default model 'standard').
    max_undo_steps, max_undo_bytes : int
        Limits of the history.

    Notes
    -----
    Views read the document and push commands (``doc.push(cmd)``); they never call the low-level mutation
    methods, which exist for the commands. Every mutation bumps :attr:`revision`; a mutation that changes an
    object's derived representations also bumps that object's :meth:`object_revision`, which the derivation
    service compares to drop stale results.
    """

    def __init__(
        self,
        settings: Settings | None = None,
        *,
        max_undo_steps: int = 1000,
        max_undo_bytes: int = 512 * 2**20,
    ) -> None:
        self._objects: list[DocObject] = []
        self._by_id: dict[int, DocObject] = {}
        self._settings = settings or Settings()
        self._selection: tuple[int, ...] = ()
        self._revision = 0
        self._obj_rev: dict[int, int] = {}
        self._next_id = 1
        # new_id may be called from a worker (objects read off the GUI thread, e.g. a paste): no two
        # callers may get the same id.
        self._id_lock = threading.Lock()
        # Running totals of the per-file limits (mrm.core.limits): pixels of the discrete sources' boxes and
        # the bytes of the project file, kept by the low-level mutations.
        self._mask_pixels = 0
        self._file_bytes = 0
        self._subscribers: list[Callable[[Changes], None]] = []
        self._batch_depth = 0
        self._pending: _Pending | None = None
        self.cache = DerivationCache()
        self.history = History(self, max_steps=max_undo_steps, max_bytes=max_undo_bytes)
        #: The project file this document was loaded from / last saved to (None for a new document).
        self.path: Path | None = None

    # ------------------------------------------------------------------ reading
    @property
    def objects(self) -> tuple[DocObject, ...]:
        """The objects in order (first = bottom of the drawing order)."""
        return tuple(self._objects)

    @property
    def ids(self) -> tuple[int, ...]:
        """The object ids in order."""
        return tuple(o.id for o in self._objects)

    def __len__(self) -> int:
        return len(self._objects)

    def __iter__(self) -> Iterator[DocObject]:
        return iter(tuple(self._objects))

    def __contains__(self, obj_id: object) -> bool:
        return obj_id in self._by_id

    def get(self, obj_id: int) -> DocObject:
        """Return the object with id ``obj_id`` (KeyError if absent)."""
        try:
            return self._by_id[obj_id]
        except KeyError:
            raise KeyError(f"no object with id {obj_id}") from None

    def index_of(self, obj_id: int) -> int:
        """Position of the object in the order."""
        for i, o in enumerate(self._objects):
            if o.id == obj_id:
                return i
        raise KeyError(f"no object with id {obj_id}")

    def find(self, name: str) -> list[DocObject]:
        """The objects called ``name``, in order."""
        return [o for o in self._objects if o.name == name]

    @property
    def settings(self) -> Settings:
        """The document settings."""
        return self._settings

    @property
    def model(self) -> str:
        """The discretization model in force."""
        return self._settings.model

    @property
    def selection(self) -> tuple[int, ...]:
        """Ids of the selected objects, in selection order."""
        return self._selection

    @property
    def revision(self) -> int:
        """Counter bumped by every mutation."""
        return self._revision

    def object_revision(self, obj_id: int) -> int:
        """Counter bumped whenever the derived representations of ``obj_id`` change (-1 if absent)."""
        return self._obj_rev.get(obj_id, -1) if obj_id in self._by_id else -1

    @property
    def is_modified(self) -> bool:
        """True when the document differs from its last saved (or loaded) state."""
        return not self.history.is_clean

    def derived(self, obj_id: int) -> Derived:
        """The representations of object ``obj_id`` under the current model, computed lazily and cached.

        ``doc.derived(i).get('euclidean')`` computes in the calling thread; the GUI computes slow ones on its
        task runner (:mod:`mrm.views.scene`).
        """
        return self.cache.entry(self.get(obj_id).source, self._settings.model)

    # ------------------------------------------------------------------ events
    def subscribe(self, callback: Callable[[Changes], None]) -> Callable[[], None]:
        """Call ``callback(changes)`` after every batch of edits; returns a function that unsubscribes."""
        self._subscribers.append(callback)

        def unsubscribe() -> None:
            if callback in self._subscribers:
                self._subscribers.remove(callback)

        return unsubscribe

    @contextmanager
    def batch(self) -> Iterator[None]:
        """Group mutations so that subscribers get one :class:`Changes` at the end (batches nest)."""
        if self._batch_depth == 0:
            self._pending = _Pending(list(self.ids), self._selection, self._settings)
        self._batch_depth += 1
        try:
            yield
        finally:
            self._batch_depth -= 1
            if self._batch_depth == 0:
                pending, self._pending = self._pending, None
                if pending is not None and pending.touched:
                    self._emit(pending)

    def _touch(self) -> _Pending:
        assert self._pending is not None, "mutations run inside batch()"
        self._pending.touched = True
        self._revision += 1
        return self._pending

    def _emit(self, p: _Pending) -> None:
        now = self.ids
        before = set(p.order)
        after = set(now)
        inserted = tuple(i for i in now if i not in before)
        removed = tuple(i for i in p.order if i not in after)
        changed = {i: frozenset(w) for i, w in p.changed.items() if i in before and i in after and w}
        reordered = [i for i in p.order if i in after] != [i for i in now if i in before]
        changes = Changes(
            revision=self._revision,
            inserted=inserted,
            removed=removed,
            changed=changed,
            reordered=reordered,
            selection=p.selection != self._selection,
            settings=p.settings != self._settings,
            reset=p.reset,
        )
        self.cache.retain((o.source, self._settings.model) for o in self._objects)
        errors: list[BaseException] = []
        for cb in list(self._subscribers):
            try:
                cb(changes)
            except Exception as e:  # one faulty view must not starve the others of the event
                errors.append(e)
        if errors:
            raise errors[0]

    # ------------------------------------------------------------------ editing (through the history)
    def push(self, cmd: Command) -> None:
        """Apply ``cmd`` and record it in the history (shortcut for ``doc.history.push``)."""
        self.history.push(cmd)

    def undo(self) -> None:
        """Undo the last step."""
        self.history.undo()

    def redo(self) -> None:
        """Redo the next step."""
        self.history.redo()

    def set_selection(self, ids: Iterable[int]) -> None:
        """Select the given objects (unknown ids are ignored). Selection is not an undoable edit."""
        sel = tuple(dict.fromkeys(i for i in ids if i in self._by_id))
        if sel == self._selection:
            return
        with self.batch():
            self._touch()
            self._selection = sel

    def new_id(self) -> int:
        """Reserve a fresh object id (ids are never reused, so undo can bring any object back)."""
        with self._id_lock:
            i = self._next_id
            self._next_id += 1
            return i

    def make_object(
        self,
        source: Source,
        name: str | None = None,
        *,
        style: Style | None = None,
        provenance: Provenance | None = None,
        georef: GeoRef | Literal["inputs"] | None = "inputs",
    ) -> DocObject:
        """Build a new object with a fresh id (not yet inserted: push an ``AddObject`` with it).

        ``georef`` defaults to what the provenance's inputs give (:func:`mrm.io.georef.result_georef`: the
        inputs' grid, scaled for DSS_α; None without provenance or for inputs on different grids), so every
        operation result keeps its inputs' place on the Earth without each caller passing it.
        """
        i = self.new_id()
        if georef == "inputs":
            georef = None
            if provenance is not None and provenance.inputs:
                ins = [self._by_id[k].georef if k in self._by_id else None for k in provenance.inputs]
                georef = result_georef(provenance.operation, provenance.params, ins)
        return DocObject(
            id=i,
            name=name if name is not None else f"Object {i}",
            source=source,
            style=style if style is not None else Style.for_index(i - 1),
            provenance=provenance,
            georef=georef,
        )

    # ------------------------------------------------------------------ limits
    def check_capacity(self, add: Iterable[DocObject] = (), remove: Iterable[int] = ()) -> None:
        """Refuse an edit that would take the document beyond the per-file limits (:mod:`mrm.core.limits`).

        Commands call this before they change anything, with the objects they will insert (or the new
        versions of objects they replace) and the ids they will remove or replace; the project file of the
        result is then guaranteed to save and reopen.

        Raises
        ------
        SizeLimitError, LimitError
            Too many pixels in the discrete sources together, or a project file too large.
        """
        pixels, nbytes = self._mask_pixels, self._file_bytes
        for i in dict.fromkeys(remove):
            o = self._by_id.get(i)
            if o is not None:
                pixels -= o.mask_pixels
                nbytes -= o.file_bytes
        for o in add:
            pixels += o.mask_pixels
            nbytes += o.file_bytes
        if pixels > self._mask_pixels or nbytes > self._file_bytes:
            limits.check_document_totals(pixels, nbytes)

    def _count(self, obj: DocObject, sign: int) -> None:
        self._mask_pixels += sign * obj.mask_pixels
        self._file_bytes += sign * obj.file_bytes

    # ------------------------------------------------------------------ low-level mutations (commands only)
    def insert_object(self, obj: DocObject, index: int | None = None) -> None:
        """Insert ``obj`` at ``index`` (default: on top). For commands; views push commands."""
        if obj.id in self._by_id:
            raise ValueError(f"an object with id {obj.id} already exists")
        with self.batch():
            p = self._touch()
            n = len(self._objects)
            idx = n if index is None else max(0, min(int(index), n))
            self._objects.insert(idx, obj)
            self._by_id[obj.id] = obj
            self._count(obj, +1)
            self._obj_rev[obj.id] = self._obj_rev.get(obj.id, 0) + 1
            with self._id_lock:
                self._next_id = max(self._next_id, obj.id + 1)
            if obj.id in p.order:  # removed and re-inserted in one batch: it may differ in every aspect
                aspects = ("source", "name", "style", "provenance", "georef")
                p.changed.setdefault(obj.id, set()).update(aspects)

    def remove_object(self, obj_id: int) -> tuple[DocObject, int]:
        """Remove an object; returns it and the position it had. For commands."""
        idx = self.index_of(obj_id)
        with self.batch():
            self._touch()
            obj = self._objects.pop(idx)
            del self._by_id[obj_id]
            self._count(obj, -1)
            self._obj_rev[obj_id] = self._obj_rev.get(obj_id, 0) + 1
            if obj_id in self._selection:
                self._selection = tuple(i for i in self._selection if i != obj_id)
        return obj, idx

    def replace_object(self, obj: DocObject) -> DocObject:
        """Replace the object with the same id by ``obj``; returns the old one. For commands."""
        old = self.get(obj.id)
        idx = self.index_of(obj.id)
        with self.batch():
            p = self._touch()
            self._objects[idx] = obj
            self._by_id[obj.id] = obj
            self._count(old, -1)
            self._count(obj, +1)
            what = p.changed.setdefault(obj.id, set())
            if old.source is not obj.source:
                what.add("source")
                self._obj_rev[obj.id] = self._obj_rev.get(obj.id, 0) + 1
            for name in ("name", "style", "provenance", "georef"):
                if getattr(old, name) != getattr(obj, name):
                    what.add(name)
        return old

    def set_order(self, ids: Sequence[int]) -> None:
        """Reorder the objects; ``ids`` must be a permutation of :attr:`ids`. For commands."""
        if sorted(ids) != sorted(self._by_id):
            raise ValueError("the new order must list every object exactly once")
        with self.batch():
            self._touch()
            self._objects = [self._by_id[i] for i in ids]

    def set_settings(self, settings: Settings) -> None:
        """Change the settings; a new model re-derives every object. For commands."""
        with self.batch():
            p = self._touch()
            if settings.model != self._settings.model:
                for o in self._objects:
                    p.changed.setdefault(o.id, set()).add("derived")
                    self._obj_rev[o.id] = self._obj_rev.get(o.id, 0) + 1
            self._settings = settings

    def reset(
        self,
        objects: Iterable[DocObject],
        settings: Settings | None = None,
        selection: Iterable[int] = (),
        *,
        clean: bool = True,
    ) -> None:
        """Replace the whole content (open/revert/new), clearing the history; subscribers get ``reset``."""
        objs = list(objects)
        ids = [o.id for o in objs]
        if len(set(ids)) != len(ids):
            raise ValueError("object ids must be unique")
        with self.batch():
            p = self._touch()
            p.reset = True
            for o in self._objects:
                self._obj_rev[o.id] = self._obj_rev.get(o.id, 0) + 1
            self._objects = objs
            self._by_id = {o.id: o for o in objs}
            self._mask_pixels = sum(o.mask_pixels for o in objs)
            self._file_bytes = sum(o.file_bytes for o in objs)
            for o in objs:
                self._obj_rev[o.id] = self._obj_rev.get(o.id, 0) + 1
            self._settings = settings or Settings()
            self._selection = tuple(dict.fromkeys(i for i in selection if i in self._by_id))
            with self._id_lock:
                self._next_id = max([self._next_id, *[i + 1 for i in ids]])
            self.history.clear(clean=clean)
