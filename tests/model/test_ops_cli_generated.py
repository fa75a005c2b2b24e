"""The operation subcommands are generated from the registry: options, help, ranges, messages."""

from __future__ import annotations

import pytest

from mrm.cli import build_parser, run_cli
from mrm.core.grids import PixelSet
from mrm.io.pixel_files import write_pixels
from mrm.ops.registry import get_operation


@pytest.mark.parametrize(
    ("command", "operation"),
    [
        ("scale", "dss"),
        ("rotate", "discrete_rotation"),
        ("simplify", "simplify"),
        ("union", "union"),
        ("corefine", "corefine"),
    ],
)
def test_every_parameter_of_the_spec_is_an_option_with_its_range(command, operation, capsys):
    with pytest.raises(SystemExit):
        build_parser().parse_args([command, "--help"])
    text = " ".join(capsys.readouterr().out.split())
    for p in get_operation(operation).params.specs():
        if p.kind == "model":
            continue
        assert f"--{p.name}" in text
        if p.minimum is not None:
            assert p.range_text() in text


def test_an_out_of_range_value_is_refused_with_the_declared_range(tmp_path, capsys):
    png = tmp_path / "a.png"
    write_pixels(PixelSet.box(0, 0, 3, 3), png)
    assert run_cli(["rotate", str(png), "--angle", "7200", "-o", str(tmp_path / "o.png")]) == 2
    err = capsys.readouterr().err
    assert "'angle' (θ) must be ≤ 3600, got 7200 (allowed: -3600 ≤ θ ≤ 3600)" in err
    assert not (tmp_path / "o.png").exists()


def test_corefine_refuses_an_alpha_out_of_range_before_reading_its_inputs(tmp_path, capsys):
    # The inputs do not exist: the declared range is checked first, with the range in the message.
    missing = str(tmp_path / "none.png")
    assert run_cli(["corefine", missing, missing, "--alpha", "2e6", "-o", str(tmp_path / "o.geojson")]) == 2
    err = capsys.readouterr().err
    assert "'alpha' (α) must be ≤ 1e+06, got 2e6 (allowed: 1e-06 ≤ α ≤ 1e+06)" in err
    assert not list(tmp_path.iterdir())


@pytest.mark.parametrize("command", ["union", "corefine"])
def test_a_two_object_result_beyond_the_limit_is_refused_in_one_line(command, tmp_path, capsys):
    # Vector inputs are read without discretizing them: the limit is met by the operation's account.
    (tmp_path / "p.wkt").write_text("POLYGON ((0 0, 100 0, 100 100, 0 100, 0 0))")
    (tmp_path / "q.wkt").write_text("POLYGON ((50 50, 150 50, 150 150, 50 150, 50 50))")
    out = tmp_path / "o.geojson"
    argv = [command, str(tmp_path / "p.wkt"), str(tmp_path / "q.wkt"), "-o", str(out), "--limit", "1000"]
    assert run_cli(argv) == 2
    err = capsys.readouterr().err
    assert err.startswith(f"mrm {command}: error: ") and "more than the limit of 1,000" in err
    assert err.count("\n") == 1 and not out.exists()
