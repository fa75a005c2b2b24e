"""The account of a result: its chain, the paper's bound, the exact measured error, the differing pixels.

One function, :func:`account_of`, computes it from a result's pinned provenance
(:class:`mrm.document.Provenance`: the operation, its parameters, and the content and provenance its inputs
had when the result was made). The inspector, ``mrm account … --json``, ``mrm scale … --json`` and scripts all
call it, so they print the same numbers (:meth:`Account.summary`). Nothing is guessed from names: the
operation is looked up in the registry (:mod:`mrm.ops.registry`), its parameters are read and range-checked by
its parameters dataclass, its place in the bound rule and its similarity come from its spec.

The chain (docs/design.md §8)
---------------------
A result's chain is the run of one-object operations (DSS_α, dR_θ,C, Sp_α and the exact Euclidean scale,
rotate, translate) that led to it, followed back through the pinned first inputs to an object that was
drawn, imported, or made by a two-object operation (EDu, EDco): that object is ``A₀``. Then

* ``A_first`` is ``R(A₀)`` (``A₀`` itself when the first step reads the Euclidean representation, ``R(D(E₀))``
  when a discrete step starts from a polygon), exactly;
* ``T`` is the composite of the steps' exact similarities (:attr:`mrm.ops.registry.OperationSpec.similarity`);
* ``A_last`` is the exact Euclidean object just before the last discretization (``T_k(R(A_{k−1}))`` for
  DSS and dR, the exact Sp result, the exact image of a Euclidean similarity), recomputed from the pinned
  input of the last step — the object the result was really made from;
* ``measured`` is the exact ``H(T(A_first), A_last)`` (:mod:`mrm.ops.measure`), set beside the bound of
  :func:`mrm.geometry.hausdorff.bounds.bound_of_chain`; ``direct`` is ``D(T(A_first))`` and the differing
  pixels are
  the paper's Figure 12 light and dark grey.

For Sp_α the account also checks ``Sp_α∘Sp_α = Sp_α`` on the result (:attr:`Account.idempotent`).

Two-object operations
---------------------
EDu and EDco are accounted for on their own pinned inputs ``E``, ``E′`` (a pixel or voxel set ``A`` stands
for ``R(A)``): the bound of the step (√n for EDu; per part for EDco / EDco_α, with the directions that hold,
:mod:`mrm.geometry.hausdorff.bounds`), and the measured distance to the Euclidean union or part
(:func:`mrm.ops.boolean.reference_parts`), computed by GEOS's overlay in the plane and manifold3d's mesh
Booleans in space (docs/adr/0061) — exact when the inputs do not overlap, otherwise exact for the overlay's
result, whose new crossing vertices are rounded to float64 (``reference_exact`` says which); between solids
the distance is a certified interval. Both inputs' own chains are listed.

Where no bound exists, :attr:`Account.no_bound` says why in words. A provenance that cannot be read (an
unknown operation, parameters out of range, a chain that mixes models) gives an account whose
:attr:`Account.error` says what is wrong; it never raises.
"""

from __future__ import annotations

import dataclasses
import logging
from dataclasses import dataclass, field
from typing import Any

from mrm.core.errors import Cancelled, MRMError, ParameterError
from mrm.core.grids import PixelSet, VoxelSet
from mrm.core.limits import DEFAULT_PIXEL_LIMIT
from mrm.core.models import DEFAULT_MODEL, Model
from mrm.core.numbers import fraction_text
from mrm.core.progress import ProgressLike, sub_progress
from mrm.geometry.discretize.exact_solid import identity_map
from mrm.geometry.hausdorff.bounds import BoundResult
from mrm.geometry.reconstruct import compact_limit_in_force
from mrm.ops.boolean import (
    PARTS,
    euclidean_discrete_corefinement,
    euclidean_discrete_union,
    reference_parts,
)
from mrm.ops.chain import Link as ChainLink
from mrm.ops.chain import chain_bound
from mrm.ops.measure import MeasuredError, PixelDifference, differing_pixels, measured_error
from mrm.ops.provenance import content_digest
from mrm.ops.registry import get_operation, input_dimension, plan_operation
from mrm.ops.representations import discrete_of, euclidean_of, exact_of
from mrm.ops.simplify import simplification

log = logging.getLogger(__name__)

