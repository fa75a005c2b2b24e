"""Provenance: how a result was made — its operation, parameters and inputs *as they were then*.

Every result of an operation keeps a :class:`Provenance` (docs/design.md §8): the operation's name, its
parameters as JSON data, the ids of its inputs and, pinned, their content and their own provenance at that
moment, so that editing or deleting an input never changes a result's account (ADR 0008). A project file
stores each pinned content once, by its :func:`content_digest`.
"""

from __future__ import annotations

import hashlib
import json
import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np
import shapely
from shapely.geometry import MultiPolygon, Polygon

from mrm.core import limits
from mrm.core.errors import LimitError, ParameterError
from mrm.core.grids import LabelMap, LabelVolume, PixelSet, VoxelSet, dimension_of
from mrm.core.limits import PARAMS_MAX_CHARS, PARAMS_MAX_DEPTH

__all__ = ["PROVENANCE_MAX_DEPTH", "Provenance", "content_digest", "freeze_json"]


def freeze_json(value: Any, depth: int = 0) -> Any:
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
        return freeze_json(float(value), depth)
    if isinstance(value, list | tuple):
        return [freeze_json(v, depth + 1) for v in value]
    if isinstance(value, Mapping):
        out = {}
        for k, v in value.items():
            if not isinstance(k, str):
                raise ParameterError(f"provenance parameter names must be strings, got {k!r}")
            limits.check_text(k, "a provenance parameter name")
            out[k] = freeze_json(v, depth + 1)
        return out
    raise ParameterError(f"provenance parameters must be JSON data, got {type(value).__name__}")


def content_digest(source: Any) -> str:
    """A digest of an object's source representation: equal digests mean equal content.

    A pixel or voxel set is hashed through its canonical (cropped) mask and origin, a geometry through its
    WKB (float64 coordinates bit for bit), a polyhedron through its canonical vertices and triangles (the same
    solid whatever the order of its triangles), so the digest names the content, not the object that holds it.
    """
    h = hashlib.sha256()
    if isinstance(source, PixelSet | VoxelSet):
        h.update(b"discrete:" if isinstance(source, PixelSet) else b"voxels:")
        h.update(np.asarray([*source.origin, *source.shape], dtype=np.int64).tobytes())
        h.update(np.packbits(source.mask, axis=None).tobytes())
    elif isinstance(source, LabelMap):
        h.update(b"labels:")
        h.update(np.asarray([*source.origin, *source.shape], dtype=np.int64).tobytes())
        h.update(source.labels.astype("<i4", copy=False).tobytes())
    elif isinstance(source, LabelVolume):
        h.update(b"label volume:")
        h.update(np.asarray([*source.origin, *source.shape], dtype=np.int64).tobytes())
        h.update(source.labels.astype("<i4", copy=False).tobytes())
    elif dimension_of(source) == 3:  # a polyhedron
        h.update(b"solid:")
        for part in source.canonical_bytes():
            h.update(part)
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
        params = freeze_json(self.params)
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
            if not (isinstance(s, PixelSet | VoxelSet | Polygon | MultiPolygon) or dimension_of(s) == 3):
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
    def of_inputs(cls, operation: str, params: Mapping[str, Any], inputs: Sequence[Any]) -> Provenance:
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
            "params": freeze_json(self.params),
            "inputs": list(self.inputs),
        }
        if contents is not None and self.sources:
            for d, s in zip(self.digests, self.sources, strict=True):
                contents.setdefault(d, s)
            out["input_contents"] = list(self.digests)
            out["input_provenance"] = [None if p is None else p.to_json(contents) for p in self.parents]
        return out
