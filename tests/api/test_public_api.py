"""``import mrm``: the curated, lazy, Qt-free library API and its image-oriented constructors."""

from __future__ import annotations

import subprocess
import sys

import numpy as np
import pytest
from PIL import Image
from shapely.geometry import Polygon

import mrm


def _run(code: str) -> str:
    return subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True).stdout


def test_every_public_name_resolves_and_is_documented():
    for name in mrm.__all__:
        value = getattr(mrm, name)
        if name != "__version__":
            assert (value.__doc__ or "").strip(), f"mrm.{name} has no docstring"
    assert {"read_pixels", "PixelSet", "reconstruct", "polygonize", "bound", "hausdorff"} <= set(mrm.__all__)


def test_import_is_lazy_and_qt_free():
    out = _run(
        "import sys, mrm\n"
        "heavy = ('mrm.', 'numpy', 'shapely', 'numba', 'PySide6')\n"
        "print(sorted(k for k in sys.modules if k.startswith(heavy)))\n"
        "mrm.reconstruct\n"
        "print(any(k.startswith('PySide6') or k.startswith('pyqtgraph') for k in sys.modules))\n"
    )
    first, second = out.strip().splitlines()
    assert first == "[]"  # nothing heavy is imported by `import mrm` alone
    assert second == "False"


def test_version_is_the_installed_distributions():
    from importlib.metadata import version

    assert mrm.__version__ == version("mr-modeler")


def test_unknown_attribute_is_an_attribute_error():
    try:
        mrm.no_such_function  # noqa: B018
    except AttributeError as e:
        assert "no_such_function" in str(e)
    else:
        raise AssertionError("mrm.no_such_function should not exist")


def test_from_image_agrees_with_reading_the_same_png(tmp_path):
    rng = np.random.default_rng(5)
    img = rng.random((7, 11)) < 0.4
    img[0, 0] = img[-1, -1] = True  # keep the bounding box the whole image
    path = tmp_path / "noise.png"
    Image.fromarray(img).save(path)
    ps = mrm.PixelSet.from_image(img)
    assert ps == mrm.read_pixels(path)
    # row 0 of the image is the top: its pixels have the largest y
    top = {(x, 6) for x in range(11) if img[0, x]}
    assert top == {p for p in ps if p[1] == 6}
    assert (ps.to_image() == img).all()


def test_from_image_invert_threshold_and_colour():
    grey = np.array([[0, 200], [90, 255]], dtype=np.uint8)
    assert sorted(mrm.PixelSet.from_image(grey, threshold=100)) == [(1, 0), (1, 1)]
    assert sorted(mrm.PixelSet.from_image(grey, threshold=100, invert=True)) == [(0, 0), (0, 1)]
    rgb = np.zeros((1, 2, 3), dtype=np.uint8)
    rgb[0, 1] = 255
    assert sorted(mrm.PixelSet.from_image(rgb, origin=(10, 20))) == [(11, 20)]
    assert sorted(mrm.PixelSet.from_image(np.array([[0.2, 0.9]]))) == [(1, 0)]


def test_to_image_with_a_box_places_the_set():
    ps = mrm.PixelSet.from_points([(1, 1)])
    img = ps.to_image((0, 0, 2, 1))  # 3 wide, 2 high: (1, 1) is in the top row
    assert img.tolist() == [[False, True, False], [False, False, False]]
    assert mrm.PixelSet.from_image(img, origin=(0, 0)) == ps


def test_reconstruct_of_an_image_round_trips_under_every_model():
    img = np.array([[1, 1, 0, 0], [0, 1, 1, 0], [0, 0, 1, 1], [1, 0, 0, 1]], dtype=bool)
    for model in ("standard", "supercover", "gauss"):
        poly = mrm.reconstruct(img, model)
        assert isinstance(poly, Polygon) or poly.geom_type == "MultiPolygon"
        assert mrm.discretize(poly, model) == mrm.PixelSet.from_image(img)


def test_polygonize_burns_back_to_the_label_image():
    labels = np.array([[1, 1, 2], [3, 2, 2], [3, 3, 0]])
    parts = mrm.polygonize(labels)
    assert sorted(parts) == [1, 2, 3]
    for label, poly in parts.items():
        assert mrm.discretize(poly, "gauss") == mrm.PixelSet.from_image(labels == label)


HUGE = 10**5000  # its repr raises ValueError (CPython refuses int → str beyond 4300 digits)
BAD_PIXELS = [(1e300, 0), (HUGE, 0), (0.5, 0), (2**40, 0), "x", [1], (1, 2, 3), True]
BAD_CALLS = {
    **{
        f"polygonize origin {k}": (lambda v=v: mrm.polygonize(np.ones((2, 2), int), origin=v))
        for k, v in enumerate(BAD_PIXELS)
    },
    **{f"segment start {k}": (lambda v=v: mrm.segment("0011", start=v)) for k, v in enumerate(BAD_PIXELS)},
    "segment closed": lambda: mrm.segment("0011", closed=HUGE),
    "segment closed list": lambda: mrm.segment("0011", closed=[1]),
    "segment adjacency": lambda: mrm.segment("0011", adjacency=(HUGE,)),
    "segment mode": lambda: mrm.segment("0011", mode=HUGE),
    "scale by a pair": lambda: mrm.scale(mrm.PixelSet.box(0, 0, 3, 3), (HUGE, 0)),
    "scale model": lambda: mrm.scale(mrm.PixelSet.box(0, 0, 3, 3), 2, model=HUGE),
    "bound model": lambda: mrm.bound("DSS 2", model=(HUGE,)),
    "discretize limit": lambda: mrm.discretize(Polygon([(0, 0), (2, 0), (0, 2)]), limit=(HUGE,)),
    "threshold": lambda: mrm.PixelSet.from_image(np.zeros((2, 2), np.uint8), threshold=HUGE),
}


@pytest.mark.parametrize("call", BAD_CALLS.values(), ids=BAD_CALLS.keys())
def test_hostile_arguments_are_refused_with_a_one_line_message(call):
    """Issue 32: integer points read with int() (OverflowError, IndexError), numba typing errors, and messages
    quoting a 5000-digit integer (ValueError) escaped the library's MRMError."""
    with pytest.raises(mrm.MRMError) as e:
        call()
    assert "\n" not in str(e.value) and len(str(e.value)) < 300
