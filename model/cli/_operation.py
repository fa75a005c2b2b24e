"""What the operation subcommands share.

Reference: ``mrm scale | rotate | simplify | union | corefine``, docs/design.md §9.

Inputs are pixel files (.png .pbm .pgm .npz), vector files (.geojson .json .wkt) or projects (.mrm) with
``--object NAME``. An operation reads the representation it needs: DSS and dR the discrete one (D(E) of a
vector input), Sp the Euclidean one (R(A) of a pixel input), EDu and EDco either (a pixel set stands for
itself as D(E)).

A vector input that is not one polygon — polygon features that overlap or share an edge, lines, points (a
GeometryCollection) — enters an operation as its discretization D(E) = ∪ D(feature) under the model in force:
the pixels ``mrm discretize`` writes and ``mrm info`` counts, computed without rounding a coordinate (every
model is union-stable). DSS, dR, EDu and EDco read exactly these pixels for a polygon too; Sp and EDco_α then
read R(D(E)), as for any pixel input. A label map (a project object) is no input of the operations (ADR
0033): the message says to split it into objects.

Outputs: a pixel result goes to .png/.pbm/.pgm/.npz, a Euclidean result to .geojson/.json/.wkt/.svg; asking
for the other kind writes the result's other representation (R of a pixel result, D of a Euclidean one —
exact both ways, since D(R(A)) = A). Files are written atomically: a failure leaves no half-written file.

The one-input operations (``scale``, ``rotate``, ``simplify``) take several inputs as ``reconstruct`` does
(docs/adr/0011): files, directories (their files of the input types), quoted globs and ``-``; ``-o`` is then
a directory or a pattern holding ``{stem}``; ``--jobs N`` spreads them over worker processes, each input's
line is printed as soon as it is done, a progress bar shows on a terminal. ``--threshold`` and ``--invert``
say how an image becomes a pixel set.

A georeferenced input (a GeoTIFF, an image with a world file, a project object with a georeference) gives a
georeferenced result (ADR 0021): the input's grid for rotate and simplify, the grid scaled by α for scale;
a .tif or .png (+ world file) result is written on that grid, a vector result in world coordinates.

``--json`` prints the info keys of the result (:func:`mrm.reps.summary.summarize`) plus ``bound`` (the error
bound of the operation as a chain, null where the model gives none) and ``measured`` (the exact Hausdorff
distance between the composite Euclidean transform of A_first and A_last; null with ``--no-measure``).
"""

from __future__ import annotations

import argparse
import logging
import time
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path
from types import SimpleNamespace
from typing import Any

from shapely.geometry import MultiPolygon, Polygon
from shapely.geometry.base import BaseGeometry

from mrm.cli._common import (
    add_image_arguments,
    add_inputs_argument,
    add_jobs_argument,
    add_limit_argument,
    add_output_argument,
    batch_total,
    extension_of,
    inputs_and_outputs,
    is_3d_input,
    load_object,
    read_voxel_input,
    run_inputs,
    voxel_limit,
)
from mrm.cli._project_input import add_object_argument, project_object
from mrm.core.errors import MRMError, NotApplicableError, ParameterError
from mrm.core.grids import LabelMap, PixelSet, VoxelSet
from mrm.geometry.discretize import discretize
from mrm.geometry.discretize.voxels import voxelize
from mrm.geometry.polyhedra import Polyhedron
from mrm.geometry.reconstruct import compact_limit_in_force, reconstruct
from mrm.io.georef import (
    GEOREFERENCED_EXTENSIONS,
    geojson_members,
    georef_summary,
    read_georef,
    write_georeferenced,
)
from mrm.io.mesh_files import MESH_EXTENSIONS, read_mesh, write_mesh
from mrm.io.pixel_files import PIXEL_EXTENSIONS, write_pixels
from mrm.io.vector_files import VECTOR_EXTENSIONS, write_geojson, write_svg, write_wkt
from mrm.io.voxel_files import VOXEL_EXTENSIONS, write_voxels
from mrm.ops.account import account_of
from mrm.ops.georef import result_georef
from mrm.ops.provenance import Provenance
from mrm.ops.registry import OperationSpec, get_operation, input_dimension, run_operation
from mrm.reps.summary import summarize, summarize_voxels

