"""Helpers shared by the ``mrm`` subcommands: argument types, reading inputs, the text table.

Subcommands that take one object read it with :func:`load_object` (a thin layer over
:func:`mrm.cli._project_input.load_input`, which picks a project's object with ``--object NAME``);
:func:`project_objects` gives every object of a project, for the commands that can take them all.
:func:`read_input` is the older all-objects reader, kept for the commands that still use it.

The command-line conventions every subcommand shares (docs/adr/0011) are argument helpers here:
:func:`add_inputs_argument` + :func:`expand_inputs` (files, directories, quoted globs, ``-``),
:func:`add_jobs_argument` (``--jobs``, capped at the CPU count), :func:`add_image_arguments`
(``--threshold``, ``--invert``), :func:`progress` (a bar on stderr for work over a second) and
:func:`run_batch` (several inputs over worker processes, each result reported as soon as it is done).

(A module whose name starts with "_" is not a subcommand.)
"""

from __future__ import annotations

import argparse
import glob
import math
import os
import sys
import threading
from collections.abc import Callable, Iterator, Sequence
from concurrent.futures import FIRST_COMPLETED, Future, ProcessPoolExecutor, wait
from contextlib import contextmanager
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from mrm.cli import os_error_text
from mrm.cli._project_input import PROJECT_EXTENSIONS, Kind, load_input
from mrm.core.errors import FileFormatError, MRMError, ParameterError
from mrm.core.grids import PixelSet, VoxelSet
from mrm.core.limits import DEFAULT_PIXEL_LIMIT, DEFAULT_VOXEL_LIMIT, check_compact_limit
from mrm.core.progress import Progress
from mrm.geometry.discretize import discretize
from mrm.io.georef import image_frame as frame_of
from mrm.io.pixel_files import PIXEL_EXTENSIONS, read_pixels
from mrm.io.project import read_project
from mrm.io.vector_files import VECTOR_EXTENSIONS, combine, read_geometry

PROJECT_EXTENSION = PROJECT_EXTENSIONS[0]


@dataclass
class Input:
    """What a subcommand read: a geometry, a pixel set, or the objects of a project.

    Attributes
    ----------
    kind : {"euclidean", "discrete", "project"}
    geometry : shapely geometry or None
        The Euclidean input; for a project, its Euclidean objects combined (None if it has none).
    pixels : PixelSet or None
        The discrete input; for a project, None (its objects are discretized under the chosen model).
    model : str or None
        The project's model, else None.
    objects : list
        A project's objects (``mrm.document.DocObject``), else empty.
    """

    kind: str
    geometry: Any = None
    pixels: PixelSet | None = None
    model: str | None = None
    objects: list[Any] = field(default_factory=list)


def positive_int(text: str) -> int:
    """Argparse type: an integer ≥ 1 (underscores allowed, e.g. 200_000_000)."""
    try:
        value = int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected a positive integer, got {text!r}") from None
    if value < 1:
        raise argparse.ArgumentTypeError(f"expected a positive integer, got {text!r}")
    return value


def compact_limit_int(text: str) -> int:
    """Argparse type of ``--compact-limit``: :func:`mrm.core.limits.check_compact_limit` of an integer."""
    try:
        return check_compact_limit(int(text))
    except (ValueError, ParameterError) as e:
        detail = str(e) if isinstance(e, ParameterError) else f"expected a whole number, got {text!r}"
        raise argparse.ArgumentTypeError(detail) from None


def cpu_count() -> int:
    """The CPUs this process may run on (its affinity mask where the system has one)."""
    try:
        return max(1, len(os.sched_getaffinity(0)))
    except (AttributeError, OSError):
        return max(1, os.cpu_count() or 1)


def jobs_count(text: str) -> int:
    """Argparse type of ``--jobs``: a positive integer, capped at the CPU count (more would only thrash)."""
    return min(positive_int(text), cpu_count())


