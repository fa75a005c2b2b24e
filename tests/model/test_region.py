"""Region representation of pixel sets: components, holes, Euler number, crack chains, fill.

Reference: docs/design.md §4.
"""

from __future__ import annotations

import numpy as np
import pytest
import skimage.data
from hypothesis import given, settings
from hypothesis import strategies as st
from hypothesis.extra.numpy import arrays
from skimage.filters import threshold_otsu
from skimage.measure import euler_number
from skimage.measure import label as sk_label

from mrm.core.errors import InvalidGeometryError, ParameterError
from mrm.core.grids import LabelMap, PixelSet
from mrm.reps.region import CrackChain, Region, fill, fill_chains, region_of

# ---------------------------------------------------------------------------------------------- helpers


def member(ps: PixelSet, pts: np.ndarray) -> np.ndarray:
    """Vectorised ``(x, y) in ps`` for an (n, 2) array."""
    if ps.is_empty():
        return np.zeros(len(pts), bool)
    (x0, y0), (h, w) = ps.origin, ps.shape
    c, r = pts[:, 0] - x0, pts[:, 1] - y0
    ok = (r >= 0) & (r < h) & (c >= 0) & (c < w)
    out = np.zeros(len(pts), bool)
    out[ok] = ps.mask[r[ok], c[ok]]
    return out


def sk_holes(mask: np.ndarray) -> tuple[np.ndarray, int]:
    """Labels of the 8-components of the complement in the padded box; the unbounded one is set to 0."""
    comp = sk_label(np.pad(~mask, 1, constant_values=True), connectivity=2)
    outside = comp[0, 0]
    comp[comp == outside] = 0
    n = int(comp.max(initial=0))
    return comp[1:-1, 1:-1], n - (1 if outside and n >= outside else 0)


def winding_fill(chains: list[CrackChain], box: tuple[int, int, int, int]) -> np.ndarray:
    """Reference fill: winding number of each pixel centre by a ray towards +x (upward crossing counts +1)."""
    xmin, ymin, xmax, ymax = box
    wind = np.zeros((ymax - ymin + 1, xmax - xmin + 1), np.int64)
    xs = np.arange(xmin, xmax + 1)
    for ch in chains:
        for (i, j), code in zip(ch.points()[:-1].tolist(), ch.codes, strict=True):
            if code in "13":
                row = j if code == "1" else j - 1
                if ymin <= row <= ymax:
                    wind[row - ymin] += np.where(i > xs, 1 if code == "1" else -1, 0)
    return wind


