"""The chain runner: operations applied in order, each with its provenance, bounded and measured (DESIGN §8).

A chain is a list of ``(operation, params)`` applied left to right to one object:

============================ =========== ===================================================================
operation                    reads       params
============================ =========== ===================================================================
``dss``                      discrete    ``alpha`` > 0, ``center`` (optional)
``discrete_rotation``        discrete    ``angle`` (degrees), ``center`` (optional)
``simplify``                 Euclidean   ``alpha`` > 0, ``center`` (optional)
``scale``                    Euclidean   ``factor`` > 0, ``center`` (optional) — an exact Euclidean scaling
``rotate``                   Euclidean   ``angle`` (degrees), ``center`` (optional) — a Euclidean rotation
``translate``                Euclidean   ``dx``, ``dy`` — an exact Euclidean translation
============================ =========== ===================================================================

The names are those of the operation registry (:mod:`mrm.ops.base`); ``DSS``, ``ROT``/``dR`` (the
discrete-Euclidean rotation), ``SP``, ``EROT`` are accepted too, as in a chain's text (``mrm bounds``). The
Euclidean similarities are applied exactly and rounded once to float64 (the rotation is the exact rational
rotation of :mod:`mrm.geometry.discretize.exact_shape`).

When a step reads the other representation than the previous one produced, the runner converts as the
document does: D(E) for a Euclidean object, R(A) for a discrete one (free, since D(R(A)) = A). A Euclidean
result goes on to the next step exactly (rational coordinates); only the results handed out are rounded to
float64, so a chain is exactly the composition of the paper's definitions — a chain of Euclidean
similarities alone measures 0, as its bound says.

What is reported (the paper's Theorems 4–16 as one rule, :mod:`mrm.geometry.hausdorff.bounds`):

* ``A_first``: the Euclidean representation of the first step's input (R(A) for a discrete input);
* ``T``: the composite of the steps' similarities (Sc_α for DSS, the exact rotation for dR, the identity for
  Sp), exact;
* ``A_last``: the Euclidean object just before the final discretization (or the final Euclidean result);
* ``bound``: the chain's error bound; ``measured``: H(T(A_first), A_last) (:mod:`mrm.ops.measure`);
* ``direct``: D(T(A_first)), the result of applying the composite transform in one step, and the pixels of
  the result that differ from it (light grey: in the result only; dark grey: in the direct result only).
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import Any

from mrm.core.errors import DEFAULT_PIXEL_LIMIT, ParameterError
from mrm.core.grids import PixelSet
from mrm.core.progress import ProgressLike, sub_progress
from mrm.geometry.discretize.exact_shape import (
    ExactShape,
    Similarity,
    exact_number,
    exact_point,
    number_to_json,
    positive_number,
)
from mrm.geometry.discretize.rational import discretize_exact
from mrm.ops.measure import MeasuredError, PixelDifference, differing_pixels, measured_error
from mrm.ops.outcome import StepOutcome, check_limit, check_model

#: The operations a chain may hold, and the representation each reads.
CHAIN_OPERATIONS = {
    "dss": "discrete",
    "discrete_rotation": "discrete",
    "simplify": "euclidean",
    "scale": "euclidean",
    "rotate": "euclidean",
    "translate": "euclidean",
}


@dataclass(frozen=True)
class ChainStepResult:
    """One step of a chain.

    Attributes
    ----------
    operation : str
        The operation's name (a key of :data:`CHAIN_OPERATIONS`).
    params : dict
        Its parameters as JSON data (exact: reading them back gives the same numbers).
    provenance : dict
        ``{"operation", "params", "inputs"}``, fit for :class:`mrm.document.Provenance`; the inputs of
        step 1 are the chain's input ids, those of later steps are empty (their input is the previous step).
    outcome : StepOutcome
        The result and what the chain needs from it.
    """

    operation: str
    params: dict[str, Any]
    provenance: dict[str, Any]
    outcome: StepOutcome

    @property
    def result(self) -> Any:
        """The step's result (a pixel set or a polygon)."""
        return self.outcome.result


