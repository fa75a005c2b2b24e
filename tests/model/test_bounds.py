"""The error-bound rule of docs/design.md §8 against the paper's printed values and its general theorems."""

from __future__ import annotations

import json
import math
from decimal import Decimal, localcontext
from fractions import Fraction
from functools import reduce

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from mrm.cli import run_cli
from mrm.core.errors import ParameterError
from mrm.geometry.hausdorff.bounds import sqrt_multiple
from mrm.ops.chain import Link, parse_chain
from mrm.ops.chain import chain_bound as bound_of_chain
from mrm.ops.declare import ALPHA_MAX, ALPHA_MIN

# The steps of a chain, made through the registry as every path makes them (the parameters read exactly).


def dss(alpha: object, center: object = None) -> Link:
    return Link.of("dss", alpha=alpha, center=center)


def rot(angle: object, center: object = None) -> Link:
    return Link.of("discrete_rotation", angle=angle, center=center)


def sp(alpha: object, center: object = None) -> Link:
    return Link.of("simplify", alpha=alpha, center=center)


def scale(factor: object, center: object = (0, 0)) -> Link:
    return Link.of("scale", factor=factor, center=center)


def erot(angle: object, center: object = (0, 0)) -> Link:
    return Link.of("rotate", angle=angle, center=center)


def translate(dx: object, dy: object) -> Link:
    return Link.of("translate", dx=dx, dy=dy)


def union() -> Link:
    return Link.of("union")


def corefine(alpha: object = None, part: str = "") -> Link:
    parts = {"": "", "common": "a_and_b", "first": "a_minus_b", "second": "b_minus_a"}
    return Link.of("corefine", parts[part], alpha=alpha)


SQRT2 = math.sqrt(2)


def prod(xs: list[Fraction]) -> Fraction:
    return reduce(lambda a, b: a * b, xs, Fraction(1))


def truncated(x: float) -> float:
    """The paper prints its bounds truncated to two decimals (1.5556 → "1.55", 0.8485 → "0.84")."""
    return math.floor(x * 100) / 100


# ----------------------------------------------------------------------------------------------------------
# The paper's printed values (§3.1 and §5.2): exact coefficient, and the printed digits
# ----------------------------------------------------------------------------------------------------------

PAPER = [
    # (chain as applied, exact coefficient of √2, printed value, where)
    ("DSS 5, DSS 0.2", Fraction(1, 5), 0.28, "Thm 4, DSS_1/5∘DSS_5"),
    ("DSS 10, DSS 0.1", Fraction(1, 10), 0.14, "Thm 4, DSS_10 then back"),
    ("DSS 5, DSS 2, DSS 0.5, DSS 0.2", Fraction(1, 10) + Fraction(2, 5), 0.70, "Thm 7, α1=5, α2=2"),
    ("DSS 2, DSS 5, DSS 0.2, DSS 0.5", Fraction(1, 10) + Fraction(2, 2), 1.55, "Thm 7, α1=2, α2=5"),
    # Fig. 12: DSS_0.2∘DSS_0.5∘DSS_10 (the 0.5 is applied first) and its inversion DSS_0.5∘DSS_0.2∘DSS_10.
    ("DSS 10, DSS 0.5, DSS 0.2", Fraction(1, 10) + Fraction(1, 5), 0.42, "Thm 10, α1=5, α2=2"),
    ("DSS 10, DSS 0.2, DSS 0.5", Fraction(1, 10) + Fraction(1, 2), 0.84, "Thm 10, α1=2, α2=5"),
]


@pytest.mark.parametrize(("chain", "coef", "printed", "where"), PAPER)
def test_the_paper_printed_values(chain: str, coef: Fraction, printed: float, where: str) -> None:
    r = bound_of_chain(parse_chain(chain))
    assert r.coefficient == coef, where
    assert r.bound is not None
    assert truncated(r.bound) == printed, where
    assert r.bound == pytest.approx(float(coef) * SQRT2, rel=1e-15)


