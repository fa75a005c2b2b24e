"""The operation framework: declarative operations, parameters with metadata, progress and cancel, guards.

An operation is an :class:`OperationSpec`: a name, a title, an arity, a *parameters dataclass* whose fields
carry their metadata (default, bounds, unit, help — see :func:`param`), and a
``run(inputs, params, progress)`` function returning an :class:`OperationResult`. Views build their panels
from :func:`param_specs`; scripts and the CLI call :func:`run_operation`, which validates the parameters
(:func:`validate_params`), estimates the result's size and refuses it beyond the pixel limit *before* any work
(:func:`check_pixel_limit`), runs the operation and stamps the result with its provenance (operation,
parameters, inputs) so that any chain can be replayed and bounded.

Long work reports through a progress object: ``update(fraction, message)`` raises
:class:`mrm.core.errors.Cancelled` once ``cancel()`` was called (from any thread), so an operation stops at its
next report. :class:`Progress` is the thread-safe implementation, :data:`NO_PROGRESS` the no-op one for
scripts; the GUI's task runner passes its own object with the same two methods.
"""

from __future__ import annotations

import dataclasses
import math
import numbers
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from fractions import Fraction
from typing import TYPE_CHECKING, Any, Literal, TypeAlias

from shapely.geometry.base import BaseGeometry

from mrm.core.errors import DEFAULT_PIXEL_LIMIT, ParameterError, SizeLimitError
from mrm.core.grids import PixelSet
from mrm.core.progress import NO_PROGRESS, NullProgress, Progress, ProgressLike, SubProgress
from mrm.geometry.hausdorff.bounds import BoundResult, ChainStep, bound_of_chain

if TYPE_CHECKING:
    from mrm.ops.outcome import StepOutcome

__all__ = [
    "NO_PROGRESS",
    "REGISTRY",
    "NullProgress",
    "OperationResult",
    "OperationSpec",
    "ParamSpec",
    "Plan",
    "PlannedResult",
    "Progress",
    "ProgressLike",
    "SubProgress",
    "bounds_of",
    "check_pixel_limit",
    "coerce_params",
    "estimate_result_pixels",
    "get_operation",
    "operations",
    "param",
    "param_specs",
    "params_from_dict",
    "params_to_dict",
    "plan_operation",
    "range_text",
    "register",
    "run_operation",
    "validate_params",
]


# ============================================================================================================
# Progress and cancel
# ============================================================================================================


# ============================================================================================================
# Parameters
# ============================================================================================================

ParamKind = Literal["float", "int", "bool", "point", "choice", "str"]


@dataclass(frozen=True)
class ParamSpec:
    """The metadata of one parameter (from the field's ``metadata["mrm"]``).

    Attributes
    ----------
    name : str
        The field name.
    label : str
        A short label for a form (defaults to the name).
    kind : str
        ``float``, ``int``, ``bool``, ``point`` (a pair of floats), ``choice`` or ``str``.
    default : object
        The default value.
    unit : str
        The unit shown after the value (``px``, ``°``, …).
    help : str
        One or two sentences for a tooltip.
    minimum, maximum : float or None
        Bounds of a number (``min_inclusive``/``max_inclusive`` tell whether they are allowed).
    choices : tuple
        The allowed values of a ``choice``.
    optional : bool
        Whether None is allowed (e.g. "no centre: the origin").
    """

    name: str
    label: str
    kind: ParamKind
    default: Any
    unit: str = ""
    help: str = ""
    minimum: float | None = None
    maximum: float | None = None
    min_inclusive: bool = True
    max_inclusive: bool = True
    choices: tuple[Any, ...] = ()
    optional: bool = False

    def as_dict(self) -> dict[str, Any]:
        """A JSON-ready description (for forms and documentation)."""
        d = dataclasses.asdict(self)
        d["choices"] = list(self.choices)
        if isinstance(self.default, tuple):
            d["default"] = list(self.default)
        return d


