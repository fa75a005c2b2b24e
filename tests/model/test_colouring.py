"""The greedy colouring of the 3D analytical view's segments, against the plain definition."""

from __future__ import annotations

import numpy as np
from hypothesis import given
from hypothesis import strategies as st

from mrm.geometry.topology.colouring import greedy_colouring


def _reference(n: int, pairs: list[tuple[int, int]], k: int) -> list[int]:
    adjacent: dict[int, set[int]] = {i: set() for i in range(n)}
    for a, b in pairs:
        if a != b:
            adjacent[a].add(b)
            adjacent[b].add(a)
    colour: list[int] = []
    for s in range(n):
        used = {colour[t] for t in adjacent[s] if t < s}
        free = [c for c in range(k) if c not in used]
        colour.append(free[0] if free else s % k)
    return colour


@given(
    st.integers(1, 30).flatmap(
        lambda n: st.tuples(
            st.just(n),
            st.lists(st.tuples(st.integers(0, n - 1), st.integers(0, n - 1)), max_size=80),
            st.integers(1, 6),
        )
    )
)
def test_greedy_colouring_is_the_definition(case: tuple[int, list[tuple[int, int]], int]) -> None:
    n, pairs, k = case
    got = greedy_colouring(n, np.array(pairs, np.int64).reshape(-1, 2), k)
    assert got.tolist() == _reference(n, pairs, k)
    # with enough colours, no two neighbours share one
    degree = max([sum(1 for a, b in pairs if i in (a, b) and a != b) for i in range(n)] + [0])
    wide = greedy_colouring(n, np.array(pairs, np.int64).reshape(-1, 2), degree + 1)
    assert all(wide[a] != wide[b] for a, b in pairs if a != b)
