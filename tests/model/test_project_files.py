"""Project files: exact round trips, golden files of every schema version, hostile and corrupt files,
migrations, atomic saves, autosave and recovery, and the example projects."""

from __future__ import annotations

import json
import os
import re
from pathlib import Path

import numpy as np
import pytest
from hypothesis import assume, given, settings
from hypothesis import strategies as st
from shapely.geometry import MultiPolygon, Polygon

from mrm.core.errors import FileFormatError, MRMError
from mrm.core.grids import LabelVolume, PixelSet, VoxelSet
from mrm.core.models import Model
from mrm.document import Document, Settings, Style
from mrm.document.commands import AddObject, ChangeSettings, RenameObject
from mrm.document.edits import PaintPixels
from mrm.geometry.polyhedra import Polyhedron
from mrm.io import autosave
from mrm.io.project import (
    SCHEMA_VERSION,
    Migration,
    dumps,
    load_project,
    loads,
    parse_project,
    read_project,
    save_project,
)
from mrm.ops.provenance import Provenance, content_digest

GOLDEN = Path(__file__).parent / "golden"
EXAMPLES = Path(__file__).parents[2] / "resources" / "examples"


def without_generator(data: bytes) -> bytes:
    return re.sub(rb'\n "generator": "[^"]*",', b"", data)


# ---------------------------------------------------------------------------------------------- golden files
def test_golden_v1_reads_as_written_down_here():
    doc = load_project(GOLDEN / "v1-all-features.mrm")
    assert doc.model == "supercover"
    assert doc.ids == (3, 5, 7, 8, 9, 10)
    assert doc.selection == (5,)
    assert not doc.is_modified and doc.history.count == 0
    diamond = doc.get(3)
    assert diamond.name == "diamond" and diamond.kind == "discrete" and diamond.provenance is None
    expected = {(x, y) for x in range(-2, 3) for y in range(-2, 3) if abs(x) + abs(y) <= 2}
    assert set(diamond.source) == expected
    tri = doc.get(5)
    assert tri.kind == "euclidean"
    assert list(tri.source.exterior.coords) == [(0.5, -0.25), (7.125, 1.0), (2.0, 6.5), (0.5, -0.25)]
    assert tri.style == Style(fill="#dd8452", stroke="#000000", opacity=0.25, stroke_width=2.0, visible=True)
    p = tri.provenance
    assert (p.operation, p.params, p.inputs) == (
        "rotate",
        {"angle": 30.0, "center": [0, 0], "exact": True, "note": None},
        (3,),
    )
    # A file from before pinned provenance: the input is pinned to what the file holds for it.
    assert p.sources == (diamond.source,) and p.digests == (content_digest(diamond.source),)
    islands = doc.get(7).source
    assert isinstance(islands, MultiPolygon) and len(islands.geoms) == 2
    assert list(islands.geoms[0].interiors[0].coords)[1] == (-8.5, -5.5)
    assert doc.get(7).style.visible is False
    assert doc.get(8).source == PixelSet.empty()
    assert doc.get(9).source.is_empty and doc.get(9).kind == "euclidean"
    assert doc.get(10).name == "ünïcode ✓"
    assert set(doc.get(10).source) == {(100, -7), (102, -7), (101, -6)}
    assert doc.get(10).style.fill == "#937860cc"


def test_golden_v5_holds_a_voxel_set_and_a_label_volume_as_written_down_here():
    doc = read_project(GOLDEN / "v5-voxels.mrm").to_document()
    octahedron = doc.get(1)
    assert isinstance(octahedron.source, VoxelSet) and octahedron.dimension == 3
    # "CC6CAA==" over a 3 × 3 × 3 box at (9, -21, 2): the unit octahedron centred on (10, -20, 3).
    assert set(octahedron.source) == {
        (10 + x, -20 + y, 3 + z)
        for x in (-1, 0, 1)
        for y in (-1, 0, 1)
        for z in (-1, 0, 1)
        if abs(x) + abs(y) + abs(z) <= 1
    }
    labels = doc.get(2).source
    assert isinstance(labels, LabelVolume)
    assert {p: labels.label_at(p) for p in [(-5, 0, 2), (-3, 1, 3), (-4, 0, 3), (-4, 1, 2)]} == {
        (-5, 0, 2): 1,
        (-3, 1, 3): 2,
        (-4, 0, 3): 7,
        (-4, 1, 2): 0,
    }
    assert doc.get(3).dimension == 2 and set(doc.get(3).source) == {(0, 0), (1, 0), (0, 1), (1, 1)}
    solid = doc.get(4).source
    assert isinstance(solid, Polyhedron) and doc.get(4).dimension == 3
    assert sorted(map(tuple, solid.vertices.tolist())) == sorted(
        [
            (2.5, 0.0, 0.0),
            (-2.5, 0.0, 0.0),
            (0.0, 2.5, 0.0),
            (0.0, -2.5, 0.0),
            (0.0, 0.0, 2.5),
            (0.0, 0.0, -2.5),
        ]
    )
    assert solid.n_faces == 8