def test_the_paper_1_35_is_an_arithmetic_slip() -> None:
    # §5.2: "DSS0.8 ∘ DSS0.2 ∘ DSS5 ∘ DSS1.25: (1/(1.25·5) + 2·1/1.25)·√2 ≈ 1.35". Theorem 7 with α1 = 1.25,
    # α2 = 5 gives (1/6.25 + 2/1.25)·√2 = 1.76·√2 ≈ 2.49; the printed 1.35 is what one gets by dropping the
    # factor 2: (1/6.25 + 1/1.25)·√2 = 0.96·√2 ≈ 1.357.
    r = bound_of_chain(parse_chain("DSS 1.25, DSS 5, DSS 0.2, DSS 0.8"))
    assert r.coefficient == Fraction(1) / Fraction("6.25") + 2 / Fraction("1.25") == Fraction(44, 25)
    assert r.bound is not None
    assert round(r.bound, 2) == 2.49
    assert truncated(r.bound) != 1.35
    assert truncated(float(Fraction(1) / Fraction("6.25") + 1 / Fraction("1.25")) * SQRT2) == 1.35


def test_the_bound_digits_are_those_of_the_exact_value() -> None:
    for coef in (
        Fraction(1, 5),
        Fraction(11, 10),
        Fraction(44, 25),
        Fraction(3, 10),
        Fraction(10**20 + 1, 3),
    ):
        with localcontext() as ctx:
            ctx.prec = 120
            exact = Decimal(coef.numerator) / Decimal(coef.denominator) * Decimal(2).sqrt()
        assert sqrt_multiple(coef) == float(exact)


# ----------------------------------------------------------------------------------------------------------
# Theorems 4, 7, 8, 9, 10, 12, 13, 15, 16 in general form: the one rule equals each closed formula
# ----------------------------------------------------------------------------------------------------------

alphas = st.lists(
    st.fractions(min_value=Fraction(1, 50), max_value=50, max_denominator=64).filter(lambda q: q > 0),
    min_size=1,
    max_size=6,
)
angles = st.lists(st.fractions(min_value=-720, max_value=720, max_denominator=8), min_size=1, max_size=6)
centres = st.tuples(st.fractions(-50, 50, max_denominator=4), st.fractions(-50, 50, max_denominator=4))
MODELS = ("standard", "supercover")


@settings(max_examples=60)
@given(st.fractions(min_value=Fraction(1, 100), max_value=100, max_denominator=1000).filter(lambda q: q > 0))
def test_theorem_4(a: Fraction) -> None:
    r = bound_of_chain([dss(a), dss(1 / a)])
    assert r.coefficient == 1 / a
    assert r.bound == pytest.approx(float(1 / a) * SQRT2, rel=1e-15)


@settings(max_examples=60)
@given(alphas)
def test_theorem_7(a: list[Fraction]) -> None:
    k = len(a)
    p = [prod(a[: i + 1]) for i in range(k)]  # P_i = α1···αi
    chain = [dss(x) for x in a] + [dss(1 / x) for x in reversed(a)]
    expected = 1 / p[k - 1] + 2 * sum((1 / p[i] for i in range(k - 1)), Fraction(0))
    assert bound_of_chain(chain).coefficient == expected


@settings(max_examples=60)
@given(alphas, st.randoms(use_true_random=False))
def test_theorem_8(a: list[Fraction], rnd: object) -> None:
    k = len(a)
    a2 = list(a)
    rnd.shuffle(a2)  # type: ignore[attr-defined]
    # DSS_1/α′1 ∘ … ∘ DSS_1/α′k ∘ DSS_αk ∘ … ∘ DSS_α1: applied α1 … αk, then 1/α′k … 1/α′1.
    chain = [dss(x) for x in a] + [dss(1 / x) for x in reversed(a2)]
    expected = sum((1 / prod(a2[: i + 1]) for i in range(k)), Fraction(0)) + sum(
        (prod(a[i:]) for i in range(1, k)), Fraction(0)
    ) / prod(a2)
    assert bound_of_chain(chain).coefficient == expected


