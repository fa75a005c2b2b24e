"""Error bounds of chains of the paper's operations: one rule for all of them (DESIGN §8).

The rule
--------
Follow the error ``e`` of a point through the chain. A Euclidean similarity of ratio ``s`` maps ``e ↦ s·e``;
each discretize-then-continue round trip ``R∘D`` adds ``√n`` (n = 2): for the cover models every point of
``R(D(E))`` lies within ``√n`` of ``E`` and every point of ``E`` within ``√n`` of ``R(D(E))``, because
``E ⊂ V(D(E))``, ``R(D(E)) ⊂ V(D(E))``, ``D(R(D(E))) = D(E)`` and a voxel has diameter ``√n``. The result
bounds the Hausdorff distance between the composite Euclidean transform ``T(A_first)`` of the first Euclidean
object and ``A_last``, the Euclidean object just before the final discretization (or the final result when the
chain ends in the Euclidean space). For ``k`` discrete operations ``D∘T_i∘R`` with ratios ``s_i``::

    H(T_k∘…∘T_1(A_first), A_last) ≤ √n · Σ_{i=2..k} Π_{j=i..k} s_j

How every operation fits
------------------------
Each step is expanded into the primitives it is made of — ``D`` (discretize), ``R`` (continue) and Euclidean
similarities — and the sequence is reduced:

- a leading ``R`` (the chain starts from a discrete object ``A``) is where ``A_first = R(A)`` is taken: no
  error;
- a trailing ``D`` is the final discretization: ``A_last`` is the object just before it;
- an inner ``D`` followed by ``R`` is a round trip: it adds ``√n``;
- an inner ``R`` followed by ``D`` is the identity, because ``D(R(A)) = A`` exactly (the continuation
  contract), so it adds nothing.

So ``DSS_α = D∘Sc_α∘R`` and ``dR_θ,C = D∘rot_θ,C∘R`` contribute a similarity (ratio α, resp. 1) with a round
trip between consecutive steps (Theorems 4, 7–10, 12, 13 all follow); ``Sp_α = Sc_1/α∘R∘D∘Sc_α`` is
``Sc_α``, a round trip, ``Sc_1/α`` (Theorem 15: ``√n/α``; chained, Theorem 16: ``Σ √n/α_i``); ``EDu`` is a
round trip of ``E ∪ E′`` (``D`` is union-stable): ``√n``; ``EDco_α`` is ``Sc_α``, a round trip, ``Sc_1/α``:
``√n/α``. The centres of the scalings and rotations and the translations change ``T`` but not the bound:
errors are vectors, only the ratio acts on them. Mixed chains need no special case: ``DSS 2, ROT 30`` is
``Sc_2``, a round trip, ``rot_30`` → ``√n``; ``SP 4, DSS 2`` discretizes Sp's result before the DSS:
``Sc_4``, round trip, ``Sc_1/4``, round trip, ``Sc_2`` → ``(1/4·2 + 2)·√n``.

What the number means per model and part
----------------------------------------
Each direction of the Hausdorff distance propagates on its own (directed distances obey the triangle
inequality and scale with the ratio), so the module tracks both:

- ``result within`` — every point of ``A_last`` lies within the bound of ``T(A_first)``;
- ``source within`` — every point of ``T(A_first)`` lies within the bound of ``A_last``.

For ``standard`` and ``supercover`` (covers) a round trip keeps both, so :attr:`BoundResult.bound` is a
Hausdorff bound. For ``gauss`` (a partition: thin parts may vanish) only ``result within`` holds (DESIGN §2):
``bound`` is ``None`` and :attr:`BoundResult.one_sided` carries the value with ``direction="result_within"``.
A union keeps both directions (``h(X ∪ Y, I ∪ Y) ≤ h(X, I)``). A co-refinement part is not Lipschitz in its
inputs: with exact inputs the common part ``R(D(E) ∩ D(E′))`` has every point of ``E ∩ E′`` within the bound
(``source within``, covers only) but may contain points far from ``E ∩ E′`` (two disjoint objects in one
pixel), while a difference part ``R(D(E) ∖ D(E′))`` has every one of its points within the bound of
``E ∖ E′`` (``result within``, all models) but may lose thin parts of it; after an earlier error neither
direction survives a co-refinement.

The arithmetic is exact: ratios are :class:`fractions.Fraction` (decimal literals such as ``1.25`` and
fractions such as ``1/5`` are read exactly) and the bound is ``coefficient · √n`` with a rational
coefficient, so the printed digits are those of the exact value.

Chains are written in the order the steps are applied (left first): the paper's
``DSS_0.8 ∘ DSS_0.2 ∘ DSS_5 ∘ DSS_1.25`` is ``"DSS 1.25, DSS 5, DSS 0.2, DSS 0.8"``.
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass, field
from decimal import Decimal, localcontext
from fractions import Fraction
from typing import Literal

from mrm.core.errors import ParameterError

#: The dimension of the space: every round trip adds √N_DIM.
N_DIM = 2

#: The discretization models whose round trips keep both directions of the Hausdorff distance.
COVER_MODELS = ("standard", "supercover")
#: Every discretization model the bound knows.
MODELS = ("standard", "supercover", "gauss")

StepKind = Literal["DSS", "ROT", "SP", "SCALE", "EROT", "TRANSLATE", "UNION", "COREFINE"]
#: The parts of a co-refinement: E∩E′ ("common"), E∖E′ ("first"), E′∖E ("second").
CorefinePart = Literal["common", "first", "second"]
Direction = Literal["result_within", "source_within"]
Point = tuple[Fraction, Fraction]

_KIND_INPUT = {"DSS": "discrete", "ROT": "discrete"}


@dataclass(frozen=True)
class ChainStep:
    """One operation of a chain, with exact parameters.

    Parameters
    ----------
    kind : str
        ``DSS`` (discrete smooth scaling, ratio ``value``), ``ROT`` (discrete-Euclidean rotation by ``value``
        degrees), ``SP`` (discrete-based simplification, factor ``value``), ``SCALE`` (Euclidean scaling by
        ``value``), ``EROT`` (Euclidean rotation by ``value`` degrees), ``TRANSLATE`` (Euclidean translation
        by ``offset``), ``UNION`` (Euclidean-discrete union with another object), ``COREFINE``
        (Euclidean-discrete co-refinement, precise when ``value`` is given).
    value : Fraction or None
        The scale factor or angle (None for TRANSLATE, UNION and a plain COREFINE).
    center : tuple of Fraction or None
        The centre of a scaling or rotation (None: the origin).
    offset : tuple of Fraction or None
        The vector of a translation.
    part : str
        For COREFINE, the part the chain follows: ``common`` (E∩E′), ``first`` (E∖E′), ``second`` (E′∖E).
    """

    kind: StepKind
    value: Fraction | None = None
    center: Point | None = None
    offset: Point | None = None
    part: CorefinePart = "common"

    @property
    def input_kind(self) -> str:
        """``discrete`` or ``euclidean``: the representation the step reads."""
        return _KIND_INPUT.get(self.kind, "euclidean")

    @property
    def output_kind(self) -> str:
        """``discrete`` or ``euclidean``: the representation the step produces."""
        return "discrete" if self.kind in ("DSS", "ROT") else "euclidean"

    def label(self) -> str:
        """The step as the parser reads it, e.g. ``DSS 5`` or ``ROT 30 about 1,2``."""
        parts: list[str] = [self.kind]
        if self.value is not None:
            parts.append(_fmt_number(self.value))
        if self.offset is not None:
            parts.append(f"{_fmt_number(self.offset[0])},{_fmt_number(self.offset[1])}")
        if self.kind == "COREFINE" and self.part != "common":
            parts.append(self.part)
        if self.center is not None:
            parts.append(f"about {_fmt_number(self.center[0])},{_fmt_number(self.center[1])}")
        return " ".join(parts)

    def ratio(self) -> Fraction:
        """The ratio of the step's Euclidean similarity (1 for rotations, translations and unions)."""
        if self.kind in ("DSS", "SCALE") and self.value is not None:
            return self.value
        return Fraction(1)