def test_the_compact_limit_is_kept_in_the_file_and_older_files_get_the_default(tmp_path):
    # Schema 6 keeps the document's compact limit (the most safety-net triangles R simplifies).
    doc = read_project(GOLDEN / "v6-compact-limit.mrm").to_document()
    assert doc.settings == Settings(model=Model.GAUSS, compact_limit=150_000)
    older = read_project(GOLDEN / "v5-voxels.mrm").to_document()
    assert older.settings.compact_limit == 20_000  # the default the program used when it wrote it
    older.push(ChangeSettings.compact_limit(older, 3))
    save_project(older, tmp_path / "p.mrm")
    assert read_project(tmp_path / "p.mrm").settings == Settings(model=Model.STANDARD, compact_limit=3)


def test_a_polyhedron_that_is_not_a_solid_is_refused_on_load_with_its_path():
    raw = json.loads((GOLDEN / "v5-voxels.mrm").read_text())
    raw["objects"][3]["source"]["triangles"][0] = [0, 4, 2]  # one triangle turned inside out
    with pytest.raises(FileFormatError, match=r"objects\[3\]\.source"):
        loads(json.dumps(raw).encode())
    raw["objects"][3]["source"]["vertices"][0] = [1e300, 0, 0]
    with pytest.raises(FileFormatError, match=r"vertices\[0\]\[0\]"):
        loads(json.dumps(raw).encode())


def test_a_voxel_source_beyond_the_voxel_limit_is_refused_with_its_path():
    raw = json.loads((GOLDEN / "v5-voxels.mrm").read_text())
    raw["objects"][0]["source"]["shape"] = [2000, 2000, 2000]
    with pytest.raises(FileFormatError, match=r"objects\[0\]\.source\.shape.*voxels"):
        loads(json.dumps(raw).encode())
    raw["objects"][0]["source"]["shape"] = [3, 3]
    with pytest.raises(FileFormatError, match=r"\[nz, ny, nx\]"):
        loads(json.dumps(raw).encode())


@pytest.mark.parametrize("path", sorted(GOLDEN.glob("v*.mrm")), ids=lambda p: p.name)
def test_every_golden_file_loads_and_resaves_in_the_current_schema(path):
    proj = read_project(path)
    version = int(path.name[1 : path.name.index("-")])
    assert proj.file_version == version
    doc = proj.to_document()
    again = dumps(doc)
    assert json.loads(again)["schema_version"] == SCHEMA_VERSION
    if version == SCHEMA_VERSION:  # a current file is written back byte for byte
        assert without_generator(again) == without_generator(path.read_bytes())
    assert dumps(loads(again)) == again


def test_there_is_a_golden_file_for_every_schema_version():
    versions = {int(p.name[1 : p.name.index("-")]) for p in GOLDEN.glob("v*.mrm")}
    assert versions == set(range(1, SCHEMA_VERSION + 1))


# ---------------------------------------------------------------------------------------------- round trips
finite = st.floats(min_value=-1e6, max_value=1e6, allow_nan=False, allow_infinity=False)
tiny = st.sampled_from([0.1, 0.2, 1 / 3, 5e-324, 2.2250738585072014e-308, -0.0, 1e-300, 0.30000000000000004])


@st.composite
def triangles(draw: st.DrawFn) -> Polygon:
    pts = [(draw(finite | tiny), draw(finite | tiny)) for _ in range(3)]
    p = Polygon(pts)
    assume(p.is_valid and p.area > 0)
    return p