def check_region(ps: PixelSet) -> Region:
    """Every property a region must have, checked against scikit-image and the definitions."""
    reg = region_of(ps)
    m = ps.mask
    # Components: skimage labels in row-major order, which is ours (row 0 is the lowest y).
    sk = sk_label(m, connectivity=1)
    assert reg.n_components == int(sk.max(initial=0))
    assert np.array_equal(reg.labels.labels, sk.astype(np.int32))
    assert reg.labels.origin == (ps.origin if not ps.is_empty() else (0, 0))
    # Holes: bounded 8-components of the complement.
    bg, n_holes = sk_holes(m)
    assert reg.n_holes == n_holes
    assert reg.euler == (euler_number(m, connectivity=1) if m.size else 0)
    # Exact inverse, and the chains alone determine the set.
    assert fill(reg) == ps
    total = 0
    seen_holes = set()
    x0, y0 = ps.origin
    for k, comp in enumerate(reg.components, start=1):
        assert comp.label == k
        rows, cols = np.nonzero(sk == k)
        assert comp.pixels == rows.size
        assert comp.bbox == (x0 + cols.min(), y0 + rows.min(), x0 + cols.max(), y0 + rows.max())
        # The outer chain starts at the lower-left corner of the lowest-leftmost pixel, going East.
        assert comp.outer.start == (x0 + cols[0], y0 + rows[0])
        assert comp.outer.codes[0] == "0"
        assert comp.outer.area2() > 0
        total += comp.outer.area2() // 2
        starts = [h.boundary.start for h in comp.holes]
        assert starts == sorted(starts, key=lambda s: (s[1], s[0]))
        inside = fill_chains(comp.outer)
        for hole in comp.holes:
            ch = hole.boundary
            assert ch.codes[0] == "1" and ch.area2() < 0
            total += ch.area2() // 2
            # The hole is the complement component on the right of its chain; check its size and box.
            c0, r0 = ch.right_pixels()[0] - (x0, y0)
            hid = bg[r0, c0]
            assert hid > 0 and hid not in seen_holes
            seen_holes.add(hid)
            hr, hc = np.nonzero(bg == hid)
            assert hole.pixels == hr.size
            assert hole.bbox == (x0 + hc.min(), y0 + hr.min(), x0 + hc.max(), y0 + hr.max())
            # Attached to the component that encloses it: inside its outer chain and 4-adjacent to it.
            hole_pts = np.stack([hc + x0, hr + y0], axis=1)
            assert member(inside, hole_pts).all()
            near = np.concatenate([hole_pts + d for d in ((1, 0), (-1, 0), (0, 1), (0, -1))])
            near = near[member(ps, near)]
            assert (sk[near[:, 1] - y0, near[:, 0] - x0] == k).any()
        for ch in (comp.outer, *(h.boundary for h in comp.holes)):
            assert ch.is_closed()
            pts = ch.points()
            assert tuple(pts[0]) == tuple(pts[-1])
            # Canonical start: the smallest (y, x) pointel of the ring.
            order = np.lexsort((pts[:, 0], pts[:, 1]))
            assert tuple(pts[order[0]]) == ch.start
            left, right = ch.left_pixels(), ch.right_pixels()
            assert member(ps, left).all() and not member(ps, right).any()
            # The object on the left is this component.
            assert (sk[left[:, 1] - y0, left[:, 0] - x0] == k).all()
    assert len(seen_holes) == n_holes
    assert total == len(ps)
    return reg


