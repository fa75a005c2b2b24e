"""``mrm scale IN --alpha A [--center X,Y] -o OUT``: discrete smooth scaling DSS_α(A) = D(Sc_α(R(A))).

A vector input is read as its discretization D(E). α is read exactly (``0.2`` is 1/5; ``1/3`` is accepted);
the result's size is estimated before anything runs and refused beyond ``--limit``. The output is a pixel
file (or, for .geojson/.wkt/.svg, the result's continuation). See :mod:`mrm.cli._operation` for ``--json``.
"""

from __future__ import annotations

from mrm.cli._operation import operation_command

NAME = "scale"
HELP = "discrete smooth scaling DSS_α (D of the continuation scaled by α) of a pixel, vector or project input"

# Options, help and ranges come from the registry's spec of 'dss' (one declaration, as for the panel).
add_arguments, run = operation_command(
    "dss", "the result: a pixel file (.png .pbm .pgm .npz) or a vector file (.geojson .wkt .svg)"
)
