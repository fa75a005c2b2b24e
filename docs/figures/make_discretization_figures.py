"""Draw the pictures of docs/discretization.md from the project's own discretization.

Run from the repository root::

    .venv/bin/python docs/figures/make_discretization_figures.py

It writes ``docs/img/discretization-polygon.png``, ``-segment.png``, ``-partition.png`` and ``-voxels.png``.
Every pixel shown comes from :func:`mrm.geometry.discretize.discretize` and every voxel from
:func:`mrm.voxelize`; only the drawing is done here, with Pillow's ImageDraw in 2D (drawn at 4× and scaled
down, for smooth lines) and matplotlib's mplot3d in 3D. The plane has y up, as in MR Modeler; in 3D, z is up.
"""

from __future__ import annotations

import sys
from collections.abc import Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import matplotlib
import numpy as np
from PIL import Image, ImageDraw, ImageFont
from shapely.geometry import LineString, Polygon

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT))

matplotlib.use("Agg")  # no window: the pictures go to files

import matplotlib.pyplot as plt  # noqa: E402
from mpl_toolkits.mplot3d.art3d import Line3DCollection, Poly3DCollection  # noqa: E402

import mrm  # noqa: E402
from mrm.core.grids import PixelSet, VoxelSet  # noqa: E402
from mrm.geometry.discretize import discretize  # noqa: E402

OUT = ROOT / "docs" / "img"

SS = 4  # supersampling factor
UNIT = 44  # screen pixels per plane unit in the final picture
LEFT, RIGHT, BELOW = 30, 10, 26  # room around the grid (tick labels), final picture pixels
TITLE_H = 62

# Colours (RGB). The pixel blue and the outline orange are those of ``mrm discretize -o OUT.svg``.
WHITE = (255, 255, 255)
GRID = (214, 219, 226)
CENTRE = (150, 158, 170)
TEXT = (40, 44, 52)
SUBTEXT = (96, 104, 116)
BLUE, BLUE_EDGE = (188, 214, 240), (118, 160, 206)
AMBER, AMBER_EDGE = (250, 204, 120), (214, 150, 40)
GREEN, GREEN_EDGE = (190, 226, 180), (110, 170, 100)
VIOLET, VIOLET_EDGE = (214, 192, 240), (146, 106, 196)
OUTLINE = (194, 65, 12)


def font(size: int, bold: bool = False) -> ImageFont.FreeTypeFont | ImageFont.ImageFont:
    """DejaVu Sans at ``size`` final-picture pixels (Pillow's own font where DejaVu is not installed)."""
    name = "DejaVuSans-Bold.ttf" if bold else "DejaVuSans.ttf"
    for folder in ("/usr/share/fonts/truetype/dejavu", "/usr/share/fonts/dejavu", "/Library/Fonts"):
        path = Path(folder) / name
        if path.exists():
            return ImageFont.truetype(str(path), size * SS)
    return ImageFont.load_default(size=size * SS)


@dataclass
class Panel:
    """One picture: pixel layers under geometries, over the window [x0, x1] × [y0, y1] of pixels."""

    title: str
    subtitle: str
    window: tuple[int, int, int, int]
    layers: list[tuple[PixelSet, tuple[int, int, int], tuple[int, int, int]]] = field(default_factory=list)
    shapes: list[tuple[Any, tuple[int, int, int]]] = field(default_factory=list)
    marks: list[tuple[float, float]] = field(default_factory=list)  # points to ring (ties, corners)
    labels: list[tuple[float, float, str]] = field(default_factory=list)  # text at plane points


