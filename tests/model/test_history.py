"""The single undo history: steps, macros, merging, the clean marker, limits, and every command type's
push → undo → redo contract checked as a property on random documents."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import event, given, settings
from hypothesis import strategies as st
from shapely.geometry import MultiPolygon, Polygon

from mrm.core.errors import InvalidGeometryError, ParameterError
from mrm.core.grids import PixelSet
from mrm.document import Document, Style
from mrm.document.commands import (
    AddObject,
    ApplyResults,
    ChangeSettings,
    MergeObjects,
    RemoveObjects,
    RenameObject,
    ReorderObjects,
    RestyleObject,
    SetSource,
)
from mrm.document.edits import (
    DeleteComponent,
    DeleteVertex,
    ErasePixels,
    FillHole,
    InsertVertex,
    MoveVertex,
    PaintPixels,
    PixelDelta,
)
from mrm.document.history import Command
from mrm.io.project import dumps
from mrm.ops.provenance import Provenance


def state(doc: Document) -> bytes:
    """The whole document state, bit for bit (the project file bytes)."""
    return dumps(doc)


def square(x0: float, y0: float, s: float) -> Polygon:
    return Polygon([(x0, y0), (x0 + s, y0), (x0 + s, y0 + s), (x0, y0 + s)])


def make_doc() -> tuple[Document, int, int]:
    doc = Document()
    a = doc.make_object(PixelSet.box(0, 0, 5, 5), "pixels")
    e = doc.make_object(square(0.25, 0.5, 4.0), "square")
    doc.push(AddObject(a))
    doc.push(AddObject(e))
    doc.history.clear()
    return doc, a.id, e.id


# ---------------------------------------------------------------------------------------------- basic stack
def test_undo_redo_walks_the_steps_and_labels_name_them():
    doc, a, _ = make_doc()
    s0 = state(doc)
    doc.push(RenameObject(a, "first"))
    s1 = state(doc)
    doc.push(RenameObject(a, "second"))
    assert doc.history.undo_label() == "Rename" and not doc.history.can_redo()
    doc.undo()
    assert state(doc) == s1 and doc.get(a).name == "first"
    doc.undo()
    assert state(doc) == s0 and doc.get(a).name == "pixels"
    assert not doc.history.can_undo()
    doc.undo()  # nothing left: no-op
    assert state(doc) == s0
    doc.redo()
    doc.redo()
    assert doc.get(a).name == "second"


def test_a_new_push_drops_the_redo_tail():
    doc, a, _ = make_doc()
    doc.push(RenameObject(a, "x"))
    doc.push(RenameObject(a, "y"))
    doc.undo()
    doc.push(RenameObject(a, "z"))
    assert doc.history.count == 2 and not doc.history.can_redo()
    doc.undo()
    assert doc.get(a).name == "x"


def test_a_refused_command_is_not_recorded_and_changes_nothing():
    doc, _, e = make_doc()
    s0 = state(doc)
    # Moving vertex 1 of the square across the opposite edge makes the ring cross itself.
    with pytest.raises(InvalidGeometryError):
        doc.push(MoveVertex(e, (0, 0, 1), (-3.0, 4.0)))
    assert state(doc) == s0 and doc.history.count == 0
    with pytest.raises(ParameterError):
        doc.push(DeleteVertex(e, (0, 0, 9)))
    with pytest.raises(InvalidGeometryError):  # a triangle cannot lose a vertex
        doc.push(DeleteVertex(e, (0, 0, 0)))
        doc.push(DeleteVertex(e, (0, 0, 0)))
    doc.undo()
    assert state(doc) == s0


def test_no_op_commands_add_no_step():
    doc, a, _ = make_doc()
    doc.push(RenameObject(a, "pixels"))  # same name
    doc.push(PaintPixels(a, PixelSet.box(1, 1, 2, 2)))  # already painted
    doc.push(ErasePixels(a, PixelSet.box(20, 20, 22, 22)))  # nothing there
    assert doc.history.count == 0 and not doc.is_modified


# ---------------------------------------------------------------------------------------------- macros
def test_a_brush_stroke_macro_is_one_step():
    doc, a, _ = make_doc()
    s0 = state(doc)
    with doc.history.macro("Brush stroke"):
        for k in range(10):
            doc.push(PaintPixels(a, PixelSet.box(6 + k, 0, 7 + k, 1)))
        assert doc.history.in_macro and not doc.history.can_undo()
    s1 = state(doc)
    assert doc.history.count == 1 and doc.history.undo_label() == "Brush stroke"
    assert doc.get(a).source == PixelSet.box(0, 0, 5, 5) | PixelSet.box(6, 0, 16, 1)
    doc.undo()
    assert state(doc) == s0
    doc.redo()
    assert state(doc) == s1


def test_nested_macros_flatten_and_empty_macros_vanish():
    doc, a, e = make_doc()
    with doc.history.macro("outer"):
        doc.push(RenameObject(a, "n1"))
        with doc.history.macro("inner"):
            doc.push(RenameObject(e, "n2"))
    with doc.history.macro("empty"):
        pass
    assert doc.history.count == 1
    doc.undo()
    assert (doc.get(a).name, doc.get(e).name) == ("pixels", "square")


def test_a_failing_macro_reverts_its_commands():
    doc, a, e = make_doc()
    s0 = state(doc)
    with pytest.raises(InvalidGeometryError), doc.history.macro("drag"):
        doc.push(RenameObject(a, "renamed"))
        doc.push(MoveVertex(e, (0, 0, 1), (-3.0, 4.0)))
    assert state(doc) == s0 and doc.history.count == 0 and not doc.history.in_macro


def test_undo_inside_an_open_macro_is_refused():
    doc, a, _ = make_doc()
    doc.history.begin_macro("m")
    doc.push(RenameObject(a, "q"))
    with pytest.raises(RuntimeError):
        doc.undo()
    doc.history.end_macro()
    with pytest.raises(RuntimeError):
        doc.history.end_macro()


# ---------------------------------------------------------------------------------------------- merging
def test_moves_of_one_drag_merge_into_one_step():
    doc, _, e = make_doc()
    s0 = state(doc)
    for k in range(5):
        doc.push(MoveVertex(e, (0, 0, 2), (4.25 + k, 4.5 + k), drag_id="d1"))
    assert doc.history.count == 1
    assert tuple(doc.get(e).source.exterior.coords[2]) == (8.25, 8.5)
    doc.undo()
    assert state(doc) == s0


def test_separate_drags_and_other_vertices_do_not_merge():
    doc, _, e = make_doc()
    doc.push(MoveVertex(e, (0, 0, 2), (5.0, 5.0), drag_id="d1"))
    doc.push(MoveVertex(e, (0, 0, 2), (6.0, 6.0), drag_id="d2"))
    doc.push(MoveVertex(e, (0, 0, 1), (5.0, 0.5), drag_id="d2"))
    doc.push(MoveVertex(e, (0, 0, 1), (5.5, 0.5)))  # no drag id: a step of its own
    doc.push(MoveVertex(e, (0, 0, 1), (5.75, 0.5)))
    assert doc.history.count == 5


def test_a_drag_back_to_the_start_leaves_no_step():
    doc, _, e = make_doc()
    doc.push(MoveVertex(e, (0, 0, 2), (6.0, 6.0), drag_id=7))
    doc.push(MoveVertex(e, (0, 0, 2), (4.25, 4.5), drag_id=7))
    assert doc.history.count == 0 and not doc.is_modified


def test_merging_never_crosses_the_clean_marker():
    doc, _, e = make_doc()
    doc.push(MoveVertex(e, (0, 0, 2), (5.0, 5.0), drag_id=1))
    doc.history.set_clean()
    doc.push(MoveVertex(e, (0, 0, 2), (6.0, 6.0), drag_id=1))
    assert doc.history.count == 2 and doc.is_modified
    doc.undo()
    assert not doc.is_modified


# ---------------------------------------------------------------------------------------------- clean marker
def test_clean_marker_follows_undo_and_becomes_unreachable_when_its_branch_is_dropped():
    doc, a, _ = make_doc()
    changes = []
    doc.history.subscribe(lambda: changes.append(doc.is_modified))
    assert not doc.is_modified
    doc.push(RenameObject(a, "x"))
    assert doc.is_modified
    doc.history.set_clean()
    assert not doc.is_modified
    doc.undo()
    assert doc.is_modified
    doc.redo()
    assert not doc.is_modified
    doc.undo()
    doc.push(RenameObject(a, "y"))  # the saved state can never come back
    assert doc.history.clean_index is None
    doc.undo()
    assert doc.is_modified
    assert changes  # listeners were told


# ---------------------------------------------------------------------------------------------- limits
def test_step_limit_drops_the_oldest_steps():
    doc = Document(max_undo_steps=3)
    o = doc.make_object(PixelSet.box(0, 0, 1, 1), "o")
    doc.push(AddObject(o))
    for k in range(5):
        doc.push(RenameObject(o.id, f"n{k}"))
    assert doc.history.count == 3
    while doc.history.can_undo():
        doc.undo()
    assert doc.get(o.id).name == "n1"
    assert doc.history.clean_index is None  # the original state is gone for good
    assert doc.is_modified


def test_byte_limit_keeps_the_newest_step_even_if_large():
    doc = Document(max_undo_bytes=10_000)
    o = doc.make_object(PixelSet.box(0, 0, 0, 0), "o")
    doc.push(AddObject(o))
    for k in range(4):  # each dab flips a 100x100 block: 1,250 packed bytes
        doc.push(PaintPixels(o.id, PixelSet.box(200 * k + 10, 0, 200 * k + 109, 99)))
    assert doc.history.byte_size() <= 10_000
    big = PixelSet.box(0, 1000, 499, 1499)  # 250,000 pixels: 31 kB packed, over the limit on its own
    doc.push(PaintPixels(o.id, big))
    assert doc.history.count == 1
    doc.undo()
    assert not big.issubset(doc.get(o.id).source)


def test_pixel_edits_store_packed_deltas_not_copies():
    doc = Document()
    o = doc.make_object(PixelSet.box(0, 0, 999, 999), "big")
    doc.push(AddObject(o))
    doc.history.clear()
    with doc.history.macro("stroke"):
        for k in range(50):
            doc.push(ErasePixels(o.id, PixelSet.box(10 * k, 10 * k, 10 * k + 4, 10 * k + 4)))
    # 50 dabs of 25 pixels: a few kB, while one copy of the mask is 1 MB.
    assert doc.history.byte_size() < 50_000


def test_pixel_delta_is_its_own_inverse():
    rng = np.random.default_rng(3)
    for _ in range(50):
        a = PixelSet(rng.random((7, 9)) < 0.5, (int(rng.integers(-5, 5)), int(rng.integers(-5, 5))))
        f = PixelSet(rng.random((5, 6)) < 0.5, (int(rng.integers(-8, 8)), int(rng.integers(-8, 8))))
        d = PixelDelta(f)
        b = d.apply(a)
        assert b == a ^ f
        assert d.apply(b) == a


# ---------------------------------------------------------------------------------------------- region edits
def nested() -> PixelSet:
    """A 11x11 frame whose hole holds a 5x5 ring, whose own hole is the single pixel (0, 0)."""
    frame = PixelSet.box(-5, -5, 5, 5) - PixelSet.box(-3, -3, 3, 3)
    ring = PixelSet.box(-2, -2, 2, 2) - PixelSet.box(0, 0, 0, 0)
    return frame | ring


def test_fill_hole_fills_exactly_the_hole_clicked():
    doc = Document()
    o = doc.make_object(nested(), "n")
    doc.push(AddObject(o))
    doc.push(FillHole(o.id, (3, -3)))  # the gap between frame and ring
    assert doc.get(o.id).source == PixelSet.box(-5, -5, 5, 5) - PixelSet.box(0, 0, 0, 0)
    doc.undo()
    doc.push(FillHole(o.id, (0, 0)))  # the ring's hole
    assert doc.get(o.id).source == nested() | PixelSet.box(0, 0, 0, 0)
    doc.undo()
    doc.push(FillHole(o.id))  # every hole
    assert doc.get(o.id).source == PixelSet.box(-5, -5, 5, 5)
    doc.undo()
    assert doc.get(o.id).source == nested()
    with pytest.raises(ParameterError):
        doc.push(FillHole(o.id, (9, 9)))  # outside: the unbounded background is no hole
    with pytest.raises(ParameterError):
        doc.push(FillHole(o.id, (-5, -5)))  # a pixel of the object


def test_a_hole_is_an_8_component_of_the_complement():
    # Two hole pixels touching at a corner form ONE hole under the (4, 8) topology.
    ps = PixelSet.box(0, 0, 4, 4) - PixelSet.from_points([(1, 1), (2, 2)])
    doc = Document()
    o = doc.make_object(ps, "d")
    doc.push(AddObject(o))
    doc.push(FillHole(o.id, (1, 1)))
    assert doc.get(o.id).source == PixelSet.box(0, 0, 4, 4)


def test_delete_component_removes_one_4_component():
    # (0,0)-(1,0) is one component; (2,1) touches it only at a corner: a component of its own.
    ps = PixelSet.from_points([(0, 0), (1, 0), (2, 1), (5, 5)])
    doc = Document()
    o = doc.make_object(ps, "c")
    doc.push(AddObject(o))
    doc.push(DeleteComponent(o.id, (1, 0)))
    assert doc.get(o.id).source == PixelSet.from_points([(2, 1), (5, 5)])
    doc.undo()
    assert doc.get(o.id).source == ps
    with pytest.raises(ParameterError):
        doc.push(DeleteComponent(o.id, (3, 3)))


def test_painting_a_euclidean_object_makes_its_pixels_the_source_and_undo_restores_the_polygon():
    from mrm.geometry.discretize import discretize

    doc, _, e = make_doc()
    poly = doc.get(e).source
    doc.push(PaintPixels(e, PixelSet.box(10, 10, 11, 11)))
    assert doc.get(e).kind == "discrete"
    assert doc.get(e).source == discretize(poly) | PixelSet.box(10, 10, 11, 11)
    doc.undo()
    assert doc.get(e).source is poly


def test_merge_is_the_union_of_the_discrete_representations():
    from mrm.geometry.discretize import discretize

    doc, a, e = make_doc()
    poly = doc.get(e).source
    doc.push(MergeObjects([e, a], name="m"))
    (m,) = doc.objects
    assert m.source == PixelSet.box(0, 0, 5, 5) | discretize(poly)
    assert m.provenance is not None and m.provenance.operation == "merge"
    assert set(m.provenance.inputs) == {a, e} and doc.selection == (m.id,)


# ---------------------------------------------------------------------------------------------- events
def test_each_push_and_undo_emits_one_batched_event():
    doc, a, e = make_doc()
    events = []
    doc.subscribe(events.append)
    doc.push(MergeObjects([a, e], name="both"))
    assert len(events) == 1
    ev = events[0]
    assert set(ev.removed) == {a, e} and len(ev.inserted) == 1 and ev.selection
    doc.undo()
    assert (
        len(events) == 2 and set(events[1].inserted) == {a, e} and set(events[1].removed) == set(ev.inserted)
    )


# ------------------------------------------------------------------------------- property: every command
coord = st.integers(-12, 12).map(lambda v: v / 2)  # pixel centres and sides: the adversarial positions
small_masks = st.tuples(st.integers(1, 6), st.integers(1, 6), st.integers(0, 2**36 - 1)).map(
    lambda t: PixelSet(
        ((t[2] >> np.arange(t[0] * t[1])) & 1).reshape(t[0], t[1]).astype(bool), (t[0] - 3, t[1] - 3)
    )
)


@st.composite
def documents(draw: st.DrawFn) -> Document:
    doc = Document()
    n_pix = draw(st.integers(1, 2))
    for _ in range(n_pix):
        ps = draw(small_masks)
        doc.push(AddObject(doc.make_object(ps)))
    ring = PixelSet.box(-3, -3, 3, 3) - PixelSet.box(-1, -1, 1, 1)  # a component with a 3x3 hole
    doc.push(AddObject(doc.make_object(ring ^ draw(small_masks).translate(4, 4), "ring")))
    n_poly = draw(st.integers(1, 2))
    for _ in range(n_poly):
        x, y = draw(coord), draw(coord)
        s = draw(st.sampled_from([1.5, 2.0, 3.25, 4.0]))
        doc.push(AddObject(doc.make_object(square(x, y, s))))
    doc.history.clear()
    return doc


def _command(draw: st.DrawFn, doc: Document, kind: str) -> Command:
    ids = list(doc.ids)
    pix = [o.id for o in doc if o.kind == "discrete"]
    euc = [o.id for o in doc if o.kind == "euclidean"]
    any_id = draw(st.sampled_from(ids))
    if kind == "add":
        return AddObject(doc.make_object(draw(small_masks)), draw(st.integers(0, len(ids))))
    if kind == "remove":
        return RemoveObjects(draw(st.lists(st.sampled_from(ids), min_size=1, max_size=len(ids), unique=True)))
    if kind == "reorder":
        return ReorderObjects(draw(st.permutations(ids)))
    if kind == "rename":
        return RenameObject(any_id, draw(st.text(max_size=8)))
    if kind == "restyle":
        return RestyleObject(
            any_id, Style(fill="#123456", opacity=draw(st.floats(0, 1)), visible=draw(st.booleans()))
        )
    if kind == "replace":
        return SetSource(draw(st.sampled_from(euc)), square(draw(coord), draw(coord), 2.5))
    if kind == "move_vertex":
        return MoveVertex(
            draw(st.sampled_from(euc)), (0, 0, draw(st.integers(0, 3))), (draw(coord), draw(coord))
        )
    if kind == "insert_vertex":
        return InsertVertex(
            draw(st.sampled_from(euc)), (0, 0, draw(st.integers(0, 4))), (draw(coord), draw(coord))
        )
    if kind == "delete_vertex":
        return DeleteVertex(draw(st.sampled_from(euc)), (0, 0, draw(st.integers(0, 3))))
    if kind == "paint":
        return PaintPixels(any_id, draw(small_masks))
    if kind == "erase":  # some of the object's own pixels, and maybe more
        pts = doc.derived(any_id).get("discrete").points()
        keep = draw(st.lists(st.booleans(), min_size=len(pts), max_size=len(pts)))
        return PaintPixels(
            any_id, PixelSet.from_points(pts[np.array(keep, dtype=bool)]) | draw(small_masks), False
        )
    if kind == "fill_hole":
        ring = [o.id for o in doc if o.name == "ring"]
        return FillHole(ring[0], draw(st.sampled_from([None, (0, 0), (-1, 1), (5, 5)])))
    if kind == "delete_component":
        target = draw(st.sampled_from(pix))
        pts = doc.get(target).source.points()
        x, y = pts[draw(st.integers(0, len(pts) - 1))] if len(pts) else (0, 0)
        return DeleteComponent(target, (int(x), int(y)))
    if kind == "merge":
        return MergeObjects(draw(st.lists(st.sampled_from(ids), min_size=2, max_size=len(ids), unique=True)))
    if kind == "settings":
        return ChangeSettings.model(doc, draw(st.sampled_from(["standard", "supercover", "gauss"])))
    if kind == "apply":
        new = doc.make_object(draw(small_masks), provenance=Provenance("scale", {"alpha": 1.5}, (any_id,)))
        return ApplyResults("Scale", add=[new], remove=[any_id] if draw(st.booleans()) else [])
    if kind == "polygon_with_hole":
        outer = square(-4.0, -4.0, 8.0)
        hole = square(draw(st.sampled_from([-2.0, -1.5])), -2.0, 3.0)
        geom = MultiPolygon([Polygon(outer.exterior.coords, [hole.exterior.coords[::-1]])])
        return SetSource(draw(st.sampled_from(euc)), geom)
    raise AssertionError(kind)


COMMAND_KINDS = [
    "add", "remove", "reorder", "rename", "restyle", "replace", "move_vertex", "insert_vertex",
    "delete_vertex", "paint", "erase", "fill_hole", "delete_component", "merge", "settings", "apply",
    "polygon_with_hole",
]  # fmt: skip

# Commands that need only the discrete side (D), not the continuation R, so they are checked even on a
# document whose Euclidean-from-discrete derivation is not involved.


@pytest.mark.parametrize("kind", COMMAND_KINDS)
@settings(max_examples=25)
@given(data=st.data())
def test_push_undo_redo_restore_states_bit_for_bit(kind, data):
    doc = data.draw(documents())
    cmd = _command(data.draw, doc, kind)
    s0 = state(doc)
    try:
        doc.push(cmd)
    except (InvalidGeometryError, ParameterError):
        assert state(doc) == s0 and doc.history.count == 0  # refused: untouched
        event("refused")
        return
    s1 = state(doc)
    if doc.history.count == 0:  # no effect, no step
        assert s1 == s0
        event("no effect")
        return
    event("applied")
    doc.undo()
    assert state(doc) == s0
    assert not doc.is_modified
    doc.redo()
    assert state(doc) == s1
    doc.undo()
    doc.redo()
    assert state(doc) == s1