# --------------------------------------------------------------------------------------------------------
# Constructors with validation
# --------------------------------------------------------------------------------------------------------


def _exact(value: object, what: str) -> Fraction:
    """Return ``value`` as an exact Fraction; refuse non-finite and non-numeric values."""
    if isinstance(value, bool):
        raise ParameterError(f"{what} must be a number, got {value!r}")
    if isinstance(value, Fraction):
        q = value
    elif isinstance(value, int):
        q = Fraction(value)
    elif isinstance(value, float):
        if not math.isfinite(value):
            raise ParameterError(f"{what} must be finite, got {value!r}")
        q = Fraction(value)
    elif isinstance(value, (str, Decimal)):
        text = str(value).strip()
        try:
            q = Fraction(text)
        except (ValueError, ZeroDivisionError):
            low = text.lower().lstrip("+-")
            if low in ("inf", "infinity", "nan"):
                raise ParameterError(f"{what} must be finite, got {text!r}") from None
            raise ParameterError(f"{what} must be a number, got {text!r}") from None
    else:
        raise ParameterError(f"{what} must be a number, got {value!r}")
    try:
        finite = math.isfinite(float(q))
    except OverflowError:
        finite = False
    if not finite:
        raise ParameterError(f"{what} must be finite, got {value!r} (too large)")
    return q


