"""Fill numba's on-disk cache once, so that no user waits for the geometry kernels to compile.

The kernels are compiled on their first call and cached next to their sources (``__pycache__``) or in
``NUMBA_CACHE_DIR``. A fresh install compiles for a minute or more on that first call. :func:`warm_up` runs
every derivation and every operation on tiny inputs, in steps that report progress, then writes a stamp; the
set-up script calls it (``python -m mrm.warmup``), the desktop application runs it on a worker thread with a
progress message when :func:`is_warm` says the stamp is missing, and the command line prints one line to
stderr when numba really compiles a kernel (:func:`watch_compiles`, docs/adr/0051).

The stamp is keyed by the numba and Python versions and by the text of every module holding kernels: an
edited kernel or a new numba makes the cache cold again. numba itself recompiles a cached kernel only when
its own module changed, not when a kernel it calls in another module did, so ``python -m mrm.warmup``
removes the cached code of every kernel module before compiling again (:func:`clear_kernel_caches`).
"""

from __future__ import annotations

import contextlib
import hashlib
import json
import logging
import os
import platform
import sys
from collections.abc import Callable, Iterator
from pathlib import Path
from typing import Any, TextIO

log = logging.getLogger(__name__)

#: Modules holding ``@njit(cache=True)`` kernels (relative to the package root).
KERNEL_MODULES = (
    "geometry/_jit.py",
    "geometry/discretize/_kernels.py",
    "geometry/dss/_kernels.py",
    "geometry/reconstruct/_kernels.py",
    "geometry/reconstruct/_base.py",
    "geometry/reconstruct/_corridor.py",
    "geometry/reconstruct/_reach.py",
    "geometry/reconstruct/_sliding.py",
    "geometry/reconstruct/_greedy.py",
    "geometry/reconstruct/_check.py",
    "geometry/reconstruct/_splice.py",
    "geometry/reconstruct/_prune.py",
    "geometry/reconstruct/_merge.py",
    "geometry/reconstruct/_relink.py",
    "geometry/reconstruct/_small_search.py",
    "geometry/reconstruct/_straighten.py",
    "geometry/reconstruct/_minlink.py",
    "geometry/reconstruct/_twins.py",
    "geometry/reconstruct/_dual.py",
    "geometry/reconstruct/convex_3d.py",
    "geometry/reconstruct/snapped_core.py",
    "geometry/reconstruct/_subdivision_kernels.py",
    "geometry/discretize/rational_kernels.py",
    "io/png_stream.py",
    "geometry/topology/cracks.py",
    "geometry/topology/labeling.py",
    "geometry/dss/segmentation.py",
    "geometry/dss/__init__.py",
    "reps/region.py",
    "geometry/topology/labeling_3d.py",
    "geometry/topology/surfels.py",
    "geometry/topology/cells_3d.py",
    "geometry/reconstruct/safety_net_3d.py",
    "geometry/reconstruct/decimate_3d.py",
    "geometry/reconstruct/_label_corners.py",
    "geometry/reconstruct/polygonize_3d.py",
    "geometry/polyhedra/predicates.py",
    "geometry/polyhedra/self_intersection.py",
    "geometry/polyhedra/manifold.py",
    "geometry/polyhedra/shells.py",
    "geometry/polyhedra/faces.py",
    "geometry/polyhedra/validation.py",
    "geometry/discretize/_kernels3d.py",
    "geometry/hausdorff/_solids_kernels.py",
    "geometry/planes/_kernels.py",
    "geometry/topology/colouring.py",
)

STAMP_NAME = "mrm-kernels-warm.json"

#: ``progress(done, total, what)``: called before each step and once at the end (done == total).
ProgressFn = Callable[[int, int, str], None]


def _package_root() -> Path:
    return Path(__file__).resolve().parent


def stamp_path() -> Path:
    """Where the stamp lives: numba's cache directory for the geometry kernels."""
    cache_dir = os.environ.get("NUMBA_CACHE_DIR")
    if cache_dir:
        return Path(cache_dir) / STAMP_NAME
    return _package_root() / "geometry" / "__pycache__" / STAMP_NAME


