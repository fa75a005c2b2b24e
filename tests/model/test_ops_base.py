"""The operation framework: progress and cancel, parameter metadata and validation, the size guard, the
registry, provenance and the chain runner."""

from __future__ import annotations

import math
import threading
import time
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from shapely.geometry import box

from mrm.core.errors import DEFAULT_PIXEL_LIMIT, Cancelled, ParameterError, SizeLimitError
from mrm.core.grids import PixelSet
from mrm.ops import setops, similarity
from mrm.ops.base import (
    NO_PROGRESS,
    REGISTRY,
    OperationResult,
    OperationSpec,
    Progress,
    ProgressLike,
    bounds_of,
    check_pixel_limit,
    estimate_result_pixels,
    get_operation,
    operations,
    param,
    param_specs,
    params_from_dict,
    params_to_dict,
    register,
    run_operation,
    validate_params,
)

# ----------------------------------------------------------------------------------------------------------
# Progress and cancel
# ----------------------------------------------------------------------------------------------------------


def test_progress_reports_clamps_and_never_goes_back() -> None:
    seen: list[tuple[float, str]] = []
    p = Progress(lambda f, m: seen.append((f, m)))
    p.update(0.25, "a")
    p.update(2.0)
    p.update(0.1, "b")
    p.update(float("nan"))
    assert seen == [(0.25, "a"), (1.0, "a"), (1.0, "b"), (1.0, "b")]
    assert p.fraction == 1.0 and p.message == "b" and not p.cancelled


def test_cancel_from_another_thread_stops_the_work_at_its_next_report() -> None:
    p = Progress()
    reports = []
    started = threading.Event()

    def work() -> None:
        try:
            for i in range(10**9):
                p.update(i / 10**9)
                reports.append(i)
                started.set()
        except Cancelled:
            reports.append(-1)

    t = threading.Thread(target=work)
    t.start()
    started.wait(5)
    p.cancel()
    t.join(5)
    assert not t.is_alive() and reports[-1] == -1 and p.cancelled
    with pytest.raises(Cancelled):
        p.check()