#: Edits of a document recorded as provenance that are no operation of the registry, and why they make no
#: error (the registry's exact operations say it themselves: :attr:`OperationSpec.exact`).
EXACT_EDITS = {"merge": "merging objects copies their content exactly"}


def is_chain_operation(name: str) -> bool:
    """True for a registered one-object operation with a similarity: a link of a one-object chain."""
    try:
        return get_operation(name).is_chain_step
    except ParameterError:
        return False


@dataclass(frozen=True)
class Link:
    """One operation of a chain as the account lists it.

    Attributes
    ----------
    operation : str
        The registry name.
    label : str
        The step as the paper writes it (``DSS 0.2``, ``ROT 30 about 1,2``), or the operation's title.
    params : dict
        Its parameters (JSON data, as recorded).
    inputs : tuple of int
        The ids of the objects it read.
    digests : tuple of str
        The digests of their content at the time.
    """

    operation: str
    label: str
    params: dict[str, Any]
    inputs: tuple[int, ...]
    digests: tuple[str, ...]

    def as_dict(self) -> dict[str, Any]:
        """JSON data."""
        return {
            "operation": self.operation,
            "label": self.label,
            "params": self.params,
            "inputs": list(self.inputs),
            "input_contents": list(self.digests),
        }


@dataclass(frozen=True)
class PartAccount:
    """The account of one part of a co-refinement."""

    part: str
    bound: BoundResult
    measured: MeasuredError | None

    def as_dict(self) -> dict[str, Any]:
        """JSON data."""
        out: dict[str, Any] = {"part": self.part, **_bound_dict(self.bound)}
        out.update(_measured_dict(self.measured, self.bound))
        return out


@dataclass(frozen=True)
class Account:
    """Everything known about the error of one result (see the module docstring).

    Attributes
    ----------
    operation : str
        The result's own operation.
    model : str
        The discretization model of the chain.
    chain : tuple of Link
        The one-object chain, oldest first (just the operation itself for EDu and EDco).
    input_chains : tuple of tuple of Link
        For a two-object operation, the chain of each input (empty for a drawn one).
    origin_digest : str
        The digest of A₀'s content (empty when unknown).
    bound : BoundResult or None
    no_bound : str
        Why there is no bound, in words (empty when there is one).
    measured : MeasuredError or None
    reference_exact : bool
        Whether the reference of the measured distance is exact (always, except for overlapping EDu/EDco).
    direct, result : PixelSet or None
        D(T(A_first)) and the result's discrete representation.
    difference : PixelDifference or None
    parts : tuple of PartAccount
        Every part of a co-refinement.
    part : str
        Which part this result is (co-refinement), else "".
    idempotent : bool or None
        For Sp_α: whether Sp_α(result) = result exactly.
    error : str
        Why the provenance could not be accounted for (nothing else is then set).
    direct_note : str
        Why the direct result was not computed although the rest was (a 3D chain whose composite map
        leaves the exact voxelization's range); empty otherwise.
    output : object
        The result as the measurement recomputed it from the pinned inputs (a pixel set, a polygon, or for
        a co-refinement a dict part → polygon); None when not measured.
    outcome : StepOutcome or None
        The operation's whole outcome behind ``output`` (for a co-refinement: its label map and parts), so
        that a caller that writes the result does not compute it a second time; None when not measured.
    """

    operation: str
    model: str = "standard"
    chain: tuple[Link, ...] = ()
    input_chains: tuple[tuple[Link, ...], ...] = ()
    origin_digest: str = ""
    bound: BoundResult | None = None
    no_bound: str = ""
    measured: MeasuredError | None = None
    reference_exact: bool = True
    direct: PixelSet | VoxelSet | None = None
    result: PixelSet | VoxelSet | None = None
    difference: PixelDifference | None = None
    parts: tuple[PartAccount, ...] = ()
    part: str = ""
    idempotent: bool | None = None
    error: str = ""
    direct_note: str = ""
    output: Any = field(default=None, repr=False, compare=False)
    outcome: Any = field(default=None, repr=False, compare=False)

    @property
    def within_bound(self) -> bool | None:
        """Whether the measured distance respects the bound where it holds (exact; None: unknown)."""
        if self.measured is None or self.bound is None:
            return None
        return _within(self.measured, self.bound)

    def summary(self) -> dict[str, Any]:
        """JSON data: the same keys and numbers wherever the account is shown."""
        out: dict[str, Any] = {
            "operation": self.operation,
            "model": self.model,
            "chain": [link.label for link in self.chain],
            "steps": [link.as_dict() for link in self.chain],
            "input_chains": [[link.label for link in c] for c in self.input_chains],
            "origin_content": self.origin_digest or None,
            "error": self.error or None,
            "no_bound": self.no_bound or None,
        }
        if self.bound is not None:
            out.update(_bound_dict(self.bound))
        else:
            out.update(bound=None, bound_one_sided=None, bound_formula=None, directions=[], guarantee=None)
        out.update(_measured_dict(self.measured, self.bound))
        out["reference_exact"] = self.reference_exact
        out["light"] = None if self.difference is None else len(self.difference.light)
        out["dark"] = None if self.difference is None else len(self.difference.dark)
        out["part"] = self.part or None
        out["parts"] = [p.as_dict() for p in self.parts]
        out["idempotent"] = self.idempotent
        out["direct_note"] = self.direct_note or None
        return out


