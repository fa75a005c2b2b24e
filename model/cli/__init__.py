"""The headless ``mrm`` subcommands (docs/design.md §9).

Each subcommand lives in its own module of this package and defines::

    NAME: str                       # the subcommand, e.g. "discretize"
    HELP: str                       # one line for ``mrm --help``
    def add_arguments(parser): ...  # its own options (the common ones are added here)
    def run(args) -> dict | None:   # does the work; returns the --json summary (or None)

Modules are discovered automatically, so adding a subcommand never edits this file.

Conventions every subcommand gets from this layer (docs/adr/0011):

* ``--model``, ``--json`` and ``--quiet`` on every subcommand; ``mrm --version``.
* ``-`` as an input reads standard input (the format is recognised from its first bytes) and ``-o -`` writes
  the result on standard output (``--format`` chooses its type; the text summary then goes to stderr).
* The folder an output file goes into is created when missing, by every subcommand alike; a run that fails
  removes the folders it created when nothing was written into them.
* Errors are one line ``mrm NAME: error: message`` on stderr with exit status 2, never a traceback: every
  :class:`mrm.core.errors.MRMError`, every ``OSError`` (read-only file system, full disk, symlink loop, name
  too long, a path through a regular file, …) and every number out of range.
* A closed standard output (``mrm … | head``) ends the command quietly with status 141 (128 + SIGPIPE, what a
  shell reports for a program killed by the closed pipe).
"""

from __future__ import annotations

import argparse
import contextlib
import errno
import importlib
import json
import os
import pkgutil
import shutil
import sys
import tempfile
from collections.abc import Iterator
from pathlib import Path
from typing import Any

from mrm.cli._interpreted import interpret_small_inputs
from mrm.core.errors import MRMError
from mrm.core.models import Model
from mrm.core.version import foreign_owner, installed_version
from mrm.warmup import watch_compiles

#: Exit status after a closed standard output.
EXIT_BROKEN_PIPE = 141
#: The exit status after Ctrl+C (128 + SIGINT), as shells report it.
EXIT_INTERRUPTED = 130


#: Largest standard input read for ``-`` (the same order as the largest input files the readers take).
MAX_STDIN_BYTES = 1 << 30


def _file_commands() -> tuple[str, ...]:
    """The subcommands written as modules of this package (``info``, ``reconstruct``, ``union`` …)."""
    return tuple(
        info.name.replace("_", "-")
        for info in pkgutil.iter_modules(__path__)
        if not info.name.startswith("_")
    )


def _command_modules() -> dict[str, Any]:
    """Every subcommand: the modules of this package, and one per one-object operation of the registry.

    Imported here, when a parser is built, not when the package is: ``mrm --version`` must not load numba.
    """
    from mrm.cli._operation import operation_command
    from mrm.ops.registry import operations

    mods: dict[str, Any] = {}
    for info in pkgutil.iter_modules(__path__):
        if info.name.startswith("_"):
            continue
        mod = importlib.import_module(f"{__name__}.{info.name}")
        name = getattr(mod, "NAME", None)
        if isinstance(name, str):
            mods[name] = mod
    for spec in operations():
        if spec.command and spec.command not in mods and spec.arity == 1:
            mods[spec.command] = operation_command(spec)
    return dict(sorted(mods.items()))


def is_subcommand(word: str) -> bool:
    """True when ``word`` names a subcommand (a module of this package, or an operation's command)."""
    if word in _file_commands():
        return True
    if not word or word.startswith("-") or "." in word or os.sep in word:
        return False  # an option or a path: no need to load the registry to know
    from mrm.ops.registry import operations

    return any(spec.command == word for spec in operations())


class _Parser(argparse.ArgumentParser):
    """An ArgumentParser whose usage errors exit with status 2 and a one-line message (argparse's default)."""


def version_text() -> str:
    """``mrm X.Y.Z`` (the installed distribution's version)."""
    return f"mrm {installed_version()}"


def build_parser() -> argparse.ArgumentParser:
    """Return the parser of every subcommand, each with ``--model``, ``--json`` and ``--quiet``."""
    parser = _Parser(
        prog="mrm",
        description="MR Modeler: multi-representation discrete geometry in 2D (pixels, polygons) "
        "and 3D (voxels, meshes).",
    )
    parser.add_argument("--version", action="version", version=version_text())
    sub = parser.add_subparsers(dest="command", metavar="COMMAND")
    for name, mod in _command_modules().items():
        p = sub.add_parser(name, help=getattr(mod, "HELP", ""), description=getattr(mod, "HELP", ""))
        p.add_argument(
            "--model",
            choices=Model.names(),
            default=None,
            help=getattr(mod, "MODEL_HELP", "discretization model (default: the project's, or 'standard')"),
        )
        p.add_argument("--json", action="store_true", help="print a machine-readable summary on stdout")
        p.add_argument(
            "-q", "--quiet", action="store_true", help="no progress bar and no per-file lines on stderr"
        )
        mod.add_arguments(p)
        if any(a.dest == "output" for a in p._actions):
            p.add_argument(
                "--format",
                metavar="EXT",
                default=None,
                help="with -o -: the type written on stdout, e.g. .geojson, .wkt, .png "
                f"(default {getattr(mod, 'STDOUT_FORMAT', '.geojson')})",
            )
        p.set_defaults(_module=mod)
    return parser


