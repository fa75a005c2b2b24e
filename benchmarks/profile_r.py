"""Profile R's compiled kernels with Linux ``perf``: where the time of one input goes, per numba function.

perf sees numba's JIT code as anonymous addresses. This script compiles the kernels afresh (into a
temporary numba cache: functions loaded from the cache carry no LLVM module to name them), writes
``/tmp/perf-PID.map`` with the address of every compiled function, then runs R on the input in a loop::

    perf record -F 2000 -g -o /tmp/r.data .venv/bin/python benchmarks/profile_r.py noise --seconds 12
    perf report -i /tmp/r.data --no-children --sort symbol -g none --time 80%-100%

The ``--time`` window leaves out the compilation at the start (about a minute). Each function's size in the
map is the distance to the next one, so a sample is charged to the function it falls in. One thread by
default (``MRM_THREADS=1``), so that samples are not split between threads. Inputs: ``noise`` (1024², 50 %),
``blob`` (the 1024² one-ring object of benchmarks/operations.py), or a scikit-image image thresholded at Otsu
(``camera``, ``coins``, ``page``, ``text``, ``horse``).
"""

from __future__ import annotations

import argparse
import os
import sys
import tempfile
import time

os.environ.setdefault("MRM_THREADS", "1")
os.environ["NUMBA_CACHE_DIR"] = tempfile.mkdtemp(prefix="mrm-profile-")  # before numba is imported

import numpy as np
from numba.core.registry import CPUDispatcher

sys.path.insert(0, os.path.join(os.path.dirname(__file__), ".."))

from mrm.core.grids import PixelSet
from mrm.geometry.reconstruct import reconstruct


def pixel_set(name: str) -> PixelSet:
    """The input called ``name`` (see the module docstring)."""
    if name == "noise":
        return PixelSet(np.random.default_rng(12345).random((1024, 1024)) < 0.5)
    if name == "blob":
        from operations import blob_1024

        return blob_1024()[1]
    import skimage.data
    from skimage.filters import threshold_otsu

    if name == "horse":
        return PixelSet(~skimage.data.horse()[::-1])
    img = getattr(skimage.data, name)()
    return PixelSet(np.asarray(img > threshold_otsu(img))[::-1])


def write_perf_map() -> int:
    """Write /tmp/perf-PID.map naming every function of every compiled mrm kernel; return their number."""
    addresses: dict[int, str] = {}
    seen: set[int] = set()
    for modname, mod in list(sys.modules.items()):
        if not modname.startswith("mrm"):
            continue
        for obj in vars(mod).values():
            if not isinstance(obj, CPUDispatcher) or id(obj) in seen:
                continue
            seen.add(id(obj))
            for cres in obj.overloads.values():
                library = cres.library
                module = getattr(library, "_final_module", None)
                if module is None:
                    continue
                for fn in module.functions:
                    if fn.is_declaration:
                        continue
                    address = library.get_pointer_to_function(fn.name)
                    if address:
                        addresses[address] = fn.name
    items = sorted(addresses.items())
    with open(f"/tmp/perf-{os.getpid()}.map", "w", encoding="ascii", errors="replace") as fh:
        for i, (address, name) in enumerate(items):
            gap = items[i + 1][0] - address if i + 1 < len(items) else 4096
            fh.write(f"{address:x} {min(gap, 1 << 20):x} {name}\n")
    return len(items)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("input", nargs="?", default="noise")
    parser.add_argument("--model", default="standard", choices=("standard", "supercover", "gauss"))
    parser.add_argument("--seconds", type=float, default=10.0, help="how long to run R after compiling")
    args = parser.parse_args()
    sys.path.insert(0, os.path.dirname(__file__))
    ps = pixel_set(args.input)
    t0 = time.perf_counter()
    reconstruct(ps, args.model)  # compiles every kernel R uses
    print(f"compiled in {time.perf_counter() - t0:.0f} s; {write_perf_map()} functions mapped", flush=True)
    runs = 0
    t0 = time.perf_counter()
    while time.perf_counter() - t0 < args.seconds:
        reconstruct(ps, args.model)
        runs += 1
    print(f"{runs} runs, {1e3 * (time.perf_counter() - t0) / runs:.1f} ms each")


if __name__ == "__main__":
    main()