masks = st.tuples(st.integers(0, 12), st.integers(0, 70), st.integers(-(2**31), 2**31 - 100), st.data())


@st.composite
def pixel_sets(draw: st.DrawFn) -> PixelSet:
    h, w = draw(st.integers(0, 12)), draw(st.integers(0, 70))
    bits = draw(st.lists(st.booleans(), min_size=h * w, max_size=h * w))
    x0, y0 = draw(st.integers(-(2**31), 2**31 - 100)), draw(st.integers(-(2**31), 2**31 - 100))
    return PixelSet(np.array(bits, dtype=bool).reshape(h, w), (x0, y0))


@st.composite
def documents(draw: st.DrawFn) -> Document:
    doc = Document(Settings(draw(st.sampled_from(["standard", "supercover", "gauss"]))))
    for _ in range(draw(st.integers(0, 4))):
        if draw(st.booleans()):
            src = draw(triangles())
            if draw(st.booleans()):
                src = MultiPolygon([src])
        else:
            src = draw(pixel_sets())
        prov = None
        if draw(st.booleans()):
            params = draw(
                st.dictionaries(
                    st.text(max_size=5),
                    st.one_of(
                        st.none(), st.booleans(), st.integers(-(2**62), 2**62), finite, st.text(max_size=5)
                    ),
                    max_size=3,
                )
            )
            prov = Provenance(draw(st.text(min_size=1, max_size=8)), params, (1, 2))
        style = Style(
            fill=f"#{draw(st.integers(0, 0xFFFFFF)):06x}",
            opacity=draw(st.floats(0, 1)),
            stroke_width=draw(st.floats(0, 100)),
            visible=draw(st.booleans()),
        )
        doc.push(AddObject(doc.make_object(src, draw(st.text(max_size=10)), style=style, provenance=prov)))
    doc.set_selection(draw(st.lists(st.sampled_from(doc.ids), unique=True)) if len(doc) else [])
    return doc


@settings(max_examples=60)
@given(documents())
def test_save_load_is_bit_identical(doc):
    data = dumps(doc)
    back = loads(data)
    assert dumps(back) == data
    assert back.objects == doc.objects
    assert back.settings == doc.settings and back.selection == doc.selection
    for a, b in zip(doc.objects, back.objects, strict=True):
        if a.kind == "euclidean":
            # floats come back bit for bit (not merely equal: -0.0 and 0.0 differ here)
            ca = np.asarray(
                a.source.exterior.coords
                if isinstance(a.source, Polygon)
                else a.source.geoms[0].exterior.coords
            )
            cb = np.asarray(
                b.source.exterior.coords
                if isinstance(b.source, Polygon)
                else b.source.geoms[0].exterior.coords
            )
            assert ca.tobytes() == cb.tobytes()


def test_integers_stay_integers_and_floats_stay_floats():
    doc = load_project(GOLDEN / "v1-all-features.mrm")
    raw = json.loads(dumps(doc))
    o = raw["objects"][0]
    assert type(o["id"]) is int and all(type(v) is int for v in o["source"]["origin"] + o["source"]["shape"])
    coords = raw["objects"][1]["source"]["geometry"]["coordinates"][0]
    assert all(type(v) is float for pt in coords for v in pt)
    assert raw["objects"][1]["provenance"]["params"]["center"] == [0, 0]  # ints inside params stay ints
    assert type(raw["objects"][1]["provenance"]["params"]["center"][0]) is int


def test_integer_coordinates_written_by_hand_are_accepted():
    text = (GOLDEN / "v1-all-features.mrm").read_text(encoding="utf-8").replace("[7.125, 1.0]", "[7, 1]")
    doc = loads(text.encode())
    assert list(doc.get(5).source.exterior.coords)[1] == (7.0, 1.0)


# ---------------------------------------------------------------------------------------------- hostile files
def golden_json() -> dict:
    return json.loads((GOLDEN / "v1-all-features.mrm").read_text(encoding="utf-8"))


def mutated(edit) -> bytes:
    data = golden_json()
    edit(data)
    return json.dumps(data).encode()


