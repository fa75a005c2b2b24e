"""Test configuration: Qt offscreen unless --headed, deterministic hypothesis profiles."""

from __future__ import annotations

import os

from hypothesis import HealthCheck, settings

settings.register_profile(
    "ci",
    derandomize=True,
    deadline=None,
    print_blob=True,
    suppress_health_check=[HealthCheck.too_slow, HealthCheck.data_too_large],
)
settings.register_profile(
    "long",
    deadline=None,
    max_examples=20_000,
    suppress_health_check=[HealthCheck.too_slow, HealthCheck.data_too_large],
)
settings.load_profile(os.environ.get("HYPOTHESIS_PROFILE", "ci"))


def pytest_addoption(parser):  # type: ignore[no-untyped-def]
    parser.addoption("--headed", action="store_true", help="show Qt windows instead of offscreen rendering")
    parser.addoption("--run-slow", action="store_true", help="also run the long property runs marked slow")


def pytest_configure(config):  # type: ignore[no-untyped-def]
    if not config.getoption("--headed"):
        os.environ["QT_QPA_PLATFORM"] = "offscreen"
    os.environ.setdefault("MRM_SETTINGS_ISOLATED", "1")
    try:  # as the application does before its QApplication exists (the 3D views' shared shaders)
        from mrm.app.application import share_opengl_contexts
    except ImportError:  # a test run without the gui extra
        return
    share_opengl_contexts()


def pytest_collection_modifyitems(config, items):  # type: ignore[no-untyped-def]
    import pytest

    if config.getoption("--run-slow") or "slow" in (config.getoption("-m") or ""):
        return
    deselected = [it for it in items if "slow" in it.keywords]
    if deselected:
        config.hook.pytest_deselected(items=deselected)
        items[:] = [it for it in items if "slow" not in it.keywords]
    _ = pytest
