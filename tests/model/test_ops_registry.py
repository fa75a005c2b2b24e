"""The operation registry: the one size estimate and guard, running, provenance, the registry itself."""

from __future__ import annotations

import threading
import time
from collections.abc import Sequence
from dataclasses import dataclass
from fractions import Fraction
from typing import Any

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from shapely.geometry import box

from mrm.core.errors import Cancelled, ParameterError, SizeLimitError
from mrm.core.grids import PixelSet
from mrm.core.limits import DEFAULT_PIXEL_LIMIT, check_pixels
from mrm.core.params import Parameters, param
from mrm.core.progress import Progress, ProgressLike
from mrm.geometry.discretize.exact_shape import Similarity
from mrm.ops import setops, similarity
from mrm.ops.estimate import estimated_pixels
from mrm.ops.registry import (
    REGISTRY,
    OperationResult,
    OperationSpec,
    get_operation,
    operations,
    register,
    run_operation,
)

# ----------------------------------------------------------------------------------------------------------
# Size estimate and guard
# ----------------------------------------------------------------------------------------------------------


def brute_force_pixels(x0: int, y0: int, x1: int, y1: int, scale: Fraction) -> int:
    """Pixels whose closed voxel meets the box of Sc_s(V(box)) (the supercover box), by enumeration."""
    lo_x, hi_x = scale * (Fraction(x0) - Fraction(1, 2)), scale * (Fraction(x1) + Fraction(1, 2))
    lo_y, hi_y = scale * (Fraction(y0) - Fraction(1, 2)), scale * (Fraction(y1) + Fraction(1, 2))
    nx = sum(
        1
        for px in range(int(lo_x) - 2, int(hi_x) + 3)
        if px + Fraction(1, 2) >= lo_x and px - Fraction(1, 2) <= hi_x
    )
    ny = sum(
        1
        for py in range(int(lo_y) - 2, int(hi_y) + 3)
        if py + Fraction(1, 2) >= lo_y and py - Fraction(1, 2) <= hi_y
    )
    return nx * ny


@settings(max_examples=60)
@given(
    st.integers(-20, 20),
    st.integers(-20, 20),
    st.integers(0, 15),
    st.integers(0, 15),
    st.sampled_from([Fraction(3, 10), Fraction(1), Fraction(2), Fraction(37, 10)]),
)
def test_the_estimate_of_a_scaled_pixel_set_is_its_voxels_box(
    x: int, y: int, w: int, h: int, scale: Fraction
) -> None:
    ps = PixelSet.box(x, y, x + w, y + h)
    assert estimated_pixels([ps], None, "supercover") == (w + 1) * (h + 1)  # no similarity: the set itself
    sim = Similarity.scaling(scale)
    assert estimated_pixels([ps], sim, "supercover") == brute_force_pixels(x, y, x + w, y + h, scale)


def test_the_estimate_of_absurd_scales_is_exact_and_refused() -> None:
    ps = PixelSet.box(0, 0, 999, 999)
    est = estimated_pixels([ps], Similarity.scaling(Fraction(10**6)), "supercover")
    assert est == (10**9 + 1) ** 2  # [-0.5e6, 999.5e6] holds 10⁹ + 1 pixel centres on each axis
    with pytest.raises(SizeLimitError) as err:
        check_pixels(est, DEFAULT_PIXEL_LIMIT, "the result")
    assert err.value.estimated == est and err.value.limit == DEFAULT_PIXEL_LIMIT
    assert "1,000,000,002,000,000,001" in str(err.value)
    check_pixels(est, None, "the result")
    assert estimated_pixels([PixelSet.empty()], Similarity.scaling(Fraction(5)), "standard") == 0
    with pytest.raises(ParameterError, match="pixel limit"):
        check_pixels(1, -1, "the result")


@dataclass(frozen=True)
class CountingParams(Parameters):
    factor: Fraction = param(1, kind="number", positive=True)


def _counting_op(calls: list[str], estimate: int) -> OperationSpec:
    P = CountingParams

    def run(inputs: Sequence[Any], p: Any, progress: ProgressLike) -> OperationResult:
        calls.append("run")
        return OperationResult(outputs=[("out", inputs[0])])

    return OperationSpec("counting", "Counting", 1, P, run, estimate=lambda inputs, p: estimate)