def _set(path, value):
    def edit(d):
        *head, last = path
        for k in head:
            d = d[k]
        d[last] = value

    return edit


HOSTILE = {
    "empty": (b"", r"the file is empty"),
    "whitespace": (b"  \n\t ", r"the file is empty"),
    "truncated": ((GOLDEN / "v1-all-features.mrm").read_bytes()[:300], r"ends unexpectedly .*truncated"),
    "garbage JSON": (b'{"format": "mrm-project", oops}', r"not valid JSON: .* \(line 1, column 27\)"),
    "random bytes": (bytes(range(256)) * 3, r"not an MR Modeler project \(not UTF-8"),
    "a list": (b"[1, 2, 3]", r"the JSON is a list of 3, not an object"),
    "no format": (b'{"objects": []}', r"no 'format' key"),
    "other format": (b'{"format": "geojson"}', r"format is 'geojson'"),
    "NaN literal": (
        (GOLDEN / "v1-all-features.mrm").read_bytes().replace(b"0.25,", b"NaN,", 1),
        r"unreadable number: NaN",
    ),
    "deep nesting": (b"[" * 100_000 + b"]" * 100_000, r"nested too deeply"),
    "integer of 5000 digits": (
        b'{"format": "mrm-project", "schema_version": 1' + b"0" * 5000 + b"}",
        r"unreadable number",
    ),
    "newer schema": (mutated(_set(["schema_version"], 99)), r"newer version of MR Modeler \(schema 99\)"),
    "schema zero": (mutated(_set(["schema_version"], 0)), r"\$\.schema_version: integer 0 out of range"),
    "schema as text": (mutated(_set(["schema_version"], "1")), r"\$\.schema_version: expected an integer"),
    "missing settings": (mutated(lambda d: d.pop("settings")), r"at \$: missing key 'settings'"),
    "unknown key": (mutated(_set(["extra"], 1)), r"at \$: unknown key 'extra'"),
    "unknown model": (
        mutated(_set(["settings", "model"], "bresenham")),
        r"\$\.settings\.model: unknown model",
    ),
    "compact limit 0": (
        mutated(_set(["settings", "compact_limit"], 0)),
        r"\$\.settings\.compact_limit: integer 0 out of range \[1, 20000000\]",
    ),
    "compact limit beyond any polyhedron": (
        mutated(_set(["settings", "compact_limit"], 10**12)),
        r"\$\.settings\.compact_limit: integer 1000000000000 out of range",
    ),
    "compact limit as text": (
        mutated(_set(["settings", "compact_limit"], "20000")),
        r"\$\.settings\.compact_limit: expected an integer",
    ),
    "compact limit as float": (
        mutated(_set(["settings", "compact_limit"], 2.5e4)),
        r"\$\.settings\.compact_limit: expected an integer",
    ),
    "unknown setting": (mutated(_set(["settings", "speed"], 1)), r"\$\.settings: unknown key 'speed'"),
    "objects not a list": (mutated(_set(["objects"], {})), r"\$\.objects: expected a list, got an object"),
    "id as float": (mutated(_set(["objects", 0, "id"], 3.0)), r"\$\.objects\[0\]\.id: expected an integer"),
    "id as bool": (
        mutated(_set(["objects", 0, "id"], True)),
        r"\$\.objects\[0\]\.id: expected an integer, got true",
    ),
    "duplicate id": (mutated(_set(["objects", 1, "id"], 3)), r"\$\.objects\[1\]\.id: id 3 is already used"),
    "name as number": (
        mutated(_set(["objects", 2, "name"], 7)),
        r"\$\.objects\[2\]\.name: expected a string",
    ),
    "bad colour": (
        mutated(_set(["objects", 0, "style", "fill"], "red")),
        r"\$\.objects\[0\]\.style: fill must be",
    ),
    "opacity 2": (
        mutated(_set(["objects", 0, "style", "opacity"], 2)),
        r"\.style\.opacity: number 2 out of range",
    ),
    "unknown source kind": (
        mutated(_set(["objects", 0, "source", "kind"], "voxels")),
        r"\$\.objects\[0\]\.source\.kind: expected 'discrete', 'labels', 'euclidean' or 'polyhedron'",
    ),
    "shape wrong length": (
        mutated(_set(["objects", 0, "source", "shape"], [5])),
        r"\$\.objects\[0\]\.source\.shape: expected \[rows, cols\]",
    ),
    "negative shape": (
        mutated(_set(["objects", 0, "source", "shape"], [5, -5])),
        r"\.source\.shape\[1\]: integer -5 out of range",
    ),
    "enormous shape": (
        mutated(_set(["objects", 0, "source", "shape"], [2**30, 2**30])),
        r"\.source\.shape: a 1073741824 x 1073741824 mask holds more than the limit",
    ),
    "enormous origin": (
        mutated(_set(["objects", 0, "source", "origin"], [10**30, 0])),
        r"\.source\.origin\[0\]: integer an integer of 31 digits out of range",
    ),
    "bits too short": (
        mutated(_set(["objects", 0, "source", "bits"], "AAAA")),
        r"\.source\.bits: expected 4 bytes of base64 for a 5 x 5 mask, got 4 characters",
    ),
    "bits not base64": (
        mutated(_set(["objects", 0, "source", "bits"], "I7*iAA==")),
        r"\.source\.bits: not valid base64",
    ),
    "enormous coordinate": (
        mutated(_set(["objects", 1, "source", "geometry", "coordinates", 0, 1], [1e300, 0.0])),
        r"\$\.objects\[1\]\.source\.geometry\.coordinates\[0\]\[1\]\[0\]: coordinate 1e\+300 outside",
    ),
    "overflowing coordinate": (
        (GOLDEN / "v1-all-features.mrm").read_bytes().replace(b"[7.125, 1.0]", b"[7.125, 1e400]"),
        r"coordinates\[0\]\[1\]\[1\]: coordinate inf outside",
    ),
    "coordinate as text": (
        mutated(_set(["objects", 1, "source", "geometry", "coordinates", 0, 1], ["7", 1.0])),
        r"coordinates\[0\]\[1\]\[0\]: expected a number, got '7'",
    ),
    "3-D position": (
        mutated(_set(["objects", 1, "source", "geometry", "coordinates", 0, 1], [7.0, 1.0, 2.0])),
        r"coordinates\[0\]\[1\]: expected a position \[x, y\]",
    ),
    "open ring": (
        mutated(_set(["objects", 1, "source", "geometry", "coordinates", 0, 3], [9.0, 9.0])),
        r"coordinates\[0\]: the ring is not closed",
    ),
    "bow tie": (
        mutated(
            _set(
                ["objects", 1, "source", "geometry", "coordinates"],
                [[[0.0, 0.0], [2.0, 2.0], [2.0, 0.0], [0.0, 2.0], [0.0, 0.0]]],
            )
        ),
        r"\$\.objects\[1\]\.source\.geometry: invalid polygon: Self-intersection",
    ),
    "geometry type": (
        mutated(_set(["objects", 1, "source", "geometry", "type"], "LineString")),
        r"geometry\.type: expected 'Polygon' or 'MultiPolygon'",
    ),
    "deep params": (
        mutated(_set(["objects", 1, "provenance", "params", "x"], json.loads("[" * 40 + "]" * 40))),
        r"\.provenance\.params\.x(\[0\])+: nested deeper than 16 levels",
    ),
    "inputs not ids": (
        mutated(_set(["objects", 1, "provenance", "inputs"], ["a"])),
        r"\.provenance\.inputs\[0\]: expected an integer",
    ),
    "selection of a missing object": (
        mutated(_set(["selection"], [42])),
        r"\$\.selection\[0\]: no object has id 42",
    ),
}