log = logging.getLogger(__name__)

#: Input file types (3D: voxel volumes and meshes, for the operations that take them).
INPUTS = tuple(
    dict.fromkeys((*PIXEL_EXTENSIONS, *VECTOR_EXTENSIONS, ".mrm", *VOXEL_EXTENSIONS, *MESH_EXTENSIONS))
)
#: Output file types of a single result (a 3D result: a voxel file, or a mesh file of its R).
OUTPUTS = tuple(
    dict.fromkeys((*PIXEL_EXTENSIONS, *VECTOR_EXTENSIONS, ".svg", *VOXEL_EXTENSIONS, *MESH_EXTENSIONS))
)


def add_two_inputs(parser: argparse.ArgumentParser) -> None:
    """Two inputs A B; ``--object`` may be given twice (for A, then for B)."""
    what = "a pixel file, a vector file, a project (.mrm), a voxel file or a mesh (both of one dimension)"
    parser.add_argument("first", metavar="A", help=what)
    parser.add_argument("second", metavar="B", help=what)
    parser.add_argument(
        "--object",
        metavar="NAME",
        action="append",
        default=None,
        help="for project inputs: the object to use; give it twice for A and B (once: every project input)",
    )


def add_common(parser: argparse.ArgumentParser, output_help: str, *, batch: bool = False) -> None:
    """``-o OUT`` (``batch``: or a directory, a pattern), ``--limit`` and ``--no-measure``."""
    add_output_argument(parser, output_help, batch=batch)
    add_limit_argument(parser)
    parser.add_argument(
        "--no-measure",
        action="store_true",
        help="skip the exact Hausdorff distance (measured: null); it can take seconds on large objects",
    )


@dataclass(frozen=True)
class OperationInput:
    """One input of an operation as the command line read it (the file is read once).

    ``value`` is the object in its source representation, ``model`` the model in force. A project object
    also brings its ``id`` and ``provenance`` (so its chain joins the account), its ``georef`` and its
    project's ``compact_limit`` (the R of voxel sets the desktop computes there); a pixel file brings its
    georeference (a GeoTIFF's, a world file's) or None.
    """

    value: Any
    model: str
    id: int = 0
    provenance: Any = None
    georef: Any = None
    compact_limit: int | None = None


def read_one(
    path: str,
    object_name: str | None,
    model: str | None,
    limit: int,
    threshold: float | None = None,
    invert: bool = False,
) -> OperationInput:
    """Read one input of an operation (a pixel file, a vector file or one object of a project)."""
    ext = extension_of(path, INPUTS, "supported input file")
    if ext != ".mrm" and is_3d_input(path):  # a voxel volume or a mesh: a 3D object, no georeference
        if ext in MESH_EXTENSIONS:  # an OBJ file's object by --object (a label volume's region)
            solid = read_mesh(path, object_name=object_name if ext == ".obj" else None)
            return OperationInput(solid, model or "standard")
        return OperationInput(read_voxel_input(path, threshold, voxel_limit(None)), model or "standard")
    if ext == ".mrm":
        if invert:
            raise ParameterError(f"{path}: --invert applies to image inputs only")
        if not Path(path).exists():
            raise FileNotFoundError(2, "No such file", path)
        obj, chosen, compact_limit = project_object(Path(path), object_name, model)
        if isinstance(obj.source, LabelMap):
            raise NotApplicableError(
                f"{Path(path).name}: {obj.name!r} is a label map, no input of the operations; Edit ▸ Split "
                "into Objects in MR Modeler gives one pixel object per label (mrm polygonize: one polygon "
                "per region)"
            )
        return OperationInput(obj.source, chosen, obj.id, obj.provenance, obj.georef, compact_limit)
    _, value, chosen = load_object(path, object_name, model, threshold=threshold, invert=invert, limit=limit)
    georef = None
    if ext in PIXEL_EXTENSIONS and ext != ".npz":
        georef = read_georef(path)
    return OperationInput(operation_source(value, chosen, limit), chosen, georef=georef)


