"""The operation registry: every operation declared once, and the one place that runs one (ADRs 0032, 0041).

An operation is an :class:`OperationSpec`: a name, a title, an arity, a parameters dataclass (a
:class:`~mrm.core.params.Parameters`, whose fields carry their declarations), the representation it reads
and the one it produces, its size estimate, its place in the paper's bound rule, its exact similarity, and a
``run(inputs, params, progress)`` function returning an :class:`OperationResult`. Everything else reads the
spec: the operation panels build their fields from :meth:`~mrm.core.params.Parameters.specs`, the command line
its options, a chain's text its words (:attr:`OperationSpec.symbol`, :attr:`OperationSpec.aliases`) and the
numbers written after them (positional parameters), the account and ``mrm bounds`` the bound
(:attr:`OperationSpec.bound`), the georeference of a result its grid (:attr:`OperationSpec.grid`).

:func:`run_operation` is the one place that runs an operation: it reads the parameters
(:meth:`OperationSpec.read_params`), checks the inputs, estimates the result's size and refuses it beyond the
pixel limit *before* any work (:func:`mrm.core.limits.check_pixels`), runs the operation and stamps the result
with its provenance (operation, parameters, inputs) and bound. :func:`plan_operation` does the same for
document objects without touching any document.
"""

from __future__ import annotations

import dataclasses
import importlib
import pkgutil
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any, Literal, TypeAlias

from shapely.geometry.base import BaseGeometry

from mrm.core.errors import ParameterError
from mrm.core.grids import PixelSet, VoxelSet, dimension_of
from mrm.core.limits import DEFAULT_PIXEL_LIMIT, check_pixels
from mrm.core.numbers import spell, value_text
from mrm.core.params import Parameters
from mrm.core.progress import NO_PROGRESS, ProgressLike
from mrm.geometry.hausdorff.bounds import BoundResult, BoundStep, bound_of_chain
from mrm.geometry.reconstruct import compact_limit_in_force
from mrm.geometry.reconstruct import held as held_reconstructions
from mrm.ops.provenance import Provenance

if TYPE_CHECKING:
    from mrm.ops.outcome import StepOutcome

__all__ = [
    "REGISTRY",
    "OperationResult",
    "OperationSpec",
    "Plan",
    "PlannedResult",
    "get_operation",
    "input_dimension",
    "operations",
    "plan_operation",
    "register",
    "run_operation",
]

Output: TypeAlias = "PixelSet | BaseGeometry"
Kind = Literal["discrete", "euclidean", "any"]


@dataclass(frozen=True)
class OperationResult:
    """What an operation produced.

    Attributes
    ----------
    outputs : list of (str, PixelSet or shapely geometry)
        Named results (one for most operations, three parts for a co-refinement).
    provenance : dict
        ``{"operation": name, "params": {...}, "inputs": [...]}``; replaying it reproduces the result.
    bound : BoundResult or None
        The error bound of the operation.
    measured : float or None
        The measured Hausdorff distance between the composite Euclidean transform of A_first and A_last.
    """

    outputs: list[tuple[str, Output]]
    provenance: dict[str, Any] = field(default_factory=dict)
    bound: BoundResult | None = None
    measured: float | None = None

    @property
    def output(self) -> Output:
        """The first (usually only) output."""
        return self.outputs[0][1]


RunFn = Callable[[Sequence[Output], Any, ProgressLike], OperationResult]
EstimateFn = Callable[[Sequence[Output], Any], int]
#: ``step(source, params, *, limit, progress, estimated=False) -> StepOutcome`` (see OperationSpec.step).
StepFn = Callable[..., "StepOutcome"]
#: ``bound(params, part, n) -> BoundStep``: the operation in the bound rule (``part``: the output followed;
#: ``n``: the dimension of its inputs, 2 or 3).
BoundFn = Callable[[Any, str, int], BoundStep]


