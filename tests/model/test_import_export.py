"""Export of objects and label maps, import of files into a document, and project inputs of the CLI."""

from __future__ import annotations

import json
import re
from pathlib import Path

import numpy as np
import pytest
from shapely.geometry import LineString, Polygon

from mrm.cli._project_input import load_input
from mrm.core.errors import FileFormatError, MRMError, ParameterError
from mrm.core.grids import PixelSet
from mrm.document import Document, Settings
from mrm.document.commands import AddObject
from mrm.io.export import export_label_map, export_object, export_objects_geojson, label_map_of
from mrm.io.imports import import_file
from mrm.io.pixel_files import read_label_map, read_pixels, write_pixels
from mrm.io.project import save_project
from mrm.io.vector_files import read_geometry, write_geojson, write_wkt
from mrm.ops.provenance import Provenance

POLY = Polygon([(0.25, 0.5), (9.75, 1.125), (4.0, 7.5)], [[(3.0, 2.0), (4.5, 3.5), (5.0, 2.0)]])
PIXELS = PixelSet.box(-3, 10, 2, 14) - PixelSet.from_points([(0, 12)])


@pytest.fixture
def doc() -> Document:
    d = Document(Settings("supercover"))
    for src, name in ((POLY, "shape"), (PIXELS, "pixels")):
        d.push(AddObject(d.make_object(src, name)))
    return d


# ---------------------------------------------------------------------------------------------- export
@pytest.mark.parametrize("ext", [".png", ".pbm", ".pgm", ".npz"])
def test_pixel_exports_hold_the_discrete_representation_in_place(doc, tmp_path, ext):
    from mrm.geometry.discretize import discretize

    for oid, expected in zip(doc.ids, (discretize(POLY, "supercover"), PIXELS), strict=True):
        path = tmp_path / f"o{oid}{ext}"
        assert export_object(doc, oid, path) == "discrete"
        assert read_pixels(path) == expected


@pytest.mark.parametrize("ext", [".geojson", ".wkt"])
def test_vector_exports_hold_the_euclidean_representation_exactly(doc, tmp_path, ext):
    path = tmp_path / f"shape{ext}"
    assert export_object(doc, doc.ids[0], path) == "euclidean"
    back = read_geometry(path)
    assert back.normalize() == POLY.normalize()  # same coordinates, bit for bit


def test_geojson_export_names_the_object_and_model(doc, tmp_path):
    export_object(doc, doc.ids[0], tmp_path / "s.geojson")
    props = json.loads((tmp_path / "s.geojson").read_text())["features"][0]["properties"]
    assert props["name"] == "shape" and props["model"] == "supercover" and props["source"] == "euclidean"


def test_a_discrete_object_exports_its_continuation(doc, tmp_path):
    from mrm.geometry.discretize import discretize

    export_object(doc, doc.ids[1], tmp_path / "p.wkt")
    assert discretize(read_geometry(tmp_path / "p.wkt"), "supercover") == PIXELS


def test_several_objects_in_one_geojson(doc, tmp_path):
    export_objects_geojson(doc, doc.ids, tmp_path / "all.geojson")
    feats = json.loads((tmp_path / "all.geojson").read_text())["features"]
    assert [f["properties"]["part"] for f in feats] == ["shape", "pixels"]


def test_svg_export_is_upright(doc, tmp_path):
    export_object(doc, doc.ids[0], tmp_path / "s.svg")
    text = (tmp_path / "s.svg").read_text()
    assert text.lstrip().startswith("<?xml") and "<svg" in text
    # y is up in the picture: the vertex (4.0, 7.5) is drawn at SVG (4.0, -7.5).
    assert re.search(r"4\.0[ ,]-7\.5", text)
    export_object(doc, doc.ids[1], tmp_path / "p.svg", rep="discrete")
    pix = (tmp_path / "p.svg").read_text()
    assert "<rect" in pix and 'y="-14.5"' in pix  # the top row y = 14 spans [13.5, 14.5]


def test_export_refuses_unknown_types_and_mismatched_representations(doc, tmp_path):
    with pytest.raises(FileFormatError, match=r"cannot export to '\.bmp'"):
        export_object(doc, doc.ids[0], tmp_path / "x.bmp")
    with pytest.raises(ParameterError):
        export_object(doc, doc.ids[0], tmp_path / "x.png", rep="euclidean")
    with pytest.raises(FileFormatError):
        export_label_map(doc, tmp_path / "x.pbm")


