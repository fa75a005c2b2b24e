"""A label map as one document object (ADR 0033): its representations, its project file, its commands.

The Euclidean representation of a label map is its watertight gauss subdivision, whatever the document's
model: each label's part discretizes back to exactly that label's pixels (checked with the exact
discretization and with GDAL's centre-rule rasterizer), and the project file gives the label map back.
"""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest

from mrm.core.errors import NotApplicableError
from mrm.core.grids import LabelMap, PixelSet
from mrm.document import Document, Settings
from mrm.document.commands import AddObject, SplitLabelMap
from mrm.document.edits import FillHole, PaintPixels
from mrm.geometry.discretize import discretize
from mrm.io.project import dumps, loads, read_project
from mrm.reps.cells import Cells

GOLDEN = Path(__file__).parent / "golden"


def _blobs(seed: int = 0, size: int = 48, n: int = 9) -> LabelMap:
    """A label map of n labels grown from random seeds (Voronoi cells), some background, holes and nesting."""
    rng = np.random.default_rng(seed)
    yy, xx = np.mgrid[0:size, 0:size]
    seeds = rng.integers(0, size, size=(n, 2))
    d = (xx[..., None] - seeds[:, 0]) ** 2 + (yy[..., None] - seeds[:, 1]) ** 2
    labels = (np.argmin(d, axis=2) + 1).astype(np.int32)
    labels[rng.random((size, size)) < 0.03] = 0  # specks of background
    labels[10:14, 10:14] = 0  # a hole
    labels[11:13, 11:13] = n + 1  # an island in it
    return LabelMap(labels, (-7, 3))


@pytest.mark.parametrize("model", ["standard", "supercover", "gauss"])
def test_the_euclidean_representation_discretizes_back_to_the_label_image_under_gauss(model):
    lm = _blobs()
    doc = Document(Settings(model=model))
    obj = doc.make_object(lm, name="parcels")
    doc.push(AddObject(obj))
    entry = doc.cache.entry(obj.source, doc.model)
    assert entry.get("discrete") is lm
    sd = entry.get("euclidean")  # the gauss subdivision whatever the document's model
    assert sorted(sd.parts) == lm.label_values()
    for label, part in sd.parts.items():
        assert part.is_valid
        assert discretize(part, "gauss") == lm.pixel_set(label), label
    # GDAL's centre rule burns the parts with their labels back to the label image.
    from rasterio import features, transform

    h, w = lm.shape
    x0, y0 = lm.origin
    # Row 0 of the raster is the top (largest y); the label array's row 0 is the lowest y.
    geo = transform.from_origin(x0 - 0.5, y0 - 0.5 + h, 1.0, 1.0)
    burnt = features.rasterize(((p, v) for v, p in sd.parts.items()), out_shape=(h, w), transform=geo)
    assert np.array_equal(burnt[::-1], lm.labels)
    # Shared boundaries: every 1-cell is one polyline, used by the parts on both sides.
    assert len(sd.polylines) == len(sd.cells.one_cells) > 0
    # The region representation is the map's cells.
    cells = entry.get("region")
    assert isinstance(cells, Cells) and cells.adjacency
    with pytest.raises(NotApplicableError, match="Split into Objects"):
        entry.get("analytical")


def test_a_label_map_object_goes_through_the_project_file_unchanged():
    lm = _blobs(seed=3)
    doc = Document(Settings(model="standard"))
    obj = doc.make_object(lm, name="parcels")
    doc.push(AddObject(obj, select=True))
    doc.push(AddObject(doc.make_object(PixelSet.box(0, 0, 3, 3), name="box")))
    data = dumps(doc)
    again = loads(data)
    back = again.get(obj.id)
    assert back.kind == "labels" and back.source == lm and back.name == "parcels"
    assert back.style == obj.style and again.selection == (obj.id,)
    assert dumps(again) == data
    record = json.loads(data)["objects"][0]["source"]
    assert record["kind"] == "labels" and record["shape"] == list(lm.shape)


def test_golden_v4_label_map_reads_as_written_down_here():
    proj = read_project(GOLDEN / "v4-label-map.mrm")
    doc = proj.to_document()
    parcels = doc.get(1)
    assert parcels.kind == "labels" and parcels.name == "parcels"
    assert parcels.source.origin == (-2, 5)
    expected = np.array(
        [[0, 1, 1, 2, 2, 0], [1, 1, 0, 2, 2, 2], [1, 1, 1, 3, 3, 2], [0, 7, 7, 3, 0, 2]], dtype=np.int32
    )
    assert np.array_equal(parcels.source.labels, expected)
    assert parcels.source.label_values() == [1, 2, 3, 7]
    assert doc.get(2).kind == "discrete" and doc.selection == (2,)