def _bound_dict(b: BoundResult) -> dict[str, Any]:
    return {
        "bound": b.bound,
        "bound_one_sided": b.one_sided,
        "bound_coefficient": fraction_text(b.coefficient),
        "bound_formula": b.formula,
        "directions": list(b.directions),
        "guarantee": b.guarantee,
    }


def _measured_dict(m: MeasuredError | None, b: BoundResult | None) -> dict[str, Any]:
    if m is None:
        return {
            "measured": None,
            "result_within": None,
            "source_within": None,
            "measured_exact": None,
            "within_bound": None,
        }
    d = m.as_dict()
    out = {
        "measured": d["measured"],
        "result_within": d["result_within"],
        "source_within": d["source_within"],
        "measured_exact": d["exact"],
        "within_bound": None if b is None else _within(m, b),
    }
    # 3D: the certified enclosures the three numbers above are the upper ends of (docs/adr/0060)
    out.update({k: v for k, v in d.items() if k.endswith("_interval")})
    return out


def _within(m: MeasuredError, b: BoundResult) -> bool | None:
    if not b.directions:
        return None
    found = [m.exceeds(b.coefficient, b.n, d) for d in b.directions]
    if any(found):
        return False
    return None if None in found else True


# ============================================================================================================
# Reading a provenance record
# ============================================================================================================


def _link_of(prov: Any) -> ChainLink:
    """The chain link a provenance record stands for (operation, parameters, part).

    Raises ParameterError when the record cannot be read.
    """
    spec = get_operation(prov.operation)
    raw = dict(prov.params)
    part = raw.pop("part", "")
    if not isinstance(part, str):
        raise ParameterError(f"the part of a {spec.name} result must be a name, got {part!r}")
    if part and part not in spec.parts:
        raise ParameterError(f"unknown {spec.name} part {part!r}")
    try:
        params = spec.read_params(raw)
    except (TypeError, ValueError) as e:  # a dataclass refusing an argument
        raise ParameterError(f"{spec.name}: {e}") from None
    return ChainLink(spec, params, part)


def _label(link: ChainLink) -> str:
    return link.label if link.spec.bound is not None else link.spec.title


def _link(prov: Any) -> Link:
    try:
        label = _label(_link_of(prov))
    except MRMError:
        label = prov.operation
    return Link(prov.operation, label, dict(prov.params), tuple(prov.inputs), tuple(prov.digests))


def chain_of(prov: Any) -> list[Any]:
    """The provenance records of a result's one-object chain, oldest first (module docstring)."""
    records = [prov]
    cur = prov
    while (
        is_chain_operation(cur.operation)
        and cur.pinned
        and cur.parents
        and cur.parents[0] is not None
        and cur.parents[0].pinned  # a record without its input's content starts nothing that can be replayed
        and is_chain_operation(cur.parents[0].operation)
        and len(records) < 100_000
    ):
        cur = cur.parents[0]
        records.insert(0, cur)
    return records


def input_chain(prov: Any | None) -> tuple[Link, ...]:
    """The links of an input's own chain (empty for a drawn or imported input)."""
    if prov is None:
        return ()
    return tuple(_link(p) for p in chain_of(prov))


# ============================================================================================================
# The account
# ============================================================================================================


