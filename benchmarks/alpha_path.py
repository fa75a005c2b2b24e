"""The path of the Operations panel's α to the kernel, traced: files, calls, parses and checks (issue 27).

The panel's α field is typed "2.5" and committed; Apply makes the parameters and runs the operation as the
worker does (``plan_operation``) up to the compiled discretization. Every call into MR Modeler's code on that
path is recorded (``sys.setprofile``); a call is on *the α's path* when one of its arguments holds the α — the
text, the exact 5/2, the parameters object, the similarity made from it — and each of those calls is listed
with its file. Also counted: the parses (``read_number`` given something other than a Fraction) and the range
checks (``ParamSpec.read`` of a number).

Run: ``QT_QPA_PLATFORM=offscreen .venv/bin/python benchmarks/alpha_path.py`` (prints a table; ``--json``).
"""

from __future__ import annotations

import argparse
import json
import os
import sys
from fractions import Fraction
from pathlib import Path
from typing import Any

os.environ.setdefault("QT_QPA_PLATFORM", "offscreen")

from PySide6 import QtWidgets

from mrm.core.grids import PixelSet
from mrm.document import Document
from mrm.document.commands import AddObject
from mrm.geometry.discretize.exact_shape import Similarity
from mrm.ops.registry import plan_operation
from mrm.ops.scaling import DSSParams
from mrm.views.op_adapter import operations
from mrm.views.operation_panel import ParamControl

ROOT = Path(__file__).resolve().parents[1]
ALPHA_TEXT = "2.5"
ALPHA = Fraction(5, 2)


def _holds_alpha(value: Any, depth: int = 0) -> bool:
    if value is None or depth > 2:
        return False
    if isinstance(value, str):
        return value.strip() == ALPHA_TEXT
    if isinstance(value, Fraction | float):
        return value == ALPHA
    if isinstance(value, DSSParams):
        return value.alpha == ALPHA
    if isinstance(value, Similarity):
        return value.ratio == ALPHA
    if isinstance(value, dict):
        return any(_holds_alpha(v, depth + 1) for v in value.values())
    if isinstance(value, list | tuple):
        return any(_holds_alpha(v, depth + 1) for v in value[:8])
    return False


def _ours(filename: str) -> str | None:
    p = Path(filename).resolve()
    for top in ("model", "views", "app"):
        base = ROOT / top
        if p.is_relative_to(base):
            return f"{top}/{p.relative_to(base)}"
    return None


def trace() -> dict[str, Any]:
    app = QtWidgets.QApplication.instance() or QtWidgets.QApplication([])
    op = next(o for o in operations() if o.name == "dss")
    alpha_info = next(p for p in op.params if p.name == "alpha")
    doc = Document()
    obj = doc.make_object(PixelSet.box(0, 0, 9, 6), "A")
    doc.push(AddObject(obj))
    control = ParamControl(alpha_info)

    calls: list[tuple[str, str]] = []
    parses = checks = 0
    to_kernel: list[str] = []  # the Python frames on the stack when the compiled discretization is entered

    def profile(frame: Any, event: str, arg: Any) -> None:
        nonlocal parses, checks, to_kernel
        if event != "call":
            return
        code = frame.f_code
        where = _ours(code.co_filename)
        if where is None:
            return
        if where.endswith(("discretize/rational_kernels.py", "discretize/_kernels.py")) and not to_kernel:
            f, stack = frame, []
            while f is not None:
                w = _ours(f.f_code.co_filename)
                if w is not None:
                    stack.append(f"{w}:{f.f_code.co_name}")
                f = f.f_back
            to_kernel = stack[::-1]
        args = [frame.f_locals.get(n) for n in code.co_varnames[: code.co_argcount + code.co_kwonlyargcount]]
        if code.co_name == "read_number" and args and not isinstance(args[0], Fraction):
            parses += 1
        if code.co_name == "_read_number" and where.endswith("core/params.py"):
            checks += 1
        if any(_holds_alpha(a) for a in args):
            calls.append((where, code.co_name))

    sys.setprofile(profile)
    try:
        # 1. the user types 0.2 in the α field and commits it (Enter)
        control.field.setText(ALPHA_TEXT)
        control.field.editingFinished.emit()
        # 2. Apply: the panel's values become the operation's parameters, then the worker's job
        params = op.spec.params.read(alpha=control.value(), center=None, model="standard")
        plan_operation([obj], op.spec, params)
    finally:
        sys.setprofile(None)
    app.processEvents()
    files = sorted({f for f, _ in calls})
    # The path proper: the field's commit and parse, then the frames that lead to the kernel.
    parse = [f"{f}:{fn}" for f, fn in calls if f.startswith("views/") or f.startswith("model/core/")]
    main_path = list(
        dict.fromkeys(parse[: parse.index("views/operation_panel.py:_field_changed") + 1] + to_kernel)
    )
    return {
        "calls": len(calls),
        "files": files,
        "parses": parses,
        "checks": checks,
        "path": [f"{f}:{fn}" for f, fn in calls],
        "to_kernel": main_path,
        "to_kernel_files": sorted({p.split(":")[0] for p in main_path}),
    }


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--json", action="store_true")
    args = ap.parse_args()
    out = trace()
    if args.json:
        print(json.dumps(out, indent=1))
        return
    print(f"α typed as {ALPHA_TEXT!r} in the Operations panel (DSS_α), to the compiled discretization:")
    print(f"  the path to the kernel: {len(out['to_kernel'])} calls in {len(out['to_kernel_files'])} files")
    for p in out["to_kernel"]:
        print(f"    {p}")
    print(
        f"  every call holding the α (with the provenance, the label, the bound): {out['calls']}, in "
        f"{len(out['files'])} files"
    )
    print(f"  parses (text or float read into an exact number): {out['parses']}")
    print(f"  range checks (a parameter's declaration reading a number): {out['checks']}")
    for f in out["files"]:
        n = sum(1 for p in out["path"] if p.startswith(f + ":"))
        print(f"    {f}  ({n} calls)")


if __name__ == "__main__":
    main()
