"""Every example written in the API reference (docs/api/*.rst) runs and prints what the page says.

The docstrings' own examples run in tests/api/test_doctests.py; these are the ones the reference adds for
the public names whose docstrings have none (issue 31: every public name with an example).
"""

from __future__ import annotations

import doctest
from pathlib import Path

import pytest

PAGES = sorted((Path(__file__).resolve().parents[2] / "docs" / "api").glob("*.rst"))


@pytest.mark.parametrize("page", PAGES, ids=[p.name for p in PAGES])
def test_the_reference_examples_run(page, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)  # the examples write their files here
    result = doctest.testfile(
        str(page),
        module_relative=False,
        optionflags=doctest.NORMALIZE_WHITESPACE | doctest.ELLIPSIS,
        verbose=False,
    )
    assert result.failed == 0
    assert result.attempted > 20