def account_of(
    provenance: Any,
    *,
    measure: bool = True,
    progress: ProgressLike | None = None,
    limit: int | None = DEFAULT_PIXEL_LIMIT,
    compact_limit: int | None = None,
) -> Account:
    """The account of a result from its pinned provenance (module docstring); never raises on bad records.

    Parameters
    ----------
    provenance : mrm.document.Provenance
        The result's provenance (with pinned inputs).
    measure : bool
        Compute the exact measured distance and the direct result (may take seconds on large objects).
    progress : object with ``update(fraction, message)``, optional
        Its ``Cancelled`` propagates (the only exception that does).
    limit : int or None
        Largest pixel set a recomputation may create.
    compact_limit : int, optional
        The compact limit of the R of voxel sets the account computes again: the document's
        (``Settings.compact_limit``), so that it measures the R its operations used. None keeps the one in
        force.
    """
    op = str(getattr(provenance, "operation", "?"))
    try:
        with compact_limit_in_force(compact_limit):
            return _account(provenance, measure, progress, limit)
    except MRMError as e:
        if isinstance(e, Cancelled):
            raise
        log.info("no account for a %s result: %s", op, e)
        return Account(op, error=str(e), chain=(_safe_link(provenance),))


def _safe_link(prov: Any) -> Link:
    try:
        return _link(prov)
    except Exception:  # the record itself is what is broken: show its name only
        return Link(str(getattr(prov, "operation", "?")), str(getattr(prov, "operation", "?")), {}, (), ())


def _account(prov: Any, measure: bool, progress: ProgressLike | None, limit: int | None) -> Account:
    if prov.operation in EXACT_EDITS:
        why = EXACT_EDITS[prov.operation]
        return Account(prov.operation, chain=(_link(prov),), no_bound=f"no error to bound: {why}")
    link = _link_of(prov)
    spec = link.spec
    if spec.exact:
        return Account(spec.name, chain=(_link(prov),), no_bound=f"no error to bound: {spec.exact}")
    if len(prov.inputs) != spec.arity:  # a hand-edited record: say so rather than fail on the missing input
        raise ParameterError(f"{spec.name} takes {spec.arity} input(s), the record names {len(prov.inputs)}")
    if not prov.pinned:
        return Account(
            spec.name,
            chain=(_link(prov),),
            error="the content of this result's inputs was not recorded (the file predates pinned "
            "provenance and no longer holds them): nothing can be measured",
        )
    if spec.is_chain_step:
        return _chain_account(prov, measure, progress, limit)
    if spec.arity == 2 and spec.bound is not None:
        return _binary_account(prov, link, measure, progress, limit)
    return Account(
        spec.name,
        chain=(_link(prov),),
        no_bound=f"{spec.title} has no place in the paper's bound rule (docs/design.md §8)",
    )


def _sub(progress: ProgressLike | None, lo: float, hi: float) -> Any:

    return None if progress is None else sub_progress(progress, lo, hi)


def _reads(link: ChainLink, source: Any, model: Model, limit: int | None) -> Any:
    """The representation the link's step works in, of ``source`` (D(E) or R(A), as the document does)."""
    if link.bound_step(input_dimension([source])).reads == "discrete":
        return discrete_of(source, model, limit=limit)
    return euclidean_of(source, model)