def test_label_map_gives_each_object_its_rank_and_the_top_one_wins():
    d = Document()
    a = d.make_object(PixelSet.box(0, 0, 3, 3), "a")
    b = d.make_object(PixelSet.box(2, 2, 5, 5), "b")
    d.push(AddObject(a))
    d.push(AddObject(b))
    lm, mapping = label_map_of(d)
    assert mapping == {1: a.id, 2: b.id}
    assert lm.pixel_set(1) == PixelSet.box(0, 0, 3, 3) - PixelSet.box(2, 2, 3, 3)
    assert lm.pixel_set(2) == PixelSet.box(2, 2, 5, 5)
    lm2, mapping2 = label_map_of(d, [b.id, a.id])
    assert lm2.pixel_set(2) == PixelSet.box(0, 0, 3, 3) and mapping2 == {1: b.id, 2: a.id}


@pytest.mark.parametrize("ext", [".png", ".npz"])
def test_label_map_files_read_back(doc, tmp_path, ext):
    from mrm.geometry.discretize import discretize

    path = tmp_path / f"labels{ext}"
    mapping = export_label_map(doc, path)
    lm = read_label_map(path)
    assert mapping == {1: doc.ids[0], 2: doc.ids[1]}
    assert lm.pixel_set(1) == discretize(POLY, "supercover") - PIXELS
    assert lm.pixel_set(2) == PIXELS


# ---------------------------------------------------------------------------------------------- import
def test_import_of_pixel_and_vector_files_is_one_undo_step(tmp_path):
    write_pixels(PIXELS, tmp_path / "mask.png")
    write_geojson([("tri", POLY), ("line", LineString([(0.0, 0.0), (5.5, 2.0)]))], tmp_path / "v.geojson")
    d = Document()
    (pid,) = import_file(d, tmp_path / "mask.png")
    assert d.get(pid).source == PIXELS and d.get(pid).name == "mask"
    ids = import_file(d, tmp_path / "v.geojson")
    assert [d.get(i).name for i in ids] == ["tri", "line"]
    assert d.get(ids[0]).kind == "euclidean" and d.get(ids[0]).source.normalize() == POLY.normalize()
    from mrm.geometry.discretize import discretize

    # A line is no shape: it comes in as its discretization.
    assert d.get(ids[1]).source == discretize(LineString([(0.0, 0.0), (5.5, 2.0)]), "standard")
    assert d.selection == tuple(ids)
    d.undo()
    assert d.ids == (pid,)


def test_import_of_a_project_gives_fresh_ids_and_follows_provenance(tmp_path):
    src = Document()
    a = src.make_object(PIXELS, "a")
    b = src.make_object(POLY, "b", provenance=Provenance("scale", {"alpha": 2.0}, (a.id, 99)))
    src.push(AddObject(a))
    src.push(AddObject(b))
    save_project(src, tmp_path / "other.mrm")
    d = Document()
    d.push(AddObject(d.make_object(PixelSet.box(0, 0, 1, 1))))
    d.push(AddObject(d.make_object(PixelSet.box(5, 5, 6, 6))))
    ids = import_file(d, tmp_path / "other.mrm")
    assert len(set(ids) | set(d.ids)) == 4
    na, nb = (d.get(i) for i in ids)
    assert na.source == PIXELS and nb.provenance.inputs == (na.id, 99)


def test_import_refuses_bad_files_and_leaves_the_document_alone(tmp_path):
    d = Document()
    (tmp_path / "x.txt").write_text("hello")
    with pytest.raises(FileFormatError, match=r"cannot import '\.txt'"):
        import_file(d, tmp_path / "x.txt")
    (tmp_path / "bad.geojson").write_text(
        '{"type": "Polygon", "coordinates": [[[0,0],[2,2],[2,0],[0,2],[0,0]]]}'
    )
    with pytest.raises(MRMError):
        import_file(d, tmp_path / "bad.geojson")
    assert len(d) == 0 and d.history.count == 0


