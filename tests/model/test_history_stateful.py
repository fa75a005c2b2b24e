"""Random sequences of edits, undos, redos, saves and loads on one document (hypothesis stateful testing).

After every step:
* the invariant holds for every object: D(Euclidean representation) = discrete representation;
* the document is exactly (bit for bit: its project-file bytes) the state recorded for the current history
  index — so every undo restores the previous state and every redo the next one;
* a refused edit leaves the document untouched;
* save → load gives the same bytes.
"""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import event, settings
from hypothesis import strategies as st
from hypothesis.stateful import RuleBasedStateMachine, invariant, precondition, rule
from shapely.geometry import MultiPolygon, Polygon

from mrm.core.errors import InvalidGeometryError, ParameterError
from mrm.core.grids import PixelSet
from mrm.document import Document, Style
from mrm.document.commands import (
    AddObject,
    ChangeSettings,
    MergeObjects,
    RemoveObjects,
    RenameObject,
    ReorderObjects,
    RestyleObject,
    SetSource,
)
from mrm.document.edits import DeleteComponent, DeleteVertex, FillHole, InsertVertex, MoveVertex, PaintPixels
from mrm.document.history import Command
from mrm.io.project import dumps, loads

half = st.integers(-16, 16).map(lambda v: v / 2)  # centres and sides of pixels: where ties are decided
anywhere = st.floats(-8, 8, allow_nan=False).map(lambda v: round(v, 3))
coords = st.one_of(half, anywhere)


@st.composite
def star_polygons(draw: st.DrawFn) -> Polygon:
    """A star-shaped polygon around a centre: simple whenever its angles strictly increase."""
    cx, cy = draw(half), draw(half)
    n = draw(st.integers(3, 7))
    angles = sorted(
        k * np.pi / 18 for k in draw(st.lists(st.integers(0, 35), min_size=n, max_size=n, unique=True))
    )
    radii = draw(st.lists(st.sampled_from([0.5, 1.0, 1.5, 2.5, 3.0, 4.25]), min_size=n, max_size=n))
    pts = [
        (cx + round(r * np.cos(a) * 4) / 4, cy + round(r * np.sin(a) * 4) / 4)
        for a, r in zip(angles, radii, strict=True)
    ]
    return Polygon(pts)


@st.composite
def pixel_sets(draw: st.DrawFn) -> PixelSet:
    h, w = draw(st.integers(1, 7)), draw(st.integers(1, 7))
    bits = draw(st.lists(st.booleans(), min_size=h * w, max_size=h * w))
    return PixelSet(
        np.array(bits, dtype=bool).reshape(h, w), (draw(st.integers(-6, 3)), draw(st.integers(-6, 3)))
    )


