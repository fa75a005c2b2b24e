"""``mrm bounds "DSS 5, DSS 2, DSS 0.5, DSS 0.2"``: the error bound of a chain of operations.

Reference: docs/design.md §8.
"""

from __future__ import annotations

import argparse
from typing import Any

from mrm.core.models import DEFAULT_MODEL
from mrm.ops.chain import chain_bound, parse_chain

NAME = "bounds"
HELP = 'error bound of a chain of operations, e.g. "DSS 5, DSS 2, DSS 0.5, DSS 0.2" (applied left to right)'


def add_arguments(parser: argparse.ArgumentParser) -> None:
    """The chain, as one argument, and the refinement switch."""
    parser.add_argument(
        "chain",
        help=(
            "steps separated by commas, applied left to right: DSS α, ROT θ [about x,y], SP α, SCALE s, "
            "EROT θ, TRANSLATE dx,dy, EDu, EDco [α] [common|first|second]"
        ),
    )
    parser.add_argument(
        "--exact-identities",
        action="store_true",
        help="merge round trips separated by an exact identity (Sp_α∘Sp_α = Sp_α, DSS 1 = identity)",
    )


def run(args: argparse.Namespace) -> dict[str, Any]:
    """Print the bound (or, with --json, return it as the summary)."""
    model = args.model or DEFAULT_MODEL
    result = chain_bound(parse_chain(args.chain), model, exact_identities=args.exact_identities)
    if not args.json:
        print(f"chain:   {', '.join(s.label for s in result.steps)}")
        print(f"bound:   {result.formula}")
        print(f"meaning: {result.guarantee}")
        for t in result.terms:
            print(f"  {t.description}: {t.factor}·√{result.n} ≈ {t.value(result.n):.4f}")
    summary = result.as_dict()
    summary["exact_identities"] = bool(args.exact_identities)
    return summary