def _positive(value: object, what: str) -> Fraction:
    q = _exact(value, what)
    if q <= 0:
        raise ParameterError(f"{what} must be positive, got {_fmt_number(q)}")
    return q


def _point(p: object, what: str) -> Point | None:
    if p is None:
        return None
    if not isinstance(p, (tuple, list)) or len(p) != 2:
        raise ParameterError(f"{what} must be a pair of numbers, got {p!r}")
    return (_exact(p[0], f"{what} x"), _exact(p[1], f"{what} y"))


def dss(alpha: object, center: object = None) -> ChainStep:
    """Discrete smooth scaling ``D∘Sc_α∘R`` (α > 0), optionally about ``center``."""
    return ChainStep("DSS", _positive(alpha, "DSS factor α"), _point(center, "DSS centre"))


def rot(angle_deg: object, center: object = None) -> ChainStep:
    """Discrete-Euclidean rotation ``D∘rot_θ,C∘R`` by ``angle_deg`` degrees about ``center``."""
    return ChainStep("ROT", _exact(angle_deg, "ROT angle"), _point(center, "ROT centre"))


def sp(alpha: object, center: object = None) -> ChainStep:
    """Discrete-based simplification ``Sc_1/α∘R∘D∘Sc_α`` (α > 0)."""
    return ChainStep("SP", _positive(alpha, "SP factor α"), _point(center, "SP centre"))


def scale(factor: object, center: object = None) -> ChainStep:
    """Euclidean scaling by ``factor`` > 0 (exact, no discretization)."""
    return ChainStep("SCALE", _positive(factor, "SCALE factor"), _point(center, "SCALE centre"))


def erot(angle_deg: object, center: object = None) -> ChainStep:
    """Euclidean rotation by ``angle_deg`` degrees about ``center`` (exact map, no discretization)."""
    return ChainStep("EROT", _exact(angle_deg, "EROT angle"), _point(center, "EROT centre"))


def translate(dx: object, dy: object) -> ChainStep:
    """Euclidean translation by (dx, dy) (exact, no discretization)."""
    return ChainStep("TRANSLATE", offset=(_exact(dx, "TRANSLATE dx"), _exact(dy, "TRANSLATE dy")))


def union() -> ChainStep:
    """Euclidean-discrete union ``R(D(E) ∪ D(E′))`` with another object."""
    return ChainStep("UNION")


def corefine(alpha: object = None, part: CorefinePart = "common") -> ChainStep:
    """Euclidean-discrete co-refinement (precise when ``alpha`` is given); the chain follows ``part``."""
    if part not in ("common", "first", "second"):
        raise ParameterError(f"COREFINE part must be common, first or second, got {part!r}")
    value = None if alpha is None else _positive(alpha, "COREFINE factor α")
    return ChainStep("COREFINE", value, part=part)


# --------------------------------------------------------------------------------------------------------
# The rule
# --------------------------------------------------------------------------------------------------------


@dataclass(frozen=True)
class BoundTerm:
    """The contribution of one round trip ``R∘D`` to the bound: ``factor · √n``.

    Attributes
    ----------
    round_trip : int
        1-based index of the round trip in the chain.
    step : int
        1-based index of the step whose discretization starts the round trip.
    description : str
        Where the round trip happens, e.g. ``R∘D between step 1 (DSS 5) and step 2 (DSS 2)``.
    factor : Fraction
        The product of the ratios of every similarity applied after it.
    """

    round_trip: int
    step: int
    description: str
    factor: Fraction

    def value(self, n: int = N_DIM) -> float:
        """``factor · √n`` as the float nearest to the exact value."""
        return sqrt_multiple(self.factor, n)

    def as_dict(self, n: int = N_DIM) -> dict[str, object]:
        """A JSON-ready summary."""
        return {
            "round_trip": self.round_trip,
            "step": self.step,
            "description": self.description,
            "factor": _fmt_fraction(self.factor),
            "value": self.value(n),
        }


