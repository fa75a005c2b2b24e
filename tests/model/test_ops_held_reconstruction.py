"""Operations on document objects use the R(A) the document holds already (plan_operation's ``held``).

A document keeps each object's Euclidean representation R(A) once a view has shown it; DSS_α and dR_θ,C,
which compute D(T(R(A))), take that one instead of computing it again (Sp_α reconstructs the scaled set, and
the boolean operations the union, so they have no R(A) to reuse). R is deterministic, so the result is the
one the operation gives from the pixels alone.
"""

from __future__ import annotations

import pytest

from mrm.commands import AddObject
from mrm.document import Document, Settings
from mrm.geometry import reconstruct as reconstruct_module
from mrm.geometry.discretize import discretize
from mrm.ops.apply import apply_operation
from mrm.ops.base import plan_operation
from tests.oracles.geometry_strategies import noisy_star


def one_object_document(model: str) -> tuple[Document, int, object]:
    ps = discretize(noisy_star(300, 60.0, seed=4), model)
    doc = Document(Settings(model=model))
    obj = doc.make_object(ps, "star")
    doc.push(AddObject(obj))
    return doc, obj.id, ps


class Recomputed(Exception):
    """Raised by a patched R: the operation computed R(A) although the document held it."""


def refuse_r(*args: object, **kwargs: object) -> None:
    raise Recomputed


@pytest.mark.parametrize(
    ("operation", "params"),
    [("dss", {"alpha": 2.0}), ("dss", {"alpha": 2.5}), ("discrete_rotation", {"angle": 30.0})],
)
@pytest.mark.parametrize("model", ["standard", "gauss"])
def test_an_operation_takes_the_r_the_document_holds(
    monkeypatch: pytest.MonkeyPatch, operation: str, params: dict[str, object], model: str
) -> None:
    doc, obj, ps = one_object_document(model)
    reference = plan_operation([doc.get(obj)], operation, {**params, "model": model})
    doc.derived(obj).get("euclidean")  # the Euclidean view has shown the object
    monkeypatch.setattr(reconstruct_module, "_run", refuse_r)
    (new,) = apply_operation(doc, operation, [obj], {**params, "model": model})
    assert doc.get(new).source == reference.results[0].source
    assert doc.get(new).source != ps


def test_r_held_under_another_model_is_not_taken(monkeypatch: pytest.MonkeyPatch) -> None:
    doc, obj, _ps = one_object_document("standard")
    doc.derived(obj).get("euclidean")
    monkeypatch.setattr(reconstruct_module, "_run", refuse_r)
    with pytest.raises(Recomputed):
        apply_operation(doc, "dss", [obj], {"alpha": 2.0, "model": "gauss"})
