"""Speed of DSS segmentation: chain steps per second for greedy segmentation and maximal segments.

Inputs: the pointel contours of Gauss-digitized disks (r = 1000 and r = 10 000, centre (1/7, 2/9)), and a
random 4-connected chain of 10⁶ steps (uniform codes, no immediate back-step: very short segments, the
worst case per step). Each figure is the median of several runs, compile time reported separately.

DGtal cannot be built here, so its speed is a *quoted* reference, not a measurement: docs/algorithms.md §5.1
reports DGtal's greedy segmentation of the 8 000-linel r = 1000 contour in 0.513 ms and its saturated
(maximal-segment) segmentation in 2.739 ms on this machine class, i.e. about 15.6 M and 2.9 M steps/s; the
commonly quoted round figure for DGtal's DSS recognition is 50 M steps/s. Ratios are printed against both.

Run: ``.venv/bin/python benchmarks/segmentation.py [--repeats N] [--cold]`` (``--cold``: time the numba
compilation itself instead of loading the cache).
"""

from __future__ import annotations

import argparse
import statistics
import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

#: Quoted, not measured here: DGtal's steps per second on the r = 1000 disk contour (docs/algorithms.md §5.1).
DGTAL_QUOTED_GREEDY = 8000 / 0.513e-3
DGTAL_QUOTED_MAXIMAL = 8000 / 2.739e-3
#: Quoted round figure for DGtal's C++ DSS recognition (steps per second), as given in the task.
DGTAL_QUOTED_ROUND = 50e6


def disk_contour(r: int) -> np.ndarray:
    """Pointel contour (object on the left) of the Gauss-digitized disk of radius r, centre (1/7, 2/9).

    The digitization is exact in integers: (x − 1/7)² + (y − 2/9)² ≤ r² ⇔ (63x − 9)² + (63y − 14)² ≤ (63r)².
    """
    from mrm.geometry.dss.segmentation import chain_points

    ys = np.arange(-r - 1, r + 2, dtype=np.int64)
    xs = np.arange(-r - 1, r + 2, dtype=np.int64)
    inside = (63 * xs[None, :] - 9) ** 2 + (63 * ys[:, None] - 14) ** 2 <= (63 * r) ** 2
    rows = {
        int(y): (int(xs[row][0]), int(xs[row][-1])) for y, row in zip(ys, inside, strict=True) if row.any()
    }
    # A disk is convex in rows: walk its boundary as runs of codes (E along the bottom, then up the right
    # side, W along the top, down the left side), built from the row extents.
    y0 = min(rows)
    y1 = max(rows)
    codes: list[str] = []
    x = rows[y0][0]
    # right side going up: pointel x-coordinate of the right edge is xmax + 1
    codes.append("0" * (rows[y0][1] + 1 - x))
    x = rows[y0][1] + 1
    for y in range(y0 + 1, y1 + 1):
        nx = rows[y][1] + 1
        codes.append("1")
        codes.append("0" * (nx - x) if nx > x else "2" * (x - nx))
        x = nx
    codes.append("1")
    codes.append("2" * (x - rows[y1][0]))
    x = rows[y1][0]
    for y in range(y1 - 1, y0 - 1, -1):
        nx = rows[y][0]
        codes.append("3")
        codes.append("2" * (x - nx) if x > nx else "0" * (nx - x))
        x = nx
    codes.append("3")
    chain = "".join(codes)
    pts = chain_points((rows[y0][0], y0), chain)
    assert (pts[-1] == pts[0]).all()
    return pts


def random_chain(n: int, seed: int = 7) -> np.ndarray:
    from mrm.geometry.dss.segmentation import chain_points

    rng = np.random.default_rng(seed)
    turns = rng.integers(-1, 2, n)  # left, straight or right: never a back-step
    codes = np.cumsum(turns) % 4
    return chain_points((0, 0), codes.tolist())


def median_time(fn, repeats: int) -> tuple[float, float]:  # type: ignore[no-untyped-def]
    """Median wall-clock and median CPU (process) time of ``repeats`` calls.

    The machine is shared: the CPU time measures the code itself better when other jobs run.
    """
    wall, cpu = [], []
    for _ in range(repeats):
        t, c = time.perf_counter(), time.process_time()
        fn()
        cpu.append(time.process_time() - c)
        wall.append(time.perf_counter() - t)
    return statistics.median(wall), statistics.median(cpu)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeats", type=int, default=7)
    parser.add_argument(
        "--cold", action="store_true", help="compile into an empty numba cache to time a cold start"
    )
    args = parser.parse_args()
    if args.cold:
        import os
        import tempfile

        os.environ["NUMBA_CACHE_DIR"] = tempfile.mkdtemp(prefix="mrm-numba-")

    t0, c0 = time.perf_counter(), time.process_time()
    from mrm.geometry.dss.segmentation import greedy_table, maximal_table, standard_dss_reach

    tiny = np.array([[0, 0], [1, 0], [1, 1]], dtype=np.int64)
    greedy_table(tiny)
    maximal_table(tiny, closed=False)
    maximal_table(np.array([[0, 0], [1, 0], [1, 1], [0, 1]]), closed=True)
    standard_dss_reach(tiny)
    print(
        f"import + first call (numba compile or cache load): {time.perf_counter() - t0:.2f} s wall, "
        f"{time.process_time() - c0:.2f} s cpu"
    )

    inputs = [
        ("disk r=1000 contour", disk_contour(1000), True),
        ("disk r=10000 contour", disk_contour(10000), True),
        ("random chain 1e6 steps", random_chain(1_000_000), False),
    ]
    print(
        f"quoted DGtal (not measured): greedy {DGTAL_QUOTED_GREEDY / 1e6:.1f} M steps/s, "
        f"maximal {DGTAL_QUOTED_MAXIMAL / 1e6:.1f} M steps/s (r=1000 disk, docs/algorithms.md §5.1); "
        f"round figure {DGTAL_QUOTED_ROUND / 1e6:.0f} M steps/s"
    )
    print(
        f"{'input':24} {'steps':>8} {'mode':8} {'segments':>8} {'wall ms':>8} {'cpu ms':>8} "
        f"{'M steps/s (cpu)':>15} {'vs quoted':>9} {'vs 50M':>7}"
    )
    for name, pts, closed in inputs:
        steps = len(pts) - 1
        for mode, fn, quoted in (
            ("greedy", lambda p=pts, c=closed: greedy_table(p, closed=c), DGTAL_QUOTED_GREEDY),
            ("maximal", lambda p=pts, c=closed: maximal_table(p, closed=c), DGTAL_QUOTED_MAXIMAL),
            ("reach", lambda p=pts, c=closed: standard_dss_reach(p, closed=c), None),
        ):
            count = len(fn())
            wall, cpu = median_time(fn, args.repeats)
            rate = steps / cpu
            vs = f"{rate / quoted:9.2f}" if quoted else f"{'-':>9}"
            print(
                f"{name:24} {steps:8d} {mode:8} {count:8d} {wall * 1e3:8.3f} {cpu * 1e3:8.3f} "
                f"{rate / 1e6:15.1f} {vs} {rate / DGTAL_QUOTED_ROUND:7.2f}"
            )


if __name__ == "__main__":
    main()
