"""What the error inspector shows of a result: rows of its pinned chain and the texts of its account.

The account itself — chain, bound, exact measured distance, differing pixels — is the model's
(:func:`mrm.ops.account.account_of`), the same one ``mrm account … --json`` prints; this module only turns it
into rows and sentences. Nothing is recomputed or guessed here.
"""

from __future__ import annotations

import html
from dataclasses import dataclass
from typing import Any

from mrm.core.grids import VoxelSet
from mrm.ops.account import Account, chain_of, changed_inputs


@dataclass(frozen=True)
class Row:
    """One row of the provenance list: the step, the object it made (or read), its pixel count."""

    step: str
    name: str
    obj_id: int | None
    pixels: str


def _count(source: Any) -> str:
    from mrm.core.grids import PixelSet
    from mrm.views.scene import pixel_count

    if isinstance(source, VoxelSet):
        n = pixel_count(source)  # type: ignore[arg-type]  # any grid set: counted off the GUI thread when big
        return "…" if n is None else f"{n:,} voxels"
    if not isinstance(source, PixelSet):
        return "polyhedron" if getattr(source, "n", None) == 3 or hasattr(source, "triangles") else "polygon"
    n = pixel_count(source)
    return "…" if n is None else f"{n:,}"


def _name(doc: Any, oid: int | None, digest: str | None, pinned: Any = None) -> str:
    from mrm.ops.provenance import content_digest

    if oid is None:
        return "?"
    if oid not in doc:
        return f"#{oid} (deleted)"
    obj = doc.get(oid)
    # The pinned source itself is unchanged by definition: no digest (a tenth of a second at 10⁸ pixels, at
    # every refresh of the inspector, on the GUI thread).
    if digest is not None and obj.source is not pinned and content_digest(obj.source) != digest:
        return f"{obj.name} (changed since)"
    return str(obj.name)


def chain_rows(doc: Any, obj: Any, account: Account) -> list[Row]:
    """The rows of a result's chain, oldest first: the start, then one per operation (pinned content)."""
    prov = obj.provenance
    if prov is None:
        return []
    records = chain_of(prov)
    first = records[0]
    rows: list[Row] = []
    for k, (oid, digest) in enumerate(
        zip(first.inputs, first.digests or [None] * len(first.inputs), strict=False)
    ):
        label = "start" if len(first.inputs) == 1 else f"input {'AB'[k] if k < 2 else k + 1}"
        src = first.sources[k] if first.sources else None
        rows.append(Row(label, _name(doc, oid, digest, src), oid, _count(src) if src is not None else "…"))
    for i, link in enumerate(account.chain):
        if i + 1 < len(records):
            nxt = records[i + 1]
            oid = nxt.inputs[0] if nxt.inputs else None
            src = nxt.sources[0] if nxt.sources else None
            digest = nxt.digests[0] if nxt.digests else None
            rows.append(
                Row(link.label, _name(doc, oid, digest, src), oid, _count(src) if src is not None else "…")
            )
        else:
            rows.append(Row(link.label, str(obj.name), obj.id, _count(obj.source)))
    return rows


def bound_text(acc: Account) -> str:
    """The bound paragraph (HTML)."""
    if acc.error:
        return f"<b>No account</b>: {html.escape(acc.error, quote=False)}"
    b = acc.bound
    parts_note = ""
    if acc.parts:
        lines = []
        for p in acc.parts:
            holds = ", ".join(_direction(d) for d in p.bound.directions) or "no direction"
            lines.append(f"{p.part}: {_value(p.bound)} ({holds})")
        parts_note = "<br><small>per part: " + "; ".join(lines) + "</small>"
    if b is None:
        return f"<b>Bound</b>: none — {html.escape(acc.no_bound or 'no rule', quote=False)}{parts_note}"
    chains = ""
    if acc.input_chains:
        listed = [", ".join(link.label for link in c) or "drawn" for c in acc.input_chains]
        chains = (
            "<br><small>inputs' chains: "
            + " | ".join(html.escape(c, quote=False) for c in listed)
            + "</small>"
        )
    return (
        f"<b>Bound</b> ({b.model}): H ≤ {_value(b)}<br><small>{html.escape(b.formula, quote=False)}<br>"
        f"{html.escape(b.guarantee, quote=False)}</small>{parts_note}{chains}"
    )


def _value(b: Any) -> str:
    if b.bound is not None:
        return f"{b.bound:.4g}"
    return f"{b.value:.4g} (one-sided)" if b.directions else f"{b.value:.4g} (no direction holds)"


def _direction(d: str) -> str:
    return {"result_within": "result within", "source_within": "source within"}.get(d, d)


def measured_text(acc: Account) -> str:
    """The measured paragraph (HTML) of a measured account."""
    m = acc.measured
    if acc.error:
        return f"<b>Measured</b>: {html.escape(acc.error, quote=False)}"
    if m is None:
        return "<b>Measured</b>: " + html.escape(acc.no_bound or "not measured", quote=False)
    verdict = ""
    if acc.within_bound is not None:
        verdict = (
            " — within the bound ✓"
            if acc.within_bound
            else " — <span style='color:#c0392b'><b>exceeds the bound</b></span>"
        )
    what = "H(T(A_first), A_last)" if acc.chain and acc.operation not in ("union", "corefine") else "H"
    if m.intervals is not None and not m.exact:  # 3D: a certified enclosure, shown as one
        lo, hi = m.intervals["both"]
        text = f"<b>Measured</b>: {what} ∈ [{lo:.6g}, {hi:.6g}] (certified){verdict}"
    else:
        text = f"<b>Measured</b>: {what} = {m.value:.4g}{verdict}"
    if acc.within_bound is None and m.intervals is not None and acc.bound is not None:
        text += "<br><small>the certified interval holds the bound: neither side is proven</small>"
    if not acc.reference_exact:  # the overlay that made E ∪ E′ or the part (docs/adr/0061 in space)
        made = "manifold3d's mesh Booleans" if isinstance(acc.result, VoxelSet) else "GEOS's overlay"
        text += f"<br><small>the Euclidean reference is {made} (crossing vertices rounded)</small>"
    if acc.difference is not None:
        unit = "voxels" if isinstance(acc.difference.light, VoxelSet) else "pixels"
        text += (
            f"<br><small>{len(acc.difference.light):,} {unit} only in the result (light grey), "
            f"{len(acc.difference.dark):,} only in the direct result D(T(A_first)) (dark grey)</small>"
        )
    if acc.direct_note:
        text += f"<br><small>{html.escape(acc.direct_note, quote=False)}</small>"
    if acc.idempotent is not None:
        text += f"<br><small>Sp_α∘Sp_α = Sp_α: {'checked ✓' if acc.idempotent else 'FAILS'}</small>"
    return text


def changes_text(doc: Any, obj: Any) -> str:
    """A sentence per input that changed or was deleted since the result was made (empty if none)."""
    return "<br>".join(c.text() for c in changed_inputs(doc, obj.provenance))
