"""``mrm scale IN --alpha A [--center X,Y] -o OUT``: discrete smooth scaling DSS_α(A) = D(Sc_α(R(A))).

A vector input is read as its discretization D(E). α is read exactly (``0.2`` is 1/5; ``1/3`` is accepted);
the result's size is estimated before anything runs and refused beyond ``--limit``. The output is a pixel
file (or, for .geojson/.wkt/.svg, the result's continuation). See :mod:`mrm.cli._operation` for ``--json``.
"""

from __future__ import annotations

import argparse
from typing import Any

from mrm.cli._operation import add_common, add_input, parse_point, run_unary

NAME = "scale"
HELP = "discrete smooth scaling DSS_α (D of the continuation scaled by α) of a pixel, vector or project input"


def add_arguments(parser: argparse.ArgumentParser) -> None:
    """Add IN, ``--object``, ``--alpha``, ``--center``, ``-o``, ``--limit``, ``--no-measure``."""
    add_input(parser)
    parser.add_argument("--alpha", required=True, metavar="A", help="scale factor α > 0 (decimal or p/q)")
    parser.add_argument(
        "--center", type=parse_point, default=None, metavar="X,Y", help="centre of the scaling (default 0,0)"
    )
    add_common(parser, "the result: a pixel file (.png .pbm .pgm .npz) or a vector file (.geojson .wkt .svg)")


def run(args: argparse.Namespace) -> dict[str, Any]:
    """Scale, write the result, return the summary."""
    return run_unary(args, "dss", {"alpha": args.alpha, "center": args.center})
