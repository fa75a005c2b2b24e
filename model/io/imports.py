"""Import of interchange files into a document as new objects (one undo step).

* pixel files (``.png`` ``.pbm`` ``.pgm`` ``.npz`` ``.tif``, grey images thresholded) → one discrete object,
  with its georeference (a GeoTIFF's, or a world file's) when it has one;
* vector files (``.geojson`` ``.json`` ``.wkt``) → one object per geometry: polygons become Euclidean objects;
  lines and points, which are no shapes, become discrete objects D(geometry) under the document's model;
* another project (``.mrm``) → copies of its objects, with fresh ids (provenance inputs follow them).
"""

from __future__ import annotations

import os
from pathlib import Path

from shapely.geometry import MultiPolygon, Polygon

from mrm.core.errors import FileFormatError
from mrm.core.limits import clean_name
from mrm.document import DocObject, Document, validate_geometry
from mrm.document.commands import ApplyResults
from mrm.geometry.discretize import discretize
from mrm.io.georef import read_pixels_georef
from mrm.io.pixel_files import PIXEL_EXTENSIONS
from mrm.io.project import read_project
from mrm.io.vector_files import VECTOR_EXTENSIONS, read_geometries
from mrm.ops.provenance import Provenance

PathLike = str | os.PathLike[str]


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
        f"{p.name}: cannot import {shown}; use .png, .pbm, .pgm, .npz, .geojson, .json, .wkt or .mrm"
    )


def import_file(doc: Document, path: PathLike, *, threshold: float | None = None) -> list[int]:
    """Add the objects of ``path`` to ``doc`` as one undo step, select them, and return their ids."""
    objs = objects_from_file(doc, path, threshold=threshold)
    if objs:
        doc.push(ApplyResults(f"Import {Path(path).name}", add=objs))
    return [o.id for o in objs]
