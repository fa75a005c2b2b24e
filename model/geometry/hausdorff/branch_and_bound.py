"""What the two branch-and-bounds of a directed distance share: the best candidate so far and the pruning.

:class:`_Run` is one computation of ``h(A, B)``: the prepared sets, the tower its numbers live in, the best
squared distance found so far (:meth:`_Run.offer`) and the progress it reports now and then (the caller's
``Cancelled`` stops it there). :func:`_lipschitz_prunes` drops a piece of edge or a box that cannot beat it.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from fractions import Fraction

from mrm.core.progress import ProgressLike
from mrm.geometry.hausdorff.exact_numbers import Num, _cmp, _sign, _Tower
from mrm.geometry.hausdorff.intervals import _INF, Rat, _down, _iv, _up
from mrm.geometry.hausdorff.shapes import _Shape

#: Depth at which a box becomes a leaf whatever its features: only exact ties get there (a square hole's
#: centre is equidistant from four edges), and those involve few features.
_MAX_DEPTH = 200


@dataclass
class _Best:
    f2: Num = -1
    x: Num = 0
    y: Num = 0
    where: str = ""


@dataclass
class _Run:
    a: _Shape
    b: _Shape
    k: int
    t: _Tower
    progress: ProgressLike | None
    best: _Best = field(default_factory=_Best)
    ticks: int = 0

    def tick(self) -> None:
        self.ticks += 1
        if self.progress is not None and self.ticks % 64 == 0:
            self.progress.update(None)

    _llo: float | None = None

    def offer(self, f2: Num, x: Num, y: Num, where: str) -> None:
        if _cmp(f2, self.best.f2) > 0:
            self.best = _Best(f2, x, y, where)
            self._llo = None

    def l_lo(self) -> float:
        """A float ≤ the best distance so far, in original units (-inf before any)."""
        if self._llo is None:
            lo = _iv(self.best.f2)[0] if _sign(self.best.f2) > 0 else -1.0
            self._llo = _down(math.ldexp(_down(math.sqrt(lo)), -self.k)) if lo > 0 else -_INF
        return self._llo


def _lipschitz_prunes(run: _Run, r2: Rat, fc2: Num) -> bool:
    """Tell exactly whether f(c) + √r2 ≤ best (then f ≤ best on the ball of radius √r2 about c)."""
    if _sign(run.best.f2) <= 0:
        return False
    llo = _iv(run.best.f2)[0]
    if llo <= 0:
        return False
    l_lo = Fraction(_down(math.sqrt(llo)))
    try:
        r_up = Fraction(_up(math.sqrt(_up(float(r2)))))
    except OverflowError:
        return False
    if l_lo <= r_up:
        return False
    return _cmp(fc2, (l_lo - r_up) ** 2) <= 0