@dataclass(frozen=True)
class BoundResult:
    """The error bound of a chain: ``coefficient · √n``, exact.

    Attributes
    ----------
    bound : float or None
        The Hausdorff bound ``H(T(A_first), A_last) ≤ bound``; None when the model (``gauss``) or a
        co-refinement only gives one direction, or none.
    coefficient : Fraction
        The rule's coefficient: ``Σ`` over the round trips of the product of the later ratios.
    n : int
        The dimension; the bound is ``coefficient · √n``.
    terms : list of BoundTerm
        One per round trip, in chain order.
    formula : str
        The sum written out, e.g. ``√2·(1/10 + 1/5 + 1/5) = 1/2·√2 ≈ 0.7071``.
    directions : tuple of str
        The directions that hold: ``result_within`` (every point of A_last within the value of T(A_first))
        and/or ``source_within`` (every point of T(A_first) within the value of A_last).
    one_sided : float or None
        The value when exactly one direction holds (``bound`` is then None).
    model : str
        The discretization model the bound is for.
    guarantee : str
        What the number means, in words.
    """

    bound: float | None
    coefficient: Fraction
    n: int
    terms: list[BoundTerm]
    formula: str
    directions: tuple[Direction, ...]
    one_sided: float | None
    model: str
    guarantee: str
    steps: tuple[ChainStep, ...] = field(default=())

    @property
    def value(self) -> float:
        """``coefficient · √n`` whatever the directions that hold."""
        return sqrt_multiple(self.coefficient, self.n)

    @property
    def sqrt_n(self) -> float:
        """``√n`` as a float."""
        return math.sqrt(self.n)

    def holds(self, direction: Direction) -> bool:
        """True when the value bounds ``direction``."""
        return direction in self.directions

    def as_dict(self) -> dict[str, object]:
        """A JSON-ready summary (the ``mrm bounds --json`` payload)."""
        return {
            "bound": self.bound,
            "coefficient": _fmt_fraction(self.coefficient),
            "coefficient_float": float(self.coefficient),
            "n": self.n,
            "sqrt_n": self.sqrt_n,
            "value": self.value,
            "terms": [t.as_dict(self.n) for t in self.terms],
            "formula": self.formula,
            "directions": list(self.directions),
            "one_sided": self.one_sided,
            "model": self.model,
            "guarantee": self.guarantee,
            "chain": [s.label() for s in self.steps],
        }


def sqrt_multiple(coefficient: Fraction, n: int = N_DIM) -> float:
    """Return the float nearest to ``coefficient · √n`` (computed with 60 significant digits)."""
    if coefficient == 0:
        return 0.0
    with localcontext() as ctx:
        ctx.prec = 60
        d = Decimal(coefficient.numerator) / Decimal(coefficient.denominator) * Decimal(n).sqrt()
    return float(d)


@dataclass(frozen=True)
class _Map:
    """An exact similarity ``z ↦ a·z + b`` of the complex plane with Gaussian-rational a and b."""

    ar: Fraction
    ai: Fraction
    br: Fraction
    bi: Fraction

    def then(self, o: _Map) -> _Map:
        """``o ∘ self``."""
        ar = o.ar * self.ar - o.ai * self.ai
        ai = o.ar * self.ai + o.ai * self.ar
        br = o.ar * self.br - o.ai * self.bi + o.br
        bi = o.ar * self.bi + o.ai * self.br + o.bi
        return _Map(ar, ai, br, bi)

    def commutes_with_round_trips(self) -> bool:
        """The identity or an integer translation: then ``R∘D∘T∘R∘D = T∘R∘D`` (D(R(A)) = A, covariance)."""
        return self.ar == 1 and self.ai == 0 and self.br.denominator == 1 and self.bi.denominator == 1


_IDENTITY = _Map(Fraction(1), Fraction(0), Fraction(0), Fraction(0))


def _about(ar: Fraction, ai: Fraction, c: Point | None) -> _Map:
    """``z ↦ c + a·(z − c)``."""
    cr, ci = c if c is not None else (Fraction(0), Fraction(0))
    return _Map(ar, ai, cr - (ar * cr - ai * ci), ci - (ar * ci + ai * cr))


