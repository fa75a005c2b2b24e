"""``mrm reconstruct IN... -o OUT``: the reversible continuation R of pixel files, written as vectors.

One input: ``OUT`` is the file to write (.geojson, .json, .wkt or .svg). Several inputs: ``OUT`` is either a
directory (existing, or a path ending with a separator or without an extension: it is created), where each
input ``NAME.png`` gives ``NAME.geojson``, or a pattern holding ``{stem}`` (the input's name without its
extension), e.g. ``out/{stem}-R.wkt``. ``--jobs N`` spreads the inputs over N worker processes.
``--features components`` writes one GeoJSON Feature per 4-connected component (property ``part``).

Inputs are pixel files (.png .pbm .pgm .npz: grey images are cut at Otsu's threshold unless
``--threshold`` is given) or projects (.mrm: the union of their objects' pixels under the model).
``--json`` prints, for one input, the info keys of the result (``model``, ``pixels``, ``components``,
``holes``, ``euler``, ``boundary_chains``, ``segments``, ``vertices``) plus ``seconds`` (the time R took),
``input`` and ``output``; for several inputs, the same keys summed over the inputs plus ``files``, the list
of the per-input summaries.
"""

from __future__ import annotations

import argparse
import os
import time
from concurrent.futures import ProcessPoolExecutor
from pathlib import Path
from typing import Any

from mrm.cli._common import (
    PROJECT_EXTENSION,
    add_limit_argument,
    extension_of,
    finite_float,
    positive_int,
    print_table,
    read_input,
)
from mrm.errors import FileFormatError, MRMError, ParameterError
from mrm.io.pixel_files import PIXEL_EXTENSIONS
from mrm.io.vector_files import VECTOR_EXTENSIONS, write_geojson, write_svg, write_wkt
from mrm.reps.pixels import PixelSet
from mrm.summary import summarize

NAME = "reconstruct"
HELP = "reversible continuation of pixel files (.png .pbm .pgm .npz .mrm) into polygons (.geojson .wkt .svg)"

INPUTS = (*PIXEL_EXTENSIONS, PROJECT_EXTENSION)
OUTPUTS = (*VECTOR_EXTENSIONS, ".svg")
_SUM_KEYS = ("pixels", "components", "holes", "euler", "boundary_chains", "segments", "vertices", "seconds")


def add_arguments(parser: argparse.ArgumentParser) -> None:
    """Add the inputs, ``-o OUT``, ``--jobs``, ``--threshold`` and ``--limit``."""
    parser.add_argument(
        "inputs", nargs="+", metavar="IN", help="pixel files (.png .pbm .pgm .npz) or projects (.mrm)"
    )
    parser.add_argument(
        "-o",
        "--output",
        required=True,
        metavar="OUT",
        help="the vector file (.geojson .json .wkt .svg); for several inputs a directory or a pattern "
        "holding {stem}",
    )
    parser.add_argument(
        "--jobs", type=positive_int, default=1, metavar="N", help="worker processes for several inputs"
    )
    parser.add_argument(
        "--threshold",
        type=finite_float,
        default=None,
        metavar="T",
        help="grey images: pixels brighter than T are in the set (default: binary images as they are, "
        "others at Otsu's threshold)",
    )
    parser.add_argument(
        "--features",
        choices=("one", "components"),
        default="one",
        help="GeoJSON: one Feature holding everything (default), or one Feature per 4-connected component "
        "(keeps large results within GDAL's object size limit)",
    )
    add_limit_argument(parser)


def _outputs(inputs: list[str], output: str) -> list[str]:
    """The output path of each input (see the module docstring); checked before any work."""
    if len(inputs) == 1 and "{stem}" not in output:
        extension_of(output, OUTPUTS, "vector output file")
        return [output]
    if "{stem}" in output:
        outs = [output.replace("{stem}", Path(i).stem) for i in inputs]
        for o in outs:
            extension_of(o, OUTPUTS, "vector output file")
    else:
        p = Path(output)
        if p.exists() and not p.is_dir():
            raise ParameterError(
                f"{output}: several inputs need a directory or a pattern with {{stem}} for -o"
            )
        if not p.exists() and p.suffix and not output.endswith(os.sep):
            raise ParameterError(
                f"{output}: several inputs need a directory or a pattern with {{stem}} for -o"
            )
        outs = [str(p / (Path(i).stem + ".geojson")) for i in inputs]
    if len(set(outs)) != len(outs):
        raise ParameterError("two inputs would write the same output file; use a pattern with {stem}")
    return outs