@dataclass(frozen=True)
class ChainResult:
    """A chain's results, its error bound and its measured error.

    Attributes
    ----------
    steps : tuple of ChainStepResult
    result : PixelSet or shapely Polygon / MultiPolygon
        The final result.
    pixels : PixelSet
        Its discrete representation (D of a Euclidean result).
    a_first, a_last, t_first : ExactShape
        A_first, A_last and T(A_first), exact.
    transform : Similarity
        The composite transform T.
    bound : mrm.geometry.hausdorff.bounds.BoundResult
        The chain's bound (``bound.bound`` is None where the model gives no two-sided bound).
    measured : MeasuredError or None
        H(T(A_first), A_last) and its two directions (None when not asked for).
    direct : PixelSet
        D(T(A_first)).
    difference : PixelDifference
        Light grey (result ∖ direct) and dark grey (direct ∖ result).
    provenance : dict
        The provenance of the final result:
        ``{"operation": "chain", "params": {"model", "steps"}, "inputs"}``.
    """

    steps: tuple[ChainStepResult, ...]
    result: Any
    pixels: PixelSet
    a_first: ExactShape
    a_last: ExactShape
    t_first: ExactShape
    transform: Similarity
    bound: Any
    measured: MeasuredError | None
    direct: PixelSet
    difference: PixelDifference
    provenance: dict[str, Any]

    def summary(self) -> dict[str, Any]:
        """A JSON-ready summary: bound, measured, the differing pixels and the chain."""
        out: dict[str, Any] = {
            "bound": self.bound.bound,
            "bound_one_sided": self.bound.one_sided,
            "bound_formula": self.bound.formula,
            "guarantee": self.bound.guarantee,
            "measured": None,
            "light": len(self.difference.light),
            "dark": len(self.difference.dark),
            "chain": [{"operation": s.operation, "params": s.params} for s in self.steps],
        }
        if self.measured is not None:
            out.update(self.measured.as_dict())
        return out


def normalize_operation(name: str) -> str:
    """The canonical name of a chain operation; the aliases are the registry's (``DSS``, ``ROT``, ``SP``…)."""
    from mrm.ops.base import get_operation

    try:
        spec = get_operation(name)
    except ParameterError:
        spec = None
    if spec is None or spec.name not in CHAIN_OPERATIONS:
        raise ParameterError(
            f"unknown chain operation {name!r}; expected one of {', '.join(CHAIN_OPERATIONS)}"
        )
    return spec.name


def _params_dict(params: Any) -> dict[str, Any]:
    if params is None:
        return {}
    if isinstance(params, Mapping):
        return dict(params)
    if hasattr(params, "__dataclass_fields__"):
        return {k: getattr(params, k) for k in params.__dataclass_fields__}
    raise ParameterError(f"operation parameters must be a mapping, got {type(params).__name__}")


def step_params(operation: str, params: Any) -> tuple[dict[str, Any], Any]:
    """Validate a step's parameters: (JSON parameters, the bounds module's ChainStep).

    The numbers are read exactly, then checked against the ranges the operation's registry spec declares
    (:func:`mrm.ops.base.coerce_params`): a chain refuses what the panel and the command line refuse, with
    the same message.
    """
    pj, step = _read_step_params(operation, params)
    import dataclasses

    from mrm.ops.base import coerce_params, get_operation

    spec = get_operation(operation)
    fields = {f.name for f in dataclasses.fields(spec.params)}
    coerce_params(spec, {k: v for k, v in pj.items() if k in fields and v is not None})
    return pj, step


