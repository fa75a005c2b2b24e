"""Sp_α far from the origin (docs/design.md §3 item 8): idempotent and exact, or refused with a message.

Near the origin the final float64 rounding of Sc_1/α is provably below R's margin; from about |α·x| = 2²⁰
on it is not, so :func:`simplification` checks the fixed point exactly there and refuses when rounding would
change it; beyond R's coordinate limit (2⁴⁰) R itself refuses. Either way: never a wrong result, never an
assertion or a crash.
"""

from __future__ import annotations

import numpy as np
import shapely
from hypothesis import given, settings
from hypothesis import strategies as st
from shapely import affinity

from mrm.core.errors import MRMError
from mrm.core.numbers import read_positive
from mrm.geometry.discretize.exact_shape import ExactShape, Similarity
from mrm.geometry.discretize.rational import discretize_exact
from mrm.ops.simplify import simplification
from tests.oracles.geometry_strategies import star_polygons
from tests.oracles.ops_reference import MODELS


def coords(g):
    return shapely.get_coordinates(shapely.normalize(g))


@settings(max_examples=60, deadline=None)
@given(
    star_polygons(max_vertices=6, max_radius=4.0),
    st.integers(30, 47),
    st.sampled_from([3, 5, 0.3, 0.7, 4]),
    st.sampled_from(MODELS),
)
def test_far_from_the_origin_sp_is_idempotent_or_refused_with_a_message(poly, k, alpha, model):
    off = 2.0**k / alpha
    far = affinity.translate(poly, off, -off / 3)
    try:
        once = simplification(far, alpha, None, model)
        twice = simplification(once.result, alpha, None, model).result
    except MRMError as e:
        assert str(e)  # a message the user can read, never an assertion
        return
    # the result is a fixed point: its discretization at scale α is the one Sp started from, exactly
    sc = Similarity.scaling(read_positive(alpha, "alpha"), None)
    assert discretize_exact(ExactShape.from_geometry(once.result).map(sc), model) == once.discrete
    assert np.array_equal(coords(once.result), coords(twice))