def add_jobs_argument(parser: argparse.ArgumentParser) -> None:
    """Add ``--jobs N``: worker processes for several inputs (at most the CPU count)."""
    parser.add_argument(
        "-j",
        "--jobs",
        type=jobs_count,
        default=1,
        metavar="N",
        help=f"worker processes for several inputs (capped at the CPU count, {cpu_count()} here)",
    )


def add_image_arguments(parser: argparse.ArgumentParser) -> None:
    """Add ``--threshold T`` and ``--invert`` (how a grey or colour image becomes a pixel set)."""
    parser.add_argument(
        "--threshold",
        type=finite_float,
        default=None,
        metavar="T",
        help="grey images: pixels brighter than T are in the set (default: binary images as they are, "
        "others at Otsu's threshold)",
    )
    parser.add_argument(
        "--invert",
        action="store_true",
        help="take the dark pixels instead (black-on-white drawings, potrace's convention)",
    )


def add_inputs_argument(parser: argparse.ArgumentParser, help: str) -> None:
    """Add the positional ``IN...``: files, directories, quoted globs (``'scans/*.png'``) or ``-``."""
    parser.add_argument(
        "inputs",
        nargs="+",
        metavar="IN",
        help=help + "; a directory stands for its files of those types, a quoted glob for its matches "
        "(also on shells that do not expand them), - for standard input",
    )


def add_output_argument(parser: argparse.ArgumentParser, what: str, *, batch: bool = True) -> None:
    """Add ``-o OUT``: ``what`` to write or, with ``batch``, for several inputs a directory or a pattern."""
    more = "; for several inputs a directory or a pattern holding {stem}" if batch else ""
    parser.add_argument("-o", "--output", required=True, metavar="OUT", help=what + more)


def add_batch_arguments(parser: argparse.ArgumentParser, inputs: str, output: str) -> None:
    """Add ``IN...`` (``inputs`` says what they are), ``-o OUT`` (``output`` one result) and ``--jobs``."""
    add_inputs_argument(parser, inputs)
    add_output_argument(parser, output)
    add_jobs_argument(parser)


def expand_inputs(items: Sequence[str], allowed: tuple[str, ...]) -> list[str]:
    """The input files named by ``items``: files as they are, directories and globs expanded.

    A directory gives its regular files (not recursive) whose extension is in ``allowed``, sorted by name;
    a pattern holding ``*``, ``?`` or ``[`` that names no existing file gives its matches (``**`` recurses),
    sorted. ``-`` (standard input) is kept as it is. Nothing matched is an error naming the item.
    """
    out: list[str] = []
    for item in items:
        p = Path(item)
        if item == "-" or p.is_file():
            out.append(item)
        elif p.is_dir():
            found = sorted(str(c) for c in p.iterdir() if has_extension(c, allowed) and c.is_file())
            if not found:
                raise ParameterError(f"{item}: the directory holds no {' '.join(allowed)} file")
            out.extend(found)
        elif any(ch in item for ch in "*?[") and not p.exists():
            matches = sorted(m for m in glob.glob(item, recursive=True) if Path(m).is_file())
            if not matches:
                raise ParameterError(f"{item}: no file matches this pattern")
            out.extend(matches)
        else:
            out.append(item)  # the reader reports it (no such file, a FIFO, …) with its own message
    return out


def has_extension(path: str | os.PathLike[str], allowed: tuple[str, ...]) -> bool:
    """True when ``path`` ends with one of ``allowed`` (a double extension such as ``.nii.gz`` whole)."""
    name = Path(path).name.lower()
    return any(name.endswith(a) for a in allowed if a.count(".") > 1) or Path(path).suffix.lower() in allowed


def stem_of(path: str | os.PathLike[str]) -> str:
    """The file's name without its extension (``brain.nii.gz`` gives ``brain``)."""
    name = Path(path).name
    if name.lower().endswith(".nii.gz"):
        return name[: -len(".nii.gz")]
    return Path(path).stem