def _json_default(o: Any) -> Any:
    import numpy as np

    if isinstance(o, np.integer):
        return int(o)
    if isinstance(o, np.floating):
        return float(o)
    if isinstance(o, np.ndarray):
        return o.tolist()
    raise TypeError(f"not JSON serialisable: {type(o).__name__}")


def silence_stdout() -> None:
    """Point stdout at devnull so that the interpreter's final flush prints no BrokenPipeError either."""
    with contextlib.suppress(OSError, ValueError):
        os.dup2(os.open(os.devnull, os.O_WRONLY), sys.stdout.fileno())


def os_error_text(e: OSError) -> str:
    """One line for an OSError: its reason and the file(s) it names (``errno`` wording, no traceback)."""
    reason = e.strerror or (errno.errorcode.get(e.errno, "") if e.errno else "") or str(e) or type(e).__name__
    if e.filename is not None:
        names = os.fsdecode(e.filename)
        if getattr(e, "filename2", None) is not None:
            names += f" -> {os.fsdecode(e.filename2)}"
        return f"{reason}: {names}"
    return reason


def _sniff(head: bytes) -> str:
    """The file extension of standard input's content, from its first bytes."""
    if head.startswith(b"\x89PNG"):
        return ".png"
    if head[:2] in (b"P1", b"P2", b"P3", b"P4", b"P5", b"P6"):
        return ".pgm"  # the Netpbm reader reads P1-P6 whatever the extension
    if head.startswith(b"PK"):
        return ".npz"
    if head[:4] in (b"II*\x00", b"MM\x00*"):
        return ".tif"
    text = head.lstrip()
    if text[:1] in (b"{", b"["):
        return ".geojson"
    return ".wkt"


class _Streams:
    """Temporary files standing for ``-`` (standard input, standard output) during one command."""

    def __init__(self) -> None:
        self.tmp: str | None = None
        self.stdin_path: str | None = None
        self.stdout_path: str | None = None

    def _dir(self) -> str:
        if self.tmp is None:
            self.tmp = tempfile.mkdtemp(prefix="mrm-")
        return self.tmp

    def stdin(self) -> str:
        if self.stdin_path is None:
            data = sys.stdin.buffer.read(MAX_STDIN_BYTES + 1)
            if len(data) > MAX_STDIN_BYTES:
                raise MRMError(f"standard input holds more than {MAX_STDIN_BYTES >> 20} MB")
            if not data:
                raise MRMError("standard input is empty")
            self.stdin_path = os.path.join(self._dir(), "stdin" + _sniff(data[:64]))
            Path(self.stdin_path).write_bytes(data)
        return self.stdin_path

    def stdout(self, ext: str) -> str:
        self.stdout_path = os.path.join(self._dir(), "stdout" + ext)
        return self.stdout_path

    def close(self) -> None:
        if self.tmp is not None:
            shutil.rmtree(self.tmp, ignore_errors=True)


def _bind_streams(args: argparse.Namespace, streams: _Streams) -> None:
    """Replace ``-`` in the inputs by standard input's content and ``-o -`` by a temporary file."""
    for key in ("input", "first", "second"):
        if getattr(args, key, None) == "-":
            setattr(args, key, streams.stdin())
    if isinstance(getattr(args, "inputs", None), list) and "-" in args.inputs:
        args.inputs = [streams.stdin() if i == "-" else i for i in args.inputs]
    if getattr(args, "output", None) == "-":
        if args.json:
            raise MRMError("-o - and --json would both write on stdout; choose one")
        ext = args.format or getattr(args._module, "STDOUT_FORMAT", ".geojson")
        ext = ext if ext.startswith(".") else "." + ext
        args.output = streams.stdout(ext.lower())
    elif getattr(args, "format", None) is not None:
        raise MRMError("--format applies to -o - only (a file's extension gives its type)")


def _output_folder(args: argparse.Namespace) -> Path | None:
    """The folder the output goes into: a file's parent, a batch's directory, a pattern's parent."""
    out = getattr(args, "output", None)
    if not isinstance(out, str) or not out:
        return None
    if "{stem}" in out:
        return Path(out.split("{stem}", 1)[0] + "x").parent
    target = Path(out)
    if out.endswith(("/", os.sep)) or (not target.suffix and getattr(args, "inputs", None)):
        return target  # a batch's output directory
    return target.parent


def _missing_folders(folder: Path | None) -> list[Path]:
    """``folder`` and its ancestors that do not exist yet, deepest first (what this run may create)."""
    missing: list[Path] = []
    p = folder
    while p is not None and p != p.parent and not p.exists() and not p.is_symlink():
        missing.append(p)
        p = p.parent
    return missing


