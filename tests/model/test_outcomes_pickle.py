"""Measured accounts travel between processes: the window measures in a worker process (ADR 0025).

An operation's outcome once held a closure (``euclidean_discrete_corefinement.<locals>.union``) as its lazily
made Euclidean object; the account that carries it could not be pickled back, and the window's measurement
of a co-refinement part never ended. Every operation of the bundled examples is measured here, its account
pickled and read back with the same numbers.
"""

from __future__ import annotations

import pickle

import pytest

from mrm.io.project import load_project
from mrm.ops.account import account_of
from mrm.resources import examples_dir

EXAMPLES = [
    "fig08-simplification",
    "fig09-10-union-corefinement",
    "fig12-dss-combinations",
    "fig13-rotations",
]


@pytest.mark.parametrize("name", EXAMPLES)
def test_the_measured_account_of_every_example_result_pickles(name: str) -> None:
    doc = load_project(examples_dir() / f"{name}.mrm")
    results = [o for o in doc if o.provenance is not None]
    assert results
    for obj in results:
        acc = account_of(obj.provenance, measure=True)
        back = pickle.loads(pickle.dumps(acc, protocol=5))
        assert back.measured == acc.measured and back.bound == acc.bound, obj.name
        if acc.outcome is not None:  # the lazily made Euclidean object is still there, and the same
            assert back.outcome.euclidean == acc.outcome.euclidean, obj.name