def _pixels_of(path: str, threshold: float | None, limit: int, model: str | None) -> tuple[PixelSet, str]:
    src = read_input(path, INPUTS, threshold=threshold, limit=limit)
    chosen = model or src.model or "standard"
    if src.kind == "discrete":
        assert src.pixels is not None
        return src.pixels, chosen
    if threshold is not None:
        raise ParameterError("--threshold applies to image inputs only")
    from mrm.cli._common import discretize_geometry

    union = PixelSet.empty()
    for obj in src.objects:
        union = union | (
            obj.source if isinstance(obj.source, PixelSet) else discretize_geometry(obj.source, chosen, limit)
        )
    return union, chosen


def _write(geom: Any, path: str, model: str, source: str, features: str = "one") -> None:
    ext = Path(path).suffix.lower()
    if ext == ".svg":
        write_svg(geom, path)
    elif ext == ".wkt":
        write_wkt(geom, path)
    elif features == "components":
        parts = list(getattr(geom, "geoms", [] if geom.is_empty else [geom]))
        write_geojson(parts, path, properties={"model": model, "source": Path(source).name})
    else:
        write_geojson(geom, path, properties={"model": model, "source": Path(source).name})


def reconstruct_file(
    path: str, output: str, model: str | None, threshold: float | None, limit: int, features: str = "one"
) -> dict[str, Any]:
    """Read one pixel file, reconstruct it, write the result; return its summary (for the worker pool)."""
    from mrm.geometry.reconstruct import reconstruct

    ps, chosen = _pixels_of(path, threshold, limit, model)
    t0 = time.perf_counter()
    geom = reconstruct(ps, chosen)
    seconds = time.perf_counter() - t0
    Path(output).parent.mkdir(parents=True, exist_ok=True)
    _write(geom, output, chosen, path, features)
    summary = {"input": str(path), "output": str(output), **summarize(ps, chosen, geom=geom)}
    summary["seconds"] = seconds
    return summary


def _one(
    job: tuple[str, str, str | None, float | None, int, str],
) -> tuple[dict[str, Any] | None, str | None]:
    try:
        return reconstruct_file(*job), None
    except MRMError as e:
        return None, f"{job[0]}: {e}"
    except OSError as e:
        return None, f"{job[0]}: {e.strerror or e}"


def run(args: argparse.Namespace) -> dict[str, Any]:
    """Reconstruct every input and write it; return the summary (see the module docstring)."""
    inputs = [str(i) for i in args.inputs]
    for i in inputs:
        extension_of(i, INPUTS, "supported input file")
    outputs = _outputs(inputs, str(args.output))
    jobs = [
        (i, o, args.model, args.threshold, args.limit, args.features)
        for i, o in zip(inputs, outputs, strict=True)
    ]
    if len(jobs) == 1:
        summary = reconstruct_file(*jobs[0])
        if not args.json:
            print_table(summary)
        return summary
    if args.jobs > 1:
        with ProcessPoolExecutor(max_workers=min(args.jobs, len(jobs))) as pool:
            results = list(pool.map(_one, jobs))
    else:
        results = [_one(j) for j in jobs]
    files = [r for r, _ in results if r is not None]
    errors = [e for _, e in results if e is not None]
    total: dict[str, Any] = {
        "model": args.model or (files[0]["model"] if files else "standard"),
        "inputs": len(jobs),
    }
    for k in _SUM_KEYS:
        values = [f.get(k) for f in files]
        total[k] = None if any(v is None for v in values) else sum(values)
    total["files"] = files
    if not args.json:
        for f in files:
            print(f"{f['input']} -> {f['output']}: {f['vertices']} vertices, {f['seconds']:.3f} s")
        print_table(total)
    if errors:
        raise FileFormatError(f"{len(errors)} of {len(jobs)} inputs failed: " + "; ".join(errors))
    return total
