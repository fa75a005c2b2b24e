"""``mrm rotate IN --angle DEG [--center X,Y] -o OUT``: discrete-Euclidean rotation dR_θ,C(A) = D(rot(R(A))).

The angle is in degrees, counter-clockwise (y up); the centre defaults to the origin. Multiples of 90° about
a pixel centre are exact pixel rotations. A vector input is read as its discretization D(E). See
:mod:`mrm.ops.rotation` for what the rotation is exactly and :mod:`mrm.cli._operation` for ``--json``.
"""

from __future__ import annotations

import argparse
from typing import Any

from mrm.cli._operation import add_common, add_input, parse_point, run_unary

NAME = "rotate"
HELP = "discrete-Euclidean rotation dR_θ,C (D of the continuation rotated by θ about C) of an input"


def add_arguments(parser: argparse.ArgumentParser) -> None:
    """Add IN, ``--object``, ``--angle``, ``--center``, ``-o``, ``--limit``, ``--no-measure``."""
    add_input(parser)
    parser.add_argument("--angle", required=True, metavar="DEG", help="angle in degrees, counter-clockwise")
    parser.add_argument(
        "--center", type=parse_point, default=None, metavar="X,Y", help="centre of the rotation (default 0,0)"
    )
    add_common(parser, "the result: a pixel file (.png .pbm .pgm .npz) or a vector file (.geojson .wkt .svg)")


def run(args: argparse.Namespace) -> dict[str, Any]:
    """Rotate, write the result, return the summary."""
    return run_unary(args, "discrete_rotation", {"angle": args.angle, "center": args.center})
