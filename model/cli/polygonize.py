"""``mrm polygonize LABELS... -o OUT.geojson``: a label image as a watertight set of polygons, one per region.

``LABELS`` is an integer label image: a grey (8 or 16 bits) or palette PNG, a PGM (the grey value is the
label), or an NPZ holding ``labels`` (and optionally ``origin``). Label 0 is the background. Each region —
a 4-connected component of one label — becomes one GeoJSON Feature with the properties ``label`` and
``pixels``. A boundary between two regions is one polyline used by both
(:mod:`mrm.geometry.reconstruct.polygonize`),
and under ``gauss`` (the only model that allows a shared boundary) every centre-rule rasterizer burns the
features with their labels back to the label image exactly.

``--json`` prints ``model``, ``labels`` (distinct non-zero labels), ``regions``, ``pixels``, ``vertices``,
``seconds`` (the time the polygonization took), ``input`` and ``output``.

Several inputs (files, directories, quoted globs, ``-``) work as for ``reconstruct`` (docs/adr/0011): ``-o``
is a directory or a pattern holding ``{stem}``, ``--jobs N`` spreads them over worker processes, each
input's line is printed when it is done; ``--json`` then gives ``inputs``, the sums and ``files``.
"""

from __future__ import annotations

import argparse
import time
from pathlib import Path
from typing import Any

from mrm.cli._common import (
    add_batch_arguments,
    add_limit_argument,
    batch_total,
    extension_of,
    inputs_and_outputs,
    run_inputs,
)
from mrm.core.grids import LabelMap
from mrm.geometry.reconstruct.polygonize import polygonize
from mrm.io.pixel_files import LABEL_READ_EXTENSIONS, read_label_map
from mrm.io.vector_files import write_regions_geojson
from mrm.reps.summary import count_vertices

NAME = "polygonize"
HELP = "label image (.png .pgm .npz) to one polygon per region, boundaries shared exactly (.geojson)"

INPUTS = LABEL_READ_EXTENSIONS
OUTPUTS = (".geojson", ".json")


def add_arguments(parser: argparse.ArgumentParser) -> None:
    """Add the inputs, ``-o OUT``, ``--jobs`` and ``--limit``."""
    add_batch_arguments(
        parser, "label images (.png grey or palette, .pgm, .npz)", "the GeoJSON file to write"
    )
    add_limit_argument(parser)


def read_labels(path: str, limit: int) -> LabelMap:
    """Read an integer label image (see the module docstring): the library's reader, the GUI's too."""
    extension_of(path, INPUTS, "label image")
    return read_label_map(path, limit=limit)


def polygonize_file(path: str, output: str, model: str | None, limit: int) -> dict[str, Any]:
    """Polygonize one label image and write its features; return its summary (batch workers call it)."""
    lm = read_labels(path, limit)
    chosen = model or "gauss"
    t0 = time.perf_counter()
    regions = polygonize(lm, model=chosen)
    seconds = time.perf_counter() - t0
    write_regions_geojson(regions, output)
    return {
        "input": str(path),
        "output": str(output),
        "model": chosen,
        "labels": len({r.label for r in regions}),
        "regions": len(regions),
        "pixels": sum(r.pixels for r in regions),
        "vertices": sum(count_vertices(r.geometry) for r in regions),
        "seconds": seconds,
    }


def _line(f: dict[str, Any]) -> str:
    return f"{f['input']} -> {f['output']}: {f['regions']} regions, {f['seconds']:.3f} s"


def run(args: argparse.Namespace) -> dict[str, Any]:
    """Polygonize every label image and write the features; return the summary."""
    pairs = inputs_and_outputs(args, INPUTS, "label image", OUTPUTS, ".geojson", "GeoJSON output file")
    jobs = [(i, o, args.model, args.limit) for i, o in pairs]

    def total(files: list[dict[str, Any]], errors: list[str]) -> dict[str, Any]:
        head = {"model": args.model or "gauss"}
        return batch_total(args, head, len(jobs), files, errors, ("regions", "pixels", "vertices", "seconds"))

    return run_inputs(args, polygonize_file, jobs, _line, total, first=f"polygonize {Path(pairs[0][0]).name}")
