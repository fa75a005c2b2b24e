"""Small inputs on a cold kernel cache run the kernels interpreted instead of compiling them first.

Compiling every kernel ``mrm reconstruct`` calls costs 130-143 s of CPU on a fresh install (numba's typing
and lowering, docs/adr/0051), while the same kernels *interpreted* — their plain Python, run by CPython on
numpy arrays, exactly the same code and so exactly the same result — take about a second on a 64×64 image
(0.8 s of CPU, less than loading the compiled kernels from the cache: 1.4 s) and 6-8 s on the worst case
accepted (a 128×128 image of noise). So when the cache lacks a compiled kernel and every input is a raster
of at most :data:`INTERPRETED_PIXELS` pixels and :data:`INTERPRETED_CRACKS` changes of value between
neighbouring pixels, the command runs with ``NUMBA_DISABLE_JIT=1`` and
compiles nothing; a larger input compiles in the foreground with the first-run notice, and
``python -m mrm.warmup`` compiles everything once (docs/adr/0057).

The decision is taken before anything imports numba: ``NUMBA_DISABLE_JIT`` is read when numba is imported
and a kernel decorated. A user's own ``NUMBA_DISABLE_JIT`` is left as it is.
"""

from __future__ import annotations

import logging
import os
import sys
import warnings
from pathlib import Path

log = logging.getLogger(__name__)

#: Inputs of at most this many pixels run interpreted on a cold cache: a 256×256 raster...
INTERPRETED_PIXELS = 256 * 256

#: ...with at most this many cracks between pixels of different values. Interpreted R costs about 0.5 ms of
#: CPU per crack (128×128 of noise, 16,300 cracks: 6.3-8 s; 256×256 of noise, 65,000: 33 s), a few discs
#: almost nothing (256×256 of discs: 1.3 s).
INTERPRETED_CRACKS = 16_384

#: The subcommands whose first run this applies to: their work is R on a 2D raster (reconstruct, polygonize)
#: or its summary (info).
COMMANDS = ("reconstruct", "polygonize", "info")

#: Raster files whose size Pillow reads from the header alone.
RASTERS = (".png", ".pbm", ".pgm", ".ppm", ".pnm")

#: Options whose value is an output path (never an input to measure).
OUTPUT_OPTIONS = ("-o", "--output")


def _inputs(argv: list[str]) -> list[Path] | None:
    """The existing files among the arguments (not the output); None when one is not a raster."""
    found: list[Path] = []
    skip = False
    for token in argv[1:]:
        if skip:
            skip = False
            continue
        if token in OUTPUT_OPTIONS:
            skip = True
            continue
        if token.startswith("-"):
            continue
        p = Path(token)
        if p.is_dir():
            return None  # a folder of inputs: their sizes are not looked at one by one here
        if not p.is_file():
            continue  # an option's value (a model name, a number) or a missing file the command reports
        if p.suffix.lower() not in RASTERS:
            return None
        found.append(p)
    return found


def _small(path: Path) -> bool:
    """True for a raster of at most INTERPRETED_PIXELS pixels and INTERPRETED_CRACKS value changes.

    The size comes from the header; only then are the samples read (at most 256×256 of them) and the cracks
    between horizontally or vertically neighbouring samples of different values counted: an upper bound of
    the boundary R traces, whatever threshold the command applies.
    """
    try:
        import numpy as np
        from PIL import Image

        with Image.open(path) as im:
            w, h = im.size
            if int(w) * int(h) > INTERPRETED_PIXELS:
                return False
            a = np.asarray(im)
    except Exception:  # the command itself reads the file and says what is wrong with it
        return False
    if a.ndim == 3:  # colour: a change in any channel
        rows, cols = np.any(a[1:] != a[:-1], axis=2), np.any(a[:, 1:] != a[:, :-1], axis=2)
    else:
        rows, cols = a[1:] != a[:-1], a[:, 1:] != a[:, :-1]
    return int(np.count_nonzero(rows)) + int(np.count_nonzero(cols)) <= INTERPRETED_CRACKS


def interpret_small_inputs(argv: list[str]) -> bool:
    """Run this command's kernels interpreted when the cache is cold and its inputs are small; say if so.

    Parameters
    ----------
    argv : list of str
        The arguments after the program name (the subcommand first).
    """
    if not argv or argv[0] not in COMMANDS or "NUMBA_DISABLE_JIT" in os.environ or "numba" in sys.modules:
        return False
    inputs = _inputs(argv)
    if not inputs:
        return False
    if not all(_small(p) for p in inputs):
        return False
    from mrm.warmup import kernels_cached

    if kernels_cached():
        return False
    os.environ["NUMBA_DISABLE_JIT"] = "1"
    # Interpreted, the FNV hashes of the boundary cells multiply numpy uint64 scalars, which wrap as they do
    # compiled but warn: the wrap is what the hash wants.
    warnings.filterwarnings("ignore", "overflow encountered in scalar", RuntimeWarning)
    log.info("cold kernel cache and %d small input(s): running the kernels interpreted", len(inputs))
    return True