def cache_key() -> dict[str, str]:
    """What the compiled cache depends on: numba, Python, the machine and the kernels' source text.

    numba's version is read from its installed metadata, not by importing it: the desktop application asks
    this before its first paint, and importing numba takes a second or more on a loaded machine.
    """
    h = hashlib.sha256()
    root = _package_root()
    for rel in KERNEL_MODULES:
        p = root / rel
        h.update(rel.encode())
        if p.is_file():
            h.update(p.read_bytes())
    return {
        "numba": _numba_version(),
        "python": platform.python_version(),
        "machine": platform.machine(),
        "sources": h.hexdigest(),
    }


def _numba_version() -> str:
    from importlib import metadata

    try:
        return metadata.version("numba")
    except metadata.PackageNotFoundError:  # a numba without metadata (a source tree): ask the module
        import numba

        return str(numba.__version__)


def _read_stamp() -> object:
    # The stamp's content, or None when there is none (or it cannot be read).
    try:
        return json.loads(stamp_path().read_text(encoding="utf-8"))
    except (OSError, ValueError):
        return None


def _stamp_is_current() -> bool:
    # The stamp was written by a warm-up of exactly these kernel sources, this numba and this Python.
    return bool(_read_stamp() == cache_key())


def is_warm() -> bool:
    """True when :func:`warm_up` ran for these kernels, this numba and this Python.

    A stale stamp (a kernel module edited since) still counts as warm when numba's cache holds an index for
    every kernel module: only the edited kernels recompile then, on first use, which no notice announces.
    A current stamp without those indexes (the cache files deleted, the stamp left) is cold.
    ``python -m mrm.warmup`` compiles again unless the stamp is current and the indexes are there.
    """
    stamp = _read_stamp()
    if stamp is None:
        return False
    if os.environ.get("NUMBA_CACHE_DIR"):
        return bool(stamp == cache_key())  # another layout: the stamp alone decides
    return _indexes_present()  # a current stamp without the cache files (deleted by hand) is cold


def _kernel_files() -> list[Path]:
    # The kernel modules that hold compiled kernels (the decorator's own module holds none).
    root = _package_root()
    files = [root / rel for rel in KERNEL_MODULES]
    return [
        p for p in files if p.name != "_jit.py" and p.is_file() and "njit" in p.read_text(encoding="utf-8")
    ]


def _indexes_present() -> bool:
    if os.environ.get("NUMBA_CACHE_DIR"):
        return False  # another layout: the stamp alone decides
    return all(any((p.parent / "__pycache__").glob(f"{p.stem}.*.nbi")) for p in _kernel_files())


def kernels_cached() -> bool:
    """True when numba's cache holds compiled code of every kernel module, whoever compiled it.

    Read from numba's index files (``<module>.<kernel>-<line>.py311.nbi``), next to the sources or under
    ``NUMBA_CACHE_DIR``; the warm-up's stamp is not needed. The command line runs small inputs interpreted
    while this is False (:mod:`mrm.cli._interpreted`).
    """
    cache_dir = os.environ.get("NUMBA_CACHE_DIR")
    if cache_dir:
        indexes = {p.name.split(".", 1)[0] for p in Path(cache_dir).rglob("*.nbi")}
        return all(p.stem in indexes for p in _kernel_files())
    return _indexes_present()


def _write_stamp() -> None:
    p = stamp_path()
    try:
        p.parent.mkdir(parents=True, exist_ok=True)
        p.write_text(json.dumps(cache_key()), encoding="utf-8")
    except OSError as exc:  # a read-only install still works, it just compiles in memory each time
        log.warning("cannot write the kernel cache stamp %s: %s", p, exc)


def _shapes() -> tuple[object, object]:
    from shapely.geometry import MultiPolygon, Polygon

    poly = Polygon([(0.3, 0.2), (9.7, 1.1), (8.4, 7.9), (1.2, 9.3)], [[(3.1, 3.2), (6.2, 3.9), (4.4, 6.1)]])
    multi = MultiPolygon([poly, Polygon([(12.5, 0.5), (15.5, 0.5), (14.0, 3.5)])])
    return poly, multi


