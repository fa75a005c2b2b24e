"""The window bound of R's corridors (:func:`mrm.geometry.reconstruct._small_search.window_bound`).

It follows the greedy chain of the first start once and lets every later chain stop where it joins it; the
value must be the one of walking every chain to its end, which decides where R searches for fewer vertices
(so R's output depends on it): checked against that walk in plain Python, on reach tables of every shape,
dead ends (reach 0) and long windows included, and on the rings of thresholded images.
"""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from mrm.core.grids import PixelSet
from mrm.core.models import Model
from mrm.geometry.reconstruct import _run
from mrm.geometry.reconstruct._small_search import window_bound

MODELS = Model.names()


def walked(reach: list[int]) -> int:
    """The fewest windows covering one lap, each start of the longest window walked to its end."""
    n = len(reach)
    s0 = max(range(n), key=lambda i: (reach[i], -i))  # the first longest window
    best = 1 << 30
    for s in range(s0, s0 + reach[s0] + 1):
        t, c = s, 0
        while t < s + n:
            if reach[t % n] <= 0:
                c = 1 << 30
                break
            t += reach[t % n]
            c += 1
        best = min(best, c)
    return best


@st.composite
def reach_tables(draw: st.DrawFn) -> list[int]:
    n = draw(st.integers(1, 300))
    top = draw(st.sampled_from([2, 4, 16, n + 1]))
    low = draw(st.sampled_from([0, 1]))
    return draw(st.lists(st.integers(low, max(low, top)), min_size=n, max_size=n))


@settings(max_examples=400, deadline=None)
@given(reach_tables())
def test_window_bound_is_the_walk_of_every_chain(reach: list[int]) -> None:
    assert window_bound(np.array(reach, dtype=np.int64)) == walked(reach)


@pytest.mark.parametrize("model", MODELS)
def test_window_bound_on_image_rings(model: str) -> None:
    import skimage.data
    from skimage.filters import threshold_otsu

    img = skimage.data.camera()
    run = _run(PixelSet(np.asarray(img > threshold_otsu(img))[::-1]), model, tables=True)
    poff = run.corridor.poff
    for k in range(poff.size - 1):
        reach = run.reach[poff[k] : poff[k + 1]]
        if reach.size:
            assert window_bound(reach) == walked(reach.tolist())