@pytest.fixture
def open_doc() -> Document:
    doc = load_project(EXAMPLES / "two-polygons.mrm")
    doc.push(RenameObject(doc.ids[0], "edited"))
    return doc


@pytest.mark.parametrize("case", sorted(HOSTILE), ids=str)
def test_hostile_files_get_a_clear_message_naming_the_problem(case, tmp_path, open_doc):
    data, pattern = HOSTILE[case]
    path = tmp_path / "bad.mrm"
    path.write_bytes(data)
    before = dumps(open_doc)
    with pytest.raises(FileFormatError, match=pattern) as info:
        load_project(path)
    assert str(info.value).startswith("bad.mrm: ")
    assert "\n" not in str(info.value)
    assert dumps(open_doc) == before and open_doc.is_modified  # the open document is untouched


@pytest.mark.parametrize("case", sorted(HOSTILE), ids=str)
def test_the_cli_reports_hostile_projects_with_exit_status_2(case, tmp_path, capsys):
    from mrm.cli import run_cli

    path = tmp_path / "bad.mrm"
    path.write_bytes(HOSTILE[case][0])
    assert run_cli(["info", str(path)]) == 2
    err = capsys.readouterr().err
    assert err.startswith("mrm info: error: bad.mrm: ") and "Traceback" not in err
    assert err.count("\n") == 1