def _read_step_params(operation: str, params: Any) -> tuple[dict[str, Any], Any]:
    from mrm.geometry.hausdorff import bounds

    p = _params_dict(params)
    center = exact_point(p.get("center"), "center")
    c_json = None if center is None else [number_to_json(center[0]), number_to_json(center[1])]
    if operation in ("dss", "simplify"):
        a = positive_number(p.get("alpha", 1), "alpha")
        make = bounds.dss if operation == "dss" else bounds.sp
        return {"alpha": number_to_json(a), "center": c_json}, make(a, center)
    if operation == "discrete_rotation":
        t = exact_number(p.get("angle", 0), "angle")
        return {"angle": number_to_json(t), "center": c_json}, bounds.rot(t, center)
    if operation == "scale":
        f = positive_number(p.get("factor", p.get("alpha", 1)), "factor")
        return {"factor": number_to_json(f), "center": c_json}, bounds.scale(f, center)
    if operation == "rotate":
        t = exact_number(p.get("angle", 0), "angle")
        return {"angle": number_to_json(t), "center": c_json}, bounds.erot(t, center)
    if operation == "translate":
        dx, dy = exact_number(p.get("dx", 0), "dx"), exact_number(p.get("dy", 0), "dy")
        return {"dx": number_to_json(dx), "dy": number_to_json(dy)}, bounds.translate(dx, dy)
    raise ParameterError(f"unknown chain operation {operation!r}")


def run_step(
    operation: str,
    source: Any,
    params: Mapping[str, Any],
    model: str,
    *,
    limit: int | None = DEFAULT_PIXEL_LIMIT,
    progress: ProgressLike | None = None,
) -> StepOutcome:
    """Apply one chain operation to a source of the representation it reads (already converted).

    ``params`` are the step's JSON parameters (:func:`step_params`); the operation is its registry spec's
    step (:meth:`mrm.ops.base.OperationSpec.outcome`), the same code the panel and the CLI run.
    """
    import dataclasses

    from mrm.ops.base import get_operation

    spec = get_operation(operation)
    fields = {f.name for f in dataclasses.fields(spec.params)}
    given = {k: v for k, v in params.items() if k in fields}
    if "model" in fields:
        given["model"] = model
    return spec.outcome(source, spec.params(**given), limit=limit, progress=progress)


def convert_for(current: Any, wanted: str, model: str, limit: int | None) -> Any:
    """The representation ``wanted`` (``discrete`` or ``euclidean``) of an object, as the document derives it.

    D(E) of a polygon (exactly, for an :class:`ExactShape`), R(A) of a pixel set; unchanged otherwise.
    """
    if wanted == "discrete" and isinstance(current, ExactShape):
        return discretize_exact(current, model, limit=limit)
    if wanted == "discrete" and not isinstance(current, PixelSet):
        from mrm.geometry.discretize import discretize

        return discretize(current, model, limit=limit)
    if wanted == "euclidean" and isinstance(current, PixelSet):
        from mrm.geometry.reconstruct import reconstruct

        return reconstruct(current, model)
    return current