def batch_outputs(
    inputs: list[str], output: str, allowed: tuple[str, ...], default_ext: str, what: str = "output file"
) -> list[str]:
    """The output path of each input, checked before any work.

    One input: ``output`` is the file (its extension one of ``allowed``). Several: ``output`` is a directory
    (existing, or ending with a separator, or without an extension: created), where input ``NAME.x`` gives
    ``NAME`` + ``default_ext``, or a pattern holding ``{stem}`` (the input's name without its extension).
    """
    if len(inputs) == 1 and "{stem}" not in output:
        extension_of(output, allowed, what)
        return [output]
    if "{stem}" in output:
        outs = [output.replace("{stem}", stem_of(i)) for i in inputs]
        for o in outs:
            extension_of(o, allowed, what)
    else:
        p = Path(output)
        if (p.exists() and not p.is_dir()) or (not p.exists() and p.suffix and not output.endswith(os.sep)):
            raise ParameterError(
                f"{output}: several inputs need a directory or a pattern with {{stem}} for -o"
            )
        outs = [str(p / (stem_of(i) + default_ext)) for i in inputs]
    if len(set(outs)) != len(outs):
        raise ParameterError("two inputs would write the same output file; use a pattern with {stem}")
    return outs


def inputs_and_outputs(
    args: argparse.Namespace,
    inputs: tuple[str, ...],
    what: str,
    outputs: tuple[str, ...],
    default_ext: str,
    output_what: str,
) -> list[tuple[str, str]]:
    """Each input of a batch subcommand with its output path, every one checked before any work.

    The inputs are ``args.inputs`` expanded (:func:`expand_inputs`), each of a type in ``inputs`` (else the
    message names it as a ``what``); the outputs come from ``-o`` (:func:`batch_outputs`).
    """
    found = expand_inputs([str(i) for i in args.inputs], inputs)
    for i in found:
        extension_of(i, inputs, what)
    outs = batch_outputs(found, str(args.output), outputs, default_ext, output_what)
    return list(zip(found, outs, strict=True))


class _Bar:
    """A progress bar (tqdm) that redraws itself while work without progress reports runs."""

    def __init__(self, bar: Any) -> None:
        self.bar = bar
        self._drawn = False
        self._stop = threading.Event()
        self._thread: threading.Thread | None = None
        if bar.total is None or bar.total == 1:
            self._thread = threading.Thread(target=self._tick, daemon=True)
            self._thread.start()

    def _tick(self) -> None:
        # Nothing before one second (quick commands stay silent), then a redraw twice a second.
        if self._stop.wait(1.0):
            return
        while True:
            self._drawn = True
            self.bar.refresh()
            if self._stop.wait(0.5):
                return

    def update(self, fraction: float | None = None, message: str | None = None) -> None:
        """``ProgressLike``: move to ``fraction`` (of a one-unit bar) and show ``message``."""
        if fraction is not None and self.bar.total:
            self.bar.n = min(self.bar.total, fraction * self.bar.total)
        if message:
            self.bar.set_postfix_str(message, refresh=False)
        self.bar.refresh()

    def advance(self, n: int = 1) -> None:
        """One more unit (a file) done."""
        self.bar.update(n)

    def write(self, line: str) -> None:
        """Print a line on stdout without breaking the bar."""
        self.bar.write(line, file=sys.stdout)

    def close(self) -> None:
        self._stop.set()
        if self._thread is not None:
            self._thread.join()
        if self._drawn:
            # tqdm clears only a bar it drew itself after its delay; ours was drawn by the ticker, so
            # clear it here, or the next line (an error message, the summary) is glued to the bar.
            self.bar.clear()
        self.bar.close()


class _NoBar:
    def update(self, fraction: float | None = None, message: str | None = None) -> None:
        pass

    def advance(self, n: int = 1) -> None:
        pass

    def write(self, line: str) -> None:
        print(line, file=sys.stdout, flush=True)

    def close(self) -> None:
        pass