@st.composite
def random_masks(draw: st.DrawFn, max_side: int = 64) -> np.ndarray:
    h = draw(st.integers(1, max_side))
    w = draw(st.integers(1, max_side))
    rng = np.random.default_rng(draw(st.integers(0, 2**32 - 1)))
    kind = draw(st.sampled_from(["noise", "blocks"]))
    density = draw(st.sampled_from([0.05, 0.2, 0.4, 0.5, 0.6, 0.75, 0.9]))
    if kind == "noise":
        return rng.random((h, w)) < density
    # Blocky shapes with rings, islands in holes and diagonal contacts, plus some salt and pepper.
    k = draw(st.integers(1, 4))
    coarse = rng.random((-(-h // k), -(-w // k))) < density
    m = np.kron(coarse, np.ones((k, k), bool))[:h, :w]
    return m ^ (rng.random((h, w)) < draw(st.sampled_from([0.0, 0.02, 0.1])))


origins = st.tuples(st.integers(-40, 40), st.integers(-40, 40))

# ---------------------------------------------------------------------------------------------- properties


@settings(max_examples=250)
@given(random_masks(), origins)
def test_region_of_random_masks(mask: np.ndarray, origin: tuple[int, int]) -> None:
    check_region(PixelSet(mask, origin))


@settings(max_examples=300)
@given(arrays(bool, st.tuples(st.integers(1, 7), st.integers(1, 7))))
def test_region_of_small_masks(mask: np.ndarray) -> None:
    check_region(PixelSet(mask))


@settings(max_examples=60)
@given(random_masks(max_side=40), origins, st.integers(-1000, 1000), st.integers(-1000, 1000))
def test_translation_covariance(mask: np.ndarray, origin: tuple[int, int], dx: int, dy: int) -> None:
    a = PixelSet(mask, origin)
    ra, rb = region_of(a), region_of(a.translate(dx, dy))
    assert rb.n_components == ra.n_components
    for ca, cb in zip(ra.components, rb.components, strict=True):
        assert cb.outer == ca.outer.translate(dx, dy)
        assert [h.boundary for h in cb.holes] == [h.boundary.translate(dx, dy) for h in ca.holes]
        assert cb.bbox == (ca.bbox[0] + dx, ca.bbox[1] + dy, ca.bbox[2] + dx, ca.bbox[3] + dy)
        assert (cb.pixels, [h.pixels for h in cb.holes]) == (ca.pixels, [h.pixels for h in ca.holes])
    assert rb.labels == LabelMap(ra.labels.labels, (ra.labels.origin[0] + dx, ra.labels.origin[1] + dy))


@settings(max_examples=60)
@given(random_masks(max_side=32), origins, st.data())
def test_component_of_and_fill_chains(mask: np.ndarray, origin: tuple[int, int], data: st.DataObject) -> None:
    ps = PixelSet(mask, origin)
    reg = region_of(ps)
    for comp in reg.components:
        pixels = fill_chains(comp.outer, [h.boundary for h in comp.holes])
        assert len(pixels) == comp.pixels
        assert all(reg.component_of(x, y) is comp for x, y in pixels)
        # Filling one hole adds exactly that hole's pixels and whatever is nested inside it.
        if comp.holes:
            i = data.draw(st.integers(0, len(comp.holes) - 1))
            hole = comp.holes[i]
            rest = [h.boundary for j, h in enumerate(comp.holes) if j != i]
            filled = fill_chains(comp.outer, rest)
            box = hole.bbox
            inside_hole = winding_fill([hole.boundary], box) == -1
            assert filled - pixels == PixelSet(inside_hole, box[:2])
            assert pixels.issubset(filled)
    if not ps.is_empty():
        x0, y0, x1, y1 = ps.bbox  # type: ignore[misc]
        x, y = data.draw(st.integers(x0 - 1, x1 + 1)), data.draw(st.integers(y0 - 1, y1 + 1))
        c = reg.component_of(x, y)
        assert (c is None) == ((x, y) not in ps)


# ---------------------------------------------------------------------------------------------- real images


def _real_images() -> list[tuple[str, np.ndarray]]:
    out = [("horse", ~skimage.data.horse())]
    for name in ("camera", "coins", "text"):
        img = getattr(skimage.data, name)()
        t = threshold_otsu(img)
        out += [(f"{name}>otsu", img > t), (f"{name}<=otsu", img <= t)]
    return out


@pytest.mark.parametrize(("name", "image"), _real_images(), ids=[n for n, _ in _real_images()])
def test_real_images_match_skimage(name: str, image: np.ndarray) -> None:
    mask = image[::-1]  # image row 0 is the top: y = H − 1 − row
    reg = region_of(PixelSet(mask))
    assert reg.n_components == sk_label(mask, connectivity=1).max()
    assert reg.n_holes == sk_holes(mask)[1]
    assert reg.euler == euler_number(mask, connectivity=1)
    assert fill(reg) == PixelSet(mask)
    if name == "horse":  # one silhouette, with a thin enclosed slit of 6 pixels (1 × 6)
        assert (reg.n_components, reg.n_holes) == (1, 1)
        assert reg.components[0].holes[0].pixels == 6


def test_real_image_full_check() -> None:
    img = skimage.data.coins()
    check_region(PixelSet(img[::-1] > threshold_otsu(img), (-100, 7)))


# ------------------------------------------------------------------------------------------ hand-made traps


def grid(rows: str) -> PixelSet:
    """A pixel set from text art, top row first ('#' = pixel), with the bottom-left cell at (0, 0)."""
    lines = [r for r in rows.strip("\n").split("\n")]
    return PixelSet(np.array([[c == "#" for c in r] for r in lines[::-1]], bool))


def test_empty_set() -> None:
    reg = region_of(PixelSet.empty())
    assert (reg.n_components, reg.n_holes, reg.euler, reg.boundary_chains) == (0, 0, 0, ())
    assert fill(reg) == PixelSet.empty()
    assert reg.component_of(0, 0) is None


def test_single_pixel() -> None:
    reg = check_region(PixelSet.from_points([(5, -3)]))
    (c,) = reg.components
    assert c.outer == CrackChain((5, -3), "0123")
    assert (c.pixels, c.bbox, c.holes) == (1, (5, -3, 5, -3), ())


def test_checkerboard_every_pixel_is_a_component() -> None:
    m = (np.add.outer(np.arange(9), np.arange(11)) % 2) == 0
    reg = check_region(PixelSet(m))
    assert reg.n_components == int(m.sum()) and reg.n_holes == 0
    assert all(c.outer.codes == "0123" for c in reg.components)


def test_ring_has_one_hole() -> None:
    ps = grid("""
###
#.#
###
""")
    reg = check_region(ps)
    (c,) = reg.components
    assert c.outer == CrackChain((0, 0), "000111222333")
    (h,) = c.holes
    assert h == type(h)(1, (1, 1, 1, 1), CrackChain((1, 1), "1032"))
    assert reg.euler == 0


def test_nested_ring_in_hole_in_ring() -> None:
    ps = grid("""
#########
#.......#
#.#####.#
#.#...#.#
#.#.#.#.#
#.#...#.#
#.#####.#
#.......#
#########
""")
    reg = check_region(ps)
    assert (reg.n_components, reg.n_holes, reg.euler) == (3, 2, 1)
    outer, middle, centre = reg.components
    assert (len(outer.holes), len(middle.holes), len(centre.holes)) == (1, 1, 0)
    assert outer.holes[0].pixels == 7 * 7 - 5 * 5
    assert middle.holes[0].pixels == 8
    assert centre.pixels == 1 and centre.bbox == (4, 4, 4, 4)


def test_ring_closed_only_diagonally_has_no_hole() -> None:
    ps = grid("""
.#.
#.#
.#.
""")
    reg = check_region(ps)
    assert (reg.n_components, reg.n_holes, reg.euler) == (4, 0, 4)


def test_hole_touching_outer_boundary_at_a_corner() -> None:
    # The hole (centre) touches the outside diagonally at its corner: no hole in (4, 8).
    ps = grid("""
##.
#.#
###
""")
    reg = check_region(ps)
    assert (reg.n_components, reg.n_holes) == (1, 0)
    # A hole whose corner pinches the outer boundary of the same component: one ring visits the pinch twice.
    ps = grid("""
####.
#..#.
#..##
#####
""")
    reg = check_region(ps)
    assert (reg.n_components, reg.n_holes) == (1, 1)


def test_pinched_outer_boundary_visits_a_pointel_twice() -> None:
    ps = grid("""
##..
##..
..##
..##
""")
    reg = check_region(ps)
    assert reg.n_components == 2  # a diagonal contact does not connect under 4-connectivity
    ps = grid("""
##.
#.#
###
""")
    reg = check_region(ps)
    (c,) = reg.components
    pts = [tuple(p) for p in c.outer.points()[:-1].tolist()]
    assert len(pts) == len(set(pts)) + 1 and pts.count((2, 2)) == 2  # the pinch between the diagonal pixels
    assert c.holes == ()
    # Derived by hand with the (4, 8) rule: down into the notch, then out through the pinch (2, 2) again.
    assert c.outer == CrackChain((0, 0), "0001123210122333")


def test_objects_touching_the_array_border() -> None:
    m = np.ones((6, 7), bool)
    m[2:4, 2:5] = False
    m[0, 3] = False  # notch from the border: not a hole
    reg = check_region(PixelSet(m, (-3, -3)))
    assert (reg.n_components, reg.n_holes) == (1, 1)
    assert reg.components[0].holes[0].pixels == 6


# ------------------------------------------------------------------------------------------- CrackChain API


def test_crack_chain_text_and_basics() -> None:
    ch = CrackChain.from_string(" 3, -2 , 00112233 ")
    assert ch == CrackChain((3, -2), "00112233")
    assert str(ch) == "3,-2,00112233"
    assert CrackChain.from_string(str(ch)) == ch
    assert len(ch) == 8 and ch.is_closed() and ch.area2() == 8
    assert ch.points().tolist() == [
        [3, -2], [4, -2], [5, -2], [5, -1], [5, 0], [4, 0], [3, 0], [3, -1], [3, -2],
    ]  # fmt: skip
    assert ch.translate(-3, 2).start == (0, 0)
    assert not CrackChain((0, 0), "001").is_closed()
    assert not CrackChain((0, 0), "").is_closed()
    assert CrackChain((0, 0), "0321").area2() == -2


@pytest.mark.parametrize(
    ("code", "left", "right"),
    [("0", (7, 4), (7, 3)), ("1", (6, 4), (7, 4)), ("2", (6, 3), (6, 4)), ("3", (7, 3), (6, 3))],
)
def test_left_and_right_pixels_follow_the_convention(
    code: str, left: tuple[int, int], right: tuple[int, int]
) -> None:
    ch = CrackChain((7, 4), code)
    assert tuple(ch.left_pixels()[0]) == left
    assert tuple(ch.right_pixels()[0]) == right


@pytest.mark.parametrize("text", ["", "1,2", "1,2,3,4", "a,2,01", "1,2,014", "1.5,2,01"])
def test_bad_chain_text_is_a_parameter_error(text: str) -> None:
    with pytest.raises(ParameterError):
        CrackChain.from_string(text)


def test_bad_chain_values() -> None:
    with pytest.raises(ParameterError):
        CrackChain((0, 0), "0x")
    with pytest.raises(ParameterError):
        CrackChain((0.5, 0), "01")  # type: ignore[arg-type]


def test_fill_chains_rejects_chains_that_bound_no_pixel_set() -> None:
    with pytest.raises(InvalidGeometryError, match="come back"):
        fill_chains(CrackChain((0, 0), "001"))
    with pytest.raises(InvalidGeometryError, match="oriented"):
        fill_chains(CrackChain((0, 0), "0321"))  # clockwise outer
    square = CrackChain((0, 0), "000111222333")
    with pytest.raises(InvalidGeometryError, match="oriented"):
        fill_chains(square, [CrackChain((1, 1), "0123")])  # counter-clockwise hole
    with pytest.raises(InvalidGeometryError, match="oriented"):
        fill_chains(square, [CrackChain((5, 5), "1032")])  # hole outside the outer chain
    assert fill_chains(square, [CrackChain((1, 1), "1032")]) == grid("###\n#.#\n###")


def test_fill_matches_winding_number_reference() -> None:
    rng = np.random.default_rng(5)
    for _ in range(30):
        m = rng.random((12, 15)) < 0.55
        ps = PixelSet(m, (-4, 9))
        reg = region_of(ps)
        box = (-6, 7, 13, 24)
        ref = winding_fill(list(reg.boundary_chains), box)
        assert set(np.unique(ref)) <= {0, 1}
        assert PixelSet(ref == 1, box[:2]) == fill(reg) == ps


@settings(max_examples=40)
@given(random_masks(max_side=32), st.data())
def test_region_level_edits_are_discrete_edits(mask: np.ndarray, data: st.DataObject) -> None:
    ps = PixelSet(mask, (3, -8))
    reg = region_of(ps)
    if reg.n_components == 0:
        return
    sk = sk_label(ps.mask, connectivity=1)
    k = data.draw(st.integers(1, reg.n_components))
    # Deleting a component deletes exactly its pixels; the label image of the edited region follows.
    edited = Region(c for c in reg.components if c.label != k)
    expected = PixelSet(ps.mask & (sk != k), ps.origin)
    assert fill(edited) == expected
    assert edited.labels == LabelMap(np.where(sk == k, 0, sk), ps.origin)
    assert edited != reg and Region(reg.components) == reg and hash(Region(reg.components)) == hash(reg)
    for comp in edited.components:
        x, y = comp.outer.left_pixels()[0].tolist()
        assert edited.component_of(x, y) is comp