def test_the_guard_refuses_before_running() -> None:
    calls: list[str] = []
    spec = _counting_op(calls, DEFAULT_PIXEL_LIMIT + 1)
    with pytest.raises(SizeLimitError) as err:
        run_operation(spec, [PixelSet.box(0, 0, 1, 1)])
    assert calls == [] and err.value.estimated == DEFAULT_PIXEL_LIMIT + 1
    # The limit is configurable, and None lifts it.
    with pytest.raises(SizeLimitError):
        run_operation(_counting_op(calls, 101), [PixelSet.box(0, 0, 1, 1)], limit=100)
    assert calls == []
    run_operation(spec, [PixelSet.box(0, 0, 1, 1)], limit=None)
    assert calls == ["run"]


def test_bad_parameters_are_refused_before_running() -> None:
    calls: list[str] = []
    spec = _counting_op(calls, 1)
    with pytest.raises(ParameterError, match=r"'factor'.*positive"):
        run_operation(spec, [PixelSet.box(0, 0, 1, 1)], {"factor": 0.0})
    with pytest.raises(ParameterError, match=r"'factor'.*finite"):
        run_operation(spec, [PixelSet.box(0, 0, 1, 1)], {"factor": float("nan")})
    with pytest.raises(ParameterError, match="takes"):
        run_operation(spec, [PixelSet.box(0, 0, 1, 1)], similarity.ScaleParams())
    with pytest.raises(ParameterError, match="1 input"):
        run_operation(spec, [])
    assert calls == []


def _bounded_numbers() -> list[tuple[str, str]]:
    return [
        (spec.name, p.name)
        for spec in operations()
        for p in spec.params.specs()
        if p.is_number and (p.minimum is not None or p.maximum is not None)
    ]


@pytest.mark.parametrize(("operation", "name"), _bounded_numbers())
@settings(max_examples=15, deadline=None)
@given(excess=st.floats(min_value=1e-3, max_value=1e12), above=st.booleans())
def test_every_number_outside_its_declared_range_is_refused_with_the_range(
    operation: str, name: str, excess: float, above: bool
) -> None:
    """The registry declares each range once; every operation refuses beyond it and says what is allowed."""
    spec = get_operation(operation)
    p = spec.params.spec(name)
    edge = p.maximum if above else p.minimum
    if edge is None:  # open on that side: any value there is allowed
        edge, above = (p.minimum, False) if above else (p.maximum, True)
    assert edge is not None
    step = Fraction(excess) * max(Fraction(1), abs(edge))
    value = edge + step if above else edge - step
    inputs = [box(0, 0, 2, 2) if spec.reads == "euclidean" else PixelSet.box(0, 0, 2, 2)] * spec.arity
    with pytest.raises(ParameterError) as info:
        run_operation(spec, inputs, {name: value})
    assert f"parameter {name!r}" in str(info.value)
    assert f"(allowed: {p.range_text()})" in str(info.value)


def test_the_declared_ranges_are_the_papers_operations_ones() -> None:
    # The list above is not empty: α of DSS, Sp, EDco; θ of dR and rotate; the Euclidean scale factor.
    assert {"dss", "discrete_rotation", "simplify", "corefine", "scale", "rotate"} <= {
        op for op, _ in _bounded_numbers()
    }


# ----------------------------------------------------------------------------------------------------------
# Running, provenance, registry
# ----------------------------------------------------------------------------------------------------------


def test_provenance_names_operation_params_and_inputs() -> None:
    a, b = PixelSet.box(0, 0, 3, 3), PixelSet.box(2, 2, 5, 5)
    res = run_operation("discrete_union", [a, b])
    assert res.output == a | b and res.outputs[0][0] == "union"
    assert res.provenance == {
        "operation": "discrete_union",
        "params": {},
        "inputs": [{"input": 0}, {"input": 1}],
    }
    assert res.bound is None and res.measured is None