def progress_enabled(args: argparse.Namespace) -> bool:
    """Whether to draw a progress bar: stderr is a terminal and ``--quiet`` was not given."""
    if getattr(args, "quiet", False):
        return False
    try:
        return sys.stderr.isatty()
    except (AttributeError, ValueError):
        return False


@contextmanager
def progress(args: argparse.Namespace, total: int | None = None, desc: str = "") -> Iterator[Any]:
    """A progress bar on stderr, shown only once the work has taken a second (tqdm's ``delay``).

    Yields an object with ``update(fraction, message)`` (the ``ProgressLike`` of :mod:`mrm.ops`),
    ``advance()`` (one of ``total`` units done) and ``write(line)`` (a result line on stdout). Without a
    terminal on stderr, or with ``--quiet``, nothing is drawn and ``write`` just prints.
    """
    if not progress_enabled(args):
        bar: Any = _NoBar()
    else:
        from tqdm import tqdm

        bar = _Bar(
            tqdm(total=total if total is not None else 1, desc=desc, delay=1.0, file=sys.stderr, leave=False)
        )
    try:
        yield bar
    finally:
        bar.close()


def interruptible(work: Callable[[Progress], Any], bar: Any = None) -> Any:
    """``work(progress)`` in a thread of its own, so that Ctrl+C stops it at once.

    Python runs a signal's handler in the main thread between two bytecodes: while a compiled kernel runs
    there (the 3D decimation: minutes with a high ``--compact-limit``), Ctrl+C waits for its end and then
    surfaces as a ``SystemError``. Here the main thread only waits; on Ctrl+C it cancels ``progress`` (the
    kernel reads its stop flag, :func:`mrm.core.progress.stop_flag`), waits for the thread to stop and
    raises ``KeyboardInterrupt`` (``mrm`` says "interrupted", exit status 130). ``bar`` gets the reports.
    """
    progress = Progress(None if bar is None else bar.update)
    outcome: list[Any] = []

    def run() -> None:
        try:
            outcome.append((True, work(progress)))
        except BaseException as e:
            outcome.append((False, e))

    thread = threading.Thread(target=run, name="mrm-work", daemon=True)
    thread.start()
    try:
        while thread.is_alive():
            thread.join(0.1)
    except KeyboardInterrupt:
        progress.cancel()
        thread.join()
        raise
    ok, value = outcome[0]
    if not ok:
        raise value
    return value


def _call(
    job: tuple[Callable[..., dict[str, Any]], tuple[Any, ...]],
) -> tuple[dict[str, Any] | None, str | None]:
    """Run one batch job in a worker; an input's error comes back as one line, never as a traceback."""
    func, job_args = job

    try:
        return func(*job_args), None
    except MRMError as e:
        return None, str(e)
    except OSError as e:
        return None, os_error_text(e)
    except (OverflowError, ZeroDivisionError) as e:
        return None, f"number out of range: {e}"
    except MemoryError:
        return None, "not enough memory"


def _one_thread_each() -> None:
    # A batch already spreads its inputs over the cores: R in each worker runs on one thread.
    os.environ["MRM_THREADS"] = "1"