@pytest.mark.parametrize(
    "labels, message",
    [
        ("@@@", "not valid base64"),
        ("AAAA", "not valid zlib data"),
        ("eJxjYGBgYIRiJihmQBJjQBJnQhIHYWYohulhh2JmJH0ABugALQ==", None),
    ],
)
def test_a_damaged_label_map_in_a_project_file_is_refused_with_its_path(labels, message):
    from mrm.core.errors import FileFormatError

    raw = json.loads((GOLDEN / "v4-label-map.mrm").read_bytes())
    src = raw["objects"][0]["source"]
    src["labels"] = labels
    if message is None:  # the right data for another shape
        src["shape"] = [4, 7]
        message = "expected 112 bytes of int32 labels for a 4 x 7 map"
    with pytest.raises(FileFormatError, match=message) as e:
        loads(json.dumps(raw).encode())
    assert "objects[0].source.labels" in str(e.value)


def test_split_into_objects_gives_one_pixel_object_per_label_in_one_undo_step():
    lm = _blobs(seed=5)
    doc = Document()
    obj = doc.make_object(lm, name="parcels")
    doc.push(AddObject(obj))
    doc.push(SplitLabelMap(obj.id))
    assert obj.id not in doc
    parts = {o.name: o for o in doc.objects}
    assert sorted(parts) == sorted(f"parcels label {v}" for v in lm.label_values())
    for v in lm.label_values():
        assert parts[f"parcels label {v}"].source == lm.pixel_set(v)
    assert doc.selection == tuple(o.id for o in doc.objects)
    doc.undo()
    assert [o.id for o in doc.objects] == [obj.id] and doc.get(obj.id).source is lm


def test_pixel_edits_say_they_do_not_apply_to_a_label_map():
    doc = Document()
    obj = doc.make_object(_blobs(seed=2), name="parcels")
    doc.push(AddObject(obj))
    for command in (PaintPixels(obj.id, PixelSet.box(0, 0, 1, 1)), FillHole(obj.id, (5, 13))):
        with pytest.raises(NotApplicableError, match=r"'parcels' is a label map.*Split into Objects"):
            doc.push(command)
    assert doc.get(obj.id).source == obj.source and doc.history.undo_label() == "Add parcels"


def test_export_writes_one_feature_per_region_as_mrm_polygonize_does(tmp_path):
    from mrm.geometry.reconstruct.polygonize import polygonize
    from mrm.io.vector_files import write_regions_geojson

    lm = _blobs(seed=7)
    out = tmp_path / "regions.geojson"
    write_regions_geojson(polygonize(lm), out)
    fc = json.loads(out.read_text())
    props = [f["properties"] for f in fc["features"]]
    assert {p["label"] for p in props} == set(lm.label_values())
    for v in lm.label_values():
        assert sum(p["pixels"] for p in props if p["label"] == v) == lm.pixel_set(v).count


def test_a_label_maps_pixels_are_looked_up_like_a_pixel_sets():
    lm = LabelMap(np.array([[0, 3], [5, 0]], np.int32), (10, 20))
    assert lm.bbox == (10, 20, 11, 21) and lm.bbox == lm.support().bbox
    assert [lm.label_at(p) for p in ((11, 20), (10, 21), (10, 20), (12, 20))] == [3, 5, 0, 0]
    assert (11, 20) in lm and (11.0, 20) in lm and (10, 20) not in lm
    for odd in ((11.5, 20), ("11", 20), (11,), None):
        assert odd not in lm and odd not in lm.support()


def test_a_label_map_too_costly_to_polygonize_keeps_its_labels_and_says_why(monkeypatch):
    """Issue 32: the window's polygons of a label map share mrm polygonize's cost check (before any work)."""
    from mrm.core.errors import LimitError
    from mrm.geometry.reconstruct import subdivision

    monkeypatch.setattr(subdivision, "_subdivide", lambda _lm: pytest.fail("subdivided before the check"))
    labels = (np.arange(150 * 150, dtype=np.int32) + 1).reshape(150, 150)  # 22,500 one-pixel labels
    doc = Document(Settings(model="gauss"))
    obj = doc.make_object(LabelMap(labels), name="noise")
    doc.push(AddObject(obj))
    entry = doc.cache.entry(obj.source, doc.model)
    for _ in range(2):  # the refusal is kept: asking again does not start the work again
        with pytest.raises(LimitError, match="22,500 labels"):
            entry.get("euclidean")
    assert entry.get("discrete") is obj.source and doc.get(obj.id).source is obj.source