# A product of factors is one step's factor in Theorems 9 and 10: it stays in the range every DSS_α declares.
products_in_range = alphas.filter(lambda a: ALPHA_MIN <= prod(a) <= ALPHA_MAX)


@settings(max_examples=60)
@given(products_in_range)
def test_theorem_9(a: list[Fraction]) -> None:
    chain = [dss(x) for x in a] + [dss(1 / prod(a))]
    expected = sum((1 / prod(a[: i + 1]) for i in range(len(a))), Fraction(0))
    assert bound_of_chain(chain).coefficient == expected


@settings(max_examples=60)
@given(products_in_range)
def test_theorem_10(a: list[Fraction]) -> None:
    chain = [dss(prod(a))] + [dss(1 / x) for x in reversed(a)]
    expected = sum((1 / prod(a[: i + 1]) for i in range(len(a))), Fraction(0))
    assert bound_of_chain(chain).coefficient == expected


@settings(max_examples=30)
@given(st.fractions(-720, 720, max_denominator=16), centres)
def test_theorem_12(theta: Fraction, c: tuple[Fraction, Fraction]) -> None:
    r = bound_of_chain([rot(theta, c), rot(-theta, c)])
    assert r.coefficient == 1
    assert r.bound == SQRT2


@settings(max_examples=40)
@given(angles, centres)
def test_theorem_13(thetas: list[Fraction], c: tuple[Fraction, Fraction]) -> None:
    k = len(thetas)
    chain = [rot(t, c) for t in thetas] + [rot(-t, c) for t in reversed(thetas)]
    assert bound_of_chain(chain).coefficient == 2 * k - 1


@settings(max_examples=40)
@given(st.fractions(min_value=Fraction(1, 100), max_value=100, max_denominator=1000).filter(lambda q: q > 0))
def test_theorem_15(a: Fraction) -> None:
    assert bound_of_chain([sp(a)]).coefficient == 1 / a


@settings(max_examples=60)
@given(alphas)
def test_theorem_16(a: list[Fraction]) -> None:
    assert bound_of_chain([sp(x) for x in a]).coefficient == sum((1 / x for x in a), Fraction(0))


@settings(max_examples=60)
@given(
    st.lists(
        st.one_of(
            st.fractions(min_value=Fraction(1, 20), max_value=20, max_denominator=32)
            .filter(lambda q: q > 0)
            .map(lambda a: ("DSS", a)),
            st.fractions(-360, 360, max_denominator=4).map(lambda t: ("ROT", t)),
        ),
        min_size=1,
        max_size=7,
    ),
    st.sampled_from(MODELS),
)
def test_design_formula_for_any_chain_of_discrete_operations(
    ops: list[tuple[str, Fraction]], model: str
) -> None:
    # docs/design.md §8: for k discrete operations D∘T_i∘R with ratios s_i, H ≤ √n·Σ_{i=2..k} Π_{j=i..k} s_j.
    steps = [dss(v) if kind == "DSS" else rot(v) for kind, v in ops]
    s = [v if kind == "DSS" else Fraction(1) for kind, v in ops]
    k = len(s)
    expected = sum((prod(s[i:]) for i in range(1, k)), Fraction(0))
    r = bound_of_chain(steps, model)
    assert r.coefficient == expected
    assert len(r.terms) == k - 1
    assert [t.factor for t in r.terms] == [prod(s[i:]) for i in range(1, k)]
    assert r.bound is not None and r.directions == ("result_within", "source_within")


def test_centres_and_translations_change_nothing() -> None:
    base = bound_of_chain([dss(3), rot(30), dss(Fraction(1, 3))])
    moved = bound_of_chain([dss(3, (5, -2)), rot(30, (1, 1)), dss(Fraction(1, 3), (0.5, 0.5))])
    assert base.coefficient == moved.coefficient == Fraction(1, 3) + Fraction(1, 3)


