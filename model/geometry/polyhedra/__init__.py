"""Polyhedra: the Euclidean solids of the 3-D side, validated exactly (docs/design.md §11).

=====================  ===================================================================================
``polyhedron``         :class:`Polyhedron`, the immutable solid value (vertices, outward triangles, faces).
``validation``         the exact validity check, in the order users fix things, with messages saying where.
``predicates``         exact orient3d / orient2d on float64: float filter, exact expansions, Fractions.
``manifold``           closed, edge-manifold, consistently oriented, manifold vertices; shells.
``self_intersection``  a uniform grid over triangle boxes and the exact triangle–triangle tests.
``shells``             each shell's volume sign and nesting (winding numbers along a perturbed ray).
``faces``              maximal sets of edge-adjacent, exactly coplanar triangles.
``repair``             the explicit repair (merge, drop flat and repeated triangles, orient), never silent.
=====================  ===================================================================================
"""

from mrm.geometry.polyhedra.polyhedron import Polyhedron
from mrm.geometry.polyhedra.repair import repair
from mrm.geometry.polyhedra.validation import MAX_TRIANGLES

__all__ = ["MAX_TRIANGLES", "Polyhedron", "repair"]