def test_the_masks_of_a_file_have_a_total_budget(monkeypatch):
    import mrm.core.limits as limits

    monkeypatch.setattr(limits, "MAX_FILE_PIXELS", 30)  # the golden masks hold 25 + 0 + 6 pixels
    with pytest.raises(
        FileFormatError, match=r"\$\.objects\[5\]\.source\.shape: the masks of the file hold more"
    ):
        parse_project((GOLDEN / "v1-all-features.mrm").read_bytes(), "g.mrm")


def test_an_image_renamed_to_mrm_is_recognised(tmp_path):
    from mrm.io.pixel_files import write_pixels

    write_pixels(PixelSet.box(0, 0, 3, 3), tmp_path / "mask.png")
    os.replace(tmp_path / "mask.png", tmp_path / "mask.mrm")
    with pytest.raises(FileFormatError, match=r"mask\.mrm: this is a PNG image, not an MR Modeler project"):
        load_project(tmp_path / "mask.mrm")
    np.savez(tmp_path / "arr.npz", mask=np.ones((2, 2), bool))
    os.replace(tmp_path / "arr.npz", tmp_path / "arr.mrm")
    with pytest.raises(FileFormatError, match=r"arr\.mrm: this is a ZIP archive"):
        load_project(tmp_path / "arr.mrm")


@settings(max_examples=200)
@given(st.binary(max_size=300))
def test_random_bytes_never_crash_the_reader(data):
    try:
        parse_project(data, "x.mrm")
    except FileFormatError as e:
        assert str(e).startswith("x.mrm: ")


@settings(max_examples=100)
@given(st.data())
def test_every_truncation_of_a_project_is_refused_cleanly(data):
    full = (GOLDEN / "v1-all-features.mrm").read_bytes()
    cut = data.draw(st.integers(0, len(full.rstrip()) - 1))
    with pytest.raises(FileFormatError):
        parse_project(full[:cut], "cut.mrm")


@settings(max_examples=150)
@given(st.data())
def test_any_value_replaced_by_a_wrong_type_is_refused_with_its_path(data):
    raw = golden_json()
    # Pick a random leaf path in the document and put a value of another type there.
    paths = []

    def walk(v, p):
        if isinstance(v, dict):
            for k, x in v.items():
                walk(x, [*p, k])
        elif isinstance(v, list):
            for i, x in enumerate(v):
                walk(x, [*p, i])
        else:
            paths.append(p)

    walk(raw, [])
    path = data.draw(st.sampled_from([p for p in paths if "params" not in p and p != ["generator"]]))
    old = raw
    for k in path[:-1]:
        old = old[k]
    original = old[path[-1]]
    bad = data.draw(
        st.sampled_from([None, [], {}, "text", True]).filter(lambda v: type(v) is not type(original))
    )
    old[path[-1]] = bad
    with pytest.raises(FileFormatError) as info:
        parse_project(json.dumps(raw).encode(), "w.mrm")
    shown = "$" + "".join(f"[{k}]" if isinstance(k, int) else f".{k}" for k in path[:2])
    assert shown in str(info.value) or "format" in str(info.value)


# ---------------------------------------------------------------------------------------------- migrations
def test_migrations_run_in_order_from_the_file_version():
    calls = []

    def v1_to_v2(d):
        calls.append(1)
        d["settings"] = {"model": d["settings"]["model"]}  # (a real one would rename keys, etc.)
        d["note_from_v1"] = True
        return d

    def v2_to_v3(d):
        calls.append(2)
        d.pop("note_from_v1")
        return d

    migrations = [Migration(1, "add note", v1_to_v2), Migration(2, "drop note", v2_to_v3)]
    proj = parse_project(
        (GOLDEN / "v1-all-features.mrm").read_bytes(), "g.mrm", migrations=migrations, current=3
    )
    assert calls == [1, 2] and proj.file_version == 1 and len(proj.objects) == 6