@dataclass(frozen=True)
class OperationSpec:
    """A declarative operation.

    Attributes
    ----------
    name : str
        The identifier (registry key, provenance).
    title : str
        What a menu shows.
    arity : int
        How many inputs it takes.
    params : type
        Its parameters dataclass (a :class:`~mrm.core.params.Parameters`).
    run : callable
        ``run(inputs, params, progress) -> OperationResult``; checks ``progress`` now and then.
    reads, produces : str
        The representation it reads and the one it makes: ``discrete`` (PixelSet), ``euclidean`` (shapely
        geometry) or ``any``.
    help : str
        A sentence for tooltips and ``--help``.
    estimate : callable, optional
        ``estimate(inputs, params) -> pixels``: the size of the largest pixel set it will make, computed
        before running for the guard.
    bound : callable, optional
        ``bound(params, part, n) -> BoundStep``: the operation in the bound rule (docs/design.md §8) on
        inputs of dimension ``n``; None for an operation with no place in it.
    similarity : callable, optional
        ``similarity(params, n=2)``: the exact Euclidean map it applies in dimension ``n`` (Sc_α for DSS, the
        exact rotation for dR, the identity for Sp: a ``Similarity`` in the plane,
        a ``Similarity3`` in space, both in ``mrm.geometry.discretize``); the account
        composes them. None for an operation that is no step of a one-object chain.
    step : callable, optional
        ``step(source, params, *, limit, progress, estimated=False) -> StepOutcome``: the operation on one
        object with its exact Euclidean image, for the account. None for an operation that is no step of a
        one-object chain.
    symbol : str
        How a chain's text and an account write the operation (``DSS``, ``ROT``, ``EDu``).
    aliases : tuple of str
        Other words a chain's text or a caller may use.
    parts : tuple of str
        The names of the outputs of a several-output operation (a co-refinement's parts), in order.
    part_words : dict
        For such an operation, the word a chain's text uses for each part (``first``, ``common``…).
    default_part : str
        The part a chain's text means when it names none (a co-refinement's common part).
    grid : str or None
        How a georeferenced input's grid carries to the result: ``same`` (the inputs' grid), ``scaled``
        (scaled by the operation's similarity) or None (no georeference).
    exact : str
        For an operation that makes no error (set operations), why: the account says it.
    command : str
        The ``mrm`` subcommand that runs it (``mrm scale`` runs DSS_α); its options are the parameters.
    """

    name: str
    title: str
    arity: int
    params: type[Parameters]
    run: RunFn
    reads: Kind = "any"
    produces: Kind = "any"
    help: str = ""
    estimate: EstimateFn | None = None
    bound: BoundFn | None = None
    similarity: Callable[..., Any] | None = None
    step: StepFn | None = None
    symbol: str = ""
    aliases: tuple[str, ...] = ()
    parts: tuple[str, ...] = ()
    part_words: Mapping[str, str] = field(default_factory=dict)
    default_part: str = ""
    grid: Literal["same", "scaled"] | None = None
    exact: str = ""
    command: str = ""

    @property
    def is_chain_step(self) -> bool:
        """True for a one-object operation with a similarity and a step: it can be a link of a chain."""
        return self.arity == 1 and self.similarity is not None and self.step is not None

    @property
    def words(self) -> tuple[str, ...]:
        """Every word that names the operation (name, symbol, aliases), in lower case."""
        return tuple(dict.fromkeys(w.lower() for w in (self.name, self.symbol, *self.aliases) if w))

    def read_params(self, params: Any = None) -> Any:
        """The operation's parameters from None (defaults), a mapping (JSON data) or an instance."""
        if params is None:
            return self.params()
        if isinstance(params, Mapping):
            return self.params.from_json(params)
        if not isinstance(params, self.params):
            raise ParameterError(f"{self.name} takes {self.params.__name__}, got {type(params).__name__}")
        return params

    def label(self, params: Any, part: str = "") -> str:
        """The step as a chain's text writes it: ``DSS 5``, ``ROT 30 about 1,2``, ``EDco 4 first``.

        The positional values (joined by commas when there are several: ``TRANSLATE 1,2``), the part when it
        is not the default one, and the centre when it is not the origin; :func:`mrm.ops.chain.parse_chain`
        reads it back.
        """
        words = [self.symbol or self.name]
        values = [getattr(params, s.name) for s in self.params.specs() if s.positional]
        if any(v is not None for v in values):
            words.append(",".join(spell(v) for v in values if v is not None))
        if part and part != self.default_part:
            words.append(self.part_words.get(part, part))
        center = getattr(params, "center", None)
        if center is not None and any(center):
            words.append(f"about {','.join(map(spell, center))}")
        return " ".join(words)

    def bound_step(self, params: Any, part: str = "", n: int = 2) -> BoundStep:
        """The operation in the bound rule on inputs of dimension ``n``; ParameterError if it has none."""
        if self.bound is None:
            raise ParameterError(f"{self.title} has no place in the paper's bound rule (docs/design.md §8)")
        return self.bound(params, part or self.default_part, n)

    def outcome(
        self,
        source: Any,
        params: Any,
        *,
        limit: int | None = DEFAULT_PIXEL_LIMIT,
        progress: ProgressLike | None = None,
    ) -> StepOutcome:
        """Run the operation as a chain step on ``source`` (already in the representation it reads)."""
        if self.step is None:
            raise ParameterError(f"{self.name} is no step of a one-object chain")
        _refuse_3d(self, [source])
        return self.step(source, params, limit=limit, progress=progress)