def _chain_account(prov: Any, measure: bool, progress: ProgressLike | None, limit: int | None) -> Account:
    records = chain_of(prov)
    links = [_link_of(r) for r in records]
    # Exact Euclidean similarities discretize nothing and carry no model: the steps that do decide it.
    models = {link.params.model for link in links if hasattr(link.params, "model")}
    if len(models) > 1:
        raise ParameterError(f"the chain mixes discretization models ({', '.join(sorted(models))})")
    model = models.pop() if models else DEFAULT_MODEL
    first = records[0]
    origin = first.sources[0]
    n = input_dimension([origin])
    bound = chain_bound(links, model, n=n)
    origin_chain = input_chain(first.parents[0]) if first.parents else ()
    transform = identity_map(n)
    for link in links:
        assert link.spec.similarity is not None
        transform = transform.then(link.spec.similarity(link.params, n))
    acc = Account(
        prov.operation,
        model=model,
        chain=tuple(_link(r) for r in records),
        input_chains=(origin_chain,) if origin_chain else (),
        origin_digest=first.digests[0],
        bound=bound,
    )
    if not measure:
        return acc
    last = links[-1]
    if progress is not None:
        progress.update(0.0, "recomputing the last step from its recorded input")
    source = _reads(last, prov.sources[0], model, limit)
    outcome = last.spec.outcome(source, last.params, limit=limit, progress=_sub(progress, 0.0, 0.3))
    result = outcome.result
    pixels = (
        result
        if isinstance(result, PixelSet | VoxelSet)
        else discrete_of(outcome.euclidean, model, limit=limit)
    )
    idempotent = None
    if last.spec.name == "simplify":
        # Sp_α∘Sp_α = Sp_α: Sp_α of the result as stored (float64) is exactly the exact result.
        again = simplification(result, last.params.alpha, last.params.center, model, limit=limit)
        idempotent = again.euclidean == outcome.euclidean
    a_first = exact_of(euclidean_of(_reads(links[0], origin, model, limit), model))
    t_first = a_first.map(transform)
    if progress is not None:
        progress.update(0.3, "the direct result D(T(A_first))")
    direct_note = ""
    try:
        direct = discrete_of(t_first, model, limit=limit, progress=_sub(progress, 0.3, 0.5))
    except ParameterError as e:
        if n != 3:
            raise
        # In space a chain of rotations composes matrices of ever more bits (docs/adr/0060): the exact image
        # may leave the exact voxelization's range. The bound and the measured distance do not need it.
        log.info("no direct result for a 3D chain: %s", e)
        direct, direct_note = (
            None,
            (
                "the direct result D(T(A_first)) is not computed: the composite of the chain's rotations has "
                "more bits than the exact voxelization takes (docs/adr/0060)"
            ),
        )
    if progress is not None:
        progress.update(0.5, "measuring the Hausdorff distance")
    measured = measured_error(t_first, outcome.euclidean, progress=_sub(progress, 0.5, 1.0))
    return dataclasses.replace(
        acc,
        measured=measured,
        direct=direct,
        result=pixels,
        difference=None if direct is None else differing_pixels(pixels, direct),
        idempotent=idempotent,
        output=result,
        direct_note=direct_note,
    )


def _binary_account(
    prov: Any,
    link: ChainLink,
    measure: bool,
    progress: ProgressLike | None,
    limit: int | None,
) -> Account:
    spec, params = link.spec, link.params
    model = params.model
    first, second = prov.sources
    n = input_dimension([first, second])
    chains = tuple(input_chain(p) for p in prov.parents)
    own = _link(prov)
    if not spec.parts:  # EDu
        bound = chain_bound([link], model, n=n)
        acc = Account(spec.name, model=model, chain=(own,), input_chains=chains, bound=bound)
        if not measure:
            return acc
        out = euclidean_discrete_union(first, second, model, limit=limit, progress=_sub(progress, 0, 0.4))
        refs, exact = reference_parts(first, second, model)
        m = measured_error(refs["union"], out.euclidean, progress=_sub(progress, 0.4, 1.0))
        return dataclasses.replace(
            acc, measured=m, reference_exact=exact, result=out.discrete, output=out.result, outcome=out
        )
    part = link.part or PARTS[0]
    part_bounds = {p: chain_bound([ChainLink(spec, params, p)], model, n=n) for p in PARTS}
    acc = Account(
        spec.name,
        model=model,
        chain=(own,),
        input_chains=chains,
        bound=part_bounds[part],
        part=part,
        parts=tuple(PartAccount(p, part_bounds[p], None) for p in PARTS),
    )
    if not part_bounds[part].directions:
        acc = dataclasses.replace(
            acc, no_bound=f"no direction of the Hausdorff distance holds for {part} under {model}"
        )
    if not measure:
        return acc
    out = euclidean_discrete_corefinement(
        first, second, model, params.alpha, limit=limit, progress=_sub(progress, 0, 0.4)
    )
    refs, exact = reference_parts(first, second, model)
    parts = []
    for k, p in enumerate(PARTS):
        sub = _sub(progress, 0.4 + 0.2 * k, 0.6 + 0.2 * k)
        m = measured_error(refs[p], out.extra["exact"][p], progress=sub)
        parts.append(PartAccount(p, part_bounds[p], m))
    mine = next(pa for pa in parts if pa.part == part)
    return dataclasses.replace(
        acc,
        parts=tuple(parts),
        measured=mine.measured,
        reference_exact=exact,
        result=out.extra["pixels"][part],
        output=out.result,
        outcome=out,
    )