# ---------------------------------------------------------------------------------------------- CLI inputs
@pytest.fixture
def project(tmp_path) -> Path:
    d = Document(Settings("gauss"))
    d.push(AddObject(d.make_object(POLY, "tri")))
    d.push(AddObject(d.make_object(PIXELS, "blob")))
    d.push(AddObject(d.make_object(PixelSet.box(0, 0, 0, 0), "twin")))
    d.push(AddObject(d.make_object(PixelSet.box(1, 0, 1, 0), "twin")))
    save_project(d, tmp_path / "p.mrm")
    return tmp_path / "p.mrm"


def test_load_input_picks_an_object_of_a_project(project):
    assert load_input(project, "blob") == ("discrete", PIXELS, "gauss")
    kind, geom, model = load_input(project, "tri", "supercover")
    assert kind == "euclidean" and geom == POLY and model == "supercover"


def test_load_input_converts_on_request(project):
    from mrm.geometry.discretize import discretize

    kind, ps, model = load_input(project, "tri", want="discrete")
    assert (kind, model) == ("discrete", "gauss") and ps == discretize(POLY, "gauss")
    kind, geom, _ = load_input(project, "blob", want="euclidean")
    assert kind == "euclidean" and discretize(geom, "gauss") == PIXELS


def test_load_input_explains_missing_and_ambiguous_objects(project, tmp_path):
    with pytest.raises(
        ParameterError, match=r"holds 4 objects; choose one with --object NAME \('tri', 'blob'"
    ):
        load_input(project)
    with pytest.raises(ParameterError, match=r"no object named 'nope'; the project holds 'tri', 'blob'"):
        load_input(project, "nope")
    with pytest.raises(ParameterError, match=r"2 objects are named 'twin'"):
        load_input(project, "twin")
    single = Document()
    single.push(AddObject(single.make_object(PIXELS, "only")))
    save_project(single, tmp_path / "one.mrm")
    assert load_input(tmp_path / "one.mrm")[1] == PIXELS  # one object: no --object needed


def test_load_input_reads_plain_files(tmp_path):
    write_pixels(PIXELS, tmp_path / "m.npz")
    write_wkt(POLY, tmp_path / "g.wkt")
    assert load_input(tmp_path / "m.npz") == ("discrete", PIXELS, "standard")
    kind, geom, _ = load_input(tmp_path / "g.wkt", model="gauss")
    assert kind == "euclidean" and geom.normalize() == POLY.normalize()
    with pytest.raises(ParameterError, match="--object applies to project"):
        load_input(tmp_path / "m.npz", "x")
    (tmp_path / "a.xyz").write_text("1")
    with pytest.raises(FileFormatError, match=r"'\.xyz' is not an input type"):
        load_input(tmp_path / "a.xyz")
    with pytest.raises(FileNotFoundError):
        load_input(tmp_path / "missing.mrm")


def test_load_input_reports_hostile_projects_as_user_errors(tmp_path):
    (tmp_path / "h.mrm").write_bytes(np.arange(100, dtype=np.uint8).tobytes())
    with pytest.raises(MRMError, match=r"h\.mrm"):
        load_input(tmp_path / "h.mrm", "x")


def test_meshes_and_volumes_import_as_3d_objects_and_a_2d_npz_stays_pixels(tmp_path):
    import mrm
    from mrm.core.errors import InvalidGeometryError
    from mrm.core.grids import VoxelSet
    from mrm.geometry.polyhedra import Polyhedron

    tet = Polyhedron(
        [[0, 0, 0], [4, 0, 0], [0, 4, 0], [0, 0, 4]], [[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]]
    )
    mrm.write_mesh(tet, tmp_path / "tet.off")
    vs = VoxelSet(np.ones((2, 2, 3), bool), (1, 2, 3))
    mrm.write_voxels(vs, tmp_path / "v.tif")
    write_pixels(PixelSet(np.ones((2, 3), bool), (5, 5)), tmp_path / "p.npz")
    doc = Document()
    ids = [i for name in ("tet.off", "v.tif", "p.npz") for i in import_file(doc, tmp_path / name)]
    got = {doc.get(i).name: doc.get(i).source for i in ids}
    assert got["tet"] == tet and got["v"] == vs
    assert isinstance(got["p"], PixelSet) and got["p"].count == 6
    (tmp_path / "open.obj").write_text("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n")  # not a closed surface
    with pytest.raises(InvalidGeometryError) as err:
        import_file(doc, tmp_path / "open.obj")
    assert "\n" not in str(err.value) and len(doc) == 3