def operation_source(value: Any, model: str, limit: int | None) -> Any:
    """What an operation reads of a file's content: a pixel set or one polygon as it is, else D(E).

    A geometry that is not one (Multi)Polygon — overlapping features, lines, points — has no exact
    Euclidean source, but its discretization is exact (union-stable): the operation reads that.
    """
    if not isinstance(value, BaseGeometry) or isinstance(value, Polygon | MultiPolygon):
        return value
    if value.is_empty:
        return Polygon()
    return discretize(value, model, limit=limit)


def _two_names(args: argparse.Namespace) -> tuple[str | None, str | None]:
    """The ``--object`` names of A and B (None: the input's only object, or a plain file)."""
    names = list(args.object or [])
    if len(names) > 2:
        raise ParameterError("--object is given at most twice (for A, then for B)")
    project = [Path(p).suffix.lower() == ".mrm" for p in (args.first, args.second)]
    if len(names) == 2:
        name_a, name_b = names
    elif len(names) == 1:
        if project[0] and project[1]:
            name_a = name_b = names[0]
        elif project[0] or project[1]:
            name_a, name_b = (names[0], None) if project[0] else (None, names[0])
        else:
            raise ParameterError("--object applies to project (.mrm) inputs only")
    else:
        name_a = name_b = None
    return name_a, name_b


def read_two(args: argparse.Namespace) -> tuple[OperationInput, OperationInput, str]:
    """Read A and B with their ``--object`` names; the model is --model, else A's project's, else B's."""
    project = [Path(p).suffix.lower() == ".mrm" for p in (args.first, args.second)]
    name_a, name_b = _two_names(args)
    a = read_one(args.first, name_a, args.model, args.limit)
    b = read_one(args.second, name_b, args.model, args.limit)
    model = args.model or (a.model if project[0] else b.model if project[1] else a.model)
    return a, b, model


def two_input_provenance(operation: str, params: dict[str, Any], a: OperationInput, b: OperationInput) -> Any:
    """The provenance of a two-input result: both inputs, with a project input's own chain."""
    ids = (a.id or 1, b.id or 2)
    return Provenance(operation, params, ids, (a.value, b.value), (a.provenance, b.provenance))


def write_result(
    result: Any,
    path: str,
    model: str,
    properties: dict[str, Any] | None = None,
    georef: Any = None,
) -> None:
    """Write a pixel set or a polygon to ``path``, converting to the representation the extension asks for.

    With a georeference (:class:`mrm.core.georef.GeoRef`), a .tif or .png is written on its grid (+ world
    file) and a vector file in world coordinates (GeoJSON with ``crs`` and ``bbox``); SVG stays a picture.
    """
    ext = extension_of(path, OUTPUTS, "output file")
    if isinstance(result, VoxelSet | Polyhedron):
        _write_3d(result, path, ext, model)
        return
    if ext in PIXEL_EXTENSIONS:
        if not isinstance(result, PixelSet):
            result = discretize(result, model)
        if georef is not None and ext in GEOREFERENCED_EXTENSIONS:
            write_georeferenced(result, path, georef)
        else:
            write_pixels(result, path)
        return
    if ext == ".svg":
        write_svg(result, path)
        return
    if isinstance(result, PixelSet):
        result = reconstruct(result, model)
    if georef is not None:
        result = georef.to_world(result)
    if ext == ".wkt":
        write_wkt(result, path)
    else:
        write_geojson(
            result,
            path,
            properties={"model": model, **(properties or {})},
            members=geojson_members(georef, result),
        )