# ============================================================================================================
# Against a document
# ============================================================================================================


@dataclass(frozen=True)
class InputChange:
    """An input of a result, or of an earlier step of its chain, that is no longer what it was then."""

    index: int
    id: int
    state: str  # "changed" or "deleted"
    step: int = 0  # 0: the result's own input; k > 0: an input of the k-th step before it

    def text(self) -> str:
        """A sentence for the inspector."""
        what = f"input {self.index + 1} (#{self.id})"
        if self.step:
            what += f" of the step {self.step} before"
        verb = "was deleted" if self.state == "deleted" else "has changed"
        return f"{what} {verb} since this result was made"


def changed_inputs(doc: Any, provenance: Any) -> list[InputChange]:
    """The inputs of a result and of the earlier steps of its chain whose content in ``doc`` differs now.

    Inputs that were intermediate results of a re-run (id 0: never in the document) are not reported.
    """
    out: list[InputChange] = []
    if provenance is None or not provenance.pinned:
        return out
    for step, record in enumerate(reversed(chain_of(provenance))):
        if not record.pinned:
            continue
        for k, (oid, digest) in enumerate(zip(record.inputs, record.digests, strict=True)):
            if oid == 0:
                continue
            if oid not in doc:
                out.append(InputChange(k, oid, "deleted", step))
                continue
            src = doc.get(oid).source
            if not any(src is s for s in record.sources) and content_digest(src) != digest:
                out.append(InputChange(k, oid, "changed", step))
    return out


@dataclass(frozen=True)
class _Intermediate:
    """An intermediate result of a re-run: what plan_operation reads of an input (id 0: not an object)."""

    id: int
    source: Any
    provenance: Any


@dataclass(frozen=True)
class RerunRequest:
    """What re-running a result's chain on the current content of its inputs needs (read on the GUI thread).

    Attributes
    ----------
    inputs : list of DocObject
        The current objects the first re-run step reads.
    steps : list of (operation, params)
        The operations of the chain from that step on, oldest first.
    compact_limit : int, optional
        The document's compact limit, which the re-run's R of voxel sets uses.
    """

    inputs: list[Any]
    steps: list[tuple[str, Any]]
    compact_limit: int | None = None

    def plan(self, progress: ProgressLike | None = None) -> Any:
        """Run the steps (pure: no document); the plan of the final result, to push as one undo step.

        Intermediate results are not added to the document: the final result's provenance pins them, with
        id 0 ("made by a re-run, not kept").
        """
        inputs = list(self.inputs)
        plan = None
        for i, (name, params) in enumerate(self.steps):
            plan = plan_operation(
                inputs,
                name,
                params,
                _sub(progress, i / len(self.steps), (i + 1) / len(self.steps)),
                compact_limit=self.compact_limit,
            )
            r = plan.results[0]
            inputs = [_Intermediate(0, r.source, r.provenance)]
        return plan


def rerun_request(doc: Any, obj_id: int) -> RerunRequest:
    """Re-run a result on the current content of its inputs: from the oldest step whose input changed.

    Hand the request to a worker (:meth:`RerunRequest.plan`) and push the plan as a new result
    (:func:`mrm.document.apply.push_plan`); the old result keeps its account.

    Raises
    ------
    ParameterError
        No provenance, nothing changed that can be re-run on, or a recorded parameter is unreadable.
    """
    prov = doc.get(obj_id).provenance
    if prov is None:
        raise ParameterError("this object was not made by an operation")
    records = chain_of(prov)
    changed = [c.step for c in changed_inputs(doc, prov) if c.state == "changed"]
    if not changed:
        raise ParameterError("no input of this result has changed since (a deleted one cannot be re-run on)")
    start = len(records) - 1 - max(changed)
    first = records[start]
    missing = [i for i in first.inputs if i not in doc]
    if missing:
        raise ParameterError(f"input #{missing[0]} was deleted: there is nothing to re-run on")
    steps = []
    for r in records[start:]:
        link = _link_of(r)
        steps.append((link.spec.name, link.params))
    return RerunRequest([doc.get(i) for i in first.inputs], steps, doc.settings.compact_limit)


__all__ = [
    "Account",
    "InputChange",
    "Link",
    "PartAccount",
    "RerunRequest",
    "account_of",
    "chain_of",
    "changed_inputs",
    "input_chain",
    "is_chain_operation",
    "rerun_request",
]
