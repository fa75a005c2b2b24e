"""The error account of a derived object: provenance chain, bound, measured distance, differing pixels.

The differing pixels are those of the paper's Figure 12: the result against the direct result.

The chain is read back through the objects' provenance (operation, parameters, inputs). For a chain of
discrete operations D∘T_i∘R with similarities T_i (smooth scaling, rotation):

* ``A_first`` = R(A₀), the continuation of the first input's pixels;
* ``T`` = T_k∘…∘T_1, the composite similarity;
* ``A_last`` = T_k(R(A_{k−1})), the Euclidean object just before the final discretization;
* the *measured* error is the exact Hausdorff distance H(T(A_first), A_last), to set beside the paper's bound
  (:func:`mrm.geometry.bounds.bound_of_chain`);
* the *direct result* is D(T(A_first)), the one-step discretization; the result's pixels that it lacks are
  drawn light grey, the ones it has that the result lost dark grey.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from fractions import Fraction
from typing import Any

import numpy as np

from mrm.document import DocObject, Document
from mrm.errors import MRMError, ParameterError
from mrm.reps.pixels import PixelSet

#: Parameter names the operations may use, per meaning.
_ALPHA = ("alpha", "factor", "ratio", "scale", "s")
_ANGLE = ("angle", "theta", "degrees", "angle_deg", "deg")
_CENTER = ("center", "centre", "c", "about")


@dataclass
class ChainLink:
    """One operation of the chain, with the object it produced."""

    obj: DocObject
    operation: str
    params: dict[str, Any]
    inputs: tuple[int, ...]
    step: Any = None  # mrm.geometry.bounds.ChainStep, or None when the operation has no bound rule

    def label(self) -> str:
        """The step as the paper writes it (``DSS 0.1``), or the operation's name."""
        try:
            step = chain_step(self.operation, self.params, decimal=True)
        except (MRMError, TypeError, ValueError, IndexError):
            step = None
        return step.label() if step is not None else self.operation


@dataclass
class Account:
    """Everything the inspector shows for one object."""

    obj: DocObject
    origin: DocObject | None = None  # A₀, when it still exists
    links: list[ChainLink] = field(default_factory=list)
    bound: Any = None  # BoundResult, parameters read exactly (what was computed)
    shown: Any = None  # BoundResult, parameters read as the decimals they print as (what is displayed)
    bound_error: str = ""
    similarity_chain: bool = False  # every step is D∘T∘R with a similarity T: measured/direct computable


def _param(params: dict[str, Any], names: tuple[str, ...]) -> Any:
    for n in names:
        if n in params and params[n] is not None:
            return params[n]
    return None


def _exact(v: Any, decimal: bool = False) -> Any:
    """A parameter as an exact number.

    A float is the dyadic rational it is, or (``decimal``) the decimal the user typed — 0.1 read as 1/10,
    which is how the paper writes its chains.
    """
    if isinstance(v, float):
        return Fraction(repr(v)) if decimal else Fraction(v)
    return v


def chain_step(operation: str, params: dict[str, Any], *, decimal: bool = False) -> Any:
    """The bounds module's step for a provenance record, or None when no rule covers the operation.

    ``decimal`` reads float parameters as the decimals they print as (for display); the default reads
    them exactly, which is what the operation computed with.
    """
    from functools import partial

    from mrm.geometry import bounds as B

    _exact_ = partial(_exact, decimal=decimal)
    op = operation.lower()
    center = _param(params, _CENTER)
    if center is not None:
        center = (_exact_(center[0]), _exact_(center[1]))
    if "rot" in op:
        return B.rot(_exact_(_param(params, _ANGLE)), center)
    if "simpl" in op or op in ("sp",):
        return B.sp(_exact_(_param(params, _ALPHA)), center)
    if "union" in op:
        return B.union()
    if "coref" in op:
        a = _param(params, _ALPHA)
        return B.corefine(None if a is None else _exact_(a), str(params.get("part", "common")))
    if op in ("dss", "scale", "smooth_scaling", "discrete_smooth_scaling") or "dss" in op or "scal" in op:
        return B.dss(_exact_(_param(params, _ALPHA)), center)
    return None


