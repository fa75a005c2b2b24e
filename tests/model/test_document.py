"""The document: objects and their four representations, settings, selection, batched events, and the
derivation cache and service (lazy, off-thread, stale results dropped)."""

from __future__ import annotations

import json
import threading
import warnings

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from shapely.geometry import LineString, MultiPolygon, Point, Polygon

import mrm.document.derive as derive
from mrm.core.errors import InvalidGeometryError, ParameterError, SizeLimitError
from mrm.core.grids import PixelSet
from mrm.document import Changes, DocObject, Document, Settings, Style, validate_geometry
from mrm.document.commands import (
    AddObject,
    ChangeSettings,
    RemoveObjects,
    RenameObject,
    ReorderObjects,
    RestyleObject,
    SetSource,
)
from mrm.document.derive import DerivationCache
from mrm.document.edits import MoveVertex, PaintPixels
from mrm.ops.provenance import Provenance


def tri(x: float = 0.0, y: float = 0.0) -> Polygon:
    return Polygon([(x, y), (x + 6.5, y + 0.5), (x + 2.0, y + 5.25)])


# ---------------------------------------------------------------------------------------------- values
def test_geometry_validation_refuses_what_cannot_be_a_shape():
    with pytest.raises(InvalidGeometryError, match="Self-intersection"):
        validate_geometry(Polygon([(0, 0), (2, 2), (2, 0), (0, 2)]))
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RuntimeWarning)  # shapely warns while building it
        nan_polygon = Polygon([(0, 0), (float("nan"), 1), (1, 0)])
    with pytest.raises(InvalidGeometryError, match="NaN or infinite"):
        validate_geometry(nan_polygon)
    with pytest.raises(InvalidGeometryError, match="must be a polygon, got a LineString"):
        validate_geometry(LineString([(0, 0), (1, 1)]))
    with pytest.raises(InvalidGeometryError, match="3-D"):
        validate_geometry(Polygon([(0, 0, 1), (1, 0, 1), (0, 1, 1)]))
    with pytest.raises(InvalidGeometryError, match="beyond the limit"):
        validate_geometry(Polygon([(0, 0), (1e12, 0), (0, 1)]))
    with pytest.raises(InvalidGeometryError):
        validate_geometry("POLYGON((0 0, 1 0, 0 1, 0 0))")
    assert validate_geometry(Point()).is_empty
    p = tri()
    assert validate_geometry(p) is p  # never altered


def test_values_are_checked_on_construction():
    with pytest.raises(ParameterError, match="colour"):
        Style(fill="blue")
    with pytest.raises(ParameterError, match="opacity"):
        Style(opacity=1.5)
    with pytest.raises(ParameterError, match="unknown discretization model"):
        Settings("bresenham")
    with pytest.raises(ParameterError, match="finite"):
        Provenance("scale", {"alpha": float("inf")})
    with pytest.raises(ParameterError, match="nested deeper"):
        Provenance("x", {"a": json.loads("[" * 20 + "]" * 20)})
    with pytest.raises(ParameterError, match="ids"):
        DocObject(0, "x", PixelSet.empty())
    params = {"alpha": 2, "list": (1, 2.5)}
    p = Provenance("scale", params, [3])
    params["alpha"] = 99  # the provenance keeps its own copy
    assert p.params == {"alpha": 2, "list": [1, 2.5]} and p.inputs == (3,)


# ---------------------------------------------------------------------------------------------- objects
def test_objects_keep_order_ids_and_lookup():
    doc = Document()
    a = doc.make_object(PixelSet.box(0, 0, 1, 1), "a")
    b = doc.make_object(tri(), "b")
    c = doc.make_object(tri(3, 3), "a")
    for o in (a, b, c):
        doc.push(AddObject(o))
    assert doc.ids == (a.id, b.id, c.id) and len(doc) == 3
    assert [o.id for o in doc.find("a")] == [a.id, c.id]
    assert doc.get(b.id).kind == "euclidean" and doc.get(a.id).kind == "discrete"
    doc.push(ReorderObjects.move(doc, c.id, 0))
    assert doc.ids == (c.id, a.id, b.id) and doc.index_of(b.id) == 2
    doc.push(RemoveObjects([a.id]))
    assert a.id not in doc
    with pytest.raises(KeyError):
        doc.get(a.id)
    doc.undo()
    assert doc.ids == (c.id, a.id, b.id)


