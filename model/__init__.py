"""MR Modeler's library: exact 2D discrete geometry with four representations (docs/design.md §1–§8).

``import mrm`` is Qt-free and cheap: the names below are loaded on first use (PEP 562), so ``mrm --version``
and the command line start fast. numpy arrays, pixel sets and shapely geometries go in and come out::

    import mrm
    ps = mrm.read_pixels("shape.png")            # or mrm.PixelSet.from_image(array), row 0 at the top
    poly = mrm.reconstruct(ps, "gauss")           # the polygon whose discretization is exactly ps
    big = mrm.scale(ps, 2, model="gauss")         # DSS_2
    mrm.hausdorff(mrm.reconstruct(big, "gauss"), ...)

Geometries may also be GeoJSON dicts or ``__geo_interface__`` objects; lists, tuples and numpy ``object``
arrays of values are batches whose results come back as ``object`` arrays (docs/adr/0053); ``transform=``
places an image as rasterio does.

Pixel (x, y) is centred on the point (x, y) and y points **up** (docs/design.md §1); image arrays are
converted by :meth:`PixelSet.from_image` / :meth:`PixelSet.to_image`, never by hand. The desktop application
is ``mrm.app`` (needs the ``gui`` extra); the command line is ``mrm.cli``.
"""

from __future__ import annotations

import importlib
from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:  # pragma: no cover - for type checkers and IDEs only
    from mrm.api import (
        bound,
        corefine,
        discretize,
        hausdorff,
        polygonize,
        reconstruct,
        rotate,
        scale,
        segment,
        simplify,
        union,
    )
    from mrm.core.errors import MRMError
    from mrm.core.georef import GeoRef
    from mrm.core.grids import LabelMap, LabelVolume, PixelSet, VoxelSet
    from mrm.core.models import Model
    from mrm.geometry.discretize.voxels import voxelize
    from mrm.geometry.dss import Segment
    from mrm.geometry.hausdorff import HausdorffDistance
    from mrm.geometry.hausdorff.bounds import BoundResult
    from mrm.geometry.polyhedra import Polyhedron
    from mrm.io.mesh_files import read_mesh, read_mesh_objects, write_mesh
    from mrm.io.pixel_files import read_label_map, read_pixels, write_label_map, write_pixels
    from mrm.io.vector_files import read_geometry, write_geojson, write_wkt
    from mrm.io.voxel_files import read_label_volume, read_voxels, write_label_volume, write_voxels

#: public name → the module that defines it (imported when the name is first used).
_LAZY = {
    "PixelSet": "mrm.core.grids",
    "LabelMap": "mrm.core.grids",
    "VoxelSet": "mrm.core.grids",
    "LabelVolume": "mrm.core.grids",
    "read_pixels": "mrm.io.pixel_files",
    "write_pixels": "mrm.io.pixel_files",
    "read_label_map": "mrm.io.pixel_files",
    "write_label_map": "mrm.io.pixel_files",
    "read_geometry": "mrm.io.vector_files",
    "write_geojson": "mrm.io.vector_files",
    "write_wkt": "mrm.io.vector_files",
    "read_voxels": "mrm.io.voxel_files",
    "voxelize": "mrm.geometry.discretize.voxels",
    "Polyhedron": "mrm.geometry.polyhedra",
    "read_mesh": "mrm.io.mesh_files",
    "read_mesh_objects": "mrm.io.mesh_files",
    "write_mesh": "mrm.io.mesh_files",
    "write_voxels": "mrm.io.voxel_files",
    "read_label_volume": "mrm.io.voxel_files",
    "write_label_volume": "mrm.io.voxel_files",
    "MRMError": "mrm.core.errors",
    # the model names and the result types of the functions (mrm.api's signatures name them)
    "Model": "mrm.core.models",
    "GeoRef": "mrm.core.georef",
    "BoundResult": "mrm.geometry.hausdorff.bounds",
    "HausdorffDistance": "mrm.geometry.hausdorff",
    "Segment": "mrm.geometry.dss",
    **{
        name: "mrm.api"
        for name in (
            "discretize",
            "reconstruct",
            "polygonize",
            "segment",
            "scale",
            "rotate",
            "simplify",
            "union",
            "corefine",
            "bound",
            "hausdorff",
        )
    },
}

__all__ = [
    "BoundResult",
    "GeoRef",
    "HausdorffDistance",
    "LabelMap",
    "LabelVolume",
    "MRMError",
    "Model",
    "PixelSet",
    "Polyhedron",
    "Segment",
    "VoxelSet",
    "__version__",
    "bound",
    "corefine",
    "discretize",
    "hausdorff",
    "polygonize",
    "read_geometry",
    "read_label_map",
    "read_label_volume",
    "read_mesh",
    "read_mesh_objects",
    "read_pixels",
    "read_voxels",
    "reconstruct",
    "rotate",
    "scale",
    "segment",
    "simplify",
    "union",
    "voxelize",
    "write_geojson",
    "write_label_map",
    "write_label_volume",
    "write_mesh",
    "write_pixels",
    "write_voxels",
    "write_wkt",
]


def __getattr__(name: str) -> Any:
    if name == "__version__":
        value: Any = importlib.import_module("mrm.core.version").installed_version()
    elif name in _LAZY:
        value = getattr(importlib.import_module(_LAZY[name]), name)
    else:
        raise AttributeError(f"module 'mrm' has no attribute {name!r}")
    globals()[name] = value  # later look-ups skip this function
    return value


def __dir__() -> list[str]:
    return sorted({*globals(), *__all__})