def _step_discretize() -> None:
    from mrm.core.models import Model
    from mrm.geometry.discretize import discretize

    poly, multi = _shapes()
    for model in Model:
        discretize(poly, model)
        discretize(multi, model)


def _pixel_sets() -> list[object]:
    import numpy as np

    from mrm.core.grids import PixelSet

    yy, xx = np.mgrid[0:14, 0:14]
    disc = (xx - 6.5) ** 2 + (yy - 6.5) ** 2 <= 36
    ring = disc & ((xx - 6.5) ** 2 + (yy - 6.5) ** 2 > 6)
    two = np.zeros((6, 12), bool)
    two[1:5, 1:4] = True
    two[1:5, 7:10] = True  # the same block again: a twin ring (ADR 0036), so fill_twins compiles here too
    return [PixelSet(disc), PixelSet(ring, (-3, 5)), PixelSet(two)]


def _step_reconstruct() -> None:
    from mrm.core.models import Model
    from mrm.geometry.reconstruct import reconstruct

    for model in Model:
        for ps in _pixel_sets():
            reconstruct(ps, model)  # type: ignore[call-overload]
    import numpy as np

    from mrm.core.grids import LabelMap
    from mrm.geometry.reconstruct.polygonize import polygonize

    yy, xx = np.mgrid[0:14, 0:14]
    two = ((xx - 6.5) ** 2 + (yy - 6.5) ** 2 <= 36).astype(np.int32) + (xx + 2 * yy > 14)
    polygonize(LabelMap(two.astype(np.int32)))  # the subdivision's polyline kernels and the region labelling


def _step_regions() -> None:
    from mrm.reps.analytical import analytical_of
    from mrm.reps.region import region_of

    for ps in _pixel_sets():
        region = region_of(ps)  # type: ignore[arg-type]
        analytical_of(region)
        warm_pools(region.labels.labels, ps.mask)  # type: ignore[attr-defined]


def warm_pools(labels: Any, mask: Any) -> None:
    """Call the level-of-detail pools as the views call them (:mod:`.geometry.topology.labeling`)."""
    import numpy as np

    from mrm.geometry.topology.labeling import lookup, max_pool, pooled_holes, pooled_labels

    pooled_labels(labels, 2)
    pooled_holes(mask, 2)
    max_pool(mask, 2)
    max_pool(mask[:, 1:], 2)  # a crop: the exact detail of a view
    lookup(np.zeros(256, np.uint32), max_pool(mask, 1))  # the pictures of big images


def _step_regions_3d() -> None:
    import numpy as np

    from mrm.geometry.planes.recognition import standard_plane_prefix
    from mrm.geometry.reconstruct.safety_net_3d import safety_net_3d
    from mrm.reps.analytical_3d import analytical_3d_of
    from mrm.reps.cells_3d import cells_3d_of
    from mrm.reps.region_3d import region_3d_of

    mask = np.ones((3, 3, 3), bool)
    mask[1, 1, 1] = False  # a cavity
    region = region_3d_of(mask, (0, 0, 0))
    _ = region.surfaces
    analytical_3d_of(region)  # the digital plane segments' kernel
    standard_plane_prefix([(0, 0, 0), (1, 0, 0), (0, 1, 1)])  # the compiled point recognizer
    cells_3d_of(mask.astype(np.int32) + np.eye(3, dtype=np.int32)[None])
    safety_net_3d(mask)
    from mrm.core.grids import VoxelSet
    from mrm.geometry.reconstruct import reconstruct_voxels

    for model in ("gauss", "standard"):  # the compact R's decimation (one kernel, both model paths)
        reconstruct_voxels(VoxelSet(mask, (0, 0, 0)), model)
    reconstruct_voxels(VoxelSet(np.ones((3, 3, 3), bool), (0, 0, 0)), "gauss")  # a convex set's grown hull
    z, y, x = np.ogrid[-2:3, -2:3, -2:3]
    octahedron = np.ascontiguousarray(np.broadcast_to(abs(x) + abs(y) + abs(z) <= 2, (5, 5, 5)))
    reconstruct_voxels(VoxelSet(octahedron, (-2, -2, -2)), "supercover")  # a lattice polytope's spiked hull
    from mrm.geometry.reconstruct.convex_3d import convex_reconstruction

    z, y, x = np.ogrid[-9:10, -9:10, -9:10]
    ball = np.ascontiguousarray(np.broadcast_to(x * x + y * y + z * z <= 64, (19, 19, 19)))
    convex_reconstruction(VoxelSet(ball, (-9, -9, -9)), "standard")  # a ball's snapped core (188 facets)
    from mrm.geometry.reconstruct.polygonize_3d import polygonize_volume

    # `mrm polygonize` of a label volume: voxels of one label touching along edges only (pinches)
    polygonize_volume(np.eye(3, dtype=np.int32)[None].repeat(2, axis=0) * 2 + ~mask[:2] * 1).polygons()
    from mrm.geometry.topology.colouring import greedy_colouring

    greedy_colouring(3, [(0, 1), (1, 2)], 2)  # the 3D analytical view's segment colours