def run_batch(
    args: argparse.Namespace,
    func: Callable[..., dict[str, Any]],
    jobs: Sequence[tuple[Any, ...]],
    line: Callable[[dict[str, Any]], str],
    *,
    desc: str = "",
) -> tuple[list[dict[str, Any]], list[str]]:
    """Run ``func(*job)`` for every job (one input each) and report each result as soon as it finishes.

    Parameters
    ----------
    args : argparse.Namespace
        For ``--jobs`` (worker processes), ``--quiet`` and ``--json`` (no per-file lines with ``--json``).
    func : callable
        A module-level function (it is sent to worker processes) returning the input's summary.
    jobs : sequence of tuple
        The arguments of each call; ``job[0]`` names the input in error messages.
    line : callable
        The line printed on stdout for a finished input.

    Returns
    -------
    summaries : list of dict
        The finished inputs' summaries, in input order.
    errors : list of str
        ``"INPUT: message"`` for each input that failed (each also printed on stderr when it happens).
    """
    results: dict[int, dict[str, Any]] = {}
    errors: list[tuple[int, str]] = []
    n_workers = min(getattr(args, "jobs", 1), len(jobs), cpu_count())

    def report(i: int, outcome: tuple[dict[str, Any] | None, str | None], bar: Any) -> None:
        summary, error = outcome
        bar.advance()
        if summary is not None:
            results[i] = summary
            if not args.json and not getattr(args, "quiet", False):
                bar.write(line(summary))
        else:
            name = str(jobs[i][0])
            text = error if error is not None and error.startswith(f"{name}: ") else f"{name}: {error}"
            errors.append((i, text))
            print(f"mrm {args.command}: error: {text}", file=sys.stderr, flush=True)

    with progress(args, total=len(jobs), desc=desc) as bar:
        if n_workers <= 1:
            for i, job in enumerate(jobs):
                report(i, _call((func, tuple(job))), bar)
        else:
            pool = ProcessPoolExecutor(max_workers=n_workers, initializer=_one_thread_each)
            try:
                pending: dict[Future[Any], int] = {
                    pool.submit(_call, (func, tuple(job))): i for i, job in enumerate(jobs)
                }
                while pending:
                    done, _ = wait(pending, return_when=FIRST_COMPLETED)
                    for fut in done:
                        report(pending.pop(fut), fut.result(), bar)
            finally:
                # On a closed stdout (BrokenPipeError) or Ctrl+C: do not start the inputs still queued.
                pool.shutdown(wait=True, cancel_futures=True)
    return [results[i] for i in sorted(results)], [e for _, e in sorted(errors)]


def run_inputs(
    args: argparse.Namespace,
    func: Callable[..., dict[str, Any]],
    jobs: Sequence[tuple[Any, ...]],
    line: Callable[[dict[str, Any]], str],
    total: Callable[[list[dict[str, Any]], list[str]], dict[str, Any]],
    *,
    first: str,
    hidden: tuple[str, ...] = (),
    bar: bool = False,
) -> dict[str, Any]:
    """Run a subcommand's inputs and return its ``--json`` summary: what every batch subcommand does.

    One job runs here under a progress bar named ``first`` (passed to ``func`` as ``bar=`` when ``bar``); its
    summary is printed as a table, without the ``hidden`` keys, unless ``--json``. Several jobs go through
    :func:`run_batch` (each input's line printed when it is done) and ``total(files, errors)`` makes the
    batch's summary (:func:`batch_total`, or the subcommand's own).
    """
    if len(jobs) == 1:
        with progress(args, desc=first) as shown:
            summary = func(*jobs[0], bar=shown) if bar else func(*jobs[0])
        if not args.json:
            print_table({k: v for k, v in summary.items() if k not in hidden})
        return summary
    files, errors = run_batch(args, func, jobs, line, desc=str(args.command))
    return total(files, errors)


def refuse_failures(errors: list[str], inputs: int) -> None:
    """Raise, after what succeeded was written, when some inputs of a batch failed (one line naming each)."""
    if errors:
        raise FileFormatError(f"{len(errors)} of {inputs} inputs failed: " + "; ".join(errors))


def batch_total(
    args: argparse.Namespace,
    head: dict[str, Any],
    inputs: int,
    files: list[dict[str, Any]],
    errors: list[str],
    sums: Sequence[str],
) -> dict[str, Any]:
    """A batch's summary: ``head``, the number of ``inputs``, the sums of ``sums``, the per-file summaries.

    A sum is ``None`` when a file lacks it. The table is printed unless ``--json``; when inputs failed, the
    batch raises after the table, so what succeeded is written and shown first.
    """
    total: dict[str, Any] = {**head, "inputs": inputs}
    for k in sums:
        values = [f.get(k) for f in files]
        total[k] = None if any(v is None for v in values) else sum(values)
    total["files"] = files
    if not args.json:
        print_table(total)
    refuse_failures(errors, inputs)
    return total


