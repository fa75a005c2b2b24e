"""``mrm simplify IN --alpha A [--center X,Y] -o OUT``: discrete-based simplification Sp_α(E).

Sp_α(E) = Sc_1/α(R(D(Sc_α(E)))): details smaller than about 1/α are simplified away, and the result lies
within √2/α of E (cover models). A pixel input is read as its continuation R(A). The output is a vector file
(or, for a pixel file, the result's discretization). See :mod:`mrm.cli._operation` for ``--json``.
"""

from __future__ import annotations

from mrm.cli._operation import operation_command

NAME = "simplify"
HELP = "discrete-based simplification Sp_α of a Euclidean object (vector, pixel or project input)"

# Options, help and ranges come from the registry's spec of 'simplify' (one declaration, as for the panel).
add_arguments, run = operation_command(
    "simplify", "the result: a vector file (.geojson .json .wkt .svg) or a pixel file (.png .pbm .npz)"
)