def param(
    default: Any,
    *,
    label: str = "",
    unit: str = "",
    help: str = "",
    minimum: float | None = None,
    maximum: float | None = None,
    min_inclusive: bool = True,
    max_inclusive: bool = True,
    positive: bool = False,
    choices: Sequence[Any] | None = None,
    optional: bool = False,
    kind: ParamKind | None = None,
) -> Any:
    """A dataclass field carrying a parameter's metadata.

    ``positive=True`` means ``minimum=0`` excluded. The kind is inferred from the default (a float, an int,
    a bool, a pair, one of ``choices``) unless given; give it when the default is None.

    Examples
    --------
    >>> @dataclass(frozen=True)
    ... class ScaleParams:
    ...     alpha: float = param(2.0, label="α", positive=True, help="scale factor")
    """
    if positive:
        minimum, min_inclusive = 0.0, False
    if kind is None:
        if choices is not None:
            kind = "choice"
        elif isinstance(default, bool):
            kind = "bool"
        elif isinstance(default, int):
            kind = "int"
        elif isinstance(default, float):
            kind = "float"
        elif isinstance(default, tuple) and len(default) == 2:
            kind = "point"
        elif isinstance(default, str):
            kind = "str"
        else:
            raise TypeError(f"cannot infer the kind of a parameter with default {default!r}; give kind=")
    meta = {
        "label": label,
        "kind": kind,
        "unit": unit,
        "help": help,
        "minimum": minimum,
        "maximum": maximum,
        "min_inclusive": min_inclusive,
        "max_inclusive": max_inclusive,
        "choices": tuple(choices or ()),
        "optional": optional,
    }
    return field(default=default, metadata={"mrm": meta})


def param_specs(params: Any) -> list[ParamSpec]:
    """The :class:`ParamSpec` of every field of a parameters dataclass (or instance), in order."""
    if not dataclasses.is_dataclass(params):
        raise TypeError(f"{params!r} is not a parameters dataclass")
    specs = []
    for f in dataclasses.fields(params):
        meta = f.metadata.get("mrm")
        if meta is None:
            raise TypeError(f"field {f.name!r} has no parameter metadata (declare it with param())")
        default = f.default if f.default is not dataclasses.MISSING else None
        specs.append(
            ParamSpec(name=f.name, label=meta["label"] or f.name, default=default, **_meta_rest(meta))
        )
    return specs


def _meta_rest(meta: dict[str, Any]) -> dict[str, Any]:
    return {k: v for k, v in meta.items() if k != "label"}


def _fmt(v: float) -> str:
    return f"{v:g}"


def range_text(spec: ParamSpec) -> str:
    """The allowed values of a number as a reader writes them: ``0 < α ≤ 1e+06``, ``−3600 ≤ θ ≤ 3600``."""
    lo, hi = spec.minimum, spec.maximum
    name = spec.label or spec.name
    left = "" if lo is None else f"{_fmt(lo)} {'≤' if spec.min_inclusive else '<'} "
    right = "" if hi is None else f" {'≤' if spec.max_inclusive else '<'} {_fmt(hi)}"
    if not left and not right:
        return f"{name} any finite number"
    return f"{left}{name}{right}"


def _check_number(spec: ParamSpec, value: Any) -> float:
    what = f"parameter {spec.name!r}" + (f" ({spec.label})" if spec.label != spec.name else "")
    if isinstance(value, bool) or not isinstance(value, numbers.Real):  # numpy scalars are Real too
        raise ParameterError(f"{what} must be a number, got {value!r}")
    if spec.kind == "int" and not isinstance(value, numbers.Integral):
        raise ParameterError(f"{what} must be an integer, got {value!r}")
    v = float(value)
    if not math.isfinite(v):
        raise ParameterError(f"{what} must be finite, got {value!r}")
    lo, hi = spec.minimum, spec.maximum
    below = lo is not None and (v < lo or (v == lo and not spec.min_inclusive))
    above = hi is not None and (v > hi or (v == hi and not spec.max_inclusive))
    if below and lo is not None:
        first = (
            "positive"
            if lo == 0 and not spec.min_inclusive
            else f"{'≥' if spec.min_inclusive else '>'} {_fmt(lo)}"
        )
        raise ParameterError(f"{what} must be {first}, got {_fmt(v)} (allowed: {range_text(spec)})")
    if above and hi is not None:
        rel = "≤" if spec.max_inclusive else "<"
        raise ParameterError(f"{what} must be {rel} {_fmt(hi)}, got {_fmt(v)} (allowed: {range_text(spec)})")
    return v