#: The operations that take 3D inputs (voxel sets, polyhedra) so far; the others refuse them in one line.
THREE_D = frozenset({"dss", "discrete_rotation", "simplify", "union", "corefine"})

#: Every registered operation, by name.
REGISTRY: dict[str, OperationSpec] = {}


def register(spec: OperationSpec) -> OperationSpec:
    """Add ``spec`` to the registry (a name can be registered once) and return it."""
    if spec.name in REGISTRY and REGISTRY[spec.name] is not spec:
        raise ValueError(f"an operation named {spec.name!r} is already registered")
    REGISTRY[spec.name] = spec
    return spec


_loaded = False


def _load_builtin() -> None:
    # Operation modules register their specs when imported. Importing every public module of the package on
    # first use keeps the registry complete for whoever asks it (a new operation needs no edit here) without
    # the registry importing them at its own import time (they import the registry).
    global _loaded
    if _loaded:
        return
    import mrm.ops as package

    for info in pkgutil.iter_modules(package.__path__):
        if not info.name.startswith("_") and info.name != "registry":
            importlib.import_module(f"{package.__name__}.{info.name}")
    _loaded = True


def get_operation(name: str | OperationSpec) -> OperationSpec:
    """The registered operation called ``name`` (its name, symbol or an alias, in any case)."""
    if isinstance(name, OperationSpec):
        return name
    _load_builtin()
    if isinstance(name, str) and name in REGISTRY:
        return REGISTRY[name]
    if isinstance(name, str):
        key = name.strip().lower().replace("-", "_").replace(" ", "_")
        for spec in REGISTRY.values():
            if key in spec.words or key.replace("_", "") in spec.words:
                return spec
    raise ParameterError(f"unknown operation {value_text(name)} (known: {', '.join(sorted(REGISTRY))})")


def operations() -> list[OperationSpec]:
    """Every registered operation, sorted by name."""
    _load_builtin()
    return [REGISTRY[k] for k in sorted(REGISTRY)]


def input_dimension(inputs: Sequence[Any]) -> int:
    """The dimension the inputs live in: 3 for voxel sets and polyhedra (and their exact images), else 2.

    Raises ParameterError for inputs of both dimensions (a pixel set and a voxel set).
    """
    dims = {dimension_of(obj) for obj in inputs}
    if len(dims) > 1:
        raise ParameterError("the inputs mix 2D and 3D objects: an operation takes objects of one dimension")
    return dims.pop() if dims else 2


def _refuse_3d(spec: OperationSpec, inputs: Sequence[Any]) -> None:
    """One line for a 3D input of an operation that does not take 3D objects yet."""
    if input_dimension(inputs) == 3 and spec.name not in THREE_D:
        takes = ", ".join(get_operation(n).title for n in sorted(THREE_D))
        raise ParameterError(f"{spec.title} does not take 3D objects yet (these do: {takes})")


def _check_inputs(spec: OperationSpec, inputs: Sequence[Output]) -> None:
    if len(inputs) != spec.arity:
        raise ParameterError(f"{spec.name} takes {spec.arity} input(s), got {len(inputs)}")
    _refuse_3d(spec, inputs)
    for i, obj in enumerate(inputs):
        if spec.reads == "discrete" and not isinstance(obj, (PixelSet, VoxelSet)):
            raise ParameterError(f"{spec.name}: input {i + 1} must be a pixel set, got {type(obj).__name__}")
        if spec.reads == "euclidean" and not isinstance(obj, BaseGeometry):
            raise ParameterError(
                f"{spec.name}: input {i + 1} must be a Euclidean geometry, got {type(obj).__name__}"
            )


