"""Export of document objects and label maps to interchange files (never the lossless project format).

The representation written follows the file type:

* ``.png`` ``.pbm`` ``.pgm`` ``.npz`` ``.tif`` — the **discrete** representation (the source, or D(E)),
  keeping its place on the grid (:func:`mrm.io.pixel_files.write_pixels`);
* ``.geojson`` ``.json`` ``.wkt`` — the **Euclidean** representation (the source, or R(A)), coordinates exact
  (:mod:`mrm.io.vector_files`);

An object with a georeference (``DocObject.georef``: it came from a GeoTIFF or an image with a world file, or
from operations on one, ADR 0021) is exported where it lies on the Earth: ``.tif`` with its transform and CRS,
``.png`` with a world file (+ ``.prj``), on the raster's frame grown to hold every pixel
(:func:`mrm.io.georef.write_georeferenced`); GeoJSON and WKT in world coordinates, GeoJSON with ``crs`` and
``bbox``. SVG pictures and the other pixel formats stay in grid coordinates.
* ``.svg`` — a picture with y up: the Euclidean shape by default (SVG is a vector format, so a plain export
  gives the shape alone, ready for an SVG editor or a publication figure), the pixels (``rep="discrete"``), or
  both (``rep="both"``: the pixels as light squares with the Euclidean shape outlined on top, the picture
  of how the two representations match).

A **label map** gives every chosen object its own label — its rank in the list, 1, 2, … — in one PNG or NPZ;
where objects overlap, the later one (higher in the drawing order) wins, as on screen.
All writes are atomic.
"""

from __future__ import annotations

import os
from collections.abc import Sequence
from pathlib import Path
from typing import Any, Literal

import numpy as np

from mrm.core.errors import FileFormatError, ParameterError
from mrm.core.grids import LabelMap, PixelSet, joint_box
from mrm.core.limits import MAX_LABEL_PIXELS, check_pixels
from mrm.document import Document
from mrm.io.georef import GEOREFERENCED_EXTENSIONS, geojson_members, same_crs, write_georeferenced
from mrm.io.pixel_files import write_label_map, write_pixels
from mrm.io.vector_files import write_geojson, write_svg, write_wkt

PathLike = str | os.PathLike[str]

PIXEL_EXTENSIONS = (".png", ".pbm", ".pgm", ".npz", ".tif", ".tiff")
VECTOR_EXTENSIONS = (".geojson", ".json", ".wkt")
PICTURE_EXTENSIONS = (".svg",)
LABEL_EXTENSIONS = (".png", ".npz")


def _ext(path: PathLike) -> str:
    return Path(path).suffix.lower()


def export_object(
    doc: Document,
    obj_id: int,
    path: PathLike,
    *,
    rep: Literal["discrete", "euclidean", "both"] | None = None,
) -> str:
    """Write one object to ``path``; the extension chooses the format (see the module notes).

    Parameters
    ----------
    doc : Document
        The document.
    obj_id : int
        The object.
    path : str or path-like
        Destination.
    rep : {'discrete', 'euclidean', 'both'}, optional
        For SVG, which representation to draw (default Euclidean; 'both' draws the discrete one under the
        Euclidean one); for other types it must match the type.

    Returns
    -------
    str
        The representation written, 'discrete', 'euclidean' or 'both'.
    """
    ext = _ext(path)
    obj = doc.get(obj_id)
    if ext in PIXEL_EXTENSIONS:
        chosen = "discrete"
    elif ext in VECTOR_EXTENSIONS:
        chosen = "euclidean"
    elif ext in PICTURE_EXTENSIONS:
        chosen = rep or "euclidean"
    else:
        shown = f"'{ext}'" if ext else "no extension"
        raise FileFormatError(
            f"{os.fspath(path)}: cannot export to {shown}; use "
            + ", ".join(PIXEL_EXTENSIONS + VECTOR_EXTENSIONS + PICTURE_EXTENSIONS)
        )
    if rep is not None and rep != chosen:
        raise ParameterError(f"a {ext} file holds the {chosen} representation, not the {rep} one")
    if rep == "both" and ext in PICTURE_EXTENSIONS:
        derived = doc.derived(obj.id)
        write_svg(derived.get("euclidean"), path, pixels=derived.get("discrete"))
        return "both"
    value = doc.derived(obj.id).get("discrete" if chosen == "discrete" else "euclidean")
    georef = obj.georef
    if ext in PIXEL_EXTENSIONS:
        if georef is not None and ext in GEOREFERENCED_EXTENSIONS:
            write_georeferenced(value, path, georef)
        else:
            write_pixels(value, path)
    elif ext == ".wkt":
        write_wkt(value if georef is None else georef.to_world(value), path)
    elif ext in VECTOR_EXTENSIONS:
        world = value if georef is None else georef.to_world(value)
        write_geojson(
            world, path, properties=_properties(doc, obj_id), members=geojson_members(georef, world)
        )
    else:
        write_svg(value, path)
    return chosen


