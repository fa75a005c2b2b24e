"""GeoJSON dicts and objects with ``__geo_interface__`` as shapely geometries: the library's inputs.

The ``__geo_interface__`` protocol is how shapely, GeoPandas, Fiona and many other Python GIS packages
hand a geometry over: an attribute holding a GeoJSON-like mapping. The library (:mod:`mrm.api`) takes such
objects and plain GeoJSON dicts wherever it takes a shapely geometry. They are read by the one GeoJSON
reader of :mod:`mrm.io.vector_files` (the checks of a ``.geojson`` file: supported types, nesting, the
vertex limit, finite coordinates, validity), after tuples and numpy arrays of coordinates (what
``__geo_interface__`` usually holds) are made lists.
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Protocol, TypeAlias, runtime_checkable

import numpy as np
from shapely.geometry import GeometryCollection
from shapely.geometry.base import BaseGeometry

from mrm.core.errors import FileFormatError, InvalidGeometryError
from mrm.core.limits import MAX_GEOMETRY_NESTING
from mrm.io.vector_files import _GEOJSON_DEPTH, _geojson_geometry, combine

__all__ = ["GeoInterface", "GeometryLike", "as_geometry", "is_geometry_like"]


@runtime_checkable
class GeoInterface(Protocol):
    """Any object with a ``__geo_interface__`` (a GeoJSON-like mapping): shapely, GeoPandas, Fiona, …."""

    @property
    def __geo_interface__(self) -> Mapping[str, object]:
        """The object as a GeoJSON geometry, Feature or FeatureCollection mapping."""


#: What the library accepts as a Euclidean geometry: shapely's, a GeoJSON mapping, or a geo-interface object.
GeometryLike: TypeAlias = BaseGeometry | Mapping[str, object] | GeoInterface


def is_geometry_like(obj: object) -> bool:
    """Whether ``obj`` is a shapely geometry, a GeoJSON mapping or a geo-interface object."""
    if isinstance(obj, BaseGeometry):
        return True
    if isinstance(obj, Mapping):
        return isinstance(obj.get("type"), str)
    return hasattr(type(obj), "__geo_interface__") or hasattr(obj, "__geo_interface__")


def as_geometry(obj: GeometryLike, what: str = "the geometry") -> BaseGeometry:
    """Return ``obj`` as a shapely geometry.

    Parameters
    ----------
    obj : shapely geometry, GeoJSON mapping or object with ``__geo_interface__``
        A GeoJSON geometry, a ``Feature`` (its geometry; a null geometry is the empty set) or a
        ``FeatureCollection`` (every feature's geometry, held together without rounding, as
        :func:`mrm.read_geometry` reads a file).
    what : str
        How messages name the argument.

    Returns
    -------
    shapely.geometry.base.BaseGeometry
        A shapely geometry is returned as it is.

    Raises
    ------
    InvalidGeometryError
        A mapping that is not GeoJSON, an unsupported type, bad coordinates or an invalid polygon (one line).

    Examples
    --------
    >>> as_geometry({"type": "Point", "coordinates": (1, 2)}).wkt
    'POINT (1 2)'
    """
    if isinstance(obj, BaseGeometry):
        return obj
    if not isinstance(obj, Mapping):
        gi = getattr(obj, "__geo_interface__", None)
        if not isinstance(gi, Mapping):
            raise InvalidGeometryError(
                f"{what}: expected a shapely geometry, a GeoJSON mapping or an object with "
                f"__geo_interface__, got {type(obj).__name__}"
            )
        obj = gi
    try:
        return _from_geojson(obj, what)
    except FileFormatError as e:  # the file reader's wording; here it is an argument, not a file
        raise InvalidGeometryError(str(e)) from None


def _from_geojson(doc: Mapping[str, object], what: str) -> BaseGeometry:
    kind = doc.get("type")
    if kind == "Feature":
        geom = doc.get("geometry")
        return GeometryCollection() if geom is None else _from_geojson(_mapping(geom, what), what)
    if kind == "FeatureCollection":
        features = doc.get("features")
        if not isinstance(features, list | tuple):
            raise InvalidGeometryError(f"{what}: a FeatureCollection needs a 'features' list")
        parts = [
            _from_geojson(_mapping(f, f"{what}, feature {i}"), f"{what}, feature {i}")
            for i, f in enumerate(features)
        ]
        return combine(parts)
    return _geojson_geometry(_plain_geometry(doc, 1), what, what)


def _mapping(obj: object, what: str) -> Mapping[str, object]:
    if isinstance(obj, Mapping):
        return obj
    gi = getattr(obj, "__geo_interface__", None)
    if isinstance(gi, Mapping):
        return gi
    raise InvalidGeometryError(f"{what}: expected a GeoJSON object, got {type(obj).__name__}")


def _plain_geometry(g: object, level: int) -> object:
    """A GeoJSON geometry mapping as the file reader takes it: a dict, lists for arrays, Python numbers."""
    if not isinstance(g, Mapping):
        return g
    d = dict(g)
    if level > MAX_GEOMETRY_NESTING + 1:
        return d  # the reader refuses the nesting itself
    members = d.get("geometries")
    if isinstance(members, list | tuple):
        d["geometries"] = [_plain_geometry(m, level + 1) for m in members]
    kind = d.get("type")
    if isinstance(kind, str) and kind in _GEOJSON_DEPTH and "coordinates" in d:
        d["coordinates"] = _plain_coordinates(d["coordinates"], _GEOJSON_DEPTH[kind])
    return d


def _plain_coordinates(c: object, depth: int) -> object:
    if isinstance(c, np.ndarray):
        c = c.tolist()
    if not isinstance(c, list | tuple):
        return c  # the reader says what is wrong
    if depth == 0:
        return [v.item() if isinstance(v, np.generic) else v for v in c]
    return [_plain_coordinates(x, depth - 1) for x in c]
