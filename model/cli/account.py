"""``mrm account PROJECT --object NAME``: the error account of a result, as the inspector shows it.

The chain that made the object (from its pinned provenance), the paper's bound, the exact measured Hausdorff
distance and the pixels that differ from the direct result — :func:`mrm.ops.account.account_of`, the one
function the inspector and the operation subcommands use, so ``--json`` prints the inspector's numbers.
"""

from __future__ import annotations

import argparse
from typing import Any

from mrm.cli._common import print_table
from mrm.core.errors import ParameterError
from mrm.io.project import read_project
from mrm.ops.account import account_of

NAME = "account"
HELP = "the error account of an object of a project: chain, bound, exact measured error, differing pixels"


def add_arguments(parser: argparse.ArgumentParser) -> None:
    """Add PROJECT, ``--object`` and ``--no-measure``."""
    parser.add_argument("project", metavar="PROJECT", help="a project file (.mrm)")
    parser.add_argument("--object", metavar="NAME", required=True, help="the object to account for")
    parser.add_argument(
        "--no-measure", action="store_true", help="the chain and the bound only (no Hausdorff distance)"
    )


def run(args: argparse.Namespace) -> dict[str, Any]:
    """Print the account (or, with --json, return it)."""
    project = read_project(args.project)
    objs = [o for o in project.objects if o.name == args.object]
    if not objs:
        raise ParameterError(f"{args.project}: no object named {args.object!r}")
    if len(objs) > 1:
        raise ParameterError(f"{args.project}: {len(objs)} objects are named {args.object!r}")
    obj = objs[0]
    if obj.provenance is None:
        raise ParameterError(f"{args.object!r} was drawn or imported: it has no provenance to account for")
    summary = {
        "object": obj.name,
        "id": obj.id,
        # under the project's compact limit: the R of voxel sets its operations used (ADR 0073)
        **account_of(
            obj.provenance, measure=not args.no_measure, compact_limit=project.settings.compact_limit
        ).summary(),
    }
    if not args.json:
        print_table({k: v for k, v in summary.items() if k not in ("steps", "parts")})
    return summary