def finite_float(text: str) -> float:
    """Argparse type: a finite number (for ``--threshold``)."""
    try:
        value = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected a number, got {text!r}") from None
    if not math.isfinite(value):
        raise argparse.ArgumentTypeError(f"expected a finite number, got {text!r}")
    return value


def add_limit_argument(parser: argparse.ArgumentParser, *, voxels: bool = False) -> None:
    """Add ``--limit N``, the largest result (in pixels) a command may create.

    With ``voxels`` the help also says what it bounds for 3D inputs: the voxels of a volume or of a result
    (:data:`~mrm.core.limits.DEFAULT_VOXEL_LIMIT` when not given, see :func:`voxel_limit`).
    """
    more = (
        f"; for 3D inputs, voxels of a volume or result (default {DEFAULT_VOXEL_LIMIT:_})" if voxels else ""
    )
    parser.add_argument(
        "--limit",
        type=positive_int,
        default=None if voxels else DEFAULT_PIXEL_LIMIT,
        metavar="N",
        help=f"largest number of pixels of an image or result (default {DEFAULT_PIXEL_LIMIT:_}){more}",
    )


def pixel_limit(limit: int | None) -> int:
    """``--limit`` for a 2D input (added with ``voxels=True``, None means the default)."""
    return DEFAULT_PIXEL_LIMIT if limit is None else limit


def voxel_limit(limit: int | None) -> int:
    """``--limit`` for a 3D input (added with ``voxels=True``, None means the default)."""
    return DEFAULT_VOXEL_LIMIT if limit is None else limit


def extension_of(path: str | os.PathLike[str], allowed: tuple[str, ...], what: str) -> str:
    """Return the lower-case extension of ``path`` or raise a FileFormatError listing ``allowed``.

    A double extension in ``allowed`` (``.nii.gz``) is recognised whole.
    """
    name = Path(path).name.lower()
    ext = next((a for a in allowed if a.count(".") > 1 and name.endswith(a)), Path(path).suffix.lower())
    if ext not in allowed:
        shown = f"'{ext}'" if ext else "no extension"
        raise FileFormatError(f"{os.fspath(path)}: {shown} is not a {what}; use {', '.join(allowed)}")
    return ext


def project_objects(path: str | os.PathLike[str]) -> tuple[list[Any], str]:
    """Every object of a project file (``mrm.document.DocObject``, in document order) and its model."""
    proj = read_project(path)
    return list(proj.objects), str(proj.settings.model)


def load_object(
    path: str | os.PathLike[str],
    object_name: str | None = None,
    model: str | None = None,
    *,
    threshold: float | None = None,
    invert: bool = False,
    limit: int = DEFAULT_PIXEL_LIMIT,
) -> tuple[Kind, Any, str]:
    """Read one object: a pixel file, a vector file, or the object ``object_name`` of a project.

    Returns ``(kind, value, model)`` as :func:`mrm.cli._project_input.load_input` does (value in its
    source representation; model the one asked for, else the project's, else 'standard'), with ``limit``
    also bounding the size of an image read from a pixel file and ``invert`` taking an image's dark pixels.
    """
    if object_name is None and Path(path).suffix.lower() in PIXEL_EXTENSIONS:
        # load_input reads images under the default limit only; read them here so that --limit applies.
        ps = read_image(path, threshold=threshold, invert=invert, limit=limit)
        return "discrete", ps, model or "standard"
    if invert:
        raise ParameterError(f"{os.fspath(path)}: --invert applies to image inputs only")
    return load_input(path, object_name, model, threshold=threshold)