def run_chain(
    source: Any,
    steps: Sequence[tuple[str, Any]],
    model: str = "standard",
    *,
    limit: int | None = DEFAULT_PIXEL_LIMIT,
    progress: ProgressLike | None = None,
    input_ids: Sequence[int] = (),
    measure: bool = True,
) -> ChainResult:
    """Apply ``steps`` in order to ``source``; bound and measure the chain.

    Parameters
    ----------
    source : PixelSet or shapely Polygon / MultiPolygon
        The object the chain starts from.
    steps : sequence of (operation, params)
        Operations of :data:`CHAIN_OPERATIONS` (aliases ``DSS``, ``ROT``, ``SP`` accepted) with their
        parameters (a mapping or a parameter dataclass).
    model : {"standard", "supercover", "gauss"}
    limit : int or None
        Largest pixel set any step may create (each step estimates its result's size first).
    progress : object with ``update(fraction, message)``, optional
        Reports progress over the whole chain; its ``Cancelled`` propagates and nothing is changed
        (the source is an immutable value; results are new values).
    input_ids : sequence of int
        Ids of the source object, recorded in the provenance.
    measure : bool
        Compute the measured Hausdorff distance (exact, may take seconds on large objects).

    Raises
    ------
    ParameterError
        An empty chain, an unknown operation, a bad parameter (named in the message).
    SizeLimitError
        A step's result would exceed ``limit`` pixels.
    """
    from mrm.geometry.hausdorff.bounds import bound_of_chain

    check_model(model)
    check_limit(limit)
    if not steps:
        raise ParameterError("the chain is empty")
    plan = []
    for op, params in steps:
        name = normalize_operation(op)
        pj, cs = step_params(name, params)
        plan.append((name, pj, cs))
    bound = bound_of_chain([cs for _, _, cs in plan], model)

    n = len(plan)
    share = 0.8 if measure else 0.9
    current = convert_for(source, CHAIN_OPERATIONS[plan[0][0]], model, limit)
    a_first = ExactShape.from_geometry(convert_for(current, "euclidean", model, limit))
    transform = Similarity.identity()
    results: list[ChainStepResult] = []
    for i, (name, pj, _) in enumerate(plan):
        sub = sub_progress(progress, share * i / n, share * (i + 1) / n)
        if progress is not None:
            progress.update(share * i / n, f"step {i + 1} of {n}: {name}")
        current = convert_for(current, CHAIN_OPERATIONS[name], model, limit)
        outcome = run_step(name, current, pj, model, limit=limit, progress=sub)
        prov = {
            "operation": name,
            "params": {**pj, "model": model},
            "inputs": [int(x) for x in input_ids] if i == 0 else [],
        }
        results.append(ChainStepResult(name, pj, prov, outcome))
        transform = transform.then(outcome.transform)
        # A Euclidean result travels on exactly: its float64 rounding is only for output.
        current = outcome.result if isinstance(outcome.result, PixelSet) else outcome.euclidean

    final = results[-1].outcome.result
    t_first = a_first.map(transform)
    a_last = results[-1].outcome.euclidean
    pixels = final if isinstance(final, PixelSet) else convert_for(final, "discrete", model, limit)
    if progress is not None:
        progress.update(share, "the direct result D(T(A_first))")
    direct = discretize_exact(t_first, model, limit=limit, progress=sub_progress(progress, share, 0.9))
    measured = None
    if measure:
        if progress is not None:
            progress.update(0.9, "measuring the Hausdorff distance")
        measured = measured_error(t_first, a_last, progress=sub_progress(progress, 0.9, 1.0))
    if progress is not None:
        progress.update(1.0, "done")
    provenance = {
        "operation": "chain",
        "params": {"model": model, "steps": [{"operation": name, "params": pj} for name, pj, _ in plan]},
        "inputs": [int(x) for x in input_ids],
    }
    return ChainResult(
        steps=tuple(results),
        result=final,
        pixels=pixels,
        a_first=a_first,
        a_last=a_last,
        t_first=t_first,
        transform=transform,
        bound=bound,
        measured=measured,
        direct=direct,
        difference=differing_pixels(pixels, direct),
        provenance=provenance,
    )


def parse_steps(text: str) -> list[tuple[str, dict[str, Any]]]:
    """Read a chain written as for ``mrm bounds`` (``"DSS 5, ROT 30 about 1,2, SP 0.5"``) into steps."""
    from mrm.geometry.hausdorff.bounds import parse_chain

    out: list[tuple[str, dict[str, Any]]] = []
    for st in parse_chain(text):
        center = None if st.center is None else [number_to_json(st.center[0]), number_to_json(st.center[1])]
        if st.kind == "DSS":
            out.append(("dss", {"alpha": st.value, "center": center}))
        elif st.kind == "ROT":
            out.append(("discrete_rotation", {"angle": st.value, "center": center}))
        elif st.kind == "SP":
            out.append(("simplify", {"alpha": st.value, "center": center}))
        elif st.kind == "SCALE":
            out.append(("scale", {"factor": st.value, "center": center}))
        elif st.kind == "EROT":
            out.append(("rotate", {"angle": st.value, "center": center}))
        elif st.kind == "TRANSLATE":
            assert st.offset is not None
            out.append(("translate", {"dx": st.offset[0], "dy": st.offset[1]}))
        else:
            raise ParameterError(f"a chain runs on one object: {st.kind} needs a second one")
    return out


__all__ = [
    "CHAIN_OPERATIONS",
    "ChainResult",
    "ChainStepResult",
    "normalize_operation",
    "parse_steps",
    "run_chain",
    "run_step",
    "step_params",
]