def _properties(doc: Document, obj_id: int) -> dict[str, Any]:
    obj = doc.get(obj_id)
    props: dict[str, Any] = {"name": obj.name, "id": obj.id, "model": doc.model, "source": obj.kind}
    if obj.provenance is not None:
        props["provenance"] = obj.provenance.to_json()
    return props


def export_objects_geojson(doc: Document, ids: Sequence[int], path: PathLike) -> None:
    """Write several objects' Euclidean shapes to one GeoJSON file, a Feature each (``part`` = its name)."""
    if _ext(path) not in (".geojson", ".json"):
        raise FileFormatError(f"{os.fspath(path)}: several objects go to a .geojson file")

    objs = [doc.get(i) for i in ids]
    georefs = [o.georef for o in objs]
    # One file holds one coordinate system: world coordinates for all, in one CRS, or grid ones for all.
    refs = [g for g in georefs if g is not None]
    if refs and (len(refs) < len(georefs) or not all(same_crs(g.crs, refs[0].crs) for g in refs)):
        raise ParameterError(
            "the objects are not all georeferenced in one CRS: export them to separate files"
        )
    parts = [
        (o.name, e if o.georef is None else o.georef.to_world(e))
        for o, e in ((o, doc.derived(o.id).get("euclidean")) for o in objs)
    ]
    members: dict[str, Any] = {}
    if georefs and georefs[0] is not None:
        from shapely.geometry import GeometryCollection

        members = geojson_members(georefs[0], GeometryCollection([g for _, g in parts if not g.is_empty]))
    write_geojson(parts, path, properties={"model": doc.model}, members=members)


def label_map_of(doc: Document, ids: Sequence[int] | None = None) -> tuple[LabelMap, dict[int, int]]:
    """The label map of objects' discrete representations.

    Parameters
    ----------
    doc : Document
        The document.
    ids : sequence of int, optional
        The objects, in drawing order (default: every object, in document order).

    Returns
    -------
    LabelMap
        Object ``ids[k]`` has label ``k + 1`` on its pixels, except where a later object covers them.
    dict
        label → object id.
    """
    chosen = list(doc.ids if ids is None else ids)
    if len(chosen) > np.iinfo(np.int32).max:
        raise ParameterError("too many objects for a label map")
    parts: list[PixelSet] = [doc.derived(i).get("discrete") for i in chosen]
    box = joint_box(p.bbox for p in parts)
    mapping = {k + 1: i for k, i in enumerate(chosen)}
    if box is None:
        return LabelMap(np.zeros((0, 0), dtype=np.int32)), mapping
    x0, y0, x1, y1 = box

    area = (x1 - x0 + 1) * (y1 - y0 + 1)
    check_pixels(area, MAX_LABEL_PIXELS, "the label map")  # four bytes a pixel: not the pixel set limit
    out = np.zeros((y1 - y0 + 1, x1 - x0 + 1), dtype=np.int32)
    for k, p in enumerate(parts, start=1):
        if p.is_empty():
            continue
        px, py = p.origin
        h, w = p.shape
        out[py - y0 : py - y0 + h, px - x0 : px - x0 + w][p.mask] = k
    return LabelMap(out, (x0, y0)), mapping


def export_label_map(doc: Document, path: PathLike, ids: Sequence[int] | None = None) -> dict[int, int]:
    """Write the label map of objects (see :func:`label_map_of`) to a .png or .npz; returns label → id."""
    if _ext(path) not in LABEL_EXTENSIONS:
        raise FileFormatError(f"{os.fspath(path)}: a label map goes to a .png or .npz file")
    lm, mapping = label_map_of(doc, ids)
    write_label_map(lm, path)
    return mapping
