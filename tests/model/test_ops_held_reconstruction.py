"""Operations on document objects use the R(A) the document holds already (plan_operation's ``held``).

A document keeps each object's Euclidean representation R(A) once a view has shown it; the operations that
start from R(A) of a pixel input (DSS_α and dR_θ,C, which compute D(T(R(A))), and Sp_α and EDco_α, which
scale it) take that one instead of computing it again. R is deterministic, so the result is the one the
operation gives from the pixels alone.
"""

from __future__ import annotations

import pytest

from mrm.document import Document, Settings
from mrm.document.apply import apply_operation
from mrm.document.commands import AddObject
from mrm.geometry import reconstruct as reconstruct_module
from mrm.geometry.discretize import discretize
from mrm.ops.registry import plan_operation
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


@pytest.mark.parametrize(
    ("operation", "params", "arity"),
    [("simplify", {"alpha": 3.0}, 1), ("corefine", {"alpha": 2.0}, 2)],
)
def test_simplification_and_precise_corefinement_start_from_the_r_held(
    monkeypatch: pytest.MonkeyPatch, operation: str, params: dict[str, object], arity: int
) -> None:
    # Sp_α and EDco_α scale R(A) of a pixel input, then reconstruct other sets (the scaled set, the parts):
    # R(A) is not computed again, one R call fewer per held input, and the result is the same. (EDu and
    # EDco at α = 1 take the pixels of a pixel input as they are: no R(A) there.)
    doc, obj, _ps = one_object_document("standard")
    calls = []
    real_run = reconstruct_module._run

    def counted(*args: object, **kwargs: object) -> object:
        calls.append(args[0])
        return real_run(*args, **kwargs)  # type: ignore[arg-type]

    monkeypatch.setattr(reconstruct_module, "_run", counted)
    ids = [obj] * arity
    reference = plan_operation([doc.get(i) for i in ids], operation, params)
    from_pixels = len(calls)
    doc.derived(obj).get("euclidean")
    calls.clear()
    new = apply_operation(doc, operation, ids, params)
    assert len(calls) == from_pixels - arity
    assert [doc.get(i).source for i in new] == [r.source for r in reference.results]
