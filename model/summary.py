"""A summary of the four representations of an object, as ``mrm info --json`` prints it (DESIGN §9).

:func:`summarize` gives the fixed keys ``model``, ``pixels``, ``components``, ``holes``, ``euler``,
``boundary_chains``, ``segments`` and ``vertices`` (plus ``bbox``). Parts of the model that are not built yet
give ``null``: the region keys need :mod:`mrm.reps.region`, ``segments`` is the analytical
representation's count (:func:`mrm.reps.analytical.segment_count`), and ``vertices`` of a discrete object its
continuation (:func:`mrm.geometry.reconstruct.reconstruct`). The region and the continuation are looked up at
call time (:func:`optional_function`).
"""

from __future__ import annotations

import importlib
from collections.abc import Callable
from typing import Any

import shapely

from mrm.core.grids import PixelSet


def optional_function(module: str, name: str) -> Callable[..., Any] | None:
    """Return ``module.name`` if that module exists and defines it, else None.

    Only the absence of ``module`` itself counts as "not built yet": an import error *inside* an existing
    module is a bug and propagates.
    """
    try:
        mod = importlib.import_module(module)
    except ModuleNotFoundError as e:
        if e.name is not None and (module == e.name or module.startswith(e.name + ".")):
            return None
        raise
    fn = getattr(mod, name, None)
    return fn if callable(fn) else None


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


def _count_segments(region: Any) -> int:
    # The analytical representation's count (greedy standard DSS around every chain), without building it.
    from mrm.reps.analytical import segment_count

    return segment_count(region)


def summarize(ps: PixelSet, model: str, geom: Any = None) -> dict[str, Any]:
    """Summarise an object's four representations.

    Parameters
    ----------
    ps : PixelSet
        The discrete representation.
    model : str
        The discretization model it was made with (or is read under).
    geom : shapely geometry, optional
        The Euclidean representation when it is the source (then ``ps`` = D(geom)); if None, the Euclidean
        representation is the continuation R(ps), when that module exists.

    Returns
    -------
    dict
        ``model``; ``pixels`` (count); ``bbox`` ([xmin, ymin, xmax, ymax] or None); ``components``,
        ``holes``, ``euler`` and ``boundary_chains`` (the number of crack chains); ``segments`` (DSS over
        all chains); ``vertices`` (of the Euclidean representation). A value whose module is not available
        yet is None.
    """
    bbox = ps.bbox
    out: dict[str, Any] = {
        "model": model,
        "pixels": len(ps),
        "bbox": None if bbox is None else list(bbox),
        "components": None,
        "holes": None,
        "euler": None,
        "boundary_chains": None,
        "segments": None,
        "vertices": None,
    }
    region_of = optional_function("mrm.reps.region", "region_of")
    if region_of is not None:
        region = region_of(ps)
        out["components"] = int(region.n_components)
        out["holes"] = int(region.n_holes)
        out["euler"] = int(region.euler)
        out["boundary_chains"] = len(region.boundary_chains)
        out["segments"] = _count_segments(region)
    if geom is not None:
        out["vertices"] = count_vertices(geom)
    elif ps.is_empty():
        out["vertices"] = 0
    else:
        reconstruct = optional_function("mrm.geometry.reconstruct", "reconstruct")
        if reconstruct is not None:
            out["vertices"] = count_vertices(reconstruct(ps, model))
    return out
