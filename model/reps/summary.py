"""A summary of the four representations of an object, as ``mrm info --json`` prints it (docs/design.md §9).

:func:`summarize` gives the fixed keys ``model``, ``pixels``, ``components``, ``holes``, ``euler``,
``boundary_chains``, ``segments`` and ``vertices`` (plus ``bbox``): the region keys from
:func:`mrm.reps.region.region_of`, ``segments`` the analytical representation's count
(:func:`mrm.reps.analytical.segment_count`), and ``vertices`` of a discrete object its continuation
(:func:`mrm.geometry.reconstruct.reconstruct`). :func:`summarize_voxels` gives the §11 keys of a voxel object.
"""

from __future__ import annotations

from typing import Any

import shapely

from mrm.core.grids import PixelSet, VoxelSet
from mrm.core.models import Model
from mrm.geometry.reconstruct import reconstruct
from mrm.reps.analytical import segment_count
from mrm.reps.analytical_3d import analytical_3d_of
from mrm.reps.region import region_of
from mrm.reps.region_3d import region_3d_of


def count_vertices(geom: Any) -> int:
    """Return the number of vertices of a shapely geometry (0 when empty).

    Ring points (without the closing repeat), line points and points, summed over the parts.
    """
    if geom is None or geom.is_empty:
        return 0
    kind = geom.geom_type
    if kind in ("Polygon", "MultiPolygon"):
        # Counted by GEOS in one call, not ring by ring (a noise image's result has 10⁵ rings): every
        # ring of a non-empty polygon repeats its first point once at its end.
        parts = shapely.get_parts(geom)
        parts = parts[~shapely.is_empty(parts)]
        rings = len(parts) + int(shapely.get_num_interior_rings(parts).sum())
        return int(shapely.get_num_coordinates(geom)) - rings
    if kind == "LinearRing":
        return len(geom.coords) - 1
    if kind == "LineString":
        return len(geom.coords)
    if kind == "Point":
        return 1
    if hasattr(geom, "geoms"):
        return sum(count_vertices(g) for g in geom.geoms)
    raise TypeError(f"cannot count the vertices of a {kind}")


def summarize(ps: PixelSet, model: Model | str, geom: Any = None) -> dict[str, Any]:
    """Summarise an object's four representations.

    Parameters
    ----------
    ps : PixelSet
        The discrete representation.
    model : str
        The discretization model it was made with (or is read under).
    geom : shapely geometry, optional
        The Euclidean representation when it is the source (then ``ps`` = D(geom)); if None, the Euclidean
        representation is the continuation R(ps).

    Returns
    -------
    dict
        ``model``; ``pixels`` (count); ``bbox`` ([xmin, ymin, xmax, ymax] or None); ``components``,
        ``holes``, ``euler`` and ``boundary_chains`` (the number of crack chains); ``segments`` (DSS over
        all chains); ``vertices`` (of the Euclidean representation).
    """
    model = Model.parse(model)
    bbox = ps.bbox
    region = region_of(ps)
    if geom is None:
        geom = reconstruct(ps, model)
    return {
        "model": str(model),
        "pixels": len(ps),
        "bbox": None if bbox is None else list(bbox),
        "components": int(region.n_components),
        "holes": int(region.n_holes),
        "euler": int(region.euler),
        "boundary_chains": len(region.boundary_chains),
        "segments": segment_count(region),
        "vertices": count_vertices(geom),
    }


def summarize_pixels(ps: PixelSet, model: Model | str, geom: Any) -> dict[str, Any]:
    """The keys of :func:`summarize` that need no kernel: ``model``, ``pixels``, ``bbox``, ``vertices``.

    For a command that only writes pixels (``mrm discretize`` without ``--json``): the region's and the
    segmentation's keys would load their kernels (compile them, on a fresh install) for a table line.
    ``geom`` is the Euclidean source (its vertices), or None for pixels read as they are (no vertices key).
    """
    bbox = ps.bbox
    out: dict[str, Any] = {
        "model": str(Model.parse(model)),
        "pixels": len(ps),
        "bbox": None if bbox is None else list(bbox),
    }
    if geom is not None:
        out["vertices"] = count_vertices(geom)
    return out


def summarize_voxels(
    vs: VoxelSet, model: Model | str, *, faces: int | None, vertices: int | None
) -> dict[str, Any]:
    """Summarise a voxel object's four representations (docs/design.md §11), as ``mrm info --json`` prints it.

    Parameters
    ----------
    vs : VoxelSet
        The discrete representation.
    model : str
        The discretization model it was made with (or is read under).
    faces, vertices : int or None
        The Euclidean representation's counts (the polyhedron's faces and vertices), None when not computed.

    Returns
    -------
    dict
        ``model``; ``voxels``; ``bbox`` ([xmin, ymin, zmin, xmax, ymax, zmax] or None); ``components``,
        ``cavities``, ``tunnels``, ``euler`` and ``surfels`` from :func:`mrm.reps.region_3d.region_3d_of`;
        ``plane_segments`` (the number of digital plane segments of the greedy segmentation,
        :func:`mrm.reps.analytical_3d.analytical_3d_of`); ``faces`` and ``vertices``.
    """
    model = Model.parse(model)
    region = region_3d_of(vs.mask, vs.origin)
    bbox = vs.bbox
    return {
        "model": str(model),
        "voxels": len(vs),
        "bbox": None if bbox is None else list(bbox),
        "components": int(region.n_components),
        "cavities": int(region.n_cavities),
        "tunnels": int(region.n_tunnels),
        "euler": int(region.euler),
        "surfels": int(region.n_surfels),
        "plane_segments": len(analytical_3d_of(region)),
        "faces": faces,
        "vertices": vertices,
    }