def _make_output_folder(args: argparse.Namespace) -> None:
    """Create the folder an output file goes into (every subcommand alike; ADR 0011).

    A batch's directory is left to the subcommand, which creates it when it writes the first file.
    """
    folder = _output_folder(args)
    out = getattr(args, "output", None)
    if folder is None or (isinstance(out, str) and ("{stem}" in out or folder == Path(out))):
        return
    folder.mkdir(parents=True, exist_ok=True)


def _remove_if_empty(folders: list[Path]) -> None:
    """Remove the folders a failed run created and left empty, deepest first (never one holding a file)."""
    for p in folders:
        try:
            p.rmdir()  # fails on a folder that holds anything: what was written stays
        except OSError:
            return


@contextlib.contextmanager
def _stdout_to_stderr(active: bool) -> Iterator[None]:
    if not active:
        yield
        return
    with contextlib.redirect_stdout(sys.stderr):
        yield


#: Subcommands that never call a compiled kernel (no first-run notice for them).
NO_KERNELS = frozenset({"bounds"})


def run_cli(argv: list[str]) -> int:
    """Parse ``argv`` (without the program name), run the subcommand, return the exit status."""
    try:
        return _run_cli(argv)
    except BrokenPipeError:
        silence_stdout()
        return EXIT_BROKEN_PIPE


def _run_cli(argv: list[str]) -> int:
    # Before the parser imports the commands (and numba): a small input on a cold cache runs interpreted.
    interpret_small_inputs(argv)
    parser = build_parser()
    args = parser.parse_args(argv)
    if getattr(args, "_module", None) is None:
        parser.print_help()
        return 2
    streams = _Streams()
    # One line on stderr as soon as numba really compiles a kernel (a fresh install, an edited kernel), never
    # on a warm run; --quiet silences it (docs/adr/0051).
    watching = (
        watch_compiles(args.command, quiet=args.quiet)
        if args.command not in NO_KERNELS
        else contextlib.nullcontext()
    )
    created: list[Path] = []
    status = 2
    try:
        _bind_streams(args, streams)
        created = _missing_folders(_output_folder(args))
        _make_output_folder(args)
        with watching, _stdout_to_stderr(streams.stdout_path is not None):
            summary = args._module.run(args)
        if streams.stdout_path is not None:
            with open(streams.stdout_path, "rb") as fh:
                shutil.copyfileobj(fh, sys.stdout.buffer)
            sys.stdout.buffer.flush()
    except MRMError as e:
        return _fail(args.command, str(e))
    except BrokenPipeError:
        raise
    except OSError as e:
        return _fail(args.command, os_error_text(e))
    except (OverflowError, ZeroDivisionError) as e:
        return _fail(args.command, f"a number is out of range (a coordinate or parameter too large): {e}")
    except MemoryError:
        return _fail(args.command, "not enough memory for this input (try a smaller --limit)")
    except KeyboardInterrupt:  # Ctrl+C: what was being written is not kept (atomic writes), no traceback
        print(f"mrm {args.command}: interrupted", file=sys.stderr)
        return EXIT_INTERRUPTED
    else:
        status = 0
    finally:
        streams.close()
        if status != 0:
            _remove_if_empty(created)  # a failed run leaves no empty output folder behind
    if args.json and summary is not None:
        print(json.dumps(summary, default=_json_default), flush=True)
    return 0


def _fail(command: str, message: str) -> int:
    print(f"mrm {command}: error: {message}", file=sys.stderr)
    return 2


def run_headless(args: list[str]) -> int | None:
    """``--version`` or a subcommand, run; None when ``args`` are neither (the desktop's, or help)."""
    if args[:1] in (["--version"], ["-V"]):
        print(version_text(), flush=True)
        foreign = foreign_owner()
        if foreign is not None:  # its files overwrite ours: say it where a puzzled user looks first
            print(
                f"mrm: warning: the unrelated distribution '{foreign}' is installed too and writes into "
                "the same 'mrm' package and command; uninstall both and reinstall MR Modeler "
                "(pip's name: mr-modeler)",
                file=sys.stderr,
            )
        return 0
    if args and is_subcommand(args[0]):
        return run_cli(args)
    return None


def main(argv: list[str] | None = None) -> int:
    """``python -m mrm``: a headless subcommand, ``--version`` or ``--help``.

    The ``mrm`` command is :func:`mrm.app.main.main`, which also starts the desktop application (the ``gui``
    extra); this layer never imports it.
    """
    args = list(sys.argv[1:] if argv is None else argv)
    try:
        status = run_headless(args)
        if status is not None:
            return status
        build_parser().print_help()
        sys.stdout.flush()
        return 0 if args[:1] in (["-h"], ["--help"]) else 2
    except BrokenPipeError:
        silence_stdout()
        return EXIT_BROKEN_PIPE