def test_concurrent_updates_are_consistent() -> None:
    p = Progress()

    def work(k: int) -> None:
        for i in range(2000):
            p.update((i + k) / 4000, f"w{k}")

    threads = [threading.Thread(target=work, args=(k,)) for k in range(4)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert p.fraction == (1999 + 3) / 4000 and p.message.startswith("w")


def test_sub_progress_maps_and_shares_the_cancel() -> None:
    seen: list[float] = []
    p = Progress(lambda f, m: seen.append(f))
    half = p.sub(0.5, 1.0)
    half.update(0.5)
    quarter = half.sub(0.0, 0.5)
    quarter.update(1.0)
    assert seen == [0.75, 0.75]
    half.sub(0.5, 1.0).update(1.0)
    assert seen[-1] == 1.0
    p.cancel()
    assert half.cancelled and quarter.cancelled
    with pytest.raises(Cancelled):
        quarter.update(0.2)


def test_the_null_progress_never_cancels() -> None:
    for i in range(3):
        NO_PROGRESS.update(i / 2, "x")
    assert not NO_PROGRESS.cancelled and NO_PROGRESS.sub(0, 1) is NO_PROGRESS
    assert isinstance(Progress(), ProgressLike) and isinstance(NO_PROGRESS, ProgressLike)


# ----------------------------------------------------------------------------------------------------------
# Parameters
# ----------------------------------------------------------------------------------------------------------


@dataclass(frozen=True)
class DemoParams:
    alpha: float = param(2.0, label="α", positive=True, maximum=1e6, help="scale factor")
    steps: int = param(3, minimum=1, maximum=10)
    centre: tuple[float, float] = param((0.0, 0.0), unit="px")
    exact: bool = param(True)
    mode: str = param("fast", choices=("fast", "slow"))
    angle: float | None = param(None, kind="float", optional=True, minimum=-360, maximum=360)


def test_param_specs_carry_the_metadata() -> None:
    specs = {s.name: s for s in param_specs(DemoParams)}
    assert [s.name for s in param_specs(DemoParams())] == list(specs)
    a = specs["alpha"]
    assert (a.kind, a.label, a.default, a.minimum, a.min_inclusive, a.maximum, a.help) == (
        "float",
        "α",
        2.0,
        0.0,
        False,
        1e6,
        "scale factor",
    )
    assert specs["steps"].kind == "int" and specs["centre"].kind == "point" and specs["centre"].unit == "px"
    assert specs["exact"].kind == "bool" and specs["mode"].choices == ("fast", "slow")
    assert specs["angle"].optional and specs["angle"].label == "angle"
    assert specs["centre"].as_dict()["default"] == [0.0, 0.0]


def test_param_needs_metadata_and_a_kind() -> None:
    @dataclass
    class Bare:
        x: float = 1.0

    with pytest.raises(TypeError, match="metadata"):
        param_specs(Bare)
    with pytest.raises(TypeError, match="kind"):
        param(None)
    with pytest.raises(TypeError):
        param_specs(3)


@pytest.mark.parametrize(
    ("changes", "match"),
    [
        ({"alpha": 0.0}, "'alpha'.*positive, got 0"),
        ({"alpha": -1.5}, "'alpha'.*positive"),
        ({"alpha": float("nan")}, "'alpha'.*finite"),
        ({"alpha": float("inf")}, "'alpha'.*finite"),
        ({"alpha": 2e6}, "'alpha'.*≤ 1e\\+06"),
        ({"alpha": "2"}, "'alpha'.*number"),
        ({"alpha": True}, "'alpha'.*number"),
        ({"alpha": None}, "'alpha'.*required"),
        ({"steps": 0}, "'steps'.*≥ 1"),
        ({"steps": 2.5}, "'steps'.*integer"),
        ({"centre": (1.0, float("nan"))}, "'centre'.*finite"),
        ({"centre": (1.0,)}, "'centre'.*pair"),
        ({"exact": 1}, "'exact'.*true or false"),
        ({"mode": "medium"}, "'mode'.*one of fast, slow"),
        ({"angle": 400.0}, "'angle'.*≤ 360"),
    ],
)
def test_validate_params_names_the_parameter(changes: dict[str, Any], match: str) -> None:
    with pytest.raises(ParameterError, match=match):
        validate_params(DemoParams(**changes))


def test_valid_params_pass_and_round_trip() -> None:
    p = DemoParams(alpha=0.5, steps=10, centre=(1, -2.5), angle=-30.0)
    validate_params(p)
    d = params_to_dict(p)
    assert d["centre"] == [1, -2.5]
    assert params_from_dict(DemoParams, d) == p
    with pytest.raises(ParameterError, match="unknown parameter"):
        params_from_dict(DemoParams, {"beta": 1})
    with pytest.raises(ParameterError, match="positive"):
        params_from_dict(DemoParams, {"alpha": 0})


# ----------------------------------------------------------------------------------------------------------
# Size estimate and guard
# ----------------------------------------------------------------------------------------------------------


def brute_force_pixels(bounds: tuple[float, float, float, float], scale: float, angle: float) -> int:
    """Pixels whose voxel meets the bounding box of the transformed box (about the origin), by enumeration."""
    if angle % 90 == 0:  # exact quarter turns, as the estimate promises
        c, s = [(1, 0), (0, 1), (-1, 0), (0, -1)][int(angle // 90) % 4]
    else:
        c, s = math.cos(math.radians(angle)), math.sin(math.radians(angle))
    xs, ys = [], []
    for x in (bounds[0], bounds[2]):
        for y in (bounds[1], bounds[3]):
            xs.append(scale * (c * x - s * y))
            ys.append(scale * (s * x + c * y))
    x0, x1, y0, y1 = min(xs), max(xs), min(ys), max(ys)
    nx = sum(1 for px in range(math.floor(x0) - 2, math.ceil(x1) + 3) if px + 0.5 >= x0 and px - 0.5 <= x1)
    ny = sum(1 for py in range(math.floor(y0) - 2, math.ceil(y1) + 3) if py + 0.5 >= y0 and py - 0.5 <= y1)
    return nx * ny


@settings(max_examples=60)
@given(
    st.integers(-20, 20),
    st.integers(-20, 20),
    st.integers(0, 15),
    st.integers(0, 15),
    st.sampled_from([0.3, 1.0, 2.0, 3.7]),
    st.sampled_from([0.0, 90.0, 180.0, -90.0, 27.0]),
)
def test_estimate_counts_the_pixels_of_the_transformed_box(
    x: int, y: int, w: int, h: int, scale: float, angle: float
) -> None:
    ps = PixelSet.box(x, y, x + w, y + h)
    b = bounds_of(ps)
    assert b == (x - 0.5, y - 0.5, x + w + 0.5, y + h + 0.5)
    est = estimate_result_pixels(b, scale=scale, angle_deg=angle)
    assert est == brute_force_pixels(b, scale, angle)


def test_estimate_of_absurd_scales_is_exact_and_refused() -> None:
    ps = PixelSet.box(0, 0, 999, 999)
    est = estimate_result_pixels(bounds_of(ps), scale=1e6)
    assert est == (10**9 + 1) ** 2  # [-0.5e6, 999.5e6] holds 10⁹ + 1 pixel centres on each axis
    with pytest.raises(SizeLimitError) as err:
        check_pixel_limit(est)
    assert err.value.estimated == est and err.value.limit == DEFAULT_PIXEL_LIMIT
    assert "1,000,000,002,000,000,001" in str(err.value)
    check_pixel_limit(est, None)
    assert estimate_result_pixels(None, scale=5) == 0
    assert estimate_result_pixels(bounds_of(box(0, 0, 1, 1)), offset=(0.5, 0)) == 3 * 2


def _counting_op(calls: list[str], estimate: int) -> OperationSpec:
    @dataclass(frozen=True)
    class P:
        factor: float = param(1.0, positive=True)

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
        run_operation(spec, [PixelSet.box(0, 0, 1, 1)], spec.params(factor=0.0))
    with pytest.raises(ParameterError, match=r"'factor'.*finite"):
        run_operation(spec, [PixelSet.box(0, 0, 1, 1)], spec.params(factor=float("nan")))
    with pytest.raises(ParameterError, match="takes"):
        run_operation(spec, [PixelSet.box(0, 0, 1, 1)], similarity.ScaleParams())
    with pytest.raises(ParameterError, match="1 input"):
        run_operation(spec, [])
    assert calls == []


def _bounded_numbers() -> list[tuple[str, str]]:
    from mrm.ops.apply import load_paper_operations

    load_paper_operations()
    return [
        (spec.name, p.name)
        for spec in operations()
        for p in spec.param_specs()
        if p.kind in ("float", "int") and (p.minimum is not None or p.maximum is not None)
    ]


@pytest.mark.parametrize(("operation", "name"), _bounded_numbers())
@settings(max_examples=15, deadline=None)
@given(excess=st.floats(min_value=1e-3, max_value=1e12), above=st.booleans())
def test_every_number_outside_its_declared_range_is_refused_with_the_range(
    operation: str, name: str, excess: float, above: bool
) -> None:
    """The registry declares each range once; every operation refuses beyond it and says what is allowed."""
    from mrm.ops.base import range_text

    spec = get_operation(operation)
    p = next(q for q in spec.param_specs() if q.name == name)
    edge = p.maximum if above else p.minimum
    if edge is None:  # open on that side: any value there is allowed
        edge, above = (p.minimum, False) if above else (p.maximum, True)
    assert edge is not None
    value = edge + excess * max(1.0, abs(edge)) if above else edge - excess * max(1.0, abs(edge))
    inputs = [box(0, 0, 2, 2) if spec.input_kind == "euclidean" else PixelSet.box(0, 0, 2, 2)] * spec.arity
    with pytest.raises(ParameterError) as info:
        run_operation(spec, inputs, {name: value})
    assert f"parameter {name!r}" in str(info.value)
    assert f"(allowed: {range_text(p)})" in str(info.value)


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


def test_a_long_operation_stops_promptly_on_cancel() -> None:
    @dataclass(frozen=True)
    class P:
        n: int = param(10**9, minimum=1)

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