#: Largest magnitude of a point parameter's coordinates (a centre), as for Euclidean sources.
POINT_LIMIT = float(2**31)


def validate_params(params: Any) -> None:
    """Check every parameter against its metadata.

    Raises
    ------
    ParameterError
        Naming the parameter: a non-number, a non-finite value, a value outside its bounds (a non-positive
        one where ``positive=True``), a point that is not a pair of finite numbers, a value not among the
        choices.
    """
    for spec in param_specs(params):
        value = getattr(params, spec.name)
        what = f"parameter {spec.name!r}"
        if value is None:
            if spec.optional:
                continue
            raise ParameterError(f"{what} is required")
        if spec.kind in ("float", "int"):
            _check_number(spec, value)
        elif spec.kind == "point":
            if not isinstance(value, (tuple, list)) or len(value) != 2:
                raise ParameterError(f"{what} must be a pair of numbers (x, y), got {value!r}")
            for v in value:
                if isinstance(v, bool) or not isinstance(v, numbers.Real) or not math.isfinite(float(v)):
                    raise ParameterError(f"{what} must be a pair of finite numbers, got {value!r}")
                if abs(float(v)) > POINT_LIMIT:
                    raise ParameterError(
                        f"{what} must have coordinates between {-POINT_LIMIT:g} and {POINT_LIMIT:g}, "
                        f"got {value!r}"
                    )
        elif spec.kind == "bool":
            if not isinstance(value, bool):
                raise ParameterError(f"{what} must be true or false, got {value!r}")
        elif spec.kind == "choice":
            if value not in spec.choices:
                opts = ", ".join(map(str, spec.choices))
                raise ParameterError(f"{what} must be one of {opts}, got {value!r}")
        elif spec.kind == "str" and not isinstance(value, str):
            raise ParameterError(f"{what} must be text, got {value!r}")


def _json_number(v: Any) -> Any:
    from fractions import Fraction

    if isinstance(v, Fraction):
        from mrm.geometry.discretize.exact_shape import number_to_json

        return number_to_json(v)
    return v


def params_to_dict(params: Any) -> dict[str, Any]:
    """The parameters as JSON-ready values (points become lists; a Fraction its exact ``"p/q"`` text)."""
    out: dict[str, Any] = {}
    for spec in param_specs(params):
        v = getattr(params, spec.name)
        out[spec.name] = [_json_number(x) for x in v] if isinstance(v, tuple) else _json_number(v)
    return out


def _read_number(v: Any, name: str) -> Any:
    """A number given as text (``"0.2"``, ``"1/3"``): a float when it is the decimal a float prints as."""
    if not isinstance(v, str):
        return v
    from fractions import Fraction

    from mrm.geometry.discretize.exact_shape import exact_number

    q = exact_number(v, f"parameter {name!r}")
    f = float(q)
    return f if math.isfinite(f) and Fraction(repr(f)) == q else q


def params_from_dict(cls: type, data: dict[str, Any]) -> Any:
    """Build and validate a parameters dataclass from a dict (unknown keys are refused).

    Numbers may be given as text, read exactly (``"1/3"`` stays the Fraction 1/3).
    """
    names = {s.name: s for s in param_specs(cls)}
    unknown = set(data) - set(names)
    if unknown:
        raise ParameterError(
            f"unknown parameter(s) {', '.join(sorted(unknown))} (expected {', '.join(names) or 'none'})"
        )
    kwargs = {}
    for k, v in data.items():
        kind = names[k].kind
        if kind == "point" and isinstance(v, list | tuple):
            v = tuple(_read_number(x, k) for x in v)
        elif kind in ("float", "int"):
            v = _read_number(v, k)
        kwargs[k] = v
    params = cls(**kwargs)
    validate_params(params)
    return params


