"""Exact Hausdorff distance between filled polygonal sets (Polygon / MultiPolygon with holes).

What is computed
----------------
For closed sets ``A`` and ``B`` the directed distance is ``h(A, B) = max_{a ∈ A} d(a, B)`` and the
Hausdorff distance ``H(A, B) = max(h(A, B), h(B, A))``. The sets are the *filled* polygons, which is what
the paper's ``H`` between Euclidean objects means: a point of ``A`` inside ``B`` is at distance 0. This
differs from the distance between the boundaries (what ``shapely.hausdorff_distance`` approximates, from
densified vertices): for ``A`` a disc of radius 10 and ``B`` the same disc with a small hole of radius 1, the
boundaries are 9 apart (the hole's rim is far from A's rim) while ``h(B, A) = 0`` and ``h(A, B) = 1``, the
radius of the largest disc that fits in the hole. For disjoint convex sets the two notions agree.

Where the maximum is (the argument the algorithm rests on)
-----------------------------------------------------------
Write ``f = d(·, B)``: 0 on ``B``, the distance to ``∂B`` outside. Split ``∂B`` into *features*: its vertices
(distance ``|x − v|``) and its edges seen as lines, valid only in the edge's slab (distance ``|ℓ(x)|/|m|``);
``f`` is the minimum of the valid features. Let ``R_k`` be the part of ``A ∖ int B`` where feature ``k`` is
nearest. On ``R_k``, ``f`` equals a convex function, so its maximum over ``R_k`` is reached on ``∂R_k``, which
is made of pieces of ``∂A``, of ``∂B`` (where ``f = 0``) and of bisectors ``{d_k = d_j}`` (a slab's side is
the bisector of the edge and its end vertex). Along a piece of ``∂A`` (a segment) ``f`` is again convex
between two consecutive changes of the nearest feature, and along a bisector (a line or a parabola) the
distance has no interior maximum (convex along a line; monotone on each side of a parabola's apex). Hence the
maximum of ``f`` over ``A`` is reached at one of

1. a vertex of ``A``;
2. a point of an edge of ``A`` where two features are equally near (the edge crosses a bisector) or where a
   line feature's slab starts or ends;
3. a point of ``int A`` equidistant from three features: a vertex of the Voronoi diagram of ``∂B``.

Case 3 is real: when ``A`` fills a hole of ``B`` (a hole of ``R(A)`` that vanished after ``DSS_1/5``), the
farthest point is the centre of the hole, not on ``∂A``. Checking vertices only — or sampling — is wrong.

How it is computed
------------------
Coordinates (float64, so dyadic rationals) are scaled by a common power of two to integers. Case 1 is
rational. For case 2 each squared feature distance is a quadratic in the edge's parameter ``t`` with rational
coefficients, so crossings are roots in ``Q(√D)``. For case 3 the equidistant points of three features are
solved symbolically (circumcentre; a bisector line meeting a parabola; angle bisectors with coefficients in
``Q(√(N₁N₂))`` meeting a parabola; three lines), which needs nested square roots. All of these numbers live
in one *tower of quadratic extensions* ``Q(√δ₁)(√δ₂)…`` in which every comparison is decided exactly (the sign
of ``a + b·√δ`` follows from the signs of ``a``, ``b`` and ``a² − b²δ``), after a float interval filter with
outward rounding settles the easy cases.

The search is a branch-and-bound that never needs to be lucky:

- case 2 splits each edge of A into pieces, drops a piece when an exact rational bound shows it cannot beat
  the best value (Lipschitz ``f(c) + r ≤ L``; the largest distance to one edge of ∂B, convex, at the piece's
  ends; the piece lies inside B), and examines the exact candidates of the remaining pieces;
- case 3 covers A with boxes, first in floats (vectorized; every float inequality carries a proven rounding
  allowance and whatever the floats cannot settle is kept), then in rationals (the convex bound taken over the
  vertices of ``box ∩ A``), and solves the triples of features that can be nearest in a small box — after an
  interval shadow of the solver has discarded the triples that certainly cannot win;
- a feature is dropped only where it cannot be the nearest one of a point outside B (an edge whose line
  leaves the box on B's side, a reflex vertex, a point outside a vertex's normal cone);
- spatial indexes (GEOS STRtree) only select *supersets* of the edges that matter, with outward-rounded boxes.

Guarantee: the result is the exact maximum. ``squared`` (a Fraction when rational) and the comparisons
(:meth:`HausdorffDistance.compare`, :meth:`HausdorffDistance.exceeds_sqrt_multiple`) are exact; ``value`` is
the float nearest to it, computed from a 2⁻²⁰⁰-wide enclosure. Typical reconstructions of a few hundred
vertices take a fraction of a second; a hole shaped like a regular polygon (many edges almost equidistant
from its centre) costs a few seconds, and the cost grows with the number of edges near the farthest points.

Modules: ``intervals`` (float enclosures with outward rounding), ``exact_numbers`` (the tower), ``shapes``
(the sets on the integer grid, exact distances to their edges), ``spatial`` (the STRtree search and the float
filters), ``branch_and_bound`` (the state the searches share), ``along_edges`` (case 2), ``interior`` and
``equidistant`` (case 3), ``distance`` (the public functions, case 1); ``bounds`` holds the paper's error
bounds.
"""

from mrm.geometry.hausdorff.distance import HausdorffDistance, directed_hausdorff, hausdorff_distance

__all__ = ["HausdorffDistance", "directed_hausdorff", "hausdorff_distance"]