def account_of(doc: Document, obj_id: int) -> Account:
    """Follow the provenance of an object back to its origin and compute the bound of the chain."""
    obj = doc.get(obj_id)
    acc = Account(obj)
    cur: DocObject | None = obj
    seen: set[int] = set()
    while cur is not None and cur.provenance is not None and cur.id not in seen:
        seen.add(cur.id)
        p = cur.provenance
        params = dict(p.params)
        try:
            step = chain_step(p.operation, params)
        except (MRMError, TypeError, ValueError, IndexError):
            step = None
        acc.links.insert(0, ChainLink(cur, p.operation, params, tuple(p.inputs), step))
        first_input = p.inputs[0] if p.inputs else None
        if first_input is None or first_input not in doc:
            cur = None
            break
        cur = doc.get(first_input)
    acc.origin = cur
    steps = [link.step for link in acc.links]
    if acc.links and all(s is not None for s in steps):
        from mrm.geometry.bounds import bound_of_chain

        try:
            acc.bound = bound_of_chain(steps, doc.model)
            shown = [chain_step(link.operation, link.params, decimal=True) for link in acc.links]
            acc.shown = bound_of_chain(shown, doc.model)
        except (MRMError, ValueError) as e:
            acc.bound_error = str(e)
    elif acc.links:
        acc.bound_error = "no bound rule for " + ", ".join(
            sorted({link.operation for link in acc.links if link.step is None})
        )
    acc.similarity_chain = (
        acc.origin is not None
        and bool(acc.links)
        and all(s is not None and s.kind in ("DSS", "ROT") for s in steps)
    )
    return acc


# ---------------------------------------------------------------------------------------------- similarities
def similarity_matrix(step: Any) -> np.ndarray:
    """The 3×3 affine matrix of a DSS (scaling about its centre) or ROT (rotation about its centre) step."""
    cx, cy = (float(step.center[0]), float(step.center[1])) if step.center is not None else (0.0, 0.0)
    if step.kind == "DSS":
        s = float(step.value)
        m = np.array([[s, 0, 0], [0, s, 0], [0, 0, 1]], dtype=float)
    elif step.kind == "ROT":
        t = math.radians(float(step.value))
        c, s = math.cos(t), math.sin(t)
        m = np.array([[c, -s, 0], [s, c, 0], [0, 0, 1]], dtype=float)
    else:
        raise ParameterError(f"{step.kind} is not a similarity")
    to = np.array([[1, 0, cx], [0, 1, cy], [0, 0, 1]], dtype=float)
    back = np.array([[1, 0, -cx], [0, 1, -cy], [0, 0, 1]], dtype=float)
    return to @ m @ back


def apply_matrix(geom: Any, m: np.ndarray) -> Any:
    """``geom`` mapped by the affine 3×3 matrix ``m``."""
    from shapely import affinity

    return affinity.affine_transform(geom, [m[0, 0], m[0, 1], m[1, 0], m[1, 1], m[0, 2], m[1, 2]])


@dataclass
class Measurement:
    """The measured side of the account (computed off the GUI thread)."""

    measured: float
    exceeds_bound: bool | None  # exact comparison with the bound (None without a two-sided bound)
    direct: PixelSet
    result: PixelSet
    light: PixelSet  # in the result, not in the direct result
    dark: PixelSet  # in the direct result, not in the result


def measure(doc: Document, acc: Account, progress: Any = None) -> Measurement:
    """Measured Hausdorff distance and the direct result of a similarity chain (see the module docstring)."""
    from mrm.geometry.discretize import discretize
    from mrm.geometry.hausdorff import hausdorff_distance
    from mrm.geometry.reconstruct import reconstruct

    if not acc.similarity_chain or acc.origin is None:
        raise ParameterError("the measured error is computed for chains of smooth scalings and rotations")
    model = doc.model
    a0 = doc.derived(acc.origin.id).get("discrete")
    a_first = reconstruct(a0, model)
    t = np.eye(3)
    for link in acc.links:
        t = similarity_matrix(link.step) @ t
    transformed = apply_matrix(a_first, t)
    last = acc.links[-1]
    prev_id = last.inputs[0]
    prev = doc.derived(prev_id).get("discrete") if prev_id in doc else None
    if prev is None:
        raise ParameterError("an intermediate object of the chain was deleted")
    a_last = apply_matrix(reconstruct(prev, model), similarity_matrix(last.step))
    if progress is not None:
        progress.update(0.1, "measuring the Hausdorff distance")
    h = hausdorff_distance(transformed, a_last, progress=progress)
    exceeds = None
    if acc.bound is not None and acc.bound.bound is not None:
        exceeds = h.exceeds_sqrt_multiple(acc.bound.coefficient, acc.bound.n)
    direct = discretize(transformed, model)
    result = doc.derived(acc.obj.id).get("discrete")
    return Measurement(h.value, exceeds, direct, result, result - direct, direct - result)
