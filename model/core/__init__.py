"""The core vocabulary of MR Modeler: what every other layer imports, and what imports nothing of theirs.

The layers (docs/adr/0041, enforced by tests/test_layers.py) are, from the bottom: ``core`` → ``geometry`` →
``reps`` → ``ops`` → ``document`` → ``io`` → ``cli`` / ``api`` / ``views`` → ``app``. The core holds the
notions the whole product shares, each declared once:

* :mod:`mrm.core.errors` — the errors a user can cause;
* :mod:`mrm.core.limits` — the limits of what a document can hold, and the one size check;
* :mod:`mrm.core.models` — the discretization model (one enum) and the tie rule of a point;
* :mod:`mrm.core.numbers` — exact numbers: the one reader of a parameter's value and its one spelling;
* :mod:`mrm.core.params` — parameter declarations, read and checked once when a parameters object is made;
* :mod:`mrm.core.grids` — pixel sets and label maps (an integer origin plus an array);
* :mod:`mrm.core.progress` — the progress and cancel protocol of long work.

Nothing here imports numba or Qt, and shapely only when a georeference maps a geometry: importing the core
is cheap.
"""