def run_operation(
    spec: OperationSpec | str,
    inputs: Sequence[Output],
    params: Any = None,
    *,
    progress: ProgressLike | None = None,
    limit: int | None = DEFAULT_PIXEL_LIMIT,
    held: Sequence[tuple[int, str, Any]] = (),
    compact_limit: int | None = None,
) -> OperationResult:
    """Read, guard, run ``spec`` and stamp the result with its provenance and bound: the one place.

    Parameters
    ----------
    spec : OperationSpec or str
        The operation (or a registered name, symbol or alias).
    inputs : sequence
        ``spec.arity`` pixel sets or geometries.
    params : parameters dataclass or mapping, optional
        Defaults when omitted; a mapping is read with :meth:`~mrm.core.params.Parameters.from_json`.
    progress : progress object, optional
        Receives ``update(fraction, message)``; cancelling it stops the work with :class:`Cancelled`.
    limit : int or None
        The largest result allowed, in pixels (None: no limit), checked on the estimate before running.
    held : sequence of (int, str, geometry), optional
        R(A) the caller holds already, as (input index, model, R(A)) for inputs that are pixel or voxel sets
        A (a document keeps each object's Euclidean representation): the operation uses it instead of
        computing R(A) again (:func:`mrm.geometry.reconstruct.held`). The result is the same either way.
    compact_limit : int, optional
        The compact limit of every R of a voxel set the operation computes (a document's
        ``Settings.compact_limit``; :func:`mrm.geometry.reconstruct.compact_limit_in_force`); None keeps
        the one in force.

    Raises
    ------
    ParameterError, SizeLimitError, Cancelled
        Bad parameters (the message gives the allowed range) or inputs; a result beyond ``limit`` (raised
        before running); a cancel.
    """
    spec = get_operation(spec)
    params = spec.read_params(params)
    _check_inputs(spec, inputs)
    if spec.estimate is not None:
        unit = "voxels" if input_dimension(inputs) == 3 else "pixels"
        check_pixels(spec.estimate(inputs, params), limit, f"{spec.title} result", unit=unit)
    progress = NO_PROGRESS if progress is None else progress
    progress.update(0.0, spec.title)
    known = [(inputs[i], m, geom) for i, m, geom in held if isinstance(inputs[i], PixelSet | VoxelSet)]
    with held_reconstructions(known), compact_limit_in_force(compact_limit):
        result = spec.run(inputs, params, progress)
    progress.update(1.0, spec.title)
    provenance = {
        "operation": spec.name,
        "params": params.to_json(),
        "inputs": [{"input": i} for i in range(len(inputs))],
    }
    bound = result.bound
    if bound is None and spec.bound is not None and spec.arity == 1:
        n = input_dimension(inputs)
        bound = bound_of_chain([spec.bound_step(params, n=n)], getattr(params, "model", "standard"), n=n)
    return dataclasses.replace(result, provenance=provenance, bound=bound)


@dataclass(frozen=True)
class PlannedResult:
    """One result of :func:`plan_operation`: what to add to a document, with its pinned provenance."""

    name: str
    source: Output
    provenance: Provenance


@dataclass(frozen=True)
class Plan:
    """What an operation produced, ready to be added to a document as one undo step.

    Attributes
    ----------
    label : str
        The undo step's label: the step as a chain writes it (:meth:`OperationSpec.label`, ``DSS 2``).
    results : list of PlannedResult
    outcome : OperationResult
        The operation's own result (bound, part bounds…).
    """

    label: str
    results: list[PlannedResult]
    outcome: OperationResult


def plan_operation(
    inputs: Sequence[Any],
    name: str | OperationSpec,
    params: Any = None,
    progress: ProgressLike | None = None,
    *,
    limit: int | None = DEFAULT_PIXEL_LIMIT,
    held: Sequence[tuple[int, str, Any]] = (),
    compact_limit: int | None = None,
) -> Plan:
    """Run an operation on document objects without touching any document: a pure function.

    Parameters
    ----------
    inputs : sequence of objects with ``id``, ``source`` and ``provenance`` (document objects)
        The input objects (immutable values: safe to read on a worker thread).
    name : str or OperationSpec
        The operation.
    params : parameters dataclass or mapping, optional
    progress : progress object, optional
    limit : int or None
    held : sequence of (int, str, geometry), optional
        R(A) the caller holds already for inputs whose source is a pixel or voxel set (:func:`run_operation`).
    compact_limit : int, optional
        The document's compact limit (:func:`run_operation`).

    Returns
    -------
    Plan
        The results, each with a provenance that pins its inputs' ids, content and provenance as they are
        now (:meth:`mrm.ops.provenance.Provenance.of_inputs`); push them as one undo step
        (:func:`mrm.document.apply.push_plan`).
    """
    spec = get_operation(name)
    params = spec.read_params(params)
    out = run_operation(
        spec,
        [o.source for o in inputs],
        params,
        progress=progress,
        limit=limit,
        held=held,
        compact_limit=compact_limit,
    )
    base = params.to_json()
    results = []
    for part, source in out.outputs:
        p = {**base, "part": part} if len(out.outputs) > 1 else base
        results.append(PlannedResult(part, source, Provenance.of_inputs(spec.name, p, list(inputs))))
    return Plan(spec.label(params), results, out)