def check_3d_output(path: str) -> None:
    """Refuse an output a 3D result cannot be written to (before the work: a voxel file or a mesh file)."""
    ext = extension_of(path, OUTPUTS, "output file")
    if ext not in MESH_EXTENSIONS and ext not in VOXEL_EXTENSIONS:
        raise ParameterError(
            f"{path}: a 3D result is written to a voxel file ({', '.join(VOXEL_EXTENSIONS)}) or a mesh file "
            f"({', '.join(MESH_EXTENSIONS)})"
        )


def _write_3d(result: VoxelSet | Polyhedron, path: str, ext: str, model: str) -> None:
    """A 3D result: its voxels to a voxel file, its Euclidean representation (R of voxels) to a mesh file."""
    check_3d_output(path)
    if ext in MESH_EXTENSIONS:
        warning = write_mesh(result if isinstance(result, Polyhedron) else reconstruct(result, model), path)
        if warning:
            log.warning("%s", warning)
        return
    write_voxels(result if isinstance(result, VoxelSet) else voxelize(result, model), path)


def two_input_georef(operation: str, a: OperationInput, b: OperationInput) -> Any:
    """The georeference of a two-input result (ADR 0021): both inputs' grid when they share one, else None."""
    return result_georef(operation, {}, [a.georef, b.georef])


def result_summary(result: Any, pixels: Any, model: str) -> dict[str, Any]:
    """The info keys of a result (its discrete representation, and the polygon when it is Euclidean)."""
    if isinstance(pixels, VoxelSet):  # the 3D keys of mrm info, without R (the mesh file's own business)
        return summarize_voxels(pixels, model, faces=None, vertices=None)
    return summarize(pixels, model, geom=None if isinstance(result, PixelSet) else result)


def unary_file(
    path: str,
    output: str,
    operation: str,
    params: dict[str, Any],
    object_name: str | None,
    model: str | None,
    limit: int,
    no_measure: bool,
    threshold: float | None = None,
    invert: bool = False,
) -> dict[str, Any]:
    """Run one unary operation on one input and write its result; return its summary (batch workers call it).

    The parameters are read and range-checked by the operation's parameters (once, by their declarations);
    the numbers are :meth:`mrm.ops.account.Account.summary`, the same as the inspector's and
    ``mrm account``'s for the same chain (a project input's own chain is part of it).
    """
    spec = get_operation(operation)
    checked = spec.read_params(params)
    given = read_one(path, object_name, model, limit, threshold, invert)
    source, chosen, georef = given.value, given.model, given.georef
    checked = checked.replace(model=chosen)
    prov = Provenance(spec.name, checked.to_json(), (given.id,), (source,), (given.provenance,))
    t0 = time.perf_counter()
    with compact_limit_in_force(given.compact_limit):  # a project's R of voxel sets, as in the desktop
        if no_measure:
            result = run_operation(spec, [source], checked, limit=limit).output
            acc = account_of(prov, measure=False, limit=limit)
        else:  # the account recomputes the step from its input: the result is made once
            acc = account_of(prov, measure=True, limit=limit)
            if acc.error:
                raise ParameterError(acc.error)
            result = acc.output
    seconds = time.perf_counter() - t0
    out_georef = result_georef(spec.name, checked, [georef])
    Path(output).parent.mkdir(parents=True, exist_ok=True)  # a batch's directory: when the first file is
    write_result(result, output, chosen, {"operation": spec.name}, out_georef)
    summary: dict[str, Any] = {"input": str(path), "output": str(output), "operation": spec.name}
    summary["params"] = checked.to_json()
    pixels = acc.result if acc.result is not None else _pixels_of(result, chosen, limit)
    summary.update(result_summary(result, pixels, chosen))
    summary["account"] = acc.summary()
    summary.update({k: v for k, v in acc.summary().items() if k not in ("operation", "model")})
    summary["seconds"] = seconds
    summary.update(georef_summary(out_georef))
    return summary


def _line(f: dict[str, Any]) -> str:
    count = f"{f['voxels']} voxels" if "voxels" in f else f"{f['pixels']} pixels"
    return f"{f['input']} -> {f['output']}: {count}, {f['seconds']:.3f} s"


#: Keys summed over the inputs of a batch.
_SUM_KEYS = ("pixels", "components", "holes", "vertices", "seconds")