def _scaling(s: Fraction, c: Point | None) -> _Map:
    return _about(s, Fraction(0), c)


def _rotation(theta: Fraction | None, c: Point | None) -> _Map | None:
    """Exact for multiples of 90°; None (not representable) otherwise."""
    if theta is None or theta % 90:
        return None
    ar, ai = [(1, 0), (0, 1), (-1, 0), (0, -1)][int(theta // 90) % 4]
    return _about(Fraction(ar), Fraction(ai), c)


# Primitive operations a step is made of, in application order.
_D = ("D",)
_R = ("R",)


def _primitives(step: ChainStep, index: int) -> list[tuple[object, ...]]:
    """Expand ``step`` into primitives, in application order.

    ("D",), ("R",), ("S", ratio, exact map or None), and the markers of unions ("U",) and co-refinements
    ("C", part).
    """
    k = step.kind
    if k == "DSS":
        return [_R, ("S", step.ratio(), _scaling(step.ratio(), step.center)), _D]
    if k == "ROT":
        return [_R, ("S", Fraction(1), _rotation(step.value, step.center)), _D]
    if k == "SP":
        assert step.value is not None
        a = step.value
        return [("S", a, _scaling(a, step.center)), _D, _R, ("S", 1 / a, _scaling(1 / a, step.center))]
    if k == "SCALE":
        return [("S", step.ratio(), _scaling(step.ratio(), step.center))]
    if k == "EROT":
        return [("S", Fraction(1), _rotation(step.value, step.center))]
    if k == "TRANSLATE":
        assert step.offset is not None
        return [("S", Fraction(1), _Map(Fraction(1), Fraction(0), *step.offset))]
    if k == "UNION":
        return [("U",), _D, _R]
    # COREFINE: Sc_α, then D of both inputs, the discrete Boolean part, R, Sc_1/α.
    alpha = step.value if step.value is not None else Fraction(1)
    return [
        ("S", alpha, _scaling(alpha, None)),
        ("C", step.part),
        _D,
        _R,
        ("S", 1 / alpha, _scaling(1 / alpha, None)),
    ]


def _merge_exact_round_trips(
    atoms: list[tuple[str, object, int]], discrete_start: bool
) -> list[tuple[str, object, int]]:
    """Drop the round trips that exact identities make free.

    A round trip is dropped when the similarities since the previous one compose to the identity or to an
    integer translation T: ``R∘D∘T∘R∘D = T∘R∘D`` because ``D(R(A)) = A`` and ``R(A + t) = R(A) + t``. A
    discrete start counts as a round trip: ``A_first = R(A)`` is already a continuation.
    """
    out: list[tuple[str, object, int]] = []
    # The composite since the last round trip kept (None: unknown, or no round trip yet).
    since: _Map | None = _IDENTITY if discrete_start else None
    for atom in atoms:
        kind, arg, _ = atom
        if kind == "RT":
            if since is not None and since.commutes_with_round_trips():
                continue  # merged into the previous round trip
            out.append(atom)
            since = _IDENTITY
        elif kind == "S":
            m = arg[1]  # type: ignore[index]
            since = since.then(m) if since is not None and m is not None else None
            out.append(atom)
        else:  # a union or a co-refinement changes the object: no identity across it
            since = None
            out.append(atom)
    return out


def bound_of_chain(
    steps: list[ChainStep] | tuple[ChainStep, ...],
    model: str = "standard",
    *,
    n: int = N_DIM,
    exact_identities: bool = False,
) -> BoundResult:
    """Return the error bound of a chain of operations (DESIGN §8), exactly.

    Parameters
    ----------
    steps : sequence of ChainStep
        The operations in the order they are applied (see :func:`parse_chain`).
    model : str
        ``standard``, ``supercover`` or ``gauss``: which directions of the bound hold (module docstring).
    n : int
        The dimension (2).
    exact_identities : bool
        Also use that a round trip followed, through similarities composing to the identity or to an integer
        translation, by another round trip is a single one (``D(R(A)) = A``; ``R`` commutes with integer
        translations). This gives ``Sp_α∘Sp_α = Sp_α`` its exact bound ``√n/α`` and ``DSS_1`` none. Off by
        default: the paper's theorems count every round trip, and so does DESIGN §8's rule.

    Returns
    -------
    BoundResult
        The bound (None where the model gives no two-sided bound), its exact coefficient, one term per
        round trip, the formula and what the number guarantees.

    Raises
    ------
    ParameterError
        An empty chain, an unknown model or a non-positive dimension.
    """
    if model not in MODELS:
        raise ParameterError(f"unknown discretization model {model!r} (expected one of {', '.join(MODELS)})")
    if n < 1:
        raise ParameterError(f"the dimension must be positive, got {n}")
    steps = tuple(steps)
    if not steps:
        raise ParameterError("the chain is empty")
    from mrm.core.limits import check_chain_steps

    check_chain_steps(len(steps))  # exact arithmetic grows with the chain: bounded up front (issue 11)

    # Expand into primitives, converting between the representations where a step needs the other one.
    prims: list[tuple[tuple[object, ...], int]] = []
    current = steps[0].input_kind
    for i, step in enumerate(steps, start=1):
        if step.input_kind != current:
            prims.append((_D if current == "euclidean" else _R, i))
        prims.extend((p, i) for p in _primitives(step, i))
        current = step.output_kind
    # A_first = R(A) for a discrete start; A_last is just before a final discretization.
    if prims and prims[0][0] == _R:
        prims = prims[1:]
    if prims and prims[-1][0] == _D:
        prims = prims[:-1]

    # Reduce: D then R is a round trip; R then D is the identity (D(R(A)) = A exactly).
    atoms: list[tuple[str, object, int]] = []
    j = 0
    while j < len(prims):
        p, i = prims[j]
        nxt = prims[j + 1][0] if j + 1 < len(prims) else None
        if p == _D and nxt == _R:
            atoms.append(("RT", prims[j + 1][1], i))
            j += 2
        elif p == _R and nxt == _D:
            j += 2
        else:
            arg: object = p[1:] if p[0] == "S" else (p[1] if len(p) > 1 else None)
            atoms.append((str(p[0]), arg, i))
            j += 1
    if exact_identities:
        atoms = _merge_exact_round_trips(atoms, steps[0].input_kind == "discrete")

    # Propagate: the coefficient of √n, and which directions still hold.
    coef = Fraction(0)
    cover = model in COVER_MODELS
    fwd = True  # every point of A_last within coef·√n of T(A_first)
    bwd = True  # every point of T(A_first) within coef·√n of A_last
    pending_corefine: str | None = None
    rts: list[tuple[int, int, Fraction]] = []  # (discretizing step, continuing step, factor so far)
    for kind, arg, i in atoms:
        if kind == "S":
            ratio = arg[0]  # type: ignore[index]
            assert isinstance(ratio, Fraction)
            coef *= ratio
            rts = [(a, b, f * ratio) for a, b, f in rts]
        elif kind == "U":
            pass  # h(X ∪ Y, I ∪ Y) ≤ h(X, I) both ways: ratio 1
        elif kind == "C":
            pending_corefine = str(arg)
            if coef != 0:  # a co-refinement of an already inexact object: no direction survives
                fwd = bwd = False
        elif kind == "RT":
            assert isinstance(arg, int)
            coef += 1
            rts.append((i, arg, Fraction(1)))
            if not cover:
                bwd = False
            if pending_corefine is not None:
                if pending_corefine == "common":
                    fwd = False
                else:
                    bwd = False
                pending_corefine = None
        else:  # pragma: no cover - the reduction leaves only the kinds above
            raise AssertionError(kind)

    terms: list[BoundTerm] = []
    for idx, (a, b, f) in enumerate(rts, start=1):
        if a == b:
            where = f"R∘D inside step {a} ({steps[a - 1].label()})"
        else:
            where = f"R∘D between step {a} ({steps[a - 1].label()}) and step {b} ({steps[b - 1].label()})"
        terms.append(BoundTerm(idx, a, where, f))
    assert sum((t.factor for t in terms), Fraction(0)) == coef

    holding: list[tuple[Direction, bool]] = [("result_within", fwd), ("source_within", bwd)]
    directions: tuple[Direction, ...] = tuple(d for d, ok in holding if ok)
    value = sqrt_multiple(coef, n)
    bound = value if len(directions) == 2 else None
    one_sided = value if len(directions) == 1 else None
    return BoundResult(
        bound=bound,
        coefficient=coef,
        n=n,
        terms=terms,
        formula=_formula(terms, coef, n),
        directions=directions,
        one_sided=one_sided,
        model=model,
        guarantee=_guarantee(directions, model, value),
        steps=steps,
    )


def _guarantee(directions: tuple[Direction, ...], model: str, value: float) -> str:
    v = f"{value:.4g}"
    if len(directions) == 2:
        return f"Hausdorff distance between T(A_first) and A_last ≤ {v} ({model} model)"
    if directions == ("result_within",):
        return (
            f"one-sided ({model}): every point of A_last lies within {v} of T(A_first); "
            "parts of T(A_first) may be lost"
        )
    if directions == ("source_within",):
        return (
            f"one-sided ({model}): every point of T(A_first) lies within {v} of A_last; "
            "A_last may hold points far from it"
        )
    return f"no bound: the {model} model and this chain give neither direction"


# --------------------------------------------------------------------------------------------------------
# Formatting
# --------------------------------------------------------------------------------------------------------


def _fmt_fraction(q: Fraction) -> str:
    return str(q.numerator) if q.denominator == 1 else f"{q.numerator}/{q.denominator}"


def _fmt_number(q: Fraction) -> str:
    """A short exact spelling of ``q``: a decimal when it terminates, else p/q."""
    if q.denominator == 1:
        return str(q.numerator)
    d = q.denominator
    while d % 2 == 0:
        d //= 2
    while d % 5 == 0:
        d //= 5
    if d == 1:
        s = format(Decimal(q.numerator) / Decimal(q.denominator), "f")
        return s
    return f"{q.numerator}/{q.denominator}"


def _formula(terms: list[BoundTerm], coef: Fraction, n: int) -> str:
    root = f"√{n}"
    if not terms:
        return "0 (no round trip: the chain is exact)"
    inner = " + ".join(_fmt_fraction(t.factor) for t in terms)
    total = root if coef == 1 else f"{_fmt_fraction(coef)}·{root}"
    return f"{root}·({inner}) = {total} ≈ {sqrt_multiple(coef, n):.4f}"


# --------------------------------------------------------------------------------------------------------
# Parser
# --------------------------------------------------------------------------------------------------------

_ALIASES: dict[str, StepKind] = {
    "dss": "DSS",
    "rot": "ROT",
    "rotate": "ROT",
    "dr": "ROT",
    "sp": "SP",
    "simplify": "SP",
    "scale": "SCALE",
    "sc": "SCALE",
    "erot": "EROT",
    "erotate": "EROT",
    "translate": "TRANSLATE",
    "tr": "TRANSLATE",
    "move": "TRANSLATE",
    "union": "UNION",
    "edu": "UNION",
    "corefine": "COREFINE",
    "co-refine": "COREFINE",
    "edco": "COREFINE",
}
_PARTS = ("common", "first", "second")

_TOKEN = re.compile(
    r"\s*(?:"
    r"(?P<num>[-+]?(?:\d+(?:\.\d*)?|\.\d+)(?:[eE][-+]?\d+)?(?:/\d+)?|[-+]?(?:inf(?:inity)?|nan)\b)"
    r"|(?P<word>[A-Za-z][A-Za-z_\-]*)"
    r"|(?P<punct>[,;()@])"
    r")",
    re.IGNORECASE,
)


def _tokenize(text: str) -> list[tuple[str, str, int]]:
    tokens: list[tuple[str, str, int]] = []
    pos = 0
    while pos < len(text):
        if text[pos:].strip() == "":
            break
        m = _TOKEN.match(text, pos)
        if m is None or m.end() == pos:
            bad = text[pos:].strip()[:12]
            raise ParameterError(f"cannot read {bad!r} at position {pos + 1} of the chain")
        kind = m.lastgroup
        assert kind is not None
        start = m.start(kind)
        tokens.append((kind, m.group(kind), start))
        pos = m.end()
    return tokens


class _Parser:
    def __init__(self, text: str) -> None:
        self.text = text
        self.tokens = _tokenize(text)
        self.i = 0

    def peek(self) -> tuple[str, str, int] | None:
        return self.tokens[self.i] if self.i < len(self.tokens) else None

    def take(self) -> tuple[str, str, int]:
        tok = self.peek()
        assert tok is not None
        self.i += 1
        return tok

    def at_punct(self, chars: str) -> bool:
        tok = self.peek()
        return tok is not None and tok[0] == "punct" and tok[1] in chars

    def number(self, what: str) -> str:
        tok = self.peek()
        if tok is None or tok[0] != "num":
            got = "the end of the chain" if tok is None else repr(tok[1])
            raise ParameterError(f"{what}: expected a number, got {got}")
        self.i += 1
        return tok[1]

    def pair(self, what: str) -> tuple[str, str]:
        paren = self.at_punct("(")
        if paren:
            self.take()
        x = self.number(what)
        if self.at_punct(","):
            self.take()
        y = self.number(what)
        if paren:
            if not self.at_punct(")"):
                raise ParameterError(f"{what}: expected ')'")
            self.take()
        return x, y

    def centre(self, label: str) -> tuple[str, str] | None:
        tok = self.peek()
        if tok is not None and ((tok[0] == "word" and tok[1].lower() in ("about", "at")) or tok[1] == "@"):
            self.take()
            return self.pair(f"{label} centre")
        return None

    def step(self) -> ChainStep:
        tok = self.peek()
        if tok is None:
            raise ParameterError("expected an operation at the end of the chain")
        if tok[0] == "punct":
            raise ParameterError(f"empty step at position {tok[2] + 1} of the chain")
        if tok[0] != "word" or tok[1].lower() not in _ALIASES:
            names = "DSS, ROT, SP, SCALE, EROT, TRANSLATE, UNION, COREFINE"
            raise ParameterError(
                f"unknown operation {tok[1]!r} at position {tok[2] + 1} (expected one of {names})"
            )
        self.take()
        kind = _ALIASES[tok[1].lower()]
        if kind == "DSS":
            a = self.number("DSS factor α")
            return dss(a, self.centre("DSS"))
        if kind == "ROT":
            a = self.number("ROT angle (degrees)")
            return rot(a, self.centre("ROT"))
        if kind == "SP":
            a = self.number("SP factor α")
            return sp(a, self.centre("SP"))
        if kind == "SCALE":
            a = self.number("SCALE factor")
            return scale(a, self.centre("SCALE"))
        if kind == "EROT":
            a = self.number("EROT angle (degrees)")
            return erot(a, self.centre("EROT"))
        if kind == "TRANSLATE":
            dx, dy = self.pair("TRANSLATE offset")
            return translate(dx, dy)
        if kind == "UNION":
            return union()
        alpha = self.number("COREFINE factor α") if (p := self.peek()) is not None and p[0] == "num" else None
        part: CorefinePart = "common"
        p = self.peek()
        if p is not None and p[0] == "word" and p[1].lower() in _PARTS:
            self.take()
            part = p[1].lower()  # type: ignore[assignment]
        return corefine(alpha, part)

    def chain(self) -> list[ChainStep]:
        if not self.tokens:
            raise ParameterError("the chain is empty")
        steps = [self.step()]
        while self.peek() is not None:
            if not self.at_punct(",;"):
                tok = self.peek()
                assert tok is not None
                raise ParameterError(
                    f"unexpected {tok[1]!r} at position {tok[2] + 1} after {steps[-1].label()!r} "
                    "(steps are separated by commas)"
                )
            self.take()
            if self.peek() is None:
                break  # a trailing separator is harmless
            steps.append(self.step())
        return steps


def parse_chain(text: str) -> list[ChainStep]:
    """Read a chain such as ``"DSS 1.25, DSS 5, DSS 0.2, DSS 0.8"`` (applied left to right).

    Grammar (case-insensitive; steps separated by ``,`` or ``;``)::

        DSS α [about cx,cy]    ROT θ [about cx,cy]    SP α [about cx,cy]    SCALE s [about cx,cy]
        EROT θ [about cx,cy]   TRANSLATE dx,dy        UNION                 COREFINE [α] [common|first|second]

    ``ROT`` is the discrete-Euclidean rotation ``dR`` (a discrete operation); ``SCALE``, ``EROT`` and
    ``TRANSLATE`` are exact Euclidean maps.

    Numbers are read exactly: decimals (``1.25``, ``2e-1``) and fractions (``1/5``). A pair may be written
    ``x,y``, ``x y`` or ``(x, y)``; ``at`` and ``@`` are synonyms of ``about``.

    Raises
    ------
    ParameterError
        On an unknown operation, a missing or malformed number, a non-finite value or a non-positive factor.
    """
    if not isinstance(text, str):
        raise ParameterError(f"a chain is a string, got {type(text).__name__}")
    return _Parser(text).chain()
