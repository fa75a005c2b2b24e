"""Write the example projects that reproduce the paper's figures, by running the operations of ``mrm.ops``.

Every derived object is made by :func:`mrm.document.apply.apply_operation`, so it carries its provenance
(operation, parameters, inputs) and the error inspector shows the paper's bound for its chain.

* ``fig12-dss-combinations.mrm``: a digital diamond A, then DSS 1.25 → DSS 5 → DSS 0.2 → DSS 0.8 (Fig. 12);
* ``fig13-rotations.mrm``: a square face A, A1 = dR_45 about (0, 0), dR_90 about (−2.5, 3.2), and
  dR_−45(A1) about (0, 0), which is not A again (Fig. 13);
* ``fig08-simplification.mrm``: a detailed polygon simplified with Sp_α for α = 1, 1/2, 1/4 (Fig. 8);
* ``fig09-10-union-corefinement.mrm``: two overlapping polygons, their union EDu and co-refinement EDco
  (Figs. 9 and 10);
* ``fig12-3d-octahedron.mrm``: the paper's Figure 12 in 3D, a digital octahedron A and the chain DSS 1.25 →
  DSS 5 → DSS 0.2 → DSS 0.8 on voxels;
* ``rotation-3d.mrm``: a digital brick turned by 30° about the axis (1, 1, 1) through its centre, turned
  back (not A again), and a quarter turn about x (exact).

Run ``.venv/bin/python resources/examples/make_examples.py`` from the repository root.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
from shapely.geometry import Polygon

from mrm.core.grids import PixelSet, VoxelSet
from mrm.document import Document
from mrm.document.apply import apply_operation
from mrm.document.commands import AddObject
from mrm.io.project import save_project
from mrm.ops.registry import get_operation

HERE = Path(__file__).parent


def _params(name: str, **values: object) -> object:
    return get_operation(name).params(**values)


def _add(doc: Document, source: object, name: str) -> int:
    obj = doc.make_object(source, name)
    doc.push(AddObject(obj))
    return int(obj.id)


def _rename_last(doc: Document, ids: list[int], name: str) -> int:
    from mrm.document.commands import RenameObject

    doc.push(RenameObject(ids[0], name))
    return ids[0]


def fig12() -> Document:
    """The digital diamond |x| + |y| ≤ 12 and the chain DSS 1.25, DSS 5, DSS 0.2, DSS 0.8."""
    doc = Document()
    yy, xx = np.mgrid[-12:13, -12:13]
    cur = _add(doc, PixelSet(np.abs(xx) + np.abs(yy) <= 12, (-12, -12)), "A (diamond)")
    for alpha in (1.25, 5.0, 0.2, 0.8):
        ids = apply_operation(doc, "dss", [cur], _params("dss", alpha=alpha))
        cur = _rename_last(doc, ids, f"DSS {alpha:g}")
    return doc


def fig13() -> Document:
    """A square face rotated by 45° and 90° about two centres, and A1 rotated back by −45°."""
    doc = Document()
    # A 13×13 square with a corner pixel at the origin (centred on the origin, the round trip is exact).
    a = _add(doc, PixelSet.box(0, 0, 12, 12), "A (square)")
    (a1,) = apply_operation(doc, "discrete_rotation", [a], _params("discrete_rotation", angle=45.0))
    _rename_last(doc, [a1], "A1 = dR45,(0,0)(A)")
    p90 = _params("discrete_rotation", angle=90.0, center=(-2.5, 3.2))
    (r90,) = apply_operation(doc, "discrete_rotation", [a], p90)
    _rename_last(doc, [r90], "dR90,(-2.5,3.2)(A)")
    (back,) = apply_operation(doc, "discrete_rotation", [a1], _params("discrete_rotation", angle=-45.0))
    _rename_last(doc, [back], "dR-45,(0,0)(A1)")
    return doc


def _leaf() -> Polygon:
    """A polygon with details at several scales: a star whose tips carry small notches."""
    pts = []
    n = 14
    for k in range(2 * n):
        r = 18.0 if k % 2 == 0 else 11.0
        t = math.pi * k / n
        # Coordinates rounded to 1/8: dyadic, so the file and the exact arithmetic agree on them.
        pts.append((round(r * math.cos(t) * 8) / 8, round(r * math.sin(t) * 8) / 8))
    return Polygon(pts)


def fig08() -> Document:
    """Sp_α of a detailed polygon for α = 1, 1/2 and 1/4: fewer details as the voxels grow."""
    doc = Document()
    e = _add(doc, _leaf(), "E (star)")
    for alpha in (1.0, 0.5, 0.25):
        ids = apply_operation(doc, "simplify", [e], _params("simplify", alpha=alpha))
        _rename_last(doc, ids, f"Sp {alpha:g}")
    return doc


def fig09_10() -> Document:
    """Two overlapping polygons, their Euclidean-discrete union and co-refinement."""
    doc = Document()
    p = _add(doc, Polygon([(0.25, 0.5), (14.5, 1.75), (16.25, 9.5), (6, 13.25), (-1.5, 7)]), "E (pentagon)")
    q = _add(doc, Polygon([(9.5, 3.25), (21, -1.5), (25.75, 10), (14.25, 14.75)]), "E' (tilted square)")
    ids = apply_operation(doc, "union", [p, q], _params("union"))
    _rename_last(doc, ids, "EDu(E, E')")
    parts = {"a_minus_b": "EDco: E ∖ E'", "a_and_b": "EDco: E ∩ E'", "b_minus_a": "EDco: E' ∖ E"}
    for i in apply_operation(doc, "corefine", [p, q], _params("corefine")):
        part = str(doc.get(i).provenance.params["part"])
        _rename_last(doc, [i], parts.get(part, f"EDco: {part}"))
    return doc


def fig12_3d() -> Document:
    """The digital octahedron |x| + |y| + |z| ≤ 10 and the chain DSS 1.25, 5, 0.2, 0.8 (Fig. 12)."""
    doc = Document()
    r = 10
    zz, yy, xx = np.mgrid[-r : r + 1, -r : r + 1, -r : r + 1]
    octahedron = VoxelSet(np.abs(xx) + np.abs(yy) + np.abs(zz) <= r, (-r, -r, -r))
    cur = _add(doc, octahedron, "A (octahedron)")
    for alpha in (1.25, 5.0, 0.2, 0.8):
        ids = apply_operation(doc, "dss", [cur], _params("dss", alpha=alpha))
        cur = _rename_last(doc, ids, f"DSS {alpha:g}")
    return doc


def rotation_3d() -> Document:
    """A 13 × 9 × 5 brick turned by 30° about (1, 1, 1) through its centre, back by −30°, and 90° about x."""
    doc = Document()
    a = _add(doc, VoxelSet.box(-6, -4, -2, 6, 4, 2), "A (brick)")
    turn = _params("discrete_rotation", angle=30.0, axis=(1.0, 1.0, 1.0), center=(0.0, 0.0, 0.0))
    (a1,) = apply_operation(doc, "discrete_rotation", [a], turn)
    _rename_last(doc, [a1], "A1 = dR30 about (1,1,1)")
    back = _params("discrete_rotation", angle=-30.0, axis=(1.0, 1.0, 1.0), center=(0.0, 0.0, 0.0))
    (a2,) = apply_operation(doc, "discrete_rotation", [a1], back)
    _rename_last(doc, [a2], "dR-30 about (1,1,1) of A1")
    quarter = _params("discrete_rotation", angle=90.0, axis=(1.0, 0.0, 0.0), center=(0.0, 0.0, 0.0))
    (q,) = apply_operation(doc, "discrete_rotation", [a], quarter)
    _rename_last(doc, [q], "dR90 about x (exact)")
    return doc


EXAMPLES = {
    "fig12-dss-combinations.mrm": fig12,
    "fig13-rotations.mrm": fig13,
    "fig08-simplification.mrm": fig08,
    "fig09-10-union-corefinement.mrm": fig09_10,
    "fig12-3d-octahedron.mrm": fig12_3d,
    "rotation-3d.mrm": rotation_3d,
}


def main() -> None:
    """Write every example next to this script."""
    for name, make in EXAMPLES.items():
        doc = make()
        doc.set_selection([])
        save_project(doc, HERE / name)
        print(f"{name}: {len(doc.objects)} objects")


if __name__ == "__main__":
    main()