def test_ids_are_never_reused_even_after_undo():
    doc = Document()
    a = doc.make_object(PixelSet.box(0, 0, 1, 1))
    doc.push(AddObject(a))
    doc.undo()
    b = doc.make_object(PixelSet.box(0, 0, 1, 1))
    assert b.id != a.id
    doc.push(AddObject(b))
    doc.history.clear()
    loaded = Document()
    loaded.reset([DocObject(40, "x", PixelSet.empty())])
    assert loaded.new_id() == 41


def test_default_names_and_styles_differ_between_objects():
    doc = Document()
    objs = [doc.make_object(PixelSet.box(0, 0, 1, 1)) for _ in range(3)]
    assert len({o.name for o in objs}) == 3 and len({o.style.fill for o in objs}) == 3


# ---------------------------------------------------------------------------------------------- events
def test_events_are_coarse_and_batched():
    doc = Document()
    got: list[Changes] = []
    unsubscribe = doc.subscribe(got.append)
    a = doc.make_object(tri(), "a")
    doc.push(AddObject(a))
    assert got[-1].inserted == (a.id,) and not got[-1].changed
    doc.push(RenameObject(a.id, "b"))
    assert got[-1].changed == {a.id: frozenset({"name"})}
    doc.push(RestyleObject(a.id, Style(opacity=0.1)))
    assert got[-1].changed == {a.id: frozenset({"style"})}
    doc.push(MoveVertex(a.id, (0, 0, 1), (7.0, 0.5)))
    assert got[-1].changed == {a.id: frozenset({"source"})}
    doc.push(ChangeSettings.model(doc, "supercover"))
    assert got[-1].settings and got[-1].changed == {a.id: frozenset({"derived"})}
    n = len(got)
    with doc.batch():
        doc.push(RenameObject(a.id, "c"))
        doc.push(RenameObject(a.id, "d"))
        doc.set_selection([a.id])
    assert len(got) == n + 1 and got[-1].selection and got[-1].changed == {a.id: frozenset({"name"})}
    doc.set_selection([a.id])  # unchanged: no event
    assert len(got) == n + 1
    revision = doc.revision
    unsubscribe()
    doc.push(RenameObject(a.id, "e"))
    assert len(got) == n + 1 and doc.revision > revision


def test_insert_then_remove_in_one_batch_is_no_net_change():
    doc = Document()
    got: list[Changes] = []
    doc.subscribe(got.append)
    with doc.batch():
        o = doc.make_object(tri())
        doc.push(AddObject(o))
        doc.undo()
    assert got[-1].inserted == () and got[-1].removed == ()


def test_a_failing_subscriber_does_not_starve_the_others():
    doc = Document()
    seen = []

    def bad(ch: Changes) -> None:
        raise RuntimeError("view bug")

    doc.subscribe(bad)
    doc.subscribe(seen.append)
    with pytest.raises(RuntimeError):
        doc.push(AddObject(doc.make_object(tri())))
    assert len(seen) == 1 and len(doc) == 1


def test_selection_ignores_unknown_ids_and_follows_removal():
    doc = Document()
    a, b = doc.make_object(tri()), doc.make_object(tri(9, 9))
    doc.push(AddObject(a))
    doc.push(AddObject(b))
    doc.set_selection([b.id, 999, a.id, b.id])
    assert doc.selection == (b.id, a.id)
    doc.push(RemoveObjects([b.id]))
    assert doc.selection == (a.id,)
    doc.undo()
    assert doc.selection == (b.id, a.id)


# ---------------------------------------------------------------------------------------------- derivations
def test_euclidean_source_derives_its_discrete_representation_with_the_document_model():
    from mrm.geometry.discretize import discretize

    doc = Document()
    # A square whose sides lie on pixel sides: the models disagree there.
    sq = Polygon([(-0.5, -0.5), (2.5, -0.5), (2.5, 2.5), (-0.5, 2.5)])
    o = doc.make_object(sq)
    doc.push(AddObject(o))
    std = doc.derived(o.id).get("discrete")
    assert std == discretize(sq, "standard")
    assert doc.derived(o.id).get("euclidean") is sq
    doc.push(ChangeSettings.model(doc, "supercover"))
    sup = doc.derived(o.id).get("discrete")
    assert sup == discretize(sq, "supercover") and sup != std
    doc.undo()
    assert doc.derived(o.id).get("discrete") == std


