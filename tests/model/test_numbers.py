"""The one reader of numbers (mrm.core.numbers): every path reads a value the same way, exactly.

The reference is written here from the definitions: a float is the decimal it prints as (``repr``), text is
Python's own ``Fraction`` of the text, and what is written to JSON reads back to the same number.
"""

from __future__ import annotations

from decimal import Decimal
from fractions import Fraction

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from mrm.core.errors import ParameterError
from mrm.core.numbers import read_number, read_point, read_positive, spell, to_json
from mrm.ops.chain import Link, chain_bound, parse_chain


@given(st.fractions())
def test_every_number_reads_back_exactly(q: Fraction) -> None:
    assert read_number(to_json(q), "x") == q
    assert read_number(spell(q), "x") == q


@given(st.integers(-(10**6), 10**6).filter(bool), st.integers(330, 2000))
def test_a_tiny_decimal_is_written_in_a_few_characters(m: int, k: int) -> None:
    # --angle 1e-400 used to come back as a 401-digit fraction in the summary and the project file.
    q = Fraction(m, 10**k)
    text = to_json(q)
    assert read_number(text, "x") == q
    assert len(str(text)) <= 15


def test_a_third_stays_a_fraction() -> None:
    assert to_json(Fraction(1, 3)) == "1/3"
    assert to_json(Fraction(1, 5)) == 0.2
    assert spell(Fraction(5, 4)) == "1.25" and spell(Fraction(-1, 8)) == "-0.125"


@given(st.floats(allow_nan=False, allow_infinity=False))
def test_a_float_is_the_decimal_it_prints_as(x: float) -> None:
    q = read_number(x, "x")
    assert q == Fraction(repr(x))
    assert read_number(repr(x), "x") == q  # the text a person types gives the same number
    assert read_number(np.float64(x), "x") == q  # and so does numpy's scalar


@given(st.fractions(), st.sampled_from(["", " ", "\u2009"]), st.sampled_from(["", "°", "×", " px"]))
def test_text_as_people_type_it(q: Fraction, space: str, unit: str) -> None:
    typed = f"{space}{q.numerator}/{q.denominator}{unit}".replace("-", "\u2212")
    assert read_number(typed, "x") == q


def test_the_bound_reads_a_chain_as_the_operations_do() -> None:
    # Issue 27: bounds._exact read 0.2 as 3602879701896397/2⁵⁴ while the operations read it as 1/5, so the
    # library's bound of DSS 5, DSS 0.2, DSS 3 printed a 17-digit fraction where the text's printed 3/5.
    from_values = chain_bound([Link.of("dss", alpha=5), Link.of("dss", alpha=0.2), Link.of("dss", alpha=3)])
    from_text = chain_bound(parse_chain("DSS 5, DSS 0.2, DSS 3"))
    assert from_values.formula == from_text.formula == "√2·(3/5 + 3) = 18/5·√2 ≈ 5.0912"


@pytest.mark.parametrize(
    ("value", "match"),
    [
        (True, "must be a number"),
        (None, "must be a number"),
        (float("nan"), "finite"),
        (float("-inf"), "finite"),
        ("nan", "finite"),
        ("abc", "must be a number"),
        ("1/0", "divides by zero"),
        ("1e-1000000", "out of every allowed range"),  # refused before a million-digit integer is made
        ("9" * 5000, "digits"),
        (Decimal("Infinity"), "finite"),
        ([1], "must be a number"),
    ],
)
def test_what_is_no_number_is_refused_with_its_name(value: object, match: str) -> None:
    with pytest.raises(ParameterError, match=match) as e:
        read_number(value, "parameter 'alpha'")
    assert "parameter 'alpha'" in str(e.value)


def test_positive_and_points() -> None:
    assert read_positive("1/3", "α") == Fraction(1, 3)
    with pytest.raises(ParameterError, match=r"positive, got -0\.5"):
        read_positive(-0.5, "α")
    assert read_point("1.5, -2", "centre") == (Fraction(3, 2), Fraction(-2))
    assert read_point(np.array([0.1, 2]), "centre") == (Fraction(1, 10), Fraction(2))
    assert read_point((1, 2, 3), "centre", 3) == (1, 2, 3)
    with pytest.raises(ParameterError, match="centre y"):
        read_point((1, "y"), "centre")
    with pytest.raises(ParameterError, match="2 numbers"):
        read_point((1, 2, 3), "centre")