def _step_operations() -> None:
    from mrm.ops.registry import operations, run_operation

    poly, _multi = _shapes()
    pixels = _pixel_sets()
    for spec in operations():
        inputs: list[object] = []
        for i in range(spec.arity):
            inputs.append(poly if spec.reads == "euclidean" else pixels[i % len(pixels)])
        try:
            run_operation(spec, inputs)
        except Exception as exc:
            log.info("warm-up of %s: %s", spec.name, exc)


def _step_files() -> None:
    """Read a tiny PNG of every colour type, so the streaming decoder's kernels are compiled too."""
    import io

    import numpy as np
    from PIL import Image

    from mrm.io.pixel_files import read_pixels

    grey = (np.arange(48, dtype=np.uint8).reshape(6, 8) * 5).astype(np.uint8)
    images = [
        Image.fromarray(grey > 100),
        Image.fromarray(grey),
        Image.fromarray(np.dstack([grey] * 3)),
        Image.fromarray(np.dstack([grey] * 3 + [grey[::-1]])),
        Image.fromarray(np.dstack([grey, grey[::-1]]), mode="LA"),
        Image.fromarray(grey).convert("P"),
        Image.fromarray(grey.astype(np.uint16) * 257),
    ]
    import tempfile

    with tempfile.TemporaryDirectory() as tmp:
        for k, im in enumerate(images):
            path = Path(tmp) / f"w{k}.png"
            buf = io.BytesIO()
            im.save(buf, format="PNG")
            path.write_bytes(buf.getvalue())
            try:
                read_pixels(path)
            except Exception as exc:
                log.info("warm-up of the PNG reader (%s): %s", im.mode, exc)


def _step_polyhedra() -> None:
    """Validate a cube with a cubic cavity, a crossing pair and a flat face; measure the 3D error.

    The validations reach every check's kernels; the cube with its cavity against the full cube reaches
    those of the measured error in 3D (:mod:`mrm.geometry.hausdorff.solids`).
    """
    import numpy as np

    from mrm.core.errors import InvalidGeometryError
    from mrm.geometry.polyhedra import Polyhedron

    corners = np.array([[i & 1, i >> 1 & 1, i >> 2 & 1] for i in range(8)], dtype=np.float64)
    tris = np.array(
        [[0, 2, 1], [1, 2, 3], [4, 5, 6], [5, 7, 6], [0, 1, 4], [1, 5, 4],
         [2, 6, 3], [3, 6, 7], [0, 4, 2], [2, 4, 6], [1, 3, 5], [3, 7, 5]],
        dtype=np.int64,
    )  # fmt: skip
    cavity = Polyhedron(np.vstack([corners * 3.0, corners + 1.0]), np.vstack([tris, tris[:, ::-1] + 8]))
    _ = cavity.n_faces
    _ = cavity.polygons  # mesh files' one polygon per face (`mrm reconstruct`, the desktop's export)
    from mrm.geometry.hausdorff.solids import solid_hausdorff

    solid_hausdorff(cavity.vertices, cavity.triangles, corners * 3.0, tris)  # the measured error in 3D
    with contextlib.suppress(InvalidGeometryError):  # the pair tests of a self-intersecting mesh
        Polyhedron(np.vstack([corners, corners + 0.5]), np.vstack([tris, tris + 8]))