def test_region_and_analytical_come_from_the_discrete_representation():
    doc = Document()
    ring = PixelSet.box(0, 0, 4, 4) - PixelSet.box(2, 2, 2, 2)
    o = doc.make_object(ring)
    doc.push(AddObject(o))
    region = doc.derived(o.id).get("region")
    assert (region.n_components, region.n_holes, region.euler) == (1, 1, 0)
    assert region.pixels == 24


def test_analytical_representation_is_derived_once_from_the_region(monkeypatch):
    seen = []
    real = derive.analytical_of

    def spy(region):
        seen.append(region)
        return real(region)

    monkeypatch.setattr(derive, "analytical_of", spy)
    doc = Document()
    o = doc.make_object(tri())
    doc.push(AddObject(o))
    d = doc.derived(o.id)
    value = d.get("analytical")
    assert d.get("analytical") is value
    assert seen == [d.get("region")] and d.get("region").pixels == d.get("discrete").count


def test_discrete_source_derives_a_euclidean_representation_whose_discretization_is_the_source():
    from mrm.geometry.discretize import discretize

    rng = np.random.default_rng(7)
    doc = Document()
    ps = PixelSet(rng.random((9, 11)) < 0.55, (-4, 2))
    o = doc.make_object(ps)
    doc.push(AddObject(o))
    for model in ("standard", "supercover", "gauss"):
        doc.push(ChangeSettings.model(doc, model))
        euclid = doc.derived(o.id).get("euclidean")
        assert discretize(euclid, model) == ps


def test_derivation_errors_are_remembered_not_recomputed(monkeypatch):
    calls = []

    def refuse(geom, model):
        calls.append(model)
        raise SizeLimitError(10**12, 10**8, "the discretization")

    monkeypatch.setattr(derive, "discretize", refuse)
    doc = Document()
    o = doc.make_object(tri())
    doc.push(AddObject(o))
    for _ in range(2):
        with pytest.raises(SizeLimitError):
            doc.derived(o.id).get("discrete")
    assert calls == ["standard"]


def test_the_cache_keeps_live_entries_and_a_few_recent_ones():
    cache = DerivationCache(keep_recent=2)
    sources = [PixelSet.box(0, 0, k, k) for k in range(5)]
    entries = [cache.entry(s, "standard") for s in sources]
    cache.retain([(sources[4], "standard")])
    assert cache.entry(sources[4], "standard") is entries[4]
    assert len(cache) == 3  # 1 live + 2 recent
    assert cache.entry(sources[0], "standard") is not entries[0]  # evicted: a fresh entry


def test_undo_finds_recent_derivations_in_the_cache():
    doc = Document()
    o = doc.make_object(tri())
    doc.push(AddObject(o))
    first = doc.derived(o.id)
    first.get("discrete")
    doc.push(SetSource(o.id, tri(1, 1)))
    doc.undo()
    assert doc.derived(o.id) is first and first.is_ready("discrete")


# ---------------------------------------------------------------------------------------------- service
class Gate:
    """A derivation that blocks until released, to control when a worker finishes."""

    def __init__(self) -> None:
        self.release = threading.Event()
        self.started = threading.Event()

    def __call__(self, geom, model):
        from mrm.geometry.discretize import discretize

        self.started.set()
        assert self.release.wait(10)
        return discretize(geom, model)


# ---------------------------------------------------------------------------------------------- invariant
@settings(max_examples=30)
@given(
    st.lists(st.tuples(st.integers(-8, 8), st.integers(-8, 8)), min_size=1, max_size=30),
    st.sampled_from(["standard", "supercover", "gauss"]),
)
def test_invariant_after_painting_a_polygon(points, model):
    from mrm.geometry.discretize import discretize

    doc = Document(Settings(model))
    o = doc.make_object(MultiPolygon([tri(), tri(10, 0)]))
    doc.push(AddObject(o))
    doc.push(PaintPixels(o.id, PixelSet.from_points(points)))
    d = doc.derived(o.id)
    assert discretize(d.get("euclidean"), model) == d.get("discrete")