def run_unary(args: argparse.Namespace, operation: str, params: dict[str, Any]) -> dict[str, Any]:
    """Run one unary operation on every input, write the results, return the --json summary.

    One input: its summary (the model's account, see :func:`unary_file`). Several: ``inputs``, the sums of
    :data:`_SUM_KEYS` and ``files``, the per-input summaries in input order; an input that fails is reported
    on stderr when it fails, the others go on, and the command then exits with status 2.
    """
    spec = get_operation(operation)
    given = {k: v for k, v in params.items() if v is not None}
    spec.read_params(given)  # refused before any input is read
    image = (args.threshold, args.invert)
    default_ext = ".png" if spec.produces == "discrete" else ".geojson"
    pairs = inputs_and_outputs(args, INPUTS, "supported input file", OUTPUTS, default_ext, "output file")
    jobs = [
        (i, o, spec.name, given, args.object, args.model, args.limit, args.no_measure, *image)
        for i, o in pairs
    ]

    def total(files: list[dict[str, Any]], errors: list[str]) -> dict[str, Any]:
        return batch_total(args, {"operation": spec.name}, len(jobs), files, errors, _SUM_KEYS)

    first = f"{args.command} {Path(pairs[0][0]).name}"
    return run_inputs(args, unary_file, jobs, _line, total, first=first, hidden=("account", "steps", "parts"))


def _pixels_of(result: Any, model: str, limit: int | None) -> Any:
    if isinstance(result, PixelSet | VoxelSet):
        return result
    if isinstance(result, Polyhedron):
        return voxelize(result, model, limit=limit)
    return discretize(result, model, limit=limit)


def _parameter_fields(operation: str) -> tuple[Any, list[Any]]:
    """The registry spec of ``operation`` and its parameters that become options (all but ``model``)."""
    spec = get_operation(operation)
    return spec, [p for p in spec.params.specs() if p.kind != "model"]


def add_parameter_options(parser: argparse.ArgumentParser, fields: list[Any]) -> None:
    """One option per parameter (``--alpha``, ``--angle``, ``--center X,Y``): label, unit, help, range.

    The values stay text: the operation's parameters read them, exactly, as every other path's.
    """
    for p in fields:
        unit = f" [{p.unit}]" if p.unit and p.unit != "×" else ""
        if p.kind == "point":
            metavar = {0: "X,Y[,Z]", 3: "X,Y,Z"}.get(p.dimension, "X,Y")
            parser.add_argument(f"--{p.name}", default=None, metavar=metavar, help=f"{p.help}{unit}")
        else:
            allowed = f" ({p.range_text()})" if p.minimum is not None or p.maximum is not None else ""
            parser.add_argument(
                f"--{p.name}",
                required=not p.optional,
                metavar=p.label.upper() if p.label.isascii() else p.name[0].upper(),
                help=f"{p.help}{unit}{allowed}; decimal or p/q, read exactly",
            )


def operation_command(spec: OperationSpec) -> SimpleNamespace:
    """The subcommand of a one-object operation (``mrm scale``), generated from its registry spec alone.

    ``NAME`` is :attr:`~mrm.ops.registry.OperationSpec.command`, ``HELP`` the spec's help. Every parameter of
    the spec's dataclass becomes an option (``--alpha``, ``--angle``, ``--center X,Y``) with its label, unit,
    help and declared range; ``model`` is the common ``--model``. The values are read exactly and
    range-checked by the operation's parameters (:meth:`~mrm.ops.registry.OperationSpec.read_params`), as
    the panel's are. The output is a pixel file for an operation that makes pixels, else a vector file (each
    writes the other kind on request: R of a pixel result, D of a Euclidean one).
    """
    fields = [p for p in spec.params.specs() if p.kind != "model"]
    pixels = spec.produces == "discrete"
    kinds = ("a pixel file (.png .pbm .pgm .npz)", "a vector file (.geojson .wkt .svg)")
    output_help = f"the result: {kinds[0] if pixels else kinds[1]} or {kinds[1] if pixels else kinds[0]}"

    def add_arguments(parser: argparse.ArgumentParser) -> None:
        add_inputs_argument(parser, "pixel files, vector files or projects (.mrm)")
        add_object_argument(parser)
        add_parameter_options(parser, fields)
        add_common(parser, output_help, batch=True)
        add_jobs_argument(parser)
        add_image_arguments(parser)

    def run(args: argparse.Namespace) -> dict[str, Any]:
        return run_unary(args, spec.name, {p.name: getattr(args, p.name) for p in fields})

    return SimpleNamespace(
        NAME=spec.command,
        HELP=spec.help,
        add_arguments=add_arguments,
        run=run,
        STDOUT_FORMAT=".png" if pixels else ".geojson",
    )


