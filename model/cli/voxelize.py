"""``mrm voxelize MESH... -o OUT``: the exact discretization D of a polyhedron, written as voxels (§11).

``MESH`` is a closed triangle mesh (.obj, .ply, .off, .stl), read and validated exactly
(:func:`mrm.io.mesh_files.read_mesh`): an open, non-manifold, self-intersecting or inverted mesh, or one with
NaN or infinite coordinates, is refused with one line naming the file and where it is wrong, exit status 2,
and nothing is written. The voxels (:func:`mrm.geometry.discretize.voxels.voxelize`, exact in the three
models) go to a voxel file (.npz, multi-page .tif/.tiff, .nii, .nii.gz) that keeps their place on the grid.

``--limit N`` bounds the voxels of the result's bounding box (checked before any array is made). Several
inputs (files, directories, quoted globs; ``--jobs N`` workers) need ``-o`` to be a directory (``NAME.obj``
gives ``NAME.npz``) or a pattern holding ``{stem}``, as for the other batch subcommands.

The summary (``--json``) holds ``input``, ``output`` and the keys of ``mrm info`` for 3D inputs (``voxels``,
``bbox``, ``components``, ``cavities``, ``tunnels``, ``euler``, ``surfels``, ``plane_segments``, and the
input polyhedron's ``faces`` and ``vertices``), plus ``seconds``.
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
    inputs_and_outputs,
    run_inputs,
    voxel_limit,
)
from mrm.cli._project_input import add_object_argument
from mrm.geometry.discretize.voxels import voxelize
from mrm.io.mesh_files import MESH_EXTENSIONS, read_mesh
from mrm.io.voxel_files import VOXEL_EXTENSIONS, write_voxels
from mrm.reps.summary import summarize_voxels

NAME = "voxelize"
#: What ``-o -`` writes without ``--format``.
STDOUT_FORMAT = ".npz"
HELP = "3D: discretize a closed mesh (.obj .ply .off .stl) into a voxel file (.npz .tif .nii .nii.gz)"

INPUTS = MESH_EXTENSIONS
OUTPUTS = VOXEL_EXTENSIONS
_SUM_KEYS = ("voxels", "surfels", "seconds")


def add_arguments(parser: argparse.ArgumentParser) -> None:
    """Add the inputs, ``-o OUT``, ``--jobs`` and ``--limit``."""
    add_batch_arguments(
        parser,
        "closed triangle meshes (.obj .ply .off .stl)",
        "the voxel file (.npz .tif .tiff .nii .nii.gz)",
    )
    add_limit_argument(parser, voxels=True)
    add_object_argument(parser)


def voxelize_file(
    path: str, output: str, model: str | None, limit: int | None, object_name: str | None = None
) -> dict[str, Any]:
    """Read one mesh (or one object of an OBJ file), voxelize it, write the voxels; return the summary.

    A module-level function: batch workers call it.
    """
    chosen = model or "standard"
    # validated exactly: an invalid mesh stops here, before anything is written
    poly = read_mesh(path, object_name=object_name)
    t0 = time.perf_counter()
    vs = voxelize(poly, chosen, limit=voxel_limit(limit))
    seconds = time.perf_counter() - t0
    Path(output).parent.mkdir(parents=True, exist_ok=True)
    write_voxels(vs, output)
    summary: dict[str, Any] = {"input": str(path), "output": str(output)}
    summary.update(summarize_voxels(vs, chosen, faces=poly.n_faces, vertices=poly.n_vertices))
    summary["seconds"] = seconds
    return summary


def _line(f: dict[str, Any]) -> str:
    return f"{f['input']} -> {f['output']}: {f['voxels']} voxels, {f['seconds']:.3f} s"


def run(args: argparse.Namespace) -> dict[str, Any]:
    """Voxelize every input and write it; return the summary (several inputs: ``files`` and totals)."""
    pairs = inputs_and_outputs(args, INPUTS, "mesh file", OUTPUTS, ".npz", "voxel output file")
    jobs = [(i, o, args.model, args.limit, args.object) for i, o in pairs]

    def total(files: list[dict[str, Any]], errors: list[str]) -> dict[str, Any]:
        head = {"model": args.model or "standard"}
        return batch_total(args, head, len(jobs), files, errors, _SUM_KEYS)

    return run_inputs(args, voxelize_file, jobs, _line, total, first=f"voxelize {Path(pairs[0][0]).name}")
