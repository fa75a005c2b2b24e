"""Draw the pictures of docs/reconstruction.md from the project's own reconstruction.

Run from the repository root::

    .venv/bin/python docs/figures/make_reconstruction_figures.py

It writes ``docs/img/reconstruction-*.png``. Every pixel, chain, segment, piece, line and vertex shown comes
from MR Modeler (:mod:`mrm.geometry.reconstruct`, :mod:`mrm.geometry.reconstruct.border`,
:mod:`mrm.geometry.dss.segmentation`, :mod:`mrm.geometry.discretize`), and every voxel and face of the 3D
picture from :func:`mrm.reconstruct`; only the drawing is done here, with Pillow's ImageDraw (drawn at 4× and
scaled down) in 2D and with matplotlib's mplot3d in 3D (the helpers of ``make_discretization_figures.py``).
The plane has y up, as in MR Modeler; in 3D, z is up.
"""

from __future__ import annotations

import sys
from pathlib import Path
from typing import Any

import numpy as np
from PIL import Image, ImageDraw, ImageFont

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT))
sys.path.insert(0, str(Path(__file__).resolve().parent))  # the 3D drawing helpers, shared with discretization

import matplotlib.pyplot as plt  # noqa: E402
from make_discretization_figures import draw_voxels, rgb, titled, voxel_axes  # noqa: E402
from mpl_toolkits.mplot3d.art3d import Poly3DCollection  # noqa: E402

import mrm  # noqa: E402
from mrm.core.grids import PixelSet, VoxelSet  # noqa: E402
from mrm.geometry.discretize import discretize  # noqa: E402
from mrm.geometry.dss.segmentation import chain_points, greedy_segmentation  # noqa: E402
from mrm.geometry.reconstruct import reconstruct_detailed  # noqa: E402
from mrm.geometry.reconstruct.border import border_paths, corridors  # noqa: E402
from mrm.geometry.reconstruct.safety_net import eroded_net  # noqa: E402
from mrm.reps.region import region_of  # noqa: E402
from mrm.reps.region_3d import region_3d_of  # noqa: E402
from mrm.reps.summary import count_vertices  # noqa: E402

OUT = ROOT / "docs" / "img"
SS = 4
WHITE = (255, 255, 255)
GRID = (214, 219, 226)
TEXT = (40, 44, 52)
SUBTEXT = (96, 104, 116)
BLUE, BLUE_EDGE = (188, 214, 240), (118, 160, 206)
PIECE, PIECE_EDGE = (226, 236, 248), (150, 178, 214)
SPLIT, SPLIT_EDGE = (250, 222, 170), (214, 150, 40)
CRACK = (40, 44, 52)
SEG = [(31, 119, 180), (44, 160, 44), (148, 103, 189), (23, 190, 207)]
LINE = (150, 150, 150)
POLY = (194, 65, 12)
SRC_COLOURS = {
    "lines": (194, 65, 12),
    "patch": (148, 103, 189),
    "splice": (44, 160, 44),
    "net": (44, 160, 44),
    "single": (31, 119, 180),
}


def font(size: int, bold: bool = False) -> Any:
    """DejaVu Sans at ``size`` final-picture pixels (Pillow's own font where DejaVu is missing)."""
    name = "DejaVuSans-Bold.ttf" if bold else "DejaVuSans.ttf"
    for folder in ("/usr/share/fonts/truetype/dejavu", "/usr/share/fonts/dejavu", "/Library/Fonts"):
        path = Path(folder) / name
        if path.exists():
            return ImageFont.truetype(str(path), size * SS)
    return ImageFont.load_default(size=size * SS)