def render(panel: Panel) -> Image.Image:
    """Draw one panel: title, pixels, grid and centres, tick labels, then the shapes on top."""
    x0, y0, x1, y1 = panel.window
    u = UNIT * SS
    left, top = LEFT * SS, TITLE_H * SS
    w = (x1 - x0 + 1) * u + left + RIGHT * SS
    h = (y1 - y0 + 1) * u + top + BELOW * SS
    img = Image.new("RGB", (w, h), WHITE)
    d = ImageDraw.Draw(img)

    def at(x: float, y: float) -> tuple[float, float]:
        """Plane point → image point (y up)."""
        return left + (x - (x0 - 0.5)) * u, top + ((y1 + 0.5) - y) * u

    def square(px: int, py: int) -> tuple[float, float, float, float]:
        ax, ay = at(px - 0.5, py + 0.5)
        bx, by = at(px + 0.5, py - 0.5)
        return ax, ay, bx, by

    def inside(px: int, py: int) -> bool:
        return x0 <= px <= x1 and y0 <= py <= y1

    # pixels
    for ps, fill, edge in panel.layers:
        for px, py in ps.points().tolist():
            if inside(px, py):
                d.rectangle(square(px, py), fill=fill, outline=edge, width=SS)
    # the grid (pixel sides) and the pixel centres
    for gx in range(x0, x1 + 2):
        d.line([at(gx - 0.5, y0 - 0.5), at(gx - 0.5, y1 + 0.5)], fill=GRID, width=SS)
    for gy in range(y0, y1 + 2):
        d.line([at(x0 - 0.5, gy - 0.5), at(x1 + 0.5, gy - 0.5)], fill=GRID, width=SS)
    for ps, _, edge in panel.layers:  # redraw the pixel borders over the grid
        for px, py in ps.points().tolist():
            if inside(px, py):
                d.rectangle(square(px, py), outline=edge, width=SS)
    r = 1.6 * SS
    for px in range(x0, x1 + 1):
        for py in range(y0, y1 + 1):
            cx, cy = at(px, py)
            d.ellipse((cx - r, cy - r, cx + r, cy + r), fill=CENTRE)
    # tick labels: x under the grid, y on its left
    small = font(11)
    for px in range(x0, x1 + 1):
        cx, cy = at(px, y0 - 0.5)
        d.text((cx, cy + 5 * SS), str(px), font=small, fill=SUBTEXT, anchor="mt")
    for py in range(y0, y1 + 1):
        cx, cy = at(x0 - 0.5, py)
        d.text((cx - 6 * SS, cy), str(py), font=small, fill=SUBTEXT, anchor="rm")
    # the Euclidean shapes on top
    for shape, colour in panel.shapes:
        parts = getattr(shape, "geoms", [shape])
        for part in parts:
            if isinstance(part, Polygon):
                for ring in (part.exterior, *part.interiors):
                    pts = [at(x, y) for x, y in ring.coords]
                    d.line(pts, fill=colour, width=3 * SS, joint="curve")
                coords = list(part.exterior.coords)[:-1]
            else:
                coords = list(part.coords)
                d.line([at(x, y) for x, y in coords], fill=colour, width=3 * SS, joint="curve")
            for x, y in coords:
                cx, cy = at(x, y)
                rr = 4.5 * SS
                d.ellipse((cx - rr, cy - rr, cx + rr, cy + rr), fill=colour)
    for x, y in panel.marks:
        cx, cy = at(x, y)
        rr = 8 * SS
        d.ellipse((cx - rr, cy - rr, cx + rr, cy + rr), outline=TEXT, width=2 * SS)
    for x, y, text in panel.labels:
        d.text(at(x, y), text, font=font(15, bold=True), fill=TEXT, anchor="mm")
    # title
    d.text((left, 8 * SS), panel.title, font=font(20, bold=True), fill=TEXT)
    d.text((left, 36 * SS), panel.subtitle, font=font(13), fill=SUBTEXT)
    return img.resize((w // SS, h // SS), Image.Resampling.LANCZOS)


def row(images: Sequence[Image.Image], gap: int = 18) -> Image.Image:
    """Panels side by side, separated by thin rules."""
    w = sum(i.width for i in images) + gap * (len(images) - 1)
    h = max(i.height for i in images)
    out = Image.new("RGB", (w, h), WHITE)
    x = 0
    for i in images:
        out.paste(i, (x, 0))
        x += i.width + gap
        if i is not images[-1]:
            ImageDraw.Draw(out).line([(x - gap // 2, 12), (x - gap // 2, h - 12)], fill=GRID, width=1)
    return out


# ---------------------------------------------------------------------------------------------- figures
def polygon_figure() -> Image.Image:
    """One triangle in the three models.

    It has a vertex on the pixel corner (−½, −½), its bottom edge along the pixel sides y = −½ and its right
    edge of slope −1 through the pixel corners (5.5, 0.5), (4.5, 1.5), … (circled).
    """
    tri = Polygon([(-0.5, -0.5), (6.5, -0.5), (1.5, 4.5)])
    window = (-2, -2, 8, 6)
    std = discretize(tri, "standard")
    sup = discretize(tri, "supercover")
    gau = discretize(tri, "gauss")
    extra = sup - std
    corners = [(6.5 - k, -0.5 + k) for k in range(1, 5)]
    return row(
        [
            render(
                Panel(
                    "standard",
                    f"{len(std)} pixels: open squares, ties go down / left",
                    window,
                    [(std, BLUE, BLUE_EDGE)],
                    shapes=[(tri, OUTLINE)],
                    marks=corners,
                )
            ),
            render(
                Panel(
                    "supercover",
                    f"{len(sup)} pixels: closed squares; {len(extra)} extra in amber",
                    window,
                    [(std, BLUE, BLUE_EDGE), (extra, AMBER, AMBER_EDGE)],
                    shapes=[(tri, OUTLINE)],
                    marks=corners,
                )
            ),
            render(
                Panel(
                    "gauss",
                    f"{len(gau)} pixels: centres inside",
                    window,
                    [(gau, BLUE, BLUE_EDGE)],
                    shapes=[(tri, OUTLINE)],
                )
            ),
        ]
    )


def segment_figure() -> Image.Image:
    """A segment of slope ½ from the corner (−½, −½) through three more corners, to (5.5, 2.5)."""
    seg = LineString([(-0.5, -0.5), (5.5, 2.5)])
    window = (-2, -2, 7, 4)
    std = discretize(seg, "standard")
    sup = discretize(seg, "supercover")
    marks = [(-0.5, -0.5), (1.5, 0.5), (3.5, 1.5), (5.5, 2.5)]
    return row(
        [
            render(
                Panel(
                    "standard",
                    f"{len(std)} pixels, 4-connected, no bubble",
                    window,
                    [(std, BLUE, BLUE_EDGE)],
                    shapes=[(seg, OUTLINE)],
                    marks=marks,
                )
            ),
            render(
                Panel(
                    "supercover",
                    f"{len(sup)} pixels: a bubble at each corner",
                    window,
                    [(std & sup, BLUE, BLUE_EDGE), (sup - std, AMBER, AMBER_EDGE)],
                    shapes=[(seg, OUTLINE)],
                    marks=marks,
                )
            ),
        ]
    )


def partition_figure() -> Image.Image:
    """The square [0, 6] × [0, 6] cut along its diagonal; every edge runs through pixel centres."""
    lower = Polygon([(0, 0), (6, 0), (6, 6)])
    upper = Polygon([(0, 0), (6, 6), (0, 6)])
    window = (-1, -1, 7, 7)
    panels = []
    for model, note in (
        ("standard", "pixels in both tiles (violet)"),
        ("gauss", "every pixel in exactly one tile"),
    ):
        a, b = discretize(lower, model), discretize(upper, model)
        both = a & b
        panels.append(
            render(
                Panel(
                    model,
                    f"{len(both)} {note}" if both.count else note,
                    window,
                    [(a - both, BLUE, BLUE_EDGE), (b - both, GREEN, GREEN_EDGE), (both, VIOLET, VIOLET_EDGE)],
                    shapes=[(lower, OUTLINE), (upper, OUTLINE)],
                    labels=[(4.5, 1.5, "A"), (1.5, 4.5, "B")],
                )
            )
        )
    return row(panels)


# ---------------------------------------------------------------------------------------------- 3D
# The camera of every 3D picture: z up, looking down 24° from the side of −y, a little from +x.
ELEV, AZIM = 24, -60


def rgb(colour: tuple[int, int, int], alpha: float = 1.0) -> tuple[float, float, float, float]:
    """A Pillow colour (0–255) as matplotlib's (0–1)."""
    return (colour[0] / 255, colour[1] / 255, colour[2] / 255, alpha)


def eye() -> np.ndarray:
    """The unit vector from the scene towards the camera (``ELEV``, ``AZIM``), to tell front from back."""
    e, a = np.radians(ELEV), np.radians(AZIM)
    return np.array([np.cos(e) * np.cos(a), np.cos(e) * np.sin(a), np.sin(e)])


def voxel_axes(fig: Any, rect: tuple[float, float, float, float], box: Sequence[int], zoom: float) -> Any:
    """A bare 3D axes over the voxels of ``box`` (x0, y0, z0, x1, y1, z1), one unit the same on every axis.

    Artists are drawn by their zorder (``computed_zorder=False``), not by mplot3d's guess of their depth,
    which fails between a large solid and small cubes: :func:`draw_voxels` orders its cubes back to front
    itself, and what is added after them is drawn over them. The projection is orthographic.
    """
    x0, y0, z0, x1, y1, z1 = box
    ax = fig.add_axes(rect, projection="3d", computed_zorder=False)
    ax.set_xlim(x0 - 0.5, x1 + 0.5)
    ax.set_ylim(y0 - 0.5, y1 + 0.5)
    ax.set_zlim(z0 - 0.5, z1 + 0.5)
    ax.set_box_aspect((x1 - x0 + 1, y1 - y0 + 1, z1 - z0 + 1), zoom=zoom)
    ax.set_axis_off()
    ax.view_init(elev=ELEV, azim=AZIM)
    ax.set_proj_type("ortho")
    return ax


Layer3D = tuple[VoxelSet, tuple[int, int, int], tuple[int, int, int]]  # voxels, fill, edge colour


def draw_voxels(ax: Any, layers: Sequence[Layer3D]) -> None:
    """Draw voxel sets as shaded unit cubes centred on their voxels (later layers win where they overlap)."""
    x0, y0, z0, x1, y1, z1 = np.array([ly[0].bbox for ly in layers]).T
    lo = np.array([x0.min(), y0.min(), z0.min()])
    shape = tuple(int(v) for v in np.array([x1.max(), y1.max(), z1.max()]) - lo + 1)
    filled = np.zeros(shape, dtype=bool)
    faces = np.empty(shape, dtype=object)
    edges = np.empty(shape, dtype=object)
    for vs, fill, edge in layers:
        for p in (vs.points() - lo).tolist():
            filled[tuple(p)] = True
            faces[tuple(p)], edges[tuple(p)] = rgb(fill), rgb(edge)
    corners = np.indices(np.array(shape) + 1).astype(float) + lo.reshape(3, 1, 1, 1) - 0.5
    cubes = ax.voxels(*corners, filled, facecolors=faces, edgecolors=edges, linewidth=0.4)
    # back to front: equal cubes of a grid, seen orthographically, paint right in the order of their centres'
    # distance to the camera
    for index, cube in cubes.items():
        cube.set_zorder(float((np.array(index) + lo) @ eye()) - 1000)


def draw_solid(ax: Any, poly: mrm.Polyhedron, colour: tuple[int, int, int] = OUTLINE) -> None:
    """Draw a polyhedron translucent: front triangles lightly filled, edges solid in front, dashed behind."""
    v, t, face = poly.vertices, poly.triangles, poly.face_of_triangle
    tri = v[t]
    front = np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0]) @ eye() > 0
    # each edge with its (one or two) triangles: seen when one faces the camera; a diagonal inside a face is
    # not an edge of the solid and is not drawn
    around: dict[tuple[int, int], list[int]] = {}
    for n, (a, b, c) in enumerate(t.tolist()):
        for u, w in ((a, b), (b, c), (c, a)):
            around.setdefault((min(u, w), max(u, w)), []).append(n)
    ahead, back = [], []
    for key, tris in around.items():
        if len({int(face[n]) for n in tris}) > 1:
            (ahead if front[tris].any() else back).append(v[list(key)])
    ax.add_collection3d(Poly3DCollection(tri[front], facecolor=rgb(colour, 0.22), edgecolor="none"))
    dashed = (0, (3, 2))
    ax.add_collection3d(Line3DCollection(back, colors=[rgb(colour, 0.8)], linewidths=1.0, linestyles=dashed))
    ax.add_collection3d(Line3DCollection(ahead, colors=[rgb(colour)], linewidths=1.8))


def octahedron(r: float) -> mrm.Polyhedron:
    """The octahedron |x| + |y| + |z| ≤ r: vertices (±r, 0, 0), (0, ±r, 0), (0, 0, ±r), eight triangles."""
    v = [[r, 0, 0], [-r, 0, 0], [0, r, 0], [0, -r, 0], [0, 0, r], [0, 0, -r]]
    t = [[0, 2, 4], [2, 1, 4], [1, 3, 4], [3, 0, 4], [2, 0, 5], [1, 2, 5], [3, 1, 5], [0, 3, 5]]
    return mrm.Polyhedron(v, t)


def titled(fig: Any, x: float, title: str, subtitle: str) -> None:
    """A panel's title and subtitle at the top of the figure, from x (figure fraction) on."""
    fig.text(x + 0.02, 0.95, title, fontsize=13, weight="bold", color=rgb(TEXT))
    fig.text(x + 0.02, 0.89, subtitle, fontsize=10, color=rgb(SUBTEXT))


def voxels_figure(path: Path) -> None:
    """The octahedron |x| + |y| + |z| ≤ 3.5 in the three models, the solid drawn over its voxels.

    Its six vertices lie on voxel faces (x = ±3.5 …), where the models differ most.
    """
    solid = octahedron(3.5)
    std, sup, gau = (mrm.voxelize(solid, m) for m in ("standard", "supercover", "gauss"))
    assert std.issubset(sup) and gau.issubset(std)
    box = (-4, -4, -4, 4, 4, 4)
    fig = plt.figure(figsize=(9.6, 3.7), dpi=100)
    for k, (model, layers, note) in enumerate(
        (
            ("standard", [(std, BLUE, BLUE_EDGE)], f"{len(std)} voxels: ties go to −x, −y, −z"),
            (
                "supercover",
                [(std, BLUE, BLUE_EDGE), (sup - std, AMBER, AMBER_EDGE)],
                f"{len(sup)} voxels, {len(sup - std)} extra in amber",
            ),
            ("gauss", [(gau, BLUE, BLUE_EDGE)], f"{len(gau)} voxels: centres inside"),
        )
    ):
        ax = voxel_axes(fig, (k / 3, 0, 1 / 3, 0.86), box, zoom=1.35)
        draw_voxels(ax, layers)
        draw_solid(ax, solid)
        titled(fig, k / 3, model, note)
    fig.savefig(path)
    plt.close(fig)


def main() -> None:
    """Write the four pictures to docs/img/."""
    OUT.mkdir(parents=True, exist_ok=True)
    for name, make in (
        ("polygon", polygon_figure),
        ("segment", segment_figure),
        ("partition", partition_figure),
    ):
        path = OUT / f"discretization-{name}.png"
        make().save(path, optimize=True)
        print(path.relative_to(ROOT))
    path = OUT / "discretization-voxels.png"
    voxels_figure(path)
    print(path.relative_to(ROOT))


if __name__ == "__main__":
    main()