def test_cancelled_before_the_run_raises() -> None:
    calls: list[str] = []
    p = Progress()
    p.cancel()
    with pytest.raises(Cancelled):
        run_operation(_counting_op(calls, 1), [PixelSet.box(0, 0, 1, 1)], progress=p)
    assert calls == []


@dataclass(frozen=True)
class SlowParams(Parameters):
    n: int = param(10**9, minimum=1)


def test_a_long_operation_stops_promptly_on_cancel() -> None:
    P = SlowParams

    def slow(inputs: Sequence[Any], p: Any, progress: ProgressLike) -> OperationResult:
        for i in range(p.n):
            progress.update(i / p.n, "working")
        return OperationResult(outputs=[("x", inputs[0])])

    spec = OperationSpec("slow", "Slow", 1, P, slow)
    prog = Progress()
    outcome: list[BaseException] = []

    def work() -> None:
        try:
            run_operation(spec, [PixelSet.box(0, 0, 1, 1)], progress=prog)
        except Cancelled as e:
            outcome.append(e)

    t = threading.Thread(target=work)
    t.start()
    while prog.fraction == 0.0 and t.is_alive():
        time.sleep(0.001)
    prog.cancel()
    t.join(5)
    assert not t.is_alive() and len(outcome) == 1


def test_input_kinds_are_checked() -> None:
    with pytest.raises(ParameterError, match="pixel set"):
        run_operation("discrete_union", [box(0, 0, 1, 1), PixelSet.box(0, 0, 1, 1)])
    with pytest.raises(ParameterError, match="Euclidean geometry"):
        run_operation("translate", [PixelSet.box(0, 0, 1, 1)])


def test_registry() -> None:
    names = {op.name for op in operations()}
    assert {
        "translate",
        "scale",
        "rotate",
        "discrete_union",
        "discrete_intersection",
        "discrete_difference",
    } <= names
    assert get_operation("scale") is similarity.SCALE and REGISTRY["discrete_union"] is setops.UNION
    with pytest.raises(ParameterError, match="unknown operation 'nope'"):
        get_operation("nope")
    register(similarity.SCALE)  # registering the same spec again is harmless
    with pytest.raises(ValueError, match="already registered"):
        register(OperationSpec("scale", "Other", 1, similarity.ScaleParams, similarity.SCALE.run))


@settings(max_examples=40)
@given(
    st.sets(st.tuples(st.integers(-4, 4), st.integers(-4, 4)), max_size=30),
    st.sets(st.tuples(st.integers(-4, 4), st.integers(-4, 4)), max_size=30),
)
def test_set_operations_are_the_set_operations(pa: set[tuple[int, int]], pb: set[tuple[int, int]]) -> None:
    a, b = PixelSet.from_points(sorted(pa)), PixelSet.from_points(sorted(pb))
    for name, expected in (
        ("discrete_union", pa | pb),
        ("discrete_intersection", pa & pb),
        ("discrete_difference", pa - pb),
    ):
        out = run_operation(name, [a, b]).output
        assert isinstance(out, PixelSet)
        assert {tuple(map(int, p)) for p in out.points()} == expected


def test_one_progress_protocol_for_the_library_the_cli_and_the_window() -> None:
    # The geometry kernels, the operations and the window's tasks take the same object: the window's
    # TaskProgress is the library's Progress, throttled to what a progress bar can show, and a sub-range
    # of a parent that has no progress at all is a valid progress.
    from mrm.app.progress import TaskProgress
    from mrm.core.progress import sub_progress

    seen: list[tuple[float, str]] = []
    p = TaskProgress(lambda f, m: seen.append((f, m)))
    assert isinstance(p, Progress) and isinstance(p, ProgressLike)
    for i in range(1, 200):
        p.update(i / 400, "working")  # within one throttle interval: one report
    p.update(1.0, "done")  # the end always goes through
    assert seen[0] == (1 / 400, "working") and seen[-1] == (1.0, "done") and len(seen) < 10
    free = sub_progress(None, 0.2, 0.4)
    free.update(0.5, "x")
    assert not free.cancelled
    shared = threading.Event()
    q = TaskProgress(event=shared)
    shared.set()  # a worker's signal handler sets the shared flag
    with pytest.raises(Cancelled):
        q.update(0.1)