def _step_voxelize() -> None:
    """D of a tetrahedron in every model, on both arithmetic paths (snapped and free coordinates)."""
    import numpy as np

    from mrm.geometry.discretize.voxel_images import integer_vertices
    from mrm.geometry.discretize.voxels import voxelize_solid, voxelize_triangles

    tris = np.array([[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]], dtype=np.int64)
    for verts in (
        [[0, 0, 0], [3, 0, 0], [0, 3, 0], [0, 0, 3]],
        [[0.1, 0.2, 0.3], [3.3, 0.1, 0], [0, 3.7, 0.2], [0, 0, 3.1]],
    ):
        v = np.array(verts, dtype=np.float64)
        for model in ("standard", "supercover", "gauss"):
            voxelize_solid(v, tris, model)
            voxelize_triangles(v, tris, model)
    integer_vertices(v)  # the exact images' reading of the vertices (voxelize_image)
    from mrm.geometry.discretize.voxels import voxelize
    from mrm.geometry.polyhedra import Polyhedron

    # A polyhedron's arrays are read-only, and numba compiles a kernel once more for a read-only argument:
    # D of a polyhedron (the operations, the desktop) takes these signatures.
    solid = Polyhedron(v, tris)
    for model in ("standard", "supercover", "gauss"):
        voxelize(solid, model)
    integer_vertices(solid.vertices)


def _step_examples() -> None:
    from mrm.io.project import load_project

    examples = _package_root().parent / "resources" / "examples"
    for p in sorted(examples.glob("*.mrm")) if examples.is_dir() else []:
        try:
            doc = load_project(p)
        except Exception as exc:
            log.info("warm-up: cannot open %s: %s", p, exc)
            continue
        for obj in doc:
            d = doc.derived(obj.id)
            for rep in ("discrete", "euclidean", "region", "analytical"):
                d.get(rep)


#: The steps, with what a user is told while each runs.
STEPS: tuple[tuple[str, Callable[[], None]], ...] = (
    ("discretization kernels", _step_discretize),
    ("reconstruction kernels", _step_reconstruct),
    ("region and segment kernels", _step_regions),
    ("3D region kernels", _step_regions_3d),
    ("operation kernels", _step_operations),
    ("file decoders", _step_files),
    ("polyhedron kernels", _step_polyhedra),
    ("voxelization kernels", _step_voxelize),
    ("example projects", _step_examples),
)


def warm_up(progress: ProgressFn | None = None) -> None:
    """Compile every kernel (numba caches them on disk) and write the stamp :func:`is_warm` reads.

    Parameters
    ----------
    progress : callable, optional
        ``progress(done, total, what)`` before each step and ``progress(total, total, "done")`` at the end.
    """
    total = len(STEPS)
    for i, (what, step) in enumerate(STEPS):
        if progress is not None:
            progress(i, total, what)
        step()
    _write_stamp()
    if progress is not None:
        progress(total, total, "done")


def load_kernels() -> None:
    """Load the kernels every derivation uses from numba's disk cache (seconds, not a compile).

    The desktop application runs this on a worker at start, so that no view pays for loading a kernel on
    the GUI thread; the operations' kernels load when an operation first runs (on its worker).
    """
    for _what, step in STEPS[:3]:
        step()


#: What the first run of a command costs at most when every kernel it calls compiles, in seconds of CPU
#: (benchmarks/first_run.py in a fresh venv, 2 cores: reconstruct of a small PNG 143 s, discretize 24-28 s
#: with --json, segment about 15 s); the notice quotes it. Other commands: DEFAULT_FIRST_RUN.
FIRST_RUN_SECONDS: dict[str, int] = {"discretize": 30, "segment": 20, "reconstruct": 150, "polygonize": 150}
DEFAULT_FIRST_RUN = "one to a few minutes of CPU"


