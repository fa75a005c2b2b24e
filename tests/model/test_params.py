"""Parameters (mrm.core.params): declared once, read once when made, exact and in range from then on."""

from __future__ import annotations

import pickle
from dataclasses import dataclass
from fractions import Fraction
from typing import Any

import pytest
from hypothesis import given
from hypothesis import strategies as st

from mrm.core.errors import ParameterError
from mrm.core.models import Model
from mrm.core.params import Parameters, param
from mrm.ops.registry import operations


@dataclass(frozen=True)
class DemoParams(Parameters):
    alpha: Fraction = param(2, kind="number", label="α", positive=True, maximum=1e6, help="scale factor")
    steps: int = param(3, minimum=1, maximum=10)
    centre: tuple[Fraction, Fraction] = param((0, 0), unit="px")
    exact: bool = param(True)
    mode: str = param("fast", choices=("fast", "slow"))
    angle: Fraction | None = param(None, kind="number", optional=True, minimum=-360, maximum=360)
    model: Model = param(Model.STANDARD)


def test_the_declarations_carry_the_metadata() -> None:
    specs = {s.name: s for s in DemoParams.specs()}
    a = specs["alpha"]
    assert (a.kind, a.label, a.default, a.minimum, a.min_inclusive, a.maximum, a.help) == (
        "number",
        "α",
        Fraction(2),
        Fraction(0),
        False,
        Fraction(10**6),
        "scale factor",
    )
    assert specs["steps"].kind == "int" and specs["centre"].kind == "point" and specs["centre"].unit == "px"
    assert specs["exact"].kind == "bool" and specs["mode"].choices == ("fast", "slow")
    assert specs["angle"].optional and specs["angle"].label == "angle"
    assert specs["model"].kind == "model"
    assert specs["centre"].as_dict()["default"] == [0, 0]
    assert a.range_text() == "0 < α ≤ 1e+06"


def test_a_declaration_needs_metadata_and_a_kind() -> None:
    @dataclass(frozen=True)
    class Bare(Parameters):
        x: float = 1.0

    with pytest.raises(TypeError, match="metadata"):
        Bare()
    with pytest.raises(TypeError, match="kind"):
        param(None)


@pytest.mark.parametrize(
    ("changes", "match"),
    [
        ({"alpha": 0.0}, "'alpha'.*positive, got 0"),
        ({"alpha": -1.5}, "'alpha'.*positive"),
        ({"alpha": float("nan")}, "'alpha'.*finite"),
        ({"alpha": float("inf")}, "'alpha'.*finite"),
        ({"alpha": 2e6}, "'alpha'.*≤ 1e\\+06, got 2000000 \\(allowed: 0 < α ≤ 1e\\+06\\)"),
        ({"alpha": "two"}, "'alpha'.*number"),
        ({"alpha": True}, "'alpha'.*number"),
        ({"alpha": None}, "'alpha'.*required"),
        ({"steps": 0}, "'steps'.*≥ 1"),
        ({"steps": 2.5}, "'steps'.*integer"),
        ({"centre": (1.0, float("nan"))}, "'centre'.*finite"),
        ({"centre": (1.0,)}, "'centre'.*2 numbers"),
        ({"centre": (2.0**40, 0)}, "'centre'.*coordinates between"),
        ({"exact": 1}, "'exact'.*true or false"),
        ({"mode": "medium"}, "'mode'.*one of fast, slow"),
        ({"angle": 400.0}, "'angle'.*≤ 360"),
        ({"model": "closest"}, "unknown discretization model 'closest'"),
    ],
)
def test_a_bad_value_is_refused_when_the_parameters_are_made(changes: dict[str, Any], match: str) -> None:
    with pytest.raises(ParameterError, match=match):
        DemoParams(**changes)


def test_values_are_read_exactly_once_and_round_trip() -> None:
    p = DemoParams(alpha=0.2, steps="10", centre="1, -2.5", angle="-1/3", model=" Gauss ")
    assert p.alpha == Fraction(1, 5) and p.steps == 10 and p.centre == (1, Fraction(-5, 2))
    assert p.angle == Fraction(-1, 3) and p.model is Model.GAUSS
    d = p.to_json()
    assert d == {
        "alpha": 0.2,
        "steps": 10,
        "centre": [1, -2.5],
        "exact": True,
        "mode": "fast",
        "angle": "-1/3",
        "model": "gauss",
    }
    assert DemoParams.from_json(d) == p
    assert pickle.loads(pickle.dumps(p)) == p  # they cross to worker processes
    assert p.replace(alpha="1/3").alpha == Fraction(1, 3)
    with pytest.raises(ParameterError, match="unknown parameter"):
        DemoParams.from_json({"beta": 1})
    with pytest.raises(ParameterError, match="positive"):
        DemoParams.from_json({"alpha": 0})


@given(st.fractions(min_value=Fraction(1, 10**6), max_value=10**6))
def test_every_form_of_a_number_gives_the_same_parameters(q: Fraction) -> None:
    as_text = DemoParams(alpha=f"{q.numerator}/{q.denominator}")
    assert as_text == DemoParams(alpha=q) == DemoParams.from_json(as_text.to_json())
    f = float(q)
    if Fraction(repr(f)) == q:  # a decimal a float prints exactly: the float reads as the same number
        assert DemoParams(alpha=f) == as_text


def test_every_operation_declares_every_parameter_and_its_defaults_are_valid() -> None:
    # The registry is the one source of the panel's fields, the CLI's options and the chain's text: every
    # field of every operation has its declaration, and the defaults make valid parameters.
    for spec in operations():
        defaults = spec.params()
        assert spec.read_params(None) == defaults
        assert spec.read_params(defaults.to_json()) == defaults
        for s in spec.params.specs():
            assert s.help, f"{spec.name}.{s.name} has no help text"


HUGE = 10**5000  # its repr raises ValueError (CPython refuses int → str beyond 4300 digits)


@pytest.mark.parametrize("name", ["alpha", "steps", "centre", "exact", "mode", "angle", "model"])
@pytest.mark.parametrize(
    "value",
    [HUGE, -HUGE, (HUGE, 0), [1, (2, HUGE)], {"x": HUGE}, "9" * 100_000],
    ids=["huge", "minus huge", "pair", "nested", "mapping", "long text"],
)
def test_a_value_holding_a_huge_integer_is_refused_in_one_short_line(name: str, value: Any) -> None:
    """Issue 32: messages quoting the value (repr) raised ValueError instead of refusing it."""
    with pytest.raises(ParameterError) as e:
        DemoParams(**{name: value})
    message = str(e.value)
    assert name in message and "\n" not in message and len(message) < 300


def test_messages_show_a_value_briefly_whatever_it_is() -> None:
    from mrm.core.numbers import value_text

    assert value_text("abc") == "'abc'" and value_text((1, 2.5)) == "(1, 2.5)"
    assert value_text(HUGE) == "<an integer of about 5,001 digits>"
    assert value_text(-HUGE) == "-<an integer of about 5,001 digits>"
    assert len(value_text(list(range(10**6)))) < 60 and len(value_text("x" * 10**6)) < 60

    class Broken:
        def __repr__(self) -> str:
            raise RuntimeError("no")

    assert value_text(Broken()).startswith("<")
