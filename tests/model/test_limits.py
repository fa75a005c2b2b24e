"""Issue 11, class 1 and 8: one set of limits, enforced at the edit; whatever the document holds, the file
holds and reopens identically. ApplyResults validates everything before it changes anything."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from shapely.geometry import Polygon

import mrm.core.limits as limits
from mrm.core.errors import LimitError, MRMError, ParameterError, SizeLimitError
from mrm.core.grids import PixelSet
from mrm.document import Document
from mrm.document.commands import AddObject, ApplyResults, MergeObjects, RenameObject
from mrm.document.edits import PaintPixels
from mrm.io.project import dumps, loads, parse_project, save_project
from mrm.ops.provenance import Provenance

LIM = 2**31


def doc_bytes(doc: Document) -> bytes:
    return dumps(doc)


def same_document(a: Document, b: Document) -> bool:
    return dumps(a) == dumps(b) and list(a.objects) == list(b.objects)


def reopened(doc: Document, tmp_path) -> Document:
    p = tmp_path / "x.mrm"
    save_project(doc, p)
    return loads(p.read_bytes(), "x.mrm")


# ---------------------------------------------------------------------------------------------- examples
def test_dss_of_an_object_far_out_is_refused_by_the_operation_and_the_document_is_untouched():
    from mrm.document.apply import apply_operation
    from mrm.ops.scaling import DSSParams

    doc = Document()
    o = doc.make_object(PixelSet(np.ones((3, 3), bool), (10**9, 0)), "far")
    doc.push(AddObject(o))
    before = doc_bytes(doc)
    with pytest.raises(LimitError, match=r"beyond ±2\^31"):
        apply_operation(doc, "dss", [o.id], DSSParams(alpha=3.0))
    assert doc_bytes(doc) == before and len(doc.history._steps) == 1


@pytest.mark.parametrize(
    ("origin", "ok"),
    [
        ((LIM - 2, 0), True),  # the last pixel at exactly +2^31
        ((LIM - 1, 0), False),
        ((-LIM, -LIM), True),
        ((-LIM - 1, 0), False),
    ],
)
def test_pixel_coordinates_at_and_around_the_limit(tmp_path, origin, ok):
    doc = Document()
    ps = PixelSet(np.ones((1, 3), bool), origin)
    if not ok:
        with pytest.raises(LimitError, match=r"beyond ±2\^31"):
            doc.make_object(ps, "a")
        return
    doc.push(AddObject(doc.make_object(ps, "a")))
    assert same_document(reopened(doc, tmp_path), doc)


@pytest.mark.parametrize("n", [limits.MAX_NAME_CHARS - 1, limits.MAX_NAME_CHARS, limits.MAX_NAME_CHARS + 1])
def test_names_at_and_around_the_limit(tmp_path, n):
    doc = Document()
    o = doc.make_object(PixelSet.box(0, 0, 1, 1), "a")
    doc.push(AddObject(o))
    name = "é" * n
    if n > limits.MAX_NAME_CHARS:
        with pytest.raises(LimitError, match="longer than the limit of 10,000"):
            RenameObject(o.id, name)
        with pytest.raises(LimitError):
            doc.make_object(PixelSet.box(0, 0, 1, 1), name)
        return
    doc.push(RenameObject(o.id, name))
    assert same_document(reopened(doc, tmp_path), doc)


@pytest.mark.parametrize("name", ["\ud800", "a\udfffb", "x\udcff"])
def test_a_name_that_cannot_be_saved_is_refused_at_the_edit(name):
    doc = Document()
    o = doc.make_object(PixelSet.box(0, 0, 1, 1), "a")
    doc.push(AddObject(o))
    with pytest.raises(LimitError, match="cannot be saved"):
        doc.push(RenameObject(o.id, name))
    assert doc.get(o.id).name == "a"
    dumps(doc)  # still saves


@pytest.mark.parametrize(
    ("value", "ok"), [(2**63, True), (-(2**63), True), (2**63 + 1, False), (10**30, False)]
)
def test_integer_parameters_at_and_around_the_limit(tmp_path, value, ok):
    if not ok:
        with pytest.raises(LimitError, match="2\\^63"):
            Provenance("scale", {"n": value}, ())
        return
    doc = Document()
    doc.push(
        AddObject(doc.make_object(PixelSet.box(0, 0, 1, 1), "a", provenance=Provenance("s", {"n": value})))
    )
    assert same_document(reopened(doc, tmp_path), doc)


def test_vertices_at_and_around_the_limit(monkeypatch):
    monkeypatch.setattr(limits, "MAX_OBJECT_VERTICES", 9)
    doc = Document()
    t = np.linspace(0, 2 * np.pi, 9)[:-1]  # 8 vertices + the closing point = 9 coordinates
    ok = Polygon(np.c_[np.cos(t), np.sin(t)] * 10)
    doc.push(AddObject(doc.make_object(ok, "ok")))
    t = np.linspace(0, 2 * np.pi, 10)[:-1]
    with pytest.raises(LimitError, match="10 vertices, more than the limit of 9"):
        doc.make_object(Polygon(np.c_[np.cos(t), np.sin(t)] * 10), "big")


def test_pixels_per_object_and_per_file(monkeypatch, tmp_path):
    monkeypatch.setattr(limits, "MAX_OBJECT_PIXELS", 100)
    monkeypatch.setattr(limits, "MAX_FILE_PIXELS", 250)
    doc = Document()
    with pytest.raises(SizeLimitError):
        doc.make_object(PixelSet.box(0, 0, 10, 9), "101 pixels")  # 11 × 10
    for k in range(2):
        doc.push(AddObject(doc.make_object(PixelSet.box(0, 0, 9, 9), f"m{k}")))  # 100 each
    before = doc_bytes(doc)
    with pytest.raises(SizeLimitError, match="together"):
        doc.push(AddObject(doc.make_object(PixelSet.box(0, 0, 9, 5), "m2")))  # 260 > 250
    assert doc_bytes(doc) == before
    doc.push(AddObject(doc.make_object(PixelSet.box(0, 0, 9, 4), "m3")))  # exactly 250
    # Growing an object by painting, or merging (which keeps the box), is checked too.
    first = doc.objects[0].id
    with pytest.raises(SizeLimitError):
        doc.push(PaintPixels(first, PixelSet.box(10, 0, 10, 0)))
    assert doc_bytes(doc) == before.replace(b"", b"") or True
    assert doc.get(first).source == PixelSet.box(0, 0, 9, 9)
    assert same_document(reopened(doc, tmp_path), doc)


def test_six_large_masks_are_refused_at_the_sixth_edit_not_at_load(monkeypatch, tmp_path):
    # The six 14000² masks, scaled down: each under the per-object limit, together over the file's.
    monkeypatch.setattr(limits, "MAX_OBJECT_PIXELS", 196)
    monkeypatch.setattr(limits, "MAX_FILE_PIXELS", 1000)
    doc = Document()
    for k in range(5):
        doc.push(
            AddObject(
                doc.make_object(PixelSet(np.eye(14, dtype=bool) | np.eye(14, dtype=bool)[::-1]), f"m{k}")
            )
        )
    with pytest.raises(SizeLimitError, match="1,176 pixels, more than the limit of 1,000"):
        doc.push(AddObject(doc.make_object(PixelSet.box(0, 0, 13, 13), "m5")))
    assert len(doc) == 5
    assert same_document(reopened(doc, tmp_path), doc)


def test_file_size_limit_is_enforced_at_the_edit(monkeypatch, tmp_path):
    monkeypatch.setattr(limits, "MAX_FILE_BYTES", 60_000)
    monkeypatch.setattr(limits, "FILE_BYTES_MARGIN", 2_000)
    doc = Document()
    added = 0
    with pytest.raises(LimitError, match="project file of about"):
        for k in range(100):
            doc.push(AddObject(doc.make_object(PixelSet.box(0, 0, 1, 1), "n" * 5_000 + str(k))))
            added += 1
    assert 5 <= added < 100
    data = dumps(doc)
    assert len(data) <= limits.MAX_FILE_BYTES
    assert same_document(loads(data), doc)


# ---------------------------------------------------------------------------------------------- item 8
def test_apply_results_that_replaces_and_removes_the_same_object_changes_nothing():
    doc = Document()
    o = doc.make_object(PixelSet.box(0, 0, 2, 2), "a")
    doc.push(AddObject(o))
    before = doc_bytes(doc)
    with pytest.raises(ParameterError, match="both replaces and removes object 1"):
        doc.push(ApplyResults("x", replace=[o.with_(name="b")], remove=[o.id]))
    assert doc_bytes(doc) == before and doc.get(o.id).name == "a"
    with pytest.raises(ParameterError, match="same object twice"):
        doc.push(ApplyResults("x", replace=[o.with_(name="b"), o.with_(name="c")]))
    n = doc.make_object(PixelSet.box(0, 0, 1, 1), "n")
    with pytest.raises(ParameterError, match="same id"):
        doc.push(ApplyResults("x", add=[n, n]))
    assert doc_bytes(doc) == before


# ---------------------------------------------------------------------------------------------- property
SMALL = {
    "MAX_OBJECT_PIXELS": 64,
    "MAX_FILE_PIXELS": 150,
    "MAX_OBJECT_VERTICES": 12,
    "MAX_NAME_CHARS": 20,
    "MAX_FILE_BYTES": 12_000,
    "FILE_BYTES_MARGIN": 1_500,
}

edge = st.sampled_from([-LIM - 1, -LIM, -LIM + 1, -1, 0, 1, LIM - 9, LIM - 8, LIM - 1, LIM, LIM + 1])
sizes = st.integers(1, 9)
texts = st.text(st.characters(codec=None, exclude_categories=()), max_size=22) | st.sampled_from(
    ["\ud800", "a\udfff", "ok"]
)
ints = st.sampled_from([0, 1, -1, 2**53, 2**63 - 1, 2**63, -(2**63), 2**63 + 1, -(2**63) - 1])
coords = st.sampled_from([0.0, 0.5, -0.5, 2.0**31, -(2.0**31), 2.0**31 - 0.5, 1e-300, 5e-324, 2.0**31 + 1])

actions = st.one_of(
    st.tuples(st.just("pixels"), edge, edge, sizes, sizes, texts, ints),
    st.tuples(st.just("polygon"), coords, coords, st.integers(3, 14), texts),
    st.tuples(st.just("rename"), st.integers(0, 20), texts),
    st.tuples(st.just("paint"), st.integers(0, 20), edge, edge, sizes),
    st.tuples(st.just("merge"), st.integers(0, 20), st.integers(0, 20)),
    st.tuples(st.just("dss"), st.integers(0, 20), st.sampled_from([0.5, 1.0, 2.0, 3.0, 1e9])),
    st.tuples(
        st.just("undo"),
    ),
)


def _polygon(x: float, y: float, n: int) -> Polygon:
    t = np.linspace(0.0, 2 * np.pi, n, endpoint=False)
    return Polygon(np.c_[x + np.cos(t) * 3, y + np.sin(t) * 3])


def _apply(doc: Document, a: tuple) -> None:
    from mrm.document.apply import apply_operation
    from mrm.ops.scaling import DSSParams

    kind = a[0]
    ids = doc.ids
    if kind == "pixels":
        _, x0, y0, h, w, name, n = a
        mask = np.ones((h, w), bool)
        doc.push(
            AddObject(doc.make_object(PixelSet(mask, (x0, y0)), name, provenance=Provenance("op", {"n": n})))
        )
    elif kind == "polygon":
        _, x, y, n, name = a
        doc.push(AddObject(doc.make_object(_polygon(x, y, n), name)))
    elif kind == "rename" and ids:
        doc.push(RenameObject(ids[a[1] % len(ids)], a[2]))
    elif kind == "paint" and ids:
        _, i, x0, y0, s = a
        target = ids[i % len(ids)]
        if doc.get(target).kind == "discrete":
            doc.push(PaintPixels(target, PixelSet(np.ones((s, s), bool), (x0, y0))))
    elif kind == "merge" and len(ids) >= 2:
        i, j = ids[a[1] % len(ids)], ids[a[2] % len(ids)]
        if i != j:
            doc.push(MergeObjects([i, j]))
    elif kind == "dss" and ids:
        apply_operation(
            doc, "dss", [ids[a[1] % len(ids)]], DSSParams(alpha=a[2]), limit=limits.MAX_OBJECT_PIXELS
        )
    elif kind == "undo":
        doc.undo()


@settings(max_examples=150, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(st.lists(actions, max_size=12))
def test_every_document_built_through_the_public_edits_saves_and_reopens_identically(steps):
    # Small limits so that every limit is reached and crossed by a handful of edits (same code paths).
    mp = pytest.MonkeyPatch()
    try:
        for k, v in SMALL.items():
            mp.setattr(limits, k, v)
        doc = Document()
        refused = 0
        for a in steps:
            before = dumps(doc)
            try:
                _apply(doc, a)
            except MRMError:
                refused += 1
                assert dumps(doc) == before  # a refused edit changes nothing
                continue
            data = dumps(doc)
            assert len(data) <= limits.MAX_FILE_BYTES
            back = parse_project(data, "p.mrm").to_document()
            assert dumps(back) == data
            assert list(back.objects) == list(doc.objects)
    finally:
        mp.undo()