def first_run_message(command: str | None = None) -> str:
    """The one line printed on stderr when a command starts compiling kernels (see :func:`watch_compiles`)."""
    seconds = FIRST_RUN_SECONDS.get(command or "")
    estimate = DEFAULT_FIRST_RUN if seconds is None else f"up to about {seconds} s of CPU"
    return (
        f"mrm: first run: compiling the geometry kernels this command needs, once "
        f"({estimate}; `python -m mrm.warmup` compiles them all ahead of time) …"
    )


class CompileLog:
    """What :func:`watch_compiles` saw: how many kernels numba compiled (not loaded from its disk cache)."""

    def __init__(self) -> None:
        self.compiled = 0
        self.announced = False


@contextlib.contextmanager
def watch_compiles(
    command: str | None = None, *, quiet: bool = False, stream: TextIO | None = None
) -> Iterator[CompileLog]:
    """Print one line on stderr (or ``stream``) when numba starts compiling a kernel inside the block.

    numba fires its ``numba:compile`` event only when a kernel is really compiled, never when it is loaded
    from the disk cache: the line therefore appears exactly on a run that compiles, whatever any stamp says,
    and never on a warm run. ``quiet`` counts without printing. numba is imported here (a command that
    runs kernels imports it anyway).

    Parameters
    ----------
    command : str, optional
        The subcommand, for the estimate the line quotes (:data:`FIRST_RUN_SECONDS`).
    quiet : bool
        Count the compiles but print nothing (``--quiet``).
    stream : text stream, optional
        Where the line goes (default: ``sys.stderr`` at the time of the compile).

    Yields
    ------
    CompileLog
        Its ``compiled`` counts the kernels compiled inside the block (nested ones included).
    """
    from numba.core import event

    record = CompileLog()

    class _Listener(event.Listener):
        def on_start(self, ev: Any) -> None:
            record.compiled += 1
            if not record.announced and not quiet:
                record.announced = True
                print(first_run_message(command), file=sys.stderr if stream is None else stream, flush=True)

        def on_end(self, ev: Any) -> None:
            pass

    listener = _Listener()
    event.register("numba:compile", listener)  # type: ignore[no-untyped-call]
    try:
        yield record
    finally:
        event.unregister("numba:compile", listener)  # type: ignore[no-untyped-call]
        if record.compiled:
            log.info("compiled %d kernels (numba's cache had not got them)", record.compiled)


def main(argv: list[str] | None = None) -> int:
    """``python -m mrm.warmup [--check]``: fill the cache (or, with ``--check``, exit 1 when it is cold)."""
    args = sys.argv[1:] if argv is None else argv
    if "--check" in args:
        return 0 if is_warm() else 1
    if _stamp_is_current() and (os.environ.get("NUMBA_CACHE_DIR") or _indexes_present()):
        print("mrm: the geometry kernels are already compiled")
        return 0

    def show(done: int, total: int, what: str) -> None:
        print(f"mrm: warm-up {done}/{total}: {what}", flush=True)

    cleared = clear_kernel_caches()
    if cleared:
        log.info("removed %d cached kernel files compiled from other sources", cleared)
    warm_up(show)
    return 0


def clear_kernel_caches() -> int:
    """Remove numba's cached code of every kernel module (next to the sources); return how many files.

    numba checks a cached kernel against its own module's file only: a kernel whose callee, in another
    module, was edited would keep running the old callee from the cache. When the kernel sources differ from
    the stamp's, the warm-up therefore compiles everything anew. (``NUMBA_CACHE_DIR`` keeps its own layout,
    which this leaves alone.)
    """
    if os.environ.get("NUMBA_CACHE_DIR"):
        return 0
    root = _package_root()
    removed = 0
    for rel in KERNEL_MODULES:
        p = root / rel
        for f in (p.parent / "__pycache__").glob(f"{p.stem}.*.nb[ic]"):
            try:
                f.unlink()
                removed += 1
            except OSError as exc:  # a read-only install: numba recompiles in memory, which is correct
                log.warning("cannot remove the cached kernel %s: %s", f, exc)
    return removed


if __name__ == "__main__":
    sys.exit(main())
