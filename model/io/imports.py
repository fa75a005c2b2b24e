"""Import of interchange files into a document as new objects (one undo step).

* pixel files (``.png`` ``.pbm`` ``.pgm`` ``.npz`` ``.tif``, grey images thresholded) → one discrete object,
  with its georeference (a GeoTIFF's, or a world file's) when it has one;
* vector files (``.geojson`` ``.json`` ``.wkt``) → one object per geometry: polygons become Euclidean objects;
  lines and points, which are no shapes, become discrete objects D(geometry) under the document's model;
* 3D files (docs/design.md §11): a mesh (``.obj`` ``.ply`` ``.off`` ``.stl``) → one polyhedron object, a
  voxel file (``.nii`` ``.nii.gz``, a multi-page ``.tif``, an ``.npz`` holding a 3-D array) → one voxel
  object, or a label volume when the ``.npz`` holds ``labels`` (:func:`solid_sources`);
* another project (``.mrm``) → copies of its objects, with fresh ids (provenance inputs follow them).
"""

from __future__ import annotations

import os
from pathlib import Path

from shapely.geometry import MultiPolygon, Polygon

from mrm.core.errors import FileFormatError, InvalidGeometryError
from mrm.core.limits import clean_name
from mrm.document import DocObject, Document, validate_geometry
from mrm.document.commands import ApplyResults
from mrm.document.objects import Source
from mrm.geometry.discretize import discretize
from mrm.io.georef import read_pixels_georef
from mrm.io.pixel_files import PIXEL_EXTENSIONS
from mrm.io.project import read_project
from mrm.io.vector_files import VECTOR_EXTENSIONS, read_geometries
from mrm.ops.provenance import Provenance

PathLike = str | os.PathLike[str]


def solid_sources(path: PathLike) -> list[tuple[str, Source]] | None:
    """The 3D objects a mesh or voxel file holds, named after the file; None for any other file.

    A mesh is checked as a closed, oriented, non-self-intersecting surface (:func:`mrm.read_mesh`); an OBJ
    file that is no such surface as a whole but whose objects each are (a label volume's regions, as
    ``mrm polygonize`` writes them) gives one object per region, named after the file and the region; a voxel
    file is told from a 2D one of the same extension by its headers (:func:`is_volume_file`). Nothing is
    decided from the contents beyond what the readers check.
    """
    from mrm.io.mesh_files import MESH_EXTENSIONS, read_mesh, read_mesh_objects
    from mrm.io.voxel_files import is_volume_file, read_label_volume, read_voxels

    p = Path(path)
    name = clean_name(p.name[: -len(".nii.gz")] if p.name.lower().endswith(".nii.gz") else p.stem or p.name)
    if p.suffix.lower() in MESH_EXTENSIONS:
        try:
            return [(name, read_mesh(p))]
        except InvalidGeometryError as whole:
            # An OBJ file of several solids apart (a label volume's regions, which share their faces):
            # one object each. Otherwise the file's own error, which says where it is wrong.
            try:
                parts = read_mesh_objects(p)
            except InvalidGeometryError:
                raise whole from None
            if len(parts) < 2:
                raise
            return [(clean_name(f"{name} {part}"), poly) for part, poly in parts]
    if not is_volume_file(p):
        return None
    if p.suffix.lower() == ".npz" and _holds_labels(p):
        return [(name, read_label_volume(p))]
    return [(name, read_voxels(p))]


def _holds_labels(path: Path) -> bool:
    import zipfile

    with zipfile.ZipFile(path) as zf:  # is_volume_file has opened it as a zip already
        return "labels.npy" in zf.namelist()


def objects_from_file(doc: Document, path: PathLike, *, threshold: float | None = None) -> list[DocObject]:
    """Read ``path`` into new objects for ``doc`` (fresh ids; not inserted yet).

    Raises
    ------
    FileFormatError, InvalidGeometryError, SizeLimitError
        For unreadable, invalid or oversized content; ``doc`` is never changed.
    """
    p = Path(path)
    ext = p.suffix.lower()
    stem = clean_name(p.stem or p.name)  # a file name undecodable as UTF-8 holds lone surrogates
    if ext == ".mrm":
        proj = read_project(p)
        new_ids = {o.id: doc.new_id() for o in proj.objects}
        out = []
        for o in proj.objects:
            prov = o.provenance
            if prov is not None:
                prov = Provenance(prov.operation, prov.params, tuple(new_ids.get(i, i) for i in prov.inputs))
            out.append(o.with_(id=new_ids[o.id], provenance=prov))
        return out

    solid = solid_sources(p)
    if solid is not None:
        return [doc.make_object(src, label) for label, src in solid]
    if ext in PIXEL_EXTENSIONS:
        # A GeoTIFF's transform and CRS (or a world file's) stay on the object (ADR 0021).
        ps, georef = read_pixels_georef(p, threshold=threshold)
        return [doc.make_object(ps, stem, georef=georef)]
    if ext in VECTOR_EXTENSIONS:
        geoms = read_geometries(p)
        out = []
        for k, (name, g) in enumerate(geoms):
            label = name if name else (stem if len(geoms) == 1 else f"{stem} {k + 1}")
            if isinstance(g, Polygon | MultiPolygon) or g.is_empty:
                out.append(doc.make_object(validate_geometry(g), label))
            else:
                out.append(doc.make_object(discretize(g, doc.model), label))
        return out
    shown = f"'{ext}'" if ext else "no extension"
    raise FileFormatError(
        f"{p.name}: cannot import {shown}; use .png, .pbm, .pgm, .npz, .tif, .geojson, .json, .wkt, .mrm, "
        "a mesh (.obj .ply .off .stl) or a volume (.nii .nii.gz)"
    )


def import_file(doc: Document, path: PathLike, *, threshold: float | None = None) -> list[int]:
    """Add the objects of ``path`` to ``doc`` as one undo step, select them, and return their ids."""
    objs = objects_from_file(doc, path, threshold=threshold)
    if objs:
        doc.push(ApplyResults(f"Import {Path(path).name}", add=objs))
    return [o.id for o in objs]
