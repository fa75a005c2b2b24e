"""``mrm simplify IN --alpha A [--center X,Y] -o OUT``: discrete-based simplification Sp_α(E).

Sp_α(E) = Sc_1/α(R(D(Sc_α(E)))): details smaller than about 1/α are simplified away, and the result lies
within √2/α of E (cover models). A pixel input is read as its continuation R(A). The output is a vector file
(or, for a pixel file, the result's discretization). See :mod:`mrm.cli._operation` for ``--json``.
"""

from __future__ import annotations

import argparse
from typing import Any

from mrm.cli._operation import add_common, add_input, parse_point, run_unary

NAME = "simplify"
HELP = "discrete-based simplification Sp_α of a Euclidean object (vector, pixel or project input)"


def add_arguments(parser: argparse.ArgumentParser) -> None:
    """Add IN, ``--object``, ``--alpha``, ``--center``, ``-o``, ``--limit``, ``--no-measure``."""
    add_input(parser)
    parser.add_argument("--alpha", required=True, metavar="A", help="α > 0: the grid spacing is 1/α")
    parser.add_argument(
        "--center", type=parse_point, default=None, metavar="X,Y", help="centre of the scalings (default 0,0)"
    )
    add_common(
        parser, "the result: a vector file (.geojson .json .wkt .svg) or a pixel file (.png .pbm .npz)"
    )


def run(args: argparse.Namespace) -> dict[str, Any]:
    """Simplify, write the result, return the summary."""
    return run_unary(args, "simplify", {"alpha": args.alpha, "center": args.center})