# ----------------------------------------------------------------------------------------------------------
# Mixed chains, unions, co-refinements, models
# ----------------------------------------------------------------------------------------------------------


@pytest.mark.parametrize(
    ("chain", "coef"),
    [
        ("DSS 2, ROT 30", Fraction(1)),  # Sc_2, R∘D, rot: the round trip is not scaled afterwards
        ("ROT 30, DSS 2", Fraction(2)),  # rot, R∘D, Sc_2: scaled by 2
        ("SP 4, DSS 2", Fraction(1, 4) * 2 + 2),  # Sc_4 R∘D Sc_1/4 | D: R∘D | Sc_2
        ("DSS 2, SP 4", Fraction(1) + Fraction(1, 4)),  # Sc_2 | R∘D | Sc_4 R∘D Sc_1/4
        ("TRANSLATE 1,2, DSS 3", Fraction(3)),  # E is discretized before the DSS
        ("SCALE 2, SCALE 0.5", Fraction(0)),  # exact Euclidean maps only
        ("EROT 30, SP 2", Fraction(1, 2)),
        ("UNION", Fraction(1)),  # EDu = R(D(E ∪ E′)): one round trip
        ("SP 2, UNION", Fraction(1, 2) + 1),
        ("DSS 1, DSS 1", Fraction(1)),  # the rule counts the round trip even where it is exact
    ],
)
def test_mixed_chains(chain: str, coef: Fraction) -> None:
    r = bound_of_chain(parse_chain(chain))
    assert r.coefficient == coef
    assert sum((t.factor for t in r.terms), Fraction(0)) == coef


def test_gauss_gives_a_one_sided_bound_only() -> None:
    r = bound_of_chain(parse_chain("DSS 5, DSS 0.2"), "gauss")
    assert r.bound is None
    assert r.directions == ("result_within",)
    assert r.one_sided == pytest.approx(SQRT2 / 5, rel=1e-15)
    assert "every point of A_last" in r.guarantee
    assert bound_of_chain(parse_chain("DSS 5, DSS 0.2"), "supercover").bound == r.one_sided


def test_corefinement_parts() -> None:
    common = bound_of_chain([corefine(4)])
    assert common.coefficient == Fraction(1, 4)  # EDco_α: √n/α
    assert common.bound is None and common.directions == ("source_within",)
    first = bound_of_chain([corefine(4, "first")])
    assert first.bound is None and first.directions == ("result_within",)
    plain = bound_of_chain([corefine()])
    assert plain.coefficient == 1 and plain.directions == ("source_within",)
    # After an earlier error no direction survives a co-refinement.
    late = bound_of_chain([sp(2), corefine(4)])
    assert late.directions == () and late.bound is None and late.one_sided is None
    assert bound_of_chain([corefine(4)], "gauss").directions == ()
    assert bound_of_chain([corefine(4, "second")], "gauss").directions == ("result_within",)


def test_union_keeps_both_directions() -> None:
    r = bound_of_chain([sp(2), union(), scale(3)])
    assert r.coefficient == (Fraction(1, 2) + 1) * 3
    assert r.bound is not None


def test_bad_model_and_empty_chain() -> None:
    with pytest.raises(ParameterError, match="model"):
        bound_of_chain([dss(2)], "bresenham")
    with pytest.raises(ParameterError, match="empty"):
        bound_of_chain([])


def test_result_as_dict_is_json() -> None:
    d = bound_of_chain(parse_chain("DSS 5, DSS 2, DSS 0.5, DSS 0.2")).as_dict()
    back = json.loads(json.dumps(d))
    assert back["coefficient"] == "1/2"
    assert back["bound"] == pytest.approx(0.7071067811865476)
    assert [t["factor"] for t in back["terms"]] == ["1/5", "1/10", "1/5"]
    assert back["formula"].startswith("√2·(1/5 + 1/10 + 1/5)")


