"""3D objects in a document (docs/design.md §11): their four representations come from the one derivation
cache, through the exact D, the 3D R and the (6, 26) region representation."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from mrm.core.errors import NotApplicableError
from mrm.core.grids import VoxelSet
from mrm.document.commands import ChangeSettings
from mrm.geometry.discretize.voxels import voxelize
from mrm.geometry.polyhedra import Polyhedron
from mrm.io.project import load_project

GOLDEN_V5 = Path(__file__).parent / "golden" / "v5-voxels.mrm"


@pytest.fixture
def doc():
    return load_project(GOLDEN_V5)


def test_a_polyhedron_object_is_voxelized_exactly_under_the_documents_model(doc):
    solid = doc.find("solid octahedron")[0]
    doc.push(ChangeSettings.model(doc, "gauss"))
    d = doc.derived(solid.id)
    # gauss: the centres p + τ inside |x| + |y| + |z| ≤ 2.5, i.e. the integer points with |x| + |y| + |z| ≤ 2
    expected = {
        (x, y, z)
        for x in range(-3, 4)
        for y in range(-3, 4)
        for z in range(-3, 4)
        if abs(x) + abs(y) + abs(z) <= 2
    }
    assert set(d.get("discrete")) == expected
    region = d.get("region")
    assert (region.n_components, region.n_cavities, region.euler) == (1, 0, 1)
    assert d.get("euclidean") is solid.source


def test_the_cost_of_a_polyhedrons_representations_is_estimated_from_its_box(doc):
    # What the desktop asks before choosing the GUI thread or a worker (it raised AttributeError: a
    # polyhedron has a 3D box, not the plane bounds of a shapely geometry).
    d = doc.derived(doc.find("solid octahedron")[0].id)
    costs = {rep: d.estimated_cost(rep) for rep in ("discrete", "region", "analytical", "euclidean")}
    assert 6**3 <= costs["discrete"] < costs["region"] < costs["analytical"]  # a 5 × 5 × 5 box + room
    d.get("region")
    assert d.estimated_cost("discrete") == d.estimated_cost("region") == 0.0


def test_a_voxel_object_gets_a_polyhedron_that_gives_it_back(doc):
    obj = doc.find("octahedron")[0]
    for model in ("standard", "supercover", "gauss"):
        doc.push(ChangeSettings.model(doc, model))
        poly = doc.derived(obj.id).get("euclidean")
        assert isinstance(poly, Polyhedron) and voxelize(poly, model) == obj.source
    # The analytical representation: the digital plane segments of its surface, those of the reference
    # segmentation (pure Python, tests/model/test_planes.py), each plane separating its voxels of A from the
    # voxels outside.
    from mrm.geometry.planes.segmentation import plane_segments_reference
    from mrm.geometry.topology.labeling_3d import label_runs_3d
    from mrm.geometry.topology.surfels import DIRS, surfels_of

    analytical = doc.derived(obj.id).get("analytical")
    vs = obj.source
    s = surfels_of(label_runs_3d(vs.mask, 6))
    reference = plane_segments_reference(s.voxel + np.array(vs.origin), s.direction, s.neighbour)
    assert 1 < len(analytical) == len(reference)
    seg = analytical.segmentation
    for k in range(len(analytical)):
        members = seg.surfels_of(k)
        inner = seg.voxel[members]
        outer = inner + DIRS[seg.direction[members]]
        plane = analytical.segment(k)
        n = np.array(plane.plane.normal)
        assert (inner @ n).max() < plane.offset < (outer @ n).min()


def test_a_label_volume_has_its_cells_and_says_why_it_has_no_meshes_yet(doc):
    obj = doc.find("labels 3D")[0]
    d = doc.derived(obj.id)
    assert d.get("region") is not None
    with pytest.raises(NotApplicableError, match="label volume"):
        d.get("euclidean")
    with pytest.raises(NotApplicableError, match="label volume's faces are shared"):
        d.get("analytical")


def test_plane_objects_leave_the_3d_ones_out(doc):
    assert [o.name for o in doc.plane_objects] == ["square"]
    assert isinstance(doc.find("octahedron")[0].source, VoxelSet)


def test_plane_work_never_loads_the_3d_kernels():
    # The desktop's first paint imports the document, the project codec and R: the dozen compiled 3D kernel
    # modules (polyhedra, voxelizer, 3D regions) must wait until a 3D object is met (0.3–0.5 s of start-up).
    import subprocess
    import sys

    code = (
        "import sys, mrm.document, mrm.document.derive, mrm.io.project, mrm.geometry.reconstruct; "
        "print(sorted(m for m in sys.modules "
        "if 'polyhedra' in m or m.endswith(('_3d', '_kernels3d', 'voxels'))))"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True).stdout
    assert out.strip() == "[]"


def test_a_voxel_objects_r_says_when_it_is_the_safety_net(doc):
    # The note the desktop shows: None for a compact R; past the document's compact limit, R is the safety
    # net, which still gives the voxels back, and the note says so with the limit.
    from mrm.document.commands import AddObject

    obj = doc.find("octahedron")[0]
    d = doc.derived(obj.id)
    d.get("euclidean")
    assert d.r_note is None
    mask = np.zeros((3, 4, 4), bool)
    mask[:, :2, :] = True
    mask[:, :, :2] = True  # an L-shaped prism: not digitally convex
    ell = doc.make_object(VoxelSet(mask, (0, 0, 0)), name="ell")
    doc.push(AddObject(ell))
    assert doc.derived(ell.id).get("euclidean") is not None and doc.derived(ell.id).r_note is None
    doc.push(ChangeSettings.compact_limit(doc, 10))
    doc.push(ChangeSettings.model(doc, "supercover"))  # a new model: R made again, past the limit now
    d = doc.derived(ell.id)
    assert d.r_note is None  # nothing said before R is made
    poly = d.get("euclidean")
    assert voxelize(poly, "supercover") == ell.source
    assert d.r_note is not None and "R is the safety net" in d.r_note and d.r_over_limit
    assert f"{poly.n_triangles:,} triangles" in d.r_note and "at most 10 triangles" in d.r_note


def test_the_compact_limit_re_derives_the_voxel_objects_only_and_is_undone(doc):
    # A setting of the document (ADR 0073): a voxel object's R depends on it, nothing else does.
    from mrm.document.commands import AddObject

    mask = np.zeros((3, 4, 4), bool)
    mask[:, :2, :] = True
    mask[:, :, :2] = True  # an L-shaped prism: not digitally convex, so its R is the decimation
    ell = doc.make_object(VoxelSet(mask, (0, 0, 0)), name="ell")
    doc.push(AddObject(ell))
    before = {o.id: doc.derived(o.id) for o in doc}
    compact = before[ell.id].get("euclidean")
    seen = []
    doc.subscribe(seen.append)
    doc.push(ChangeSettings.compact_limit(doc, 10))
    assert doc.history.undo_label() == "Compact R up to 10 triangles"
    (changes,) = seen
    voxel_sets = {o.id for o in doc if isinstance(o.source, VoxelSet)}
    assert voxel_sets == {doc.find("octahedron")[0].id, ell.id}
    assert {i for i, what in changes.changed.items() if "derived" in what} == voxel_sets
    for o in doc:  # the others keep what was derived for them
        assert (doc.derived(o.id) is before[o.id]) == (o.id not in voxel_sets)
    net = doc.derived(ell.id).get("euclidean")
    assert net.n_triangles > 10 and net.n_triangles > compact.n_triangles
    assert voxelize(net, "standard") == ell.source  # exact either way
    doc.undo()
    assert doc.settings.compact_limit == 20_000 and doc.derived(ell.id) is before[ell.id]
    doc.redo()
    assert doc.derived(ell.id).get("euclidean") is net  # the entry kept for a redo


def test_a_documents_operations_and_account_read_the_r_of_its_compact_limit(doc):
    # DSS_α scales R(A): under a compact limit of 10 a staircase's R is its safety net, so DSS reads the net,
    # in the document's operations and in its error account, and the result is not the default one's.
    from mrm.document.apply import apply_operation
    from mrm.document.commands import AddObject
    from mrm.geometry.reconstruct.safety_net_3d import safety_net_3d
    from mrm.ops.account import account_of
    from mrm.ops.registry import plan_operation, run_operation

    z, y, x = np.mgrid[0:6, 0:6, 0:6]
    stairs = doc.make_object(VoxelSet((x + y + z <= 7) | (x >= 4), (0, 0, 0)), name="stairs")
    doc.push(AddObject(stairs))
    params = {"alpha": 1.5}
    default = plan_operation([stairs], "dss", params).results[0].source
    doc.push(ChangeSettings.compact_limit(doc, 10))
    (made,) = apply_operation(doc, "dss", [stairs.id], params)
    result = doc.get(made).source
    net = safety_net_3d(stairs.source.mask, stairs.source.origin)
    scaled_net = run_operation(
        "dss", [stairs.source], params, held=[(0, doc.model, Polyhedron(net.vertices, net.triangles))]
    )
    assert result == scaled_net.output and result != default
    acc = account_of(doc.get(made).provenance, compact_limit=doc.settings.compact_limit)
    assert not acc.error and acc.output == result  # the account measured the R the operation read
    assert account_of(doc.get(made).provenance).output == default  # elsewhere, the default limit's R
