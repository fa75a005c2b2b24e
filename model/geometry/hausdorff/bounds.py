"""Error bounds of chains of the paper's operations: one rule for all of them (docs/design.md §8).

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
Hausdorff bound. For ``gauss`` (a partition: thin parts may vanish) only ``result within`` holds
(docs/design.md §2): ``bound`` is ``None`` and :attr:`BoundResult.one_sided` carries the value with
``direction="result_within"``. A union keeps both directions (``h(X ∪ Y, I ∪ Y) ≤ h(X, I)``). A co-refinement
part is not Lipschitz in its inputs: with exact inputs the common part ``R(D(E) ∩ D(E′))`` has every point of
``E ∩ E′`` within the bound (``source within``, covers only) but may contain points far from ``E ∩ E′`` (two
disjoint objects in one pixel), while a difference part ``R(D(E) ∖ D(E′))`` has every one of its points within
the bound of ``E ∖ E′`` (``result within``, all models) but may lose thin parts of it; after an earlier error
neither direction survives a co-refinement.

The arithmetic is exact: ratios are :class:`fractions.Fraction` (decimal literals such as ``1.25`` and
fractions such as ``1/5`` are read exactly) and the bound is ``coefficient · √n`` with a rational
coefficient, so the printed digits are those of the exact value.

Chains are written in the order the steps are applied (left first): the paper's
``DSS_0.8 ∘ DSS_0.2 ∘ DSS_5 ∘ DSS_1.25`` is ``"DSS 1.25, DSS 5, DSS 0.2, DSS 0.8"``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from decimal import Decimal, localcontext
from fractions import Fraction
from typing import Literal, TypeAlias

from mrm.core.errors import ParameterError
from mrm.core.limits import check_chain_steps
from mrm.core.models import Model
from mrm.core.numbers import fraction_text
from mrm.geometry.discretize.exact_shape import Similarity

#: The dimension of the plane: every round trip adds √N_DIM (a step made in 3D passes n = 3).
N_DIM = 2

#: The parts of a co-refinement: E∩E′ ("common"), E∖E′ ("first"), E′∖E ("second").
CorefinePart = Literal["common", "first", "second"]
Direction = Literal["result_within", "source_within"]
Representation = Literal["discrete", "euclidean"]


# --------------------------------------------------------------------------------------------------------
# What a step is made of
# --------------------------------------------------------------------------------------------------------


@dataclass(frozen=True)
class Discretize:
    """``D``: the step discretizes."""


@dataclass(frozen=True)
class Continue:
    """``R``: the step continues a discrete object (D(R(A)) = A)."""


@dataclass(frozen=True)
class Similar:
    """A Euclidean similarity of ratio ``ratio``; ``exact`` is the exact map when it is known."""

    ratio: Fraction
    exact: Similarity | None = None


@dataclass(frozen=True)
class Unite:
    """The discrete union with another object (EDu): ratio 1 both ways."""


@dataclass(frozen=True)
class CorefinePartOf:
    """The discrete Boolean part a co-refinement continues, and the chain follows."""

    part: CorefinePart = "common"


Primitive: TypeAlias = Discretize | Continue | Similar | Unite | CorefinePartOf


@dataclass(frozen=True)
class BoundStep:
    """One operation of a chain as the bound rule sees it: what it is made of, in application order.

    The operations declare their step (:attr:`mrm.ops.registry.OperationSpec.bound`); this module knows
    nothing of their names. ``reads`` and ``produces`` are the representations the step takes and gives
    (a conversion is inserted where consecutive steps disagree, as the document does).

    Attributes
    ----------
    label : str
        The step as a chain's text writes it (``DSS 5``, ``ROT 30 about 1,2``), for the terms' descriptions.
    reads, produces : str
        ``discrete`` or ``euclidean``.
    primitives : tuple
        ``Discretize``, ``Continue``, ``Similar``, ``Unite`` and ``CorefinePartOf`` in application order.
    """

    label: str
    reads: Representation
    produces: Representation
    primitives: tuple[Primitive, ...]


def discrete_similarity_step(label: str, sim: Similarity) -> BoundStep:
    """``D∘T∘R`` (DSS_α, dR_θ,C): a similarity between a continuation and a discretization."""
    return BoundStep(label, "discrete", "discrete", (Continue(), Similar(sim.ratio, sim), Discretize()))


def euclidean_similarity_step(label: str, sim: Similarity) -> BoundStep:
    """An exact Euclidean similarity (scale, rotate, translate): no round trip."""
    return BoundStep(label, "euclidean", "euclidean", (Similar(sim.ratio, sim),))


def simplification_step(label: str, sim: Similarity) -> BoundStep:
    """``T⁻¹∘R∘D∘T`` (Sp_α with T = Sc_α): a round trip at the scale of ``sim``."""
    back = sim.inverse()
    prims = (Similar(sim.ratio, sim), Discretize(), Continue(), Similar(back.ratio, back))
    return BoundStep(label, "euclidean", "euclidean", prims)


def union_step(label: str) -> BoundStep:
    """``R(D(E) ∪ D(E′))`` (EDu): one round trip of the union."""
    return BoundStep(label, "euclidean", "euclidean", (Unite(), Discretize(), Continue()))


def corefine_step(label: str, sim: Similarity, part: CorefinePart) -> BoundStep:
    """``T⁻¹∘R∘(part of D∘T)`` (EDco, EDco_α with T = Sc_α): the chain follows ``part``."""
    back = sim.inverse()
    prims = (
        Similar(sim.ratio, sim),
        CorefinePartOf(part),
        Discretize(),
        Continue(),
        Similar(back.ratio, back),
    )
    return BoundStep(label, "euclidean", "euclidean", prims)


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
            "factor": fraction_text(self.factor),
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
    model: Model
    guarantee: str
    steps: tuple[BoundStep, ...] = field(default=())

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
            "coefficient": fraction_text(self.coefficient),
            "coefficient_float": float(self.coefficient),
            "n": self.n,
            "sqrt_n": self.sqrt_n,
            "value": self.value,
            "terms": [t.as_dict(self.n) for t in self.terms],
            "formula": self.formula,
            "directions": list(self.directions),
            "one_sided": self.one_sided,
            "model": str(self.model),
            "guarantee": self.guarantee,
            "chain": [s.label for s in self.steps],
        }


def sqrt_multiple(coefficient: Fraction, n: int = N_DIM) -> float:
    """Return the float nearest to ``coefficient · √n`` (computed with 60 significant digits)."""
    if coefficient == 0:
        return 0.0
    with localcontext() as ctx:
        ctx.prec = 60
        d = Decimal(coefficient.numerator) / Decimal(coefficient.denominator) * Decimal(n).sqrt()
    return float(d)


def _commutes_with_round_trips(t: Similarity) -> bool:
    """The identity or an integer translation: then ``R∘D∘T∘R∘D = T∘R∘D`` (D(R(A)) = A, covariance)."""
    return t.a == 1 and t.b == 0 and t.tx.denominator == 1 and t.ty.denominator == 1


# A reduced chain: round trips ("RT", continuing step), similarities ("S", Similar), union and co-refinement
# markers ("U", None), ("C", part); each with the 1-based index of its step.
_Atom = tuple[str, object, int]


def _merge_exact_round_trips(atoms: list[_Atom], discrete_start: bool) -> list[_Atom]:
    """Drop the round trips that exact identities make free.

    A round trip is dropped when the similarities since the previous one compose to the identity or to an
    integer translation T: ``R∘D∘T∘R∘D = T∘R∘D`` because ``D(R(A)) = A`` and ``R(A + t) = R(A) + t``. A
    discrete start counts as a round trip: ``A_first = R(A)`` is already a continuation.
    """
    out: list[_Atom] = []
    # The composite since the last round trip kept (None: unknown, or no round trip yet).
    since: Similarity | None = Similarity.identity() if discrete_start else None
    for atom in atoms:
        kind, arg, _ = atom
        if kind == "RT":
            if since is not None and _commutes_with_round_trips(since):
                continue  # merged into the previous round trip
            out.append(atom)
            since = Similarity.identity()
        elif kind == "S":
            assert isinstance(arg, Similar)
            since = since.then(arg.exact) if since is not None and arg.exact is not None else None
            out.append(atom)
        else:  # a union or a co-refinement changes the object: no identity across it
            since = None
            out.append(atom)
    return out


def bound_of_chain(
    steps: list[BoundStep] | tuple[BoundStep, ...],
    model: Model | str = Model.STANDARD,
    *,
    n: int = N_DIM,
    exact_identities: bool = False,
) -> BoundResult:
    """Return the error bound of a chain of operations (docs/design.md §8), exactly.

    Parameters
    ----------
    steps : sequence of BoundStep
        The operations in the order they are applied, as they declare themselves
        (:func:`mrm.ops.chain.chain_bound` makes them from a chain's text or a result's provenance).
    model : Model or str
        ``standard``, ``supercover`` or ``gauss``: which directions of the bound hold (module docstring).
    n : int
        The dimension (2 for pixels, 3 for voxels).
    exact_identities : bool
        Also use that a round trip followed, through similarities composing to the identity or to an integer
        translation, by another round trip is a single one (``D(R(A)) = A``; ``R`` commutes with integer
        translations). This gives ``Sp_α∘Sp_α = Sp_α`` its exact bound ``√n/α`` and ``DSS_1`` none. Off by
        default: the paper's theorems count every round trip, and so does the rule of docs/design.md §8.

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
    model = Model.parse(model)
    if n < 1:
        raise ParameterError(f"the dimension must be positive, got {n}")
    steps = tuple(steps)
    if not steps:
        raise ParameterError("the chain is empty")
    check_chain_steps(len(steps))  # exact arithmetic grows with the chain: bounded up front (issue 11)

    # Expand into primitives, converting between the representations where a step needs the other one.
    prims: list[tuple[Primitive, int]] = []
    current = steps[0].reads
    for i, step in enumerate(steps, start=1):
        if step.reads != current:
            prims.append((Discretize() if current == "euclidean" else Continue(), i))
        prims.extend((p, i) for p in step.primitives)
        current = step.produces
    # A_first = R(A) for a discrete start; A_last is just before a final discretization.
    if prims and isinstance(prims[0][0], Continue):
        prims = prims[1:]
    if prims and isinstance(prims[-1][0], Discretize):
        prims = prims[:-1]

    # Reduce: D then R is a round trip; R then D is the identity (D(R(A)) = A exactly).
    atoms: list[_Atom] = []
    j = 0
    while j < len(prims):
        p, i = prims[j]
        nxt = prims[j + 1][0] if j + 1 < len(prims) else None
        if isinstance(p, Discretize) and isinstance(nxt, Continue):
            atoms.append(("RT", prims[j + 1][1], i))
            j += 2
        elif isinstance(p, Continue) and isinstance(nxt, Discretize):
            j += 2
        else:
            if isinstance(p, Similar):
                atoms.append(("S", p, i))
            elif isinstance(p, Unite):
                atoms.append(("U", None, i))
            elif isinstance(p, CorefinePartOf):
                atoms.append(("C", p.part, i))
            else:  # pragma: no cover - a lone D or R cannot remain after the conversions above
                raise AssertionError(p)
            j += 1
    if exact_identities:
        atoms = _merge_exact_round_trips(atoms, steps[0].reads == "discrete")

    # Propagate: the coefficient of √n, and which directions still hold.
    coef = Fraction(0)
    fwd = True  # every point of A_last within coef·√n of T(A_first)
    bwd = True  # every point of T(A_first) within coef·√n of A_last
    pending_corefine: str | None = None
    rts: list[tuple[int, int, Fraction]] = []  # (discretizing step, continuing step, factor so far)
    for kind, arg, i in atoms:
        if kind == "S":
            assert isinstance(arg, Similar)
            coef *= arg.ratio
            rts = [(a, b, f * arg.ratio) for a, b, f in rts]
        elif kind == "U":
            pass  # h(X ∪ Y, I ∪ Y) ≤ h(X, I) both ways: ratio 1
        elif kind == "C":
            pending_corefine = str(arg)
            if coef != 0:  # a co-refinement of an already inexact object: no direction survives
                fwd = bwd = False
        else:  # "RT"
            assert isinstance(arg, int)
            coef += 1
            rts.append((i, arg, Fraction(1)))
            if not model.is_cover:
                bwd = False
            if pending_corefine is not None:
                if pending_corefine == "common":
                    fwd = False
                else:
                    bwd = False
                pending_corefine = None

    terms: list[BoundTerm] = []
    for idx, (a, b, f) in enumerate(rts, start=1):
        if a == b:
            where = f"R∘D inside step {a} ({steps[a - 1].label})"
        else:
            where = f"R∘D between step {a} ({steps[a - 1].label}) and step {b} ({steps[b - 1].label})"
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


def _formula(terms: list[BoundTerm], coef: Fraction, n: int) -> str:
    root = f"√{n}"
    if not terms:
        return "0 (no round trip: the chain is exact)"
    inner = " + ".join(fraction_text(t.factor) for t in terms)
    total = root if coef == 1 else f"{fraction_text(coef)}·{root}"
    return f"{root}·({inner}) = {total} ≈ {sqrt_multiple(coef, n):.4f}"