# ----------------------------------------------------------------------------------------------------------
# Parser
# ----------------------------------------------------------------------------------------------------------


def test_parser_reads_every_token() -> None:
    steps = parse_chain(
        "dss 1.25 about 3,4; Rot -30 @ (1, 2.5), sp 1/5, SCALE 2e-1 at 0 0, erot 90, translate -1, 2.5, "
        "UNION, corefine, COREFINE 8 first,"
    )
    assert steps == [
        dss(Fraction(5, 4), (3, 4)),
        rot(-30, (1, Fraction(5, 2))),
        sp(Fraction(1, 5)),
        scale(Fraction(1, 5), (0, 0)),
        erot(90),
        translate(-1, Fraction(5, 2)),
        union(),
        corefine(),
        corefine(8, "first"),
    ]
    assert steps[0].params.alpha == Fraction(5, 4)  # decimals are read exactly, not as floats


def test_labels_parse_back() -> None:
    steps = parse_chain(
        "DSS 1.25 about 3,4, ROT 1/3, TRANSLATE 1,2, COREFINE 2 second, EROT -45 about 0.5,0.5"
    )
    assert parse_chain(", ".join(s.label for s in steps)) == steps


@pytest.mark.parametrize(
    ("text", "match"),
    [
        ("", "empty"),
        ("   ", "empty"),
        ("DSS", "expected a number"),
        # The chain's text is refused with the range the operation declares, as the panel and the CLI say it.
        ("DSS 0", "'alpha' \\(α\\) must be ≥ 1e-06, got 0 \\(allowed: 1e-06 ≤ α ≤ 1e\\+06\\)"),
        ("DSS -2", "must be ≥ 1e-06, got -2"),
        ("SP 0", "must be ≥ 1e-06"),
        ("SCALE -1", "'factor' must be ≥ 1e-06"),
        ("COREFINE 0", "must be ≥ 1e-06"),
        ("DSS nan", "finite"),
        ("DSS inf", "finite"),
        ("DSS 1e999", "≤ 1e\\+06"),  # read exactly: the range says what is wrong
        ("ROT inf", "finite"),
        ("FOO 3", "unknown operation 'FOO'"),
        ("DSS 5 DSS 2", "separated by commas"),
        ("DSS 5,, DSS 2", "empty step"),
        ("ROT 30 about 1", "centre"),
        ("TRANSLATE 1", "TRANSLATE"),
        ("DSS 1/0", "divides by zero"),
        ("DSS 2 $", "cannot read"),
    ],
)
def test_parser_errors(text: str, match: str) -> None:
    with pytest.raises(ParameterError, match=match):
        parse_chain(text)


def test_constructors_refuse_bad_values() -> None:
    for bad in (0, -1, float("nan"), float("inf"), "x", None, True):
        with pytest.raises(ParameterError):
            dss(bad)
    with pytest.raises(ParameterError):
        rot(float("nan"))
    with pytest.raises(ParameterError):
        translate(1, float("inf"))
    with pytest.raises(ParameterError):  # a centre is 2 numbers (a pixel set's) or 3 (a voxel set's)
        dss(2, (1, 2, 3, 4))


# ----------------------------------------------------------------------------------------------------------
# CLI
# ----------------------------------------------------------------------------------------------------------