class DocumentMachine(RuleBasedStateMachine):
    def __init__(self) -> None:
        super().__init__()
        self.doc = Document(max_undo_steps=10_000)
        #: states[i] = the document bytes after i applied steps
        self.states: list[bytes] = [dumps(self.doc)]
        self.checked: dict[int, object] = {}

    # ------------------------------------------------------------------ helpers
    def push(self, cmd: Command) -> None:
        h = self.doc.history
        before = dumps(self.doc)
        count, index = h.count, h.index
        try:
            self.doc.push(cmd)
        except (InvalidGeometryError, ParameterError):
            assert dumps(self.doc) == before, "a refused edit changed the document"
            assert (h.count, h.index) == (count, index)
            event(f"refused {type(cmd).__name__}")
            return
        event(f"applied {type(cmd).__name__}")
        after = dumps(self.doc)
        self.record(index, before, after)

    def record(self, index: int, before: bytes, after: bytes) -> None:
        """Update the expected states after an edit made at history index ``index``."""
        h = self.doc.history
        if h.index == index + 1:  # a new step; the redo tail is gone
            assert h.count == h.index
            self.states = [*self.states[: index + 1], after]
        elif h.index == index and after == before:  # no effect: nothing recorded, redo tail kept
            pass
        elif h.index == index:  # merged into the previous step
            assert h.count == index and index > 0
            self.states = [*self.states[:index], after]
        elif h.index == index - 1:  # merged, and the step came back to where it started
            assert after == self.states[index - 1]
            self.states = self.states[:index]
        else:
            raise AssertionError(f"unexpected history move from index {index} to {h.index}")

    def ids(self, kind: str | None = None) -> list[int]:
        return [o.id for o in self.doc if kind is None or o.kind == kind]

    # ------------------------------------------------------------------ rules: objects
    @rule(poly=star_polygons())
    def add_polygon(self, poly: Polygon) -> None:
        if not poly.is_valid:
            return
        self.push(AddObject(self.doc.make_object(poly)))

    @rule(ps=pixel_sets())
    def add_pixels(self, ps: PixelSet) -> None:
        self.push(AddObject(self.doc.make_object(ps)))

    @precondition(lambda self: len(self.doc) > 0)
    @rule(data=st.data())
    def remove(self, data: st.DataObject) -> None:
        ids = self.ids()
        self.push(
            RemoveObjects(data.draw(st.lists(st.sampled_from(ids), min_size=1, max_size=2, unique=True)))
        )

    @precondition(lambda self: len(self.doc) > 1)
    @rule(data=st.data())
    def reorder(self, data: st.DataObject) -> None:
        self.push(ReorderObjects(data.draw(st.permutations(self.ids()))))

    @precondition(lambda self: len(self.doc) > 0)
    @rule(data=st.data(), name=st.text(max_size=6))
    def rename(self, data: st.DataObject, name: str) -> None:
        self.push(RenameObject(data.draw(st.sampled_from(self.ids())), name))

    @precondition(lambda self: len(self.doc) > 0)
    @rule(data=st.data(), opacity=st.sampled_from([0.0, 0.3, 1.0]))
    def restyle(self, data: st.DataObject, opacity: float) -> None:
        self.push(RestyleObject(data.draw(st.sampled_from(self.ids())), Style(opacity=opacity)))

    @precondition(lambda self: len(self.doc) > 1)
    @rule(data=st.data())
    def merge(self, data: st.DataObject) -> None:
        self.push(
            MergeObjects(
                data.draw(st.lists(st.sampled_from(self.ids()), min_size=2, max_size=3, unique=True))
            )
        )

    @rule(model=st.sampled_from(["standard", "supercover", "gauss"]))
    def change_model(self, model: str) -> None:
        self.push(ChangeSettings.model(self.doc, model))

    # ------------------------------------------------------------------ rules: polygons
    @precondition(lambda self: len(self.doc) > 0)
    @rule(data=st.data(), x=coords, y=coords, drag=st.sampled_from([None, 1, 2]))
    def move_vertex(self, data: st.DataObject, x: float, y: float, drag: int | None) -> None:
        oid = data.draw(st.sampled_from(self.ids()))
        v = (0, 0, data.draw(st.integers(0, 8)))
        self.push(MoveVertex(oid, v, (x, y), drag_id=drag))

    @precondition(lambda self: len(self.doc) > 0)
    @rule(data=st.data(), x=coords, y=coords)
    def insert_vertex(self, data: st.DataObject, x: float, y: float) -> None:
        oid = data.draw(st.sampled_from(self.ids()))
        self.push(InsertVertex(oid, (0, 0, data.draw(st.integers(0, 8))), (x, y)))

    @precondition(lambda self: len(self.doc) > 0)
    @rule(data=st.data())
    def delete_vertex(self, data: st.DataObject) -> None:
        oid = data.draw(st.sampled_from(self.ids()))
        self.push(DeleteVertex(oid, (0, data.draw(st.integers(0, 1)), data.draw(st.integers(0, 8)))))

    @precondition(lambda self: len(self.doc) > 0)
    @rule(data=st.data(), poly=star_polygons(), hole=st.booleans())
    def replace_geometry(self, data: st.DataObject, poly: Polygon, hole: bool) -> None:
        if not poly.is_valid:
            return
        geom = poly
        if hole:
            c = poly.centroid
            sq = [
                (c.x - 0.25, c.y - 0.25),
                (c.x - 0.25, c.y + 0.25),
                (c.x + 0.25, c.y + 0.25),
                (c.x + 0.25, c.y - 0.25),
            ]
            geom = MultiPolygon([Polygon(poly.exterior.coords, [sq])])
            if not geom.is_valid:
                return
        self.push(SetSource(data.draw(st.sampled_from(self.ids())), geom))

    # ------------------------------------------------------------------ rules: pixels
    @precondition(lambda self: len(self.doc) > 0)
    @rule(data=st.data(), dabs=st.lists(pixel_sets(), min_size=1, max_size=4), value=st.booleans())
    def brush_stroke(self, data: st.DataObject, dabs: list[PixelSet], value: bool) -> None:
        oid = data.draw(st.sampled_from(self.ids()))
        h = self.doc.history
        index, before = h.index, dumps(self.doc)
        with h.macro("Brush"):
            for d in dabs:
                self.doc.push(PaintPixels(oid, d, value))
        self.record(index, before, dumps(self.doc))

    @precondition(lambda self: len(self.doc) > 0)
    @rule(data=st.data(), x=st.integers(-6, 6), y=st.integers(-6, 6), every=st.booleans())
    def fill_hole(self, data: st.DataObject, x: int, y: int, every: bool) -> None:
        self.push(FillHole(data.draw(st.sampled_from(self.ids())), None if every else (x, y)))

    @precondition(lambda self: len(self.doc) > 0)
    @rule(data=st.data(), x=st.integers(-6, 6), y=st.integers(-6, 6))
    def delete_component(self, data: st.DataObject, x: int, y: int) -> None:
        oid = data.draw(st.sampled_from(self.ids()))
        pts = self.doc.derived(oid).get("discrete").points()
        if len(pts) and data.draw(st.booleans()):  # mostly a pixel of the object, sometimes anywhere
            x, y = (int(v) for v in pts[data.draw(st.integers(0, len(pts) - 1))])
        self.push(DeleteComponent(oid, (x, y)))

    # ------------------------------------------------------------------ rules: history
    @rule()
    def undo(self) -> None:
        self.doc.undo()

    @rule()
    def redo(self) -> None:
        self.doc.redo()

    @rule()
    def undo_redo_all(self) -> None:
        h = self.doc.history
        index = h.index
        while h.can_undo():
            h.undo()
        assert dumps(self.doc) == self.states[0]
        while h.index < index:
            h.redo()

    @rule()
    def save_and_load(self) -> None:
        data = dumps(self.doc)
        back = loads(data)
        assert dumps(back) == data
        assert back.objects == self.doc.objects

    # ------------------------------------------------------------------ invariants
    @invariant()
    def state_matches_the_history_index(self) -> None:
        assert dumps(self.doc) == self.states[self.doc.history.index]

    @invariant()
    def discretization_of_the_euclidean_representation_is_the_discrete_one(self) -> None:
        from mrm.geometry.discretize import discretize

        for o in self.doc:
            d = self.doc.derived(o.id)
            if id(d) in self.checked and self.checked[id(d)] is d:
                continue  # this source was checked under this model already (sources are immutable)
            self.checked[id(d)] = d
            euclid = d.get("euclidean")
            assert discretize(euclid, self.doc.model) == d.get("discrete"), (o.kind, self.doc.model)
            if o.kind == "euclidean":
                assert euclid is o.source
            else:
                assert d.get("discrete") is o.source


DocumentMachine.TestCase.settings = settings(max_examples=80, stateful_step_count=35, deadline=None)
TestDocumentMachine = DocumentMachine.TestCase


class LongDocumentMachine(DocumentMachine):
    """The same machine, much longer (``pytest -m slow``)."""


LongDocumentMachine.TestCase.settings = settings(
    max_examples=1500, stateful_step_count=60, deadline=None, derandomize=False
)
TestLongDocumentMachine = pytest.mark.slow(LongDocumentMachine.TestCase)