# ============================================================================================================
# Size guard
# ============================================================================================================

Bounds = tuple[float, float, float, float]


def bounds_of(obj: PixelSet | BaseGeometry) -> Bounds | None:
    """The Euclidean bounding box of an object: ``V(A)``'s for a pixel set, the geometry's own otherwise."""
    if isinstance(obj, PixelSet):
        bb = obj.bbox
        if bb is None:
            return None
        return (bb[0] - 0.5, bb[1] - 0.5, bb[2] + 0.5, bb[3] + 0.5)
    if obj.is_empty:
        return None
    b = obj.bounds
    return (float(b[0]), float(b[1]), float(b[2]), float(b[3]))


def estimate_result_pixels(
    bounds: Bounds | None,
    *,
    scale: float = 1.0,
    angle_deg: float = 0.0,
    center: tuple[float, float] = (0.0, 0.0),
    offset: tuple[float, float] = (0.0, 0.0),
) -> int:
    """How many pixels the bounding box of the transformed object covers (an upper bound of the result).

    The box is mapped by ``x ↦ center + scale·rot(angle)·(x − center) + offset``; the count is the number of
    pixels whose voxel meets the image's bounding box, computed with exact integers (no overflow, so an
    absurd scale reports the absurd size it would have had).
    """
    if bounds is None:
        return 0
    c = math.cos(math.radians(angle_deg)) if angle_deg % 90 else [1, 0, -1, 0][int(angle_deg // 90) % 4]
    s = math.sin(math.radians(angle_deg)) if angle_deg % 90 else [0, 1, 0, -1][int(angle_deg // 90) % 4]
    fc, fs, k = Fraction(c), Fraction(s), Fraction(scale)
    cx, cy = Fraction(center[0]), Fraction(center[1])
    ox, oy = Fraction(offset[0]), Fraction(offset[1])
    xs, ys = [], []
    for x in (bounds[0], bounds[2]):
        for y in (bounds[1], bounds[3]):
            dx, dy = Fraction(x) - cx, Fraction(y) - cy
            xs.append(cx + k * (fc * dx - fs * dy) + ox)
            ys.append(cy + k * (fs * dx + fc * dy) + oy)
    half = Fraction(1, 2)
    nx = math.floor(max(xs) + half) - math.ceil(min(xs) - half) + 1
    ny = math.floor(max(ys) + half) - math.ceil(min(ys) - half) + 1
    return max(nx, 0) * max(ny, 0)


def check_pixel_limit(
    estimated: int, limit: int | None = DEFAULT_PIXEL_LIMIT, what: str = "the result"
) -> None:
    """Raise :class:`SizeLimitError` (with the size it would have had) when ``estimated > limit``."""
    if limit is not None and estimated > limit:
        raise SizeLimitError(estimated, limit, what)


# ============================================================================================================
# Operations
# ============================================================================================================

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
        ``{"operation": name, "params": {...}, "inputs": [...]}``: each input is the provenance of that input
        when the caller gave it, else ``{"input": index}``. Replaying it reproduces the result.
    bound : BoundResult or None
        The error bound of the operation (of the chain, when run by :func:`run_chain`).
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


@dataclass(frozen=True)
class OperationSpec:
    """A declarative operation.

    Attributes
    ----------
    name : str
        The identifier (registry key, provenance, CLI).
    title : str
        What a menu shows.
    arity : int
        How many inputs it takes.
    params : type
        Its parameters dataclass (fields declared with :func:`param`).
    run : callable
        ``run(inputs, params, progress) -> OperationResult``; checks ``progress`` now and then.
    input_kind, output_kind : str
        ``discrete`` (PixelSet), ``euclidean`` (shapely geometry) or ``any``.
    help : str
        A sentence for tooltips and ``--help``.
    estimate : callable, optional
        ``estimate(inputs, params) -> pixels``: the result's size, computed before running for the guard.
    chain_step : callable, optional
        ``chain_step(params) -> ChainStep``: the step in the bound model (DESIGN §8).
    similarity : callable, optional
        ``similarity(params) -> Similarity``: the exact Euclidean similarity the operation applies (Sc_α for
        DSS, the exact rotation for dR, the identity for Sp); the account composes them (DESIGN §8). None for
        an operation that is no step of a one-object chain.
    aliases : tuple of str
        Other names a chain's text or the CLI may use (``DSS``, ``ROT``, ``SP``…).
    step : callable, optional
        ``step(source, params, *, limit, progress, estimated=False) -> StepOutcome``: the operation on one
        object with what a chain needs besides the result (its exact Euclidean image); the chain runner and
        the account call it through :meth:`outcome`. ``estimated`` says the caller checked the size
        estimate already. None for an operation that is no step of a one-object chain.
    """

    name: str
    title: str
    arity: int
    params: type
    run: RunFn
    input_kind: Kind = "any"
    output_kind: Kind = "any"
    help: str = ""
    estimate: EstimateFn | None = None
    chain_step: Callable[[Any], ChainStep] | None = None
    similarity: Callable[[Any], Any] | None = None
    aliases: tuple[str, ...] = ()
    step: StepFn | None = None

    @property
    def reads(self) -> Kind:
        """The representation the operation reads: ``discrete``, ``euclidean`` or ``any``."""
        return self.input_kind

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
        return self.step(source, params, limit=limit, progress=progress)

    def default_params(self) -> Any:
        """The parameters with their defaults."""
        return self.params()

    def param_specs(self) -> list[ParamSpec]:
        """The metadata of the parameters, for forms."""
        return param_specs(self.params)


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
    # the framework importing them at its own import time (they import the framework).
    global _loaded
    if _loaded:
        return
    import importlib
    import pkgutil

    import mrm.ops as package

    for info in pkgutil.iter_modules(package.__path__):
        if not info.name.startswith("_") and info.name != "base":
            importlib.import_module(f"{package.__name__}.{info.name}")
    _loaded = True


def get_operation(name: str) -> OperationSpec:
    """The registered operation ``name``."""
    _load_builtin()
    if name in REGISTRY:
        return REGISTRY[name]
    key = str(name).strip().lower().replace("-", "_").replace(" ", "_")
    for spec in REGISTRY.values():
        if key == spec.name or key in (a.lower() for a in spec.aliases):
            return spec
    raise ParameterError(f"unknown operation {name!r} (known: {', '.join(sorted(REGISTRY))})")


def operations() -> list[OperationSpec]:
    """Every registered operation, sorted by name."""
    _load_builtin()
    return [REGISTRY[k] for k in sorted(REGISTRY)]


def _check_inputs(spec: OperationSpec, inputs: Sequence[Output]) -> None:
    if len(inputs) != spec.arity:
        raise ParameterError(f"{spec.name} takes {spec.arity} input(s), got {len(inputs)}")
    for i, obj in enumerate(inputs):
        if spec.input_kind == "discrete" and not isinstance(obj, PixelSet):
            raise ParameterError(f"{spec.name}: input {i + 1} must be a pixel set, got {type(obj).__name__}")
        if spec.input_kind == "euclidean" and not isinstance(obj, BaseGeometry):
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
    model: str | None = None,
    held: Sequence[tuple[int, str, Any]] = (),
) -> OperationResult:
    """Validate, guard, run ``spec`` and stamp the result with its provenance and bound: the one place.

    Parameters
    ----------
    spec : OperationSpec or str
        The operation (or a registered name or alias).
    inputs : sequence
        ``spec.arity`` pixel sets or geometries.
    params : parameters dataclass or mapping, optional
        Defaults when omitted; a mapping is read with :func:`params_from_dict` (unknown names refused).
    progress : progress object, optional
        Receives ``update(fraction, message)``; cancelling it stops the work with :class:`Cancelled`.
    limit : int or None
        The largest result allowed, in pixels (None: no limit), checked on the estimate before running.
    model : str, optional
        The discretization model of the bound for operations whose parameters carry none.
    held : sequence of (int, str, geometry), optional
        R(A) the caller holds already, as (input index, model, R(A)) for inputs that are pixel sets A (a
        document keeps each object's Euclidean representation, :func:`mrm.ops.apply.held_euclidean`): the
        operation uses it instead of computing R(A) again (:func:`mrm.geometry.reconstruct.held`). The
        result is the same either way.

    Raises
    ------
    ParameterError, SizeLimitError, Cancelled
        Bad parameters (the message gives the allowed range) or inputs; a result beyond ``limit`` (raised
        before running); a cancel.
    """
    spec = get_operation(spec) if isinstance(spec, str) else spec
    params = coerce_params(spec, params)
    _check_inputs(spec, inputs)
    if spec.estimate is not None:
        check_pixel_limit(spec.estimate(inputs, params), limit, f"{spec.title} result")
    progress = NO_PROGRESS if progress is None else progress
    progress.update(0.0, spec.title)
    known = [(inputs[i], m, geom) for i, m, geom in held if isinstance(inputs[i], PixelSet)]
    if known:
        from mrm.geometry.reconstruct import held as held_reconstructions

        with held_reconstructions(known):
            result = spec.run(inputs, params, progress)
    else:
        result = spec.run(inputs, params, progress)
    progress.update(1.0, spec.title)
    provenance = {
        "operation": spec.name,
        "params": params_to_dict(params),
        "inputs": [{"input": i} for i in range(len(inputs))],
    }
    bound = result.bound
    if bound is None and spec.chain_step is not None:
        own_model = getattr(params, "model", None) or model or "standard"
        bound = bound_of_chain([spec.chain_step(params)], own_model)
    return dataclasses.replace(result, provenance=provenance, bound=bound)


def coerce_params(spec: OperationSpec, params: Any) -> Any:
    """The operation's parameters dataclass from None (defaults), a mapping or an instance, validated."""
    if params is None:
        params = spec.default_params()
    elif isinstance(params, dict):
        params = params_from_dict(spec.params, params)
    if not isinstance(params, spec.params):
        raise ParameterError(f"{spec.name} takes {spec.params.__name__}, got {type(params).__name__}")
    validate_params(params)
    return params


@dataclass(frozen=True)
class PlannedResult:
    """One result of :func:`plan_operation`: what to add to a document, with its pinned provenance."""

    name: str
    source: Output
    provenance: Any  # mrm.document.Provenance


@dataclass(frozen=True)
class Plan:
    """What an operation produced, ready to be added to a document as one undo step.

    Attributes
    ----------
    label : str
        The undo step's label (the operation's title).
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
) -> Plan:
    """Run an operation on document objects without touching any document: a pure function.

    Parameters
    ----------
    inputs : sequence of mrm.document.DocObject
        The input objects (immutable values: safe to read on a worker thread).
    name : str or OperationSpec
        The operation.
    params : parameters dataclass or mapping, optional
    progress : progress object, optional
    limit : int or None
    held : sequence of (int, str, geometry), optional
        R(A) the caller holds already for inputs whose source is a pixel set (:func:`run_operation`).

    Returns
    -------
    Plan
        The results, each with a provenance that pins its inputs' ids, content and provenance as they are
        now (:meth:`mrm.document.Provenance.of_inputs`); push them with
        ``doc.push(ApplyResults(plan.label, add=[doc.make_object(r.source, r.name, provenance=r.provenance)
        for r in plan.results]))``, as :func:`mrm.ops.apply.apply_operation` does.
    """
    from mrm.document import Provenance

    spec = get_operation(name) if isinstance(name, str) else name
    params = coerce_params(spec, params)
    out = run_operation(spec, [o.source for o in inputs], params, progress=progress, limit=limit, held=held)
    base = params_to_dict(params)
    results = []
    for part, source in out.outputs:
        p = {**base, "part": part} if len(out.outputs) > 1 else base
        results.append(PlannedResult(part, source, Provenance.of_inputs(spec.name, p, list(inputs))))
    return Plan(spec.title, results, out)
