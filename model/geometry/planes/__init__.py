"""Digital plane segments: exact recognition, preimages and the segmentation of surfel surfaces.

Reference: docs/design.md §11 (analytical representation). :mod:`.cone` holds the one exact structure
(the cone of admissible normals), :mod:`.recognition` the two recognizers built on it, and
:mod:`.segmentation` the greedy segmentation of the closed surfaces of a voxel set.
"""

from mrm.geometry.planes.cone import Cone
from mrm.geometry.planes.recognition import (
    DigitalPlane,
    PointPlane,
    SurfelPlane,
    recognize_points,
    recognize_surfels,
    smallest_normal,
)

__all__ = [
    "Cone",
    "DigitalPlane",
    "PointPlane",
    "SurfelPlane",
    "recognize_points",
    "recognize_surfels",
    "smallest_normal",
]