class Canvas:
    """A supersampled picture of the plane window [x0, x1] × [y0, y1] (pixel indices), y up."""

    def __init__(self, window: tuple[int, int, int, int], unit: int, title: str, subtitle: str) -> None:
        self.x0, self.y0, self.x1, self.y1 = window
        self.u = unit * SS
        self.left = 14 * SS
        self.top = 58 * SS
        w = (self.x1 - self.x0 + 1) * self.u + 2 * self.left
        h = (self.y1 - self.y0 + 1) * self.u + self.top + 14 * SS
        self.img = Image.new("RGB", (w, h), WHITE)
        self.d = ImageDraw.Draw(self.img)
        self.d.text((self.left, 8 * SS), title, fill=TEXT, font=font(17, bold=True))
        self.d.text((self.left, 32 * SS), subtitle, fill=SUBTEXT, font=font(13))

    def xy(self, x: float, y: float) -> tuple[float, float]:
        """Picture coordinates of the plane point (x, y)."""
        return (self.left + (x - self.x0 + 0.5) * self.u, self.top + (self.y1 - y + 0.5) * self.u)

    def pixels(
        self, ps: PixelSet, fill: tuple[int, int, int], edge: tuple[int, int, int] | None = None
    ) -> None:
        """Fill the squares of a pixel set."""
        for x, y in ps.points().tolist():
            self.rect(x - 0.5, x + 0.5, y - 0.5, y + 0.5, fill, edge)

    def rect(
        self, x0: float, x1: float, y0: float, y1: float, fill: Any, edge: Any = None, width: int = 1
    ) -> None:
        """Draw the rectangle [x0, x1] × [y0, y1] of the plane."""
        a = self.xy(x0, y1)
        b = self.xy(x1, y0)
        self.d.rectangle([a, b], fill=fill, outline=edge, width=width * SS if edge else 0)

    def grid(self) -> None:
        """Draw the pixel sides."""
        for x in range(self.x0, self.x1 + 2):
            self.d.line(
                [self.xy(x - 0.5, self.y0 - 0.5), self.xy(x - 0.5, self.y1 + 0.5)], fill=GRID, width=SS
            )
        for y in range(self.y0, self.y1 + 2):
            self.d.line(
                [self.xy(self.x0 - 0.5, y - 0.5), self.xy(self.x1 + 0.5, y - 0.5)], fill=GRID, width=SS
            )

    def polyline(self, pts: Any, colour: Any, width: float, closed: bool = False) -> None:
        """Draw a polyline through plane points."""
        p = [self.xy(float(x), float(y)) for x, y in pts]
        if closed:
            p.append(p[0])
        self.d.line(p, fill=colour, width=max(1, int(width * SS)), joint="curve")

    def dot(self, x: float, y: float, r: float, colour: Any) -> None:
        """Draw a dot of radius r (final-picture pixels) at a plane point."""
        cx, cy = self.xy(x, y)
        self.d.ellipse([cx - r * SS, cy - r * SS, cx + r * SS, cy + r * SS], fill=colour)

    def line_through(self, px: float, py: float, dx: float, dy: float, colour: Any, width: float) -> None:
        """Draw the line through (px, py) with direction (dx, dy), clipped to the window."""
        # clip the infinite line to the window
        a, b = -1e9, 1e9
        for o, d, lo, hi in ((px, dx, self.x0 - 0.5, self.x1 + 0.5), (py, dy, self.y0 - 0.5, self.y1 + 0.5)):
            if abs(d) > 1e-12:
                t0, t1 = sorted(((lo - o) / d, (hi - o) / d))
                a, b = max(a, t0), min(b, t1)
        if b <= a:
            return
        self.polyline([(px + a * dx, py + a * dy), (px + b * dx, py + b * dy)], colour, width)

    def save(self, name: str) -> None:
        """Scale down and write ``docs/img/NAME``."""
        w, h = self.img.size
        self.img.resize((w // SS, h // SS), Image.LANCZOS).save(OUT / name, optimize=True)


def from_rows(rows: list[str], origin: tuple[int, int] = (0, 0)) -> PixelSet:
    """A pixel set drawn as text, top row first ('#' = in the set)."""
    return PixelSet(np.array([[c == "#" for c in r] for r in rows[::-1]], dtype=bool), origin)


SHAPE = from_rows(
    [
        "..............................",
        "..........########............",
        ".......#############..........",
        ".....#################........",
        "....###################.......",
        "...#########....#######.......",
        "...########......#######......",
        "..#########......#######......",
        "..##########....########......",
        "..#######################.....",
        "...######################.....",
        "...#####################......",
        "....###################.......",
        ".....################.........",
        "........##########............",
        "..........###.................",
        "..........#...................",
        "..........#...................",
        "..........######..............",
        "..............................",
    ],
    (0, 0),
)


def crack_polyline(chain: Any) -> np.ndarray:
    """The pointels of a crack chain in plane coordinates."""
    return chain.points().astype(float) - 0.5


def figure_pipeline() -> None:
    """The four steps on one shape: segments, corridor, lines and polygon, check."""
    ps = SHAPE
    x0, y0, x1, y1 = ps.bbox
    window = (x0 - 1, y0 - 1, x1 + 1, y1 + 1)
    unit = 26
    region = region_of(ps)
    chains = region.boundary_chains
    d = reconstruct_detailed(ps, "standard")
    greedy = sum(len(greedy_segmentation(chain_points(c.start, c.codes), closed=True)) for c in chains)

    # 1. pixels, crack boundary and its greedy digital straight segments
    c = Canvas(
        window,
        unit,
        "1. The crack boundary and its digital straight segments",
        f"{len(ps)} pixels, {len(chains)} crack rings, {greedy} greedy standard DSS (coloured by segment)",
    )
    c.pixels(ps, BLUE, BLUE_EDGE)
    c.grid()
    for ch in chains:
        pts = crack_polyline(ch)
        segs = greedy_segmentation(chain_points(ch.start, ch.codes), closed=True)
        for k, s in enumerate(segs):
            idx = [i % (len(pts) - 1) for i in range(s.first, s.last + 1)]
            c.polyline(pts[idx], SEG[k % len(SEG)], 3.5)
    c.save("reconstruction-segments.png")

    # 2. border path and corridor: full pieces, split pieces of pixels visited twice, gates
    cors = corridors(chains, "standard")
    paths = border_paths(chains)
    c = Canvas(
        window,
        unit,
        "2. Border path and corridor",
        "pieces: open squares (blue), outer parts of pixels visited twice (amber); gates: dark",
    )
    c.grid()
    for cor in cors:
        for p in cor.pieces.tolist():
            split = (p[1] - p[0]) < 1 or (p[3] - p[2]) < 1
            c.rect(p[0], p[1], p[2], p[3], SPLIT if split else PIECE, SPLIT_EDGE if split else PIECE_EDGE)
        for a, b in zip(cor.gate_left.tolist(), cor.gate_right.tolist(), strict=True):
            c.polyline([a, b], (40, 44, 52), 2.5)
    for path in paths:
        c.polyline(path.pixels.astype(float), (31, 119, 180), 1.5, closed=True)
    c.save("reconstruction-corridor.png")

    # 3. chosen lines and the polygon
    c = Canvas(
        window,
        unit,
        "3. Chosen lines and R(A)",
        f"{d.n_vertices} vertices for {greedy} greedy segments; grey: the lines used; violet: a patch",
    )
    c.pixels(ps, BLUE, BLUE_EDGE)
    c.grid()
    for r in d.rings:
        for w in sorted({int(v) for v in r.edge_window.tolist() if v >= 0}):
            px, py, dx, dy = r.lines[w].tolist()
            c.line_through(px, py, dx, dy, LINE, 1.0)
        c.polyline(r.vertices, POLY, 3.0, closed=True)
        for (x, y), s in zip(r.vertices.tolist(), r.sources, strict=True):
            c.dot(x, y, 4.0, SRC_COLOURS[s])
    c.save("reconstruction-polygon.png")

    # 4. the check: D(R(A)) = A, and the safety net for comparison
    geom = d.geometry
    back = discretize(geom, "standard")
    net = eroded_net(ps)
    c = Canvas(
        window,
        unit,
        "4. D(R(A)) = A exactly; the safety net R0 for comparison",
        f"R(A): {count_vertices(geom)} vertices, D(R(A)) = A: {back == ps}; "
        f"R0 (green): {count_vertices(net)} vertices",
    )
    c.pixels(back, BLUE, BLUE_EDGE)
    c.grid()
    for poly in getattr(net, "geoms", [net]):
        for ring in (poly.exterior, *poly.interiors):
            c.polyline(np.asarray(ring.coords), (44, 160, 44), 1.6)
    for poly in getattr(geom, "geoms", [geom]):
        for ring in (poly.exterior, *poly.interiors):
            c.polyline(np.asarray(ring.coords), POLY, 3.0)
    c.save("reconstruction-check.png")


def figure_preimage() -> None:
    """One window, its gates and a fan of lines of its preimage."""
    # One window of a digital straight path: its gates and a fan of lines crossing them all, in order.
    ps = from_rows(["..........#####", ".....######....", "######.........", "###############"])
    chains = region_of(ps).boundary_chains
    cor = corridors(chains, "standard")[0]
    d = reconstruct_detailed(ps, "standard")
    r = d.rings[0]
    n = len(cor)

    def turns(i: int) -> int:
        """Number of crossing directions among the gates of the window from piece i."""
        dirs = {int(cor.gate_dir[k % n]) for k in range(i + 1, i + int(r.reach[i]) + 1)}
        return len(dirs)

    # the longest window that climbs the staircase (gates crossed in two directions)
    i = max(range(n), key=lambda k: (turns(k), int(r.reach[k])))
    j = i + int(r.reach[i])
    gates = [((k % n), cor.gate_left[k % n], cor.gate_right[k % n]) for k in range(i + 1, j + 1)]
    x0, y0, x1, y1 = ps.bbox
    c = Canvas(
        (x0 - 1, y0 - 1, x1 + 1, y1 + 1),
        40,
        "The preimage of a window",
        f"gates {i + 1}…{j} (black): the lines crossing them all in order (light) and the one chosen (red)",
    )
    c.pixels(ps, BLUE, BLUE_EDGE)
    c.grid()
    for p in cor.pieces[[k % n for k in range(i, j + 1)]].tolist():
        c.rect(p[0], p[1], p[2], p[3], None, PIECE_EDGE, 2)
    rng = np.random.default_rng(1)
    first, last = gates[0], gates[-1]
    for _ in range(4000):
        a = first[1] + rng.random() * (first[2] - first[1])
        b = last[1] + rng.random() * (last[2] - last[1])
        dx, dy = b - a
        ok = True
        for _k, gl, gr in gates:
            # crossing parameter of the line a + t (b - a) with the gate's supporting line, inside the gate
            if gl[0] == gr[0]:
                if dx == 0:
                    ok = False
                    break
                t = (gl[0] - a[0]) / dx
                y = a[1] + t * dy
                ok = min(gl[1], gr[1]) < y < max(gl[1], gr[1])
            else:
                if dy == 0:
                    ok = False
                    break
                t = (gl[1] - a[1]) / dy
                x = a[0] + t * dx
                ok = min(gl[0], gr[0]) < x < max(gl[0], gr[0])
            if not ok:
                break
        if ok and rng.random() < 0.06:
            c.line_through(a[0], a[1], dx, dy, (246, 178, 150), 0.8)
    for _k, gl, gr in gates:
        c.polyline([gl, gr], (20, 20, 20), 3.0)
    px, py, dx, dy = r.lines[i].tolist()
    c.line_through(px, py, dx, dy, POLY, 2.5)
    c.save("reconstruction-preimage.png")


def figure_models() -> None:
    """The same shape under the cover models and under gauss."""
    ps = from_rows(
        [
            ".########.",
            "##########",
            "###....###",
            "##......##",
            "###....###",
            "#########.",
            "....#.....",
            "....####..",
        ]
    )
    x0, y0, x1, y1 = ps.bbox
    for model, label in (("standard", "cover models (standard, supercover)"), ("gauss", "gauss")):
        d = reconstruct_detailed(ps, model)
        cors = corridors(region_of(ps).boundary_chains, model)
        c = Canvas(
            (x0 - 1, y0 - 1, x1 + 1, y1 + 1),
            40,
            f"Corridor and R(A), {label}",
            f"{d.n_vertices} vertices; dual squares between the centres; R may cross pixel sides"
            if model == "gauss"
            else f"{d.n_vertices} vertices; every pixel of A crossed or inside, no outside centre inside",
        )
        if model == "gauss":
            c.pixels(ps, (236, 240, 246))
        c.grid()
        for cor in cors:
            for p in cor.pieces.tolist():
                split = (p[1] - p[0]) < 1 or (p[3] - p[2]) < 1
                c.rect(p[0], p[1], p[2], p[3], SPLIT if split else PIECE, SPLIT_EDGE if split else PIECE_EDGE)
        for x, y in ps.points().tolist():
            c.dot(x, y, 2.5, (90, 110, 140))
        if model == "gauss":
            # the outside centres the boundary keeps out, as rings
            inside = set(map(tuple, ps.points().tolist()))
            for x in range(x0 - 1, x1 + 2):
                for y in range(y0 - 1, y1 + 2):
                    if (x, y) not in inside:
                        c.dot(x, y, 2.5, (90, 110, 140))
                        c.dot(x, y, 1.4, WHITE)
        for r in d.rings:
            c.polyline(r.vertices, POLY, 3.0, closed=True)
            for x, y in r.vertices.tolist():
                c.dot(x, y, 3.5, POLY)
        c.save(f"reconstruction-{model}.png")


def figure_gauss_disk() -> None:
    """A digitized disk under gauss: the staircase V(A) (GDAL's polygonize) against R(A)."""
    r = 9.4
    yy, xx = np.mgrid[-11:12, -11:12]
    ps = PixelSet((xx - 0.3) ** 2 + (yy - 0.2) ** 2 <= r * r, (-11, -11))
    d = reconstruct_detailed(ps, "gauss")
    stair = sum(
        int(np.count_nonzero(ch.code_array() != np.roll(ch.code_array(), 1)))
        for ch in region_of(ps).boundary_chains
    )
    x0, y0, x1, y1 = ps.bbox
    c = Canvas(
        (x0 - 1, y0 - 1, x1 + 1, y1 + 1),
        22,
        "gauss: R(A) against the staircase",
        f"staircase V(A) {stair} vertices (grey); R(A) {d.n_vertices} vertices; D_gauss(R(A)) = A",
    )
    c.pixels(ps, BLUE)
    c.grid()
    for ch in region_of(ps).boundary_chains:
        c.polyline(crack_polyline(ch), (120, 120, 120), 1.5, closed=True)
    for x, y in ps.points().tolist():
        c.dot(x, y, 1.6, (60, 80, 110))
    for ring in d.rings:
        c.polyline(ring.vertices, POLY, 2.6, closed=True)
        for x, y in ring.vertices.tolist():
            c.dot(x, y, 3.2, POLY)
    assert discretize(d.geometry, "gauss") == ps
    c.save("reconstruction-gauss-disk.png")


# Face colours of the 3D picture; neighbouring faces never share one (see ``face_colours``).
FACE_COLOURS = [
    (31, 119, 180),
    (255, 127, 14),
    (44, 160, 44),
    (214, 39, 40),
    (148, 103, 189),
    (23, 190, 207),
    (188, 189, 34),
    (227, 119, 194),
]
LIGHT = np.array([0.3, -0.6, 0.75]) / np.linalg.norm(
    [0.3, -0.6, 0.75]
)  # from the front, above, a little right


def face_colours(poly: mrm.Polyhedron) -> list[tuple[int, int, int]]:
    """One colour per face, greedily chosen so that two faces sharing an edge differ."""
    face = poly.face_of_triangle.tolist()
    owners: dict[tuple[int, int], set[int]] = {}
    for f, (a, b, c) in zip(face, poly.triangles.tolist(), strict=True):
        for u, w in ((a, b), (b, c), (c, a)):
            owners.setdefault((min(u, w), max(u, w)), set()).add(f)
    neighbours: dict[int, set[int]] = {f: set() for f in range(poly.n_faces)}
    for fs in owners.values():
        for f in fs:
            neighbours[f] |= fs - {f}
    chosen: list[int] = []
    for f in range(poly.n_faces):
        taken = {chosen[g] for g in neighbours[f] if g < f}
        chosen.append(next(k for k in range(len(FACE_COLOURS)) if k not in taken))
    return [FACE_COLOURS[k] for k in chosen]


def split_small(tri: np.ndarray, size: float = 0.5) -> list[np.ndarray]:
    """A triangle cut into quarters until no side is longer than ``size``.

    mplot3d paints polygons back to front by their mean depth, which goes wrong for long thin triangles next
    to small ones (the strips of a face); small pieces of nearly equal size paint in the right order.
    """
    out, todo = [], [np.asarray(tri, dtype=float)]
    while todo:
        t = todo.pop()
        if max(np.linalg.norm(t[i] - t[i - 1]) for i in range(3)) <= size:
            out.append(t)
            continue
        a, b, c = t
        ab, bc, ca = (a + b) / 2, (b + c) / 2, (c + a) / 2
        todo += [np.array(q) for q in ((a, ab, ca), (ab, b, bc), (ca, bc, c), (ab, bc, ca))]
    return out


def figure_3d() -> None:
    """A voxel set with a tunnel and a voxel meeting it along an edge, next to its safety net."""
    ring = [
        (x, y, z) for x in range(4) for y in range(4) for z in range(2) if not (1 <= x <= 2 and 1 <= y <= 2)
    ]
    vs = VoxelSet.from_points([*ring, (4, 1, 2)])  # (4, 1, 2) meets (3, 1, 1) along an edge only
    reg = region_3d_of(vs.mask, vs.origin)
    for model in ("standard", "supercover", "gauss"):
        assert mrm.voxelize(mrm.reconstruct(vs, model), model) == vs
    poly = safety_net_polyhedron(vs)
    pieces, fills = shaded_pieces(poly)
    fig = plt.figure(figsize=(8.4, 3.6), dpi=100)
    box = (*vs.bbox[:3], *vs.bbox[3:])
    ax = voxel_axes(fig, (0, 0.0, 0.5, 0.9), box, zoom=1.2)
    draw_voxels(ax, [(vs, BLUE, BLUE_EDGE)])
    titled(
        fig,
        0,
        f"A: {len(vs)} voxels",
        f"{reg.n_components} components, {reg.n_tunnels} tunnel, {reg.n_cavities} cavities",
    )
    ax = voxel_axes(fig, (0.5, 0.0, 0.5, 0.9), box, zoom=1.2)
    # edges in the fill colour close the hairline gaps between the pieces
    ax.add_collection3d(Poly3DCollection(pieces, facecolors=fills, edgecolors=fills, linewidths=0.6))
    titled(
        fig,
        0.5,
        "the safety net: V(A) eroded by ¼",
        f"{poly.n_faces} faces, {poly.n_shells} shells; D = A in the three models",
    )
    fig.savefig(OUT / "reconstruction-3d.png")
    plt.close(fig)


def safety_net_polyhedron(vs: VoxelSet) -> mrm.Polyhedron:
    """The safety net of a voxel set: V(A) eroded by ¼, where R starts."""
    from mrm.geometry.reconstruct.safety_net_3d import safety_net_3d

    net = safety_net_3d(vs.mask, vs.origin)
    return mrm.Polyhedron(net.vertices, net.triangles)


def shaded_pieces(poly: mrm.Polyhedron, size: float = 0.5) -> tuple[list[np.ndarray], list[str]]:
    """The triangles of a polyhedron cut small for mplot3d, each shaded by its face's colour."""
    colours = face_colours(poly)
    pieces, fills = [], []
    for t, f in zip(poly.triangles.tolist(), poly.face_of_triangle.tolist(), strict=True):
        tri = poly.vertices[t]
        n = np.cross(tri[1] - tri[0], tri[2] - tri[0])
        shade = 0.62 + 0.38 * max(0.0, float(n @ LIGHT / np.linalg.norm(n)))
        fill = rgb(tuple(round(shade * c) for c in colours[f]))
        for piece in split_small(tri, size):
            pieces.append(piece)
            fills.append(fill)
    return pieces, fills


def figure_compact_3d() -> None:
    """A digital ball: its safety net, R under gauss and under the covers; then a digital octahedron's R."""
    r = 7
    g = np.arange(-r - 1, r + 2)
    z, y, x = np.meshgrid(g, g, g, indexing="ij")
    vs = VoxelSet((x - 0.3) ** 2 + (y - 0.1) ** 2 + (z - 0.2) ** 2 <= r * r, (-r - 1,) * 3)
    shown = [("the safety net (V(A) eroded by ¼)", safety_net_polyhedron(vs))]
    for model in ("gauss", "standard"):
        poly = mrm.reconstruct(vs, model)
        assert mrm.voxelize(poly, model) == vs
        name = "gauss" if model == "gauss" else "the covers"
        shown.append((f"R(A) under {name}", poly))
    octahedron = VoxelSet(abs(x) + abs(y) + abs(z) <= r, (-r - 1,) * 3)
    poly = mrm.reconstruct(octahedron, "gauss")
    assert mrm.voxelize(poly, "gauss") == octahedron
    shown.append(("octahedron r = 7, gauss", poly))
    fig = plt.figure(figsize=(15.2, 3.9), dpi=100)
    box = (-r, -r, -r, r, r, r)
    for col, (title, poly) in enumerate(shown):
        pieces, fills = shaded_pieces(poly)
        ax = voxel_axes(fig, (col / 4, 0.0, 1 / 4, 0.88), box, zoom=1.25)
        ax.add_collection3d(Poly3DCollection(pieces, facecolors=fills, edgecolors=fills, linewidths=0.4))
        sizes = f"{poly.n_faces} faces, {poly.n_triangles} triangles, {poly.n_vertices} vertices"
        titled(fig, col / 4, title, sizes)
    fig.savefig(OUT / "reconstruction-3d-compact.png")
    plt.close(fig)


def figure_convex_3d() -> None:
    """R under gauss of three digitally convex sets: their convex hulls, grown (ADR 0068)."""
    from mrm.geometry.reconstruct.convex_3d import convex_reconstruction

    def grid(r: int) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        g = np.arange(-r - 1, r + 2)
        z, y, x = np.meshgrid(g, g, g, indexing="ij")
        return x, y, z

    x, y, z = grid(9)
    ball = VoxelSet((x - 0.3) ** 2 + (y - 0.1) ** 2 + (z - 0.2) ** 2 <= 81, (-10,) * 3)
    rot = np.array([[0.8, -0.6, 0.0], [0.36, 0.48, -0.8], [0.48, 0.64, 0.6]])  # a rotation, exact rationals
    xe, ye, ze = grid(12)
    d = np.stack([xe, ye, ze], axis=-1) @ rot.T
    ellipsoid = VoxelSet(
        (d[..., 0] / 12) ** 2 + (d[..., 1] / 7) ** 2 + (d[..., 2] / 4.5) ** 2 <= 1, (-13,) * 3
    )
    xo, yo, zo = grid(60)
    octahedron = VoxelSet(abs(xo) + abs(yo) + abs(zo) <= 60, (-61,) * 3)
    shown = [
        ("ball r = 9", ball, 9),
        ("a turned ellipsoid", ellipsoid, 9),
        ("octahedron r = 60", octahedron, 60),
    ]
    fig = plt.figure(figsize=(12.0, 4.1), dpi=100)
    for col, (title, vs, r) in enumerate(shown):
        found = convex_reconstruction(vs)
        assert found is not None
        poly = found.polyhedron
        assert mrm.voxelize(poly, "gauss") == vs
        pieces, fills = shaded_pieces(poly, size=0.5 * r / 7)
        ax = voxel_axes(fig, (col / 3, 0.0, 1 / 3, 0.86), (-r, -r, -r, r, r, r), zoom=1.25)
        ax.add_collection3d(Poly3DCollection(pieces, facecolors=fills, edgecolors=fills, linewidths=0.4))
        sizes = f"{len(vs):,} voxels: {poly.n_faces} faces, {poly.n_vertices} vertices"
        titled(fig, col / 3, f"{title}, its grown hull", sizes)
    fig.savefig(OUT / "reconstruction-3d-convex.png")
    plt.close(fig)


def section(poly: mrm.Polyhedron, z: float) -> list[np.ndarray]:
    """The segments where the plane at height z cuts the triangles (z off every vertex)."""
    out = []
    for t in poly.triangles:
        p = poly.vertices[t]
        d = p[:, 2] - z
        ends = []
        for i in range(3):
            a, b = p[i], p[(i + 1) % 3]
            da, db = d[i], d[(i + 1) % 3]
            if (da < 0) != (db < 0):
                ends.append((a + (b - a) * (da / (da - db)))[:2])
        if len(ends) == 2:
            out.append(np.array(ends))
    return out


def tip_section(fig: Any, rect: tuple[float, float, float, float], vs: VoxelSet, poly: Any, box: Any) -> None:
    """R cut by the plane z = 0.01 over the squares of the voxels in the layer z = 0 (filled: in A)."""
    ax = fig.add_axes(rect)
    ax.set_aspect("equal")
    ax.set_axis_off()
    layer = {(int(p[0]), int(p[1])) for p in vs.points() if p[2] == 0}
    for i in range(box[0], box[3] + 2):
        for j in range(box[1], box[4] + 1):
            fill = "#f3d9a6" if (i, j) in layer else "#ffffff"
            ax.add_patch(plt.Rectangle((i - 0.5, j - 0.5), 1, 1, facecolor=fill, edgecolor="#b8b8b8"))
    for seg in section(poly, 0.01):
        ax.plot(seg[:, 0], seg[:, 1], color="#1f5fa8", linewidth=2.2)
    ax.set_xlim(box[0] - 0.6, box[3] + 1.6)
    ax.set_ylim(box[1] - 0.6, box[4] + 0.6)


def figure_spiked_3d() -> None:
    """R under the covers of lattice polytopes: conv(A)'s facets moved in, with spikes (ADR 0069)."""
    from mrm.geometry.reconstruct.convex_3d import convex_reconstruction

    r = 8
    g = np.arange(-r, r + 1)
    z, y, x = np.meshgrid(g, g, g, indexing="ij")
    octahedron = VoxelSet(abs(x) + abs(y) + abs(z) <= r, (-r,) * 3)
    pts = octahedron.points()
    lopsided = VoxelSet.from_points(
        pts[(pts[:, 0] <= 5) & (pts[:, 1] + pts[:, 2] <= 6) & (abs(pts).sum(1) <= 7)]
    )
    fig = plt.figure(figsize=(12.0, 4.1), dpi=100)
    shown = [
        ("octahedron r = 8, supercover", octahedron, "supercover", (-r, -r, -r, r, r, r), 1.25),
        ("its tip, cut at z = 0", octahedron, "supercover", (4, -2, -2, 8, 2, 2), 1.0),
        ("a lopsided polytope, standard", lopsided, "standard", (-7, -7, -7, 7, 7, 7), 1.25),
    ]
    for col, (title, vs, model, box, zoom) in enumerate(shown):
        found = convex_reconstruction(vs, model)
        assert found is not None
        poly = found.polyhedron
        assert mrm.voxelize(poly, model) == vs and mrm.voxelize(poly, "supercover") == vs
        sizes = f"{len(vs):,} voxels: {poly.n_faces} faces, {poly.n_vertices} vertices"
        titled(fig, col / 3, title, sizes)
        if col == 1:  # the section z = 0.01 near the tip, over the voxels' squares in that layer
            tip_section(fig, (col / 3 + 0.03, 0.05, 1 / 3 - 0.06, 0.78), vs, poly, box)
            continue
        pieces, fills = shaded_pieces(poly, size=0.5 * r / 7)
        ax = voxel_axes(fig, (col / 3, 0.0, 1 / 3, 0.86), box, zoom=zoom)
        ax.add_collection3d(Poly3DCollection(pieces, facecolors=fills, edgecolors=fills, linewidths=0.4))
    fig.savefig(OUT / "reconstruction-3d-spiked.png")
    plt.close(fig)


def figure_snapped_3d() -> None:
    """R under the covers of a ball: its core, snapped inward, with a spike at each tip (ADR 0070)."""
    from mrm.geometry.reconstruct.convex_3d import convex_reconstruction

    r = 12
    g = np.arange(-r - 1, r + 2)
    z, y, x = np.meshgrid(g, g, g, indexing="ij")
    ball = VoxelSet(x * x + y * y + z * z <= r * r, (-r - 1,) * 3)
    found = convex_reconstruction(ball, "supercover")
    assert found is not None and found.facets > 64
    poly = found.polyhedron
    assert mrm.voxelize(poly, "supercover") == ball
    fig = plt.figure(figsize=(8.4, 4.1), dpi=100)
    sizes = f"{len(ball):,} voxels: {poly.n_faces} faces, {poly.n_triangles} triangles"
    titled(fig, 0.0, "ball r = 12, supercover", sizes)
    pieces, fills = shaded_pieces(poly, size=0.5 * r / 7)
    ax = voxel_axes(fig, (0.0, 0.0, 0.5, 0.86), (-r, -r, -r, r, r, r), zoom=1.25)
    ax.add_collection3d(Poly3DCollection(pieces, facecolors=fills, edgecolors=fills, linewidths=0.4))
    box = (r - 4, -2, 0, r, 2, 0)
    titled(fig, 0.5, "its tip, cut at z = 0", "filled squares: the voxels of A in that layer")
    tip_section(fig, (0.53, 0.05, 0.44, 0.78), ball, poly, box)
    fig.savefig(OUT / "reconstruction-3d-snapped.png")
    plt.close(fig)


def surfel_square(p: np.ndarray, e: np.ndarray) -> np.ndarray:
    """The unit square between voxel p and its neighbour p + e, as 4 corners."""
    c = p + e / 2
    u, v = [np.eye(3)[k] for k in range(3) if e[k] == 0]
    return np.array([c - u / 2 - v / 2, c + u / 2 - v / 2, c + u / 2 + v / 2, c - u / 2 + v / 2])


def figure_plane_segments_3d() -> None:
    """The digital plane segments of an octahedron and of a ball, one colour per segment."""
    from mrm.geometry.topology.surfels import DIRS
    from mrm.reps.analytical_3d import analytical_3d_of

    fig = plt.figure(figsize=(8.4, 3.8), dpi=100)
    for col, (name, r) in enumerate((("octahedron", 6), ("ball", 9))):
        g = np.arange(-r - 1, r + 2)
        z, y, x = np.meshgrid(g, g, g, indexing="ij")
        mask = (abs(x) + abs(y) + abs(z) <= r) if name == "octahedron" else (x * x + y * y + z * z <= r * r)
        reg = region_3d_of(mask, (-r - 1,) * 3)
        an = analytical_3d_of(reg)
        seg = an.segmentation
        # neighbouring segments get different colours (greedy over the surfel edges)
        nb = np.concatenate(
            [
                s.neighbours + k
                for s, k in zip(reg.surfaces, np.cumsum([0] + [len(s) for s in reg.surfaces]), strict=False)
            ]
        )
        touching: dict[int, set[int]] = {k: set() for k in range(len(an))}
        for i, row in enumerate(nb):
            for j in row:
                a, b = int(seg.segment_of[i]), int(seg.segment_of[j])
                if a != b:
                    touching[a].add(b)
        chosen: list[int] = []
        for k in range(len(an)):
            taken = {chosen[g2] for g2 in touching[k] if g2 < k}
            chosen.append(next(c for c in range(len(FACE_COLOURS)) if c not in taken))
        squares, fills = [], []
        for i in range(len(seg.direction)):
            e = DIRS[seg.direction[i]].astype(float)
            shade = 0.62 + 0.38 * max(0.0, float(e @ LIGHT / np.linalg.norm(LIGHT)))
            squares.append(surfel_square(seg.voxel[i].astype(float), e))
            fills.append(rgb(tuple(round(shade * c) for c in FACE_COLOURS[chosen[int(seg.segment_of[i])]])))
        box = (-r, -r, -r, r, r, r)
        ax = voxel_axes(fig, (0.5 * col, 0.0, 0.5, 0.9), box, zoom=1.25)
        ax.add_collection3d(Poly3DCollection(squares, facecolors=fills, edgecolors=fills, linewidths=0.4))
        what = "|x| + |y| + |z|" if name == "octahedron" else "x² + y² + z²"
        bound = r if name == "octahedron" else r * r
        titled(
            fig,
            0.5 * col,
            f"the digital {name} {what} ≤ {bound}",
            f"{len(seg.direction)} surfels, {len(an)} digital plane segments",
        )
    fig.savefig(OUT / "plane-segments-3d.png")
    plt.close(fig)


def main() -> None:
    """Draw every picture."""
    OUT.mkdir(parents=True, exist_ok=True)
    figure_pipeline()
    figure_preimage()
    figure_models()
    figure_gauss_disk()
    figure_3d()
    figure_compact_3d()
    figure_convex_3d()
    figure_spiked_3d()
    figure_snapped_3d()
    figure_plane_segments_3d()


if __name__ == "__main__":
    main()
