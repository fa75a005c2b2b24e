"""Parameters written to JSON (provenance, ``--json``) read back exactly, and stay short."""

from __future__ import annotations

from fractions import Fraction

from hypothesis import given
from hypothesis import strategies as st

from mrm.geometry.discretize.exact_shape import exact_number, number_to_json


@given(st.fractions())
def test_every_number_reads_back_exactly(q: Fraction) -> None:
    assert exact_number(number_to_json(q), "x") == q


@given(st.integers(-(10**6), 10**6).filter(bool), st.integers(330, 2000))
def test_a_tiny_decimal_is_written_in_a_few_characters(m: int, k: int) -> None:
    # --angle 1e-400 used to come back as a 401-digit fraction in the summary and the project file.
    q = Fraction(m, 10**k)
    text = number_to_json(q)
    assert exact_number(text, "x") == q
    assert len(str(text)) <= 15


def test_a_third_stays_a_fraction() -> None:
    assert number_to_json(Fraction(1, 3)) == "1/3"
    assert number_to_json(Fraction(1, 5)) == 0.2