def test_a_missing_migration_is_reported():
    with pytest.raises(FileFormatError, match="no migration from project schema 1 to 2"):
        parse_project((GOLDEN / "v1-all-features.mrm").read_bytes(), "g.mrm", migrations=[], current=2)


# ---------------------------------------------------------------------------------------------- atomic saves
def test_save_marks_clean_and_sets_the_path(tmp_path):
    doc = load_project(EXAMPLES / "two-polygons.mrm")
    doc.push(RenameObject(doc.ids[0], "renamed"))
    assert doc.is_modified
    save_project(doc, tmp_path / "out.mrm")
    assert not doc.is_modified and doc.path == tmp_path / "out.mrm"
    assert load_project(tmp_path / "out.mrm").get(doc.ids[0]).name == "renamed"


@pytest.mark.parametrize("failure", ["fsync", "replace", "write"])
def test_an_interrupted_save_leaves_the_previous_file_intact(tmp_path, monkeypatch, failure):
    import mrm.io.atomic as atomic

    path = tmp_path / "p.mrm"
    doc = load_project(EXAMPLES / "two-polygons.mrm")
    save_project(doc, path)
    previous = path.read_bytes()
    doc.push(PaintPixels(doc.ids[0], PixelSet.box(0, 0, 30, 30)))

    def boom(*a, **k):
        raise OSError(28, "No space left on device")

    if failure == "write":
        real_fdopen = os.fdopen

        class HalfWriter:
            def __init__(self, fh):
                self.fh = fh

            def write(self, data):
                self.fh.write(data[: len(data) // 2])  # half the bytes reach the disk, then the crash
                raise OSError(5, "Input/output error")

            def __getattr__(self, name):
                return getattr(self.fh, name)

            def __enter__(self):
                return self

            def __exit__(self, *exc):
                return self.fh.__exit__(*exc)

        monkeypatch.setattr(atomic.os, "fdopen", lambda *a, **k: HalfWriter(real_fdopen(*a, **k)))
    else:
        monkeypatch.setattr(atomic.os, failure, boom)
    with pytest.raises(OSError):
        save_project(doc, path)
    monkeypatch.undo()
    assert path.read_bytes() == previous
    assert sorted(p.name for p in tmp_path.iterdir()) == ["p.mrm"]  # no temporary file left behind
    assert doc.is_modified  # not marked clean: the edits are in no file
    assert load_project(path).objects == load_project(EXAMPLES / "two-polygons.mrm").objects


# ---------------------------------------------------------------------------------------------- autosave
class Clock:
    def __init__(self) -> None:
        self.t = 1000.0

    def __call__(self) -> float:
        return self.t


def test_autosave_after_n_edits_and_recovery_restores_the_edited_document(tmp_path):
    project = tmp_path / "work.mrm"
    doc = load_project(EXAMPLES / "two-polygons.mrm")
    save_project(doc, project)
    clock = Clock()
    saver = autosave.Autosaver(doc, interval=60, every_edits=3, clock=clock)
    a = doc.ids[0]
    doc.push(RenameObject(a, "one"))
    doc.push(RenameObject(a, "two"))
    assert saver.tick() is None  # 2 edits, 0 s: not yet
    doc.push(RenameObject(a, "three"))
    side = saver.tick()
    assert side == tmp_path / f".work.mrm.{saver.writer}.autosave" and side.exists()
    assert autosave.find_recovery(project) is None  # its writer is alive: nothing to recover yet
    expected = dumps(doc)
    saver.close()  # the window goes away without discarding its side file, as in a crash
    # On the next start:
    rec = autosave.find_recovery(project)
    assert rec is not None and rec.project == project and rec.saved_at
    restored = rec.restore()
    assert without_generator(dumps(restored)) == without_generator(expected)
    assert restored.is_modified and restored.path == project
    assert load_project(project).get(a).name != "three"  # the project itself was never touched


def test_autosave_after_the_interval(tmp_path):
    doc = load_project(EXAMPLES / "two-polygons.mrm")
    save_project(doc, tmp_path / "w.mrm")
    clock = Clock()
    saver = autosave.Autosaver(doc, interval=60, every_edits=100, clock=clock)
    doc.push(RenameObject(doc.ids[0], "x"))
    clock.t += 59
    assert saver.tick() is None
    clock.t += 2
    assert saver.tick() is not None
    assert saver.tick() is None  # nothing new since


def test_saving_or_undoing_to_the_saved_state_drops_the_side_file(tmp_path):
    project = tmp_path / "w.mrm"
    doc = load_project(EXAMPLES / "two-polygons.mrm")
    save_project(doc, project)
    saver = autosave.Autosaver(doc, every_edits=1, clock=Clock())
    doc.push(RenameObject(doc.ids[0], "x"))
    side = saver.tick()
    assert side is not None and side.exists()
    doc.undo()
    saver.tick()
    assert not side.exists() and autosave.find_recovery(project) is None
    doc.redo()
    side = saver.tick()
    assert side is not None and side.exists()
    save_project(doc, project)
    saver.tick()
    assert not side.exists()


def test_a_side_file_older_than_the_project_is_ignored(tmp_path):
    project = tmp_path / "w.mrm"
    doc = load_project(EXAMPLES / "two-polygons.mrm")
    save_project(doc, project)
    side = autosave.side_file(project)
    side.write_bytes(dumps(doc))
    os.utime(side, (1_000_000, 1_000_000))
    assert autosave.find_recovery(project) is None


def test_untitled_autosaves_of_dead_processes_are_found(tmp_path):
    doc = Document()
    doc.push(AddObject(doc.make_object(PixelSet.box(0, 0, 2, 2), "p")))
    saver = autosave.Autosaver(doc, every_edits=1, directory=tmp_path, clock=Clock())
    mine = saver.tick()
    assert mine is not None and mine.parent == tmp_path
    assert autosave.find_orphans(tmp_path) == []  # this process is alive: not an orphan
    dead = tmp_path / "untitled-4194999-abcd.mrm.autosave"  # above Linux's largest pid
    os.replace(mine, dead)
    (found,) = autosave.find_orphans(tmp_path)
    assert found.path == dead and found.project is None
    restored = found.restore()
    assert restored.path is None and restored.is_modified and restored.objects == doc.objects
    found.discard()
    assert not dead.exists()


def test_a_damaged_side_file_is_offered_but_reports_on_restore(tmp_path):
    project = tmp_path / "w.mrm"
    save_project(Document(), project)
    autosave.side_file(project).write_bytes(b'{"format": "mrm-proj')
    rec = autosave.find_recovery(project)
    assert rec is not None
    with pytest.raises(FileFormatError):
        rec.restore()


# ---------------------------------------------------------------------------------------------- examples
@pytest.mark.parametrize("path", sorted(EXAMPLES.glob("*.mrm")), ids=lambda p: p.name)
def test_example_projects_load_and_satisfy_the_invariant(path):

    import mrm

    doc = load_project(path)
    assert len(doc) >= 1
    for o in doc:
        d = doc.derived(o.id)
        # D(Euclidean) = discrete: a polygon's pixels, or a 3D example's R(A) voxelized (mrm.discretize)
        assert mrm.discretize(d.get("euclidean"), doc.model) == d.get("discrete")
        region = d.get("region")
        counted = region.voxels if o.dimension == 3 else region.pixels
        assert counted == d.get("discrete").count


def test_examples_hold_what_their_names_say():
    diamond = load_project(EXAMPLES / "diamond.mrm").objects[0].source
    assert set(diamond) == {(x, y) for x in range(-12, 13) for y in range(-12, 13) if abs(x) + abs(y) <= 12}
    a, b = load_project(EXAMPLES / "two-polygons.mrm").objects
    assert (
        a.kind == b.kind == "euclidean" and a.source.intersects(b.source) and not a.source.contains(b.source)
    )


def test_user_errors_from_files_are_mrm_errors():
    assert issubclass(FileFormatError, MRMError)