def read_image(
    path: str | os.PathLike[str],
    *,
    threshold: float | None = None,
    invert: bool = False,
    limit: int = DEFAULT_PIXEL_LIMIT,
) -> PixelSet:
    """Read a pixel file; ``invert`` takes the pixels *not* in the set, within the image's frame."""
    ps = read_pixels(path, threshold=threshold, limit=limit)
    if not invert:
        return ps
    return ps.complement(image_frame(path))


def image_frame(path: str | os.PathLike[str]) -> tuple[int, int, int, int]:
    """The box of every pixel of an image file (:func:`mrm.io.georef.image_frame`, kept here for callers)."""
    return frame_of(path)


def read_project_input(path: str | os.PathLike[str]) -> Input:
    """Read every object of a project file; its Euclidean objects combined as ``geometry``."""
    objects, model = project_objects(path)
    euclidean = [o.source for o in objects if not isinstance(o.source, PixelSet)]
    geom = combine(euclidean) if euclidean else None
    return Input("project", geometry=geom, model=model, objects=objects)


def read_input(
    path: str | os.PathLike[str],
    allowed: tuple[str, ...],
    *,
    threshold: float | None = None,
    invert: bool = False,
    limit: int = DEFAULT_PIXEL_LIMIT,
) -> Input:
    """Read a pixel file, a vector file or a project, chosen by the extension (one of ``allowed``)."""
    ext = extension_of(path, allowed, "supported input file")
    if ext == PROJECT_EXTENSION:
        return read_project_input(path)
    if ext in PIXEL_EXTENSIONS:
        return Input("discrete", pixels=read_image(path, threshold=threshold, invert=invert, limit=limit))
    if ext in VECTOR_EXTENSIONS:
        return Input("euclidean", geometry=read_geometry(path))
    raise FileFormatError(f"{os.fspath(path)}: cannot read {ext} files")  # unreachable with sane ``allowed``


def is_3d_input(path: str | os.PathLike[str]) -> bool:
    """True for a mesh file (by its extension) or a voxel file (:func:`mrm.io.voxel_files.is_volume_file`).

    A ``.npz`` or ``.tif`` is 3D when it holds a 3-D array or a stack of pages, else it is a 2D pixel file.
    """
    from mrm.io.mesh_files import MESH_EXTENSIONS
    from mrm.io.voxel_files import is_volume_file

    return Path(path).suffix.lower() in MESH_EXTENSIONS or is_volume_file(path)


def read_voxel_input(path: str | os.PathLike[str], threshold: float | None, limit: int | None) -> VoxelSet:
    """The voxel set of a voxel file, ``--threshold`` for grey volumes, ``--limit`` (None: the default)."""
    from mrm.io.voxel_files import read_voxels

    return read_voxels(path, threshold=threshold, limit=voxel_limit(limit))


def discretize_geometry(geom: Any, model: str, limit: int) -> PixelSet:
    """D(geom) under ``model`` with :func:`mrm.geometry.discretize.discretize`."""
    return discretize(geom, model, limit=limit)


_LABELS = {
    "boundary_chains": "boundary chains",
    "bbox": "bounding box",
}


def _shown(value: Any) -> str:
    if value is None:
        return "–"
    if isinstance(value, float):
        return f"{value:.3f}"
    if isinstance(value, list | tuple):
        return " ".join(str(v) for v in value)
    return str(value)


def print_table(summary: dict[str, Any], keys: list[str] | None = None) -> None:
    """Print ``summary`` as a two-column table on stdout (None shows as "–")."""
    rows = [
        (k, summary[k]) for k in (keys or list(summary)) if k in summary and not isinstance(summary[k], dict)
    ]
    rows = [(k, v) for k, v in rows if not (isinstance(v, list) and v and isinstance(v[0], dict))]
    width = max((len(_LABELS.get(k, k)) for k, _ in rows), default=0)
    for k, v in rows:
        print(f"{_LABELS.get(k, k):<{width}}  {_shown(v)}", file=sys.stdout)