@dataclass(frozen=True)
class TwoInputRun:
    """A two-object operation as ``mrm union`` and ``mrm corefine`` run it (:func:`two_input_command`).

    Attributes
    ----------
    a, b : OperationInput
        The inputs as read.
    model : str
        The model in force.
    params : dict
        The operation's parameters as JSON data (exact numbers), ``model`` first, as recorded.
    account : mrm.ops.account.Account
        The one account of the result (measured unless ``--no-measure``).
    computed : object
        What ``direct`` computed when the account did not (``--no-measure``), else None.
    seconds : float
        The time the operation (and its measurement) took.
    georef : GeoRef or None
        The result's georeference: both inputs' grid when they share one.
    """

    a: OperationInput
    b: OperationInput
    model: str
    params: dict[str, Any]
    account: Any
    computed: Any
    seconds: float
    georef: Any


def two_input_command(
    operation: str,
    output_help: str,
    finish: Callable[[argparse.Namespace, TwoInputRun], dict[str, Any]],
    direct: Callable[..., Any],
    outputs: tuple[str, ...] | None = None,
    check_output: Callable[[str, int], None] | None = None,
) -> tuple[Any, Any]:
    """``(add_arguments, run)`` of a two-object subcommand, generated from the operation's registry spec.

    The options are the spec's parameters, read exactly and range-checked as for the one-object commands.
    ``run`` calls ``finish(args, TwoInputRun)`` for what the subcommand writes and prints;
    ``direct(a, b, model, params, limit)`` computes the result when the account does not (``--no-measure``);
    ``outputs``, when given, are the output types, checked first; ``check_output(output, n)``, when given,
    checks the output for inputs of dimension ``n`` once they are read, before any work.
    The numbers are those of the one account of the result (:func:`mrm.ops.account.account_of`): the
    account's recomputation is the result written, so nothing is computed twice.
    """
    spec, fields = _parameter_fields(operation)

    def add_arguments(parser: argparse.ArgumentParser) -> None:
        add_two_inputs(parser)
        add_parameter_options(parser, fields)
        add_common(parser, output_help)

    def run(args: argparse.Namespace) -> dict[str, Any]:
        if outputs is not None:
            extension_of(args.output, outputs, "output file")
        given = {p.name: getattr(args, p.name) for p in fields if getattr(args, p.name) is not None}
        checked = spec.read_params(given)  # the declared ranges, before any input is read
        a, b, model = read_two(args)
        if check_output is not None:
            check_output(str(args.output), input_dimension([a.value, b.value]))
        params = checked.replace(model=model).to_json()
        t0 = time.perf_counter()
        # the first project input's compact limit (ADR 0073): the R of voxel sets computed there
        with compact_limit_in_force(a.compact_limit or b.compact_limit):
            acc = account_of(
                two_input_provenance(spec.name, params, a, b), measure=not args.no_measure, limit=args.limit
            )
            if acc.error:
                raise MRMError(acc.error)
            computed = None if acc.outcome is not None else direct(a, b, model, params, args.limit)
        seconds = time.perf_counter() - t0
        georef = two_input_georef(spec.name, a, b)
        return finish(args, TwoInputRun(a, b, model, params, acc, computed, seconds, georef))

    return add_arguments, run
