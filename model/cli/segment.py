"""``mrm segment --chain X,Y,CODES``: cut a Freeman chain into digital straight segments.

Reference: docs/design.md §5, §9.

The chain's points are its start (point 0) and the point after each code (point i follows code i − 1); codes
are 0 = E, 1 = N, 2 = W, 3 = S. Segments are listed as ``[first, last, a, b, mu, omega]``: indices into those
points (both included, consecutive greedy segments share their end point) and DGtal's characteristics
(μ ≤ a·x − b·y < μ + ω on every point of the segment).
"""

from __future__ import annotations

import argparse
import sys
from typing import Any

from mrm.core.errors import InvalidGeometryError, ParameterError
from mrm.geometry.dss.segmentation import chain_points, greedy_segmentation, maximal_segments

#: Largest |x| or |y| of a chain point.
CHAIN_COORD_LIMIT = 2**31

NAME = "segment"
HELP = "segment a Freeman chain into digital straight segments (greedy or maximal)"


def add_arguments(parser: argparse.ArgumentParser) -> None:
    """Add ``--chain``, ``--closed``, ``--closed-end``, ``--adjacency`` and ``--mode``."""
    parser.add_argument(
        "--chain",
        required=True,
        metavar="X,Y,CODES",
        help="start point and Freeman codes (0=E 1=N 2=W 3=S), e.g. 0,0,00100100",
    )
    parser.add_argument(
        "--closed",
        action="store_true",
        help="read the chain as closed (it must come back to its start); default: open",
    )
    parser.add_argument(
        "--closed-end",
        choices=("wrap", "truncate"),
        default="wrap",
        help="closed greedy chains: end the last segment back on point 0 (wrap, default) or at the last "
        "point before it, as DGtal's circulator segmentation does (truncate)",
    )
    parser.add_argument(
        "--adjacency",
        type=int,
        choices=(4, 8),
        default=4,
        help="4: standard (4-connected) segments, the default; 8: naive (8-connected) segments",
    )
    parser.add_argument(
        "--mode",
        choices=("greedy", "maximal"),
        default="greedy",
        help="greedy segmentation from point 0 (default) or all maximal segments (tangential cover)",
    )


def parse_chain(text: str) -> tuple[tuple[int, int], str]:
    """Parse ``"X,Y,CODES"`` into ``((X, Y), CODES)``; raise ParameterError on malformed text."""
    parts = text.split(",")
    if len(parts) != 3:
        raise ParameterError(f"--chain must be X,Y,CODES (three comma-separated fields), got {text!r}")
    xs, ys, codes = (p.strip() for p in parts)
    try:
        x, y = int(xs), int(ys)
    except ValueError:
        raise ParameterError(f"--chain start must be two integers, got {xs!r} and {ys!r}") from None
    bad = codes.translate(str.maketrans("", "", "0123"))
    if bad:
        raise ParameterError(f"--chain codes must be Freeman codes 0-3 (0=E 1=N 2=W 3=S), got {bad[0]!r}")
    # Points are int64 and the characteristics multiply a coordinate by a slope term (up to the chain's
    # length): keep every point within ±2³¹ so that a·x − b·y cannot overflow.
    reach = CHAIN_COORD_LIMIT - len(codes)
    if abs(x) > reach or abs(y) > reach:
        raise ParameterError(
            f"--chain start ({xs}, {ys}) is out of range: the chain's points must stay within ±2**31"
        )
    return (x, y), codes


def run(args: argparse.Namespace) -> dict[str, Any]:
    """Segment the chain; print a table unless ``--json``; return the JSON summary."""
    # Imported here, not at the top: the segmentation loads numba, which ``mrm --help`` and a one-line
    # usage error should not wait for (the parser imports every subcommand module).

    start, codes = parse_chain(args.chain)
    pts = chain_points(start, codes)
    if args.closed and (pts[-1] != pts[0]).any():
        raise InvalidGeometryError(
            f"--closed: the chain ends at ({pts[-1, 0]}, {pts[-1, 1]}), not back at its start {start}"
        )
    if args.mode == "greedy":
        segs = greedy_segmentation(
            pts, closed=args.closed, adjacency=args.adjacency, closed_end=args.closed_end
        )
    else:
        segs = maximal_segments(pts, closed=args.closed, adjacency=args.adjacency)
    summary: dict[str, Any] = {
        "segments": [s.as_list() for s in segs],
        "count": len(segs),
        "points": len(pts),
        "closed": bool(args.closed),
        "mode": args.mode,
        "adjacency": args.adjacency,
        "leaning_points": [[list(s.uf), list(s.ul), list(s.lf), list(s.ll)] for s in segs],
    }
    if args.closed and args.mode == "greedy":
        summary["closed_end"] = args.closed_end
    if not args.json:
        kind = "standard (4-connected)" if args.adjacency == 4 else "naive (8-connected)"
        shape = "closed" if args.closed else "open"
        print(
            f"{shape} chain from {start}, {len(codes)} codes, {len(pts)} points: "
            f"{len(segs)} {args.mode} {kind} segments",
            file=sys.stdout,
        )
        head = ("first", "last", "a", "b", "mu", "omega", "Uf", "Ul", "Lf", "Ll")
        rows = [
            (*map(str, s.as_list()), *(f"({p[0]},{p[1]})" for p in (s.uf, s.ul, s.lf, s.ll))) for s in segs
        ]
        widths = [max(len(h), *(len(r[k]) for r in rows)) for k, h in enumerate(head)]
        print("  ".join(h.rjust(w) for h, w in zip(head, widths, strict=True)), file=sys.stdout)
        for r in rows:
            print("  ".join(c.rjust(w) for c, w in zip(r, widths, strict=True)), file=sys.stdout)
    return summary