def test_cli_bounds_json(capsys: pytest.CaptureFixture[str]) -> None:
    assert run_cli(["bounds", "DSS 5, DSS 2, DSS 0.5, DSS 0.2", "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["bound"] == pytest.approx(SQRT2 / 2)
    assert out["coefficient"] == "1/2"
    assert out["sqrt_n"] == pytest.approx(SQRT2)
    assert len(out["terms"]) == 3 and "formula" in out


def test_cli_bounds_text_and_gauss(capsys: pytest.CaptureFixture[str]) -> None:
    assert run_cli(["bounds", "--model", "gauss", "SP 4, SP 2", "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["bound"] is None and out["one_sided"] == pytest.approx(0.75 * SQRT2)
    assert run_cli(["bounds", "ROT 30, ROT -30"]) == 0
    text = capsys.readouterr().out
    assert "√2" in text and "1.4142" in text


def test_cli_bounds_error(capsys: pytest.CaptureFixture[str]) -> None:
    assert run_cli(["bounds", "DSS 0, DSS 2"]) == 2
    err = capsys.readouterr().err
    assert err.startswith("mrm bounds: error:") and "must be ≥ 1e-06, got 0" in err


# ----------------------------------------------------------------------------------------------------------
# The opt-in refinement: round trips separated by an exact identity merge (D(R(A)) = A)
# ----------------------------------------------------------------------------------------------------------


@pytest.mark.parametrize(
    ("chain", "rule", "refined"),
    [
        ("SP 4, SP 4", Fraction(1, 2), Fraction(1, 4)),  # the paper's Sp_α∘Sp_α = Sp_α: Theorem 15's bound
        ("SP 4 about 1,2, SP 4 about 1,2", Fraction(1, 2), Fraction(1, 4)),
        ("SP 4, SP 4 about 1,2", Fraction(1, 2), Fraction(1, 4)),  # composite: a translation by (-3, -6)
        ("SP 4, SP 4 about 0.1,0", Fraction(1, 2), Fraction(1, 2)),  # a translation by (-0.3, 0)
        ("DSS 1, DSS 1, DSS 1", Fraction(2), Fraction(0)),  # DSS_1 = D∘R is the identity on pixel sets
        ("SP 2, TRANSLATE 3,4, SP 2", Fraction(1), Fraction(1, 2)),  # integer translations commute with R∘D
        ("SP 2, TRANSLATE 0.5,0, SP 2", Fraction(1), Fraction(1, 2)),  # ½ at scale 2 is one pixel
        ("SP 2, TRANSLATE 0.25,0, SP 2", Fraction(1), Fraction(1)),
        ("ROT 90 about 1,0, ROT -90 about 1,0", Fraction(1), Fraction(1)),  # R∘rot ≠ rot∘R
        ("TRANSLATE 1,0, DSS 1", Fraction(1), Fraction(1)),  # a Euclidean start is not a continuation
        ("SP 2, UNION, SP 2", Fraction(2), Fraction(2)),  # a union changes the object
    ],
)
def test_exact_identities_refinement(chain: str, rule: Fraction, refined: Fraction) -> None:
    steps = parse_chain(chain)
    assert bound_of_chain(steps).coefficient == rule
    tight = bound_of_chain(steps, exact_identities=True)
    assert tight.coefficient == refined
    assert sum((t.factor for t in tight.terms), Fraction(0)) == refined


@settings(max_examples=40)
@given(alphas)
def test_refinement_never_loosens_and_keeps_theorem_16_for_distinct_factors(a: list[Fraction]) -> None:
    steps = [sp(x) for x in a]
    rule = bound_of_chain(steps).coefficient
    tight = bound_of_chain(steps, exact_identities=True).coefficient
    assert tight <= rule
    # Consecutive equal factors merge (Sp_α∘Sp_α = Sp_α); otherwise every round trip counts.
    expected = sum((1 / x for i, x in enumerate(a) if i == 0 or a[i - 1] != x), Fraction(0))
    assert tight == expected


def test_cli_exact_identities(capsys: pytest.CaptureFixture[str]) -> None:
    assert run_cli(["bounds", "SP 4, SP 4", "--json"]) == 0
    plain = json.loads(capsys.readouterr().out)
    assert run_cli(["bounds", "SP 4, SP 4", "--exact-identities", "--json"]) == 0
    tight = json.loads(capsys.readouterr().out)
    assert plain["coefficient"] == "1/2" and tight["coefficient"] == "1/4" and tight["exact_identities"]
