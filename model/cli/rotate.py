"""``mrm rotate IN --angle DEG [--center X,Y] -o OUT``: discrete-Euclidean rotation dR_θ,C(A) = D(rot(R(A))).

The angle is in degrees, counter-clockwise (y up); the centre defaults to the origin. Multiples of 90° about
a pixel centre are exact pixel rotations. A vector input is read as its discretization D(E). See
:mod:`mrm.ops.rotation` for what the rotation is exactly and :mod:`mrm.cli._operation` for ``--json``.
"""

from __future__ import annotations

from mrm.cli._operation import operation_command

NAME = "rotate"
HELP = "discrete-Euclidean rotation dR_θ,C (D of the continuation rotated by θ about C) of an input"

# Options, help and ranges come from the registry's spec of 'discrete_rotation' (declared once).
add_arguments, run = operation_command(
    "discrete_rotation",
    "the result: a pixel file (.png .pbm .pgm .npz) or a vector file (.geojson .wkt .svg)",
)
