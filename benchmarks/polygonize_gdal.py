"""``mrm polygonize`` of a classified GeoTIFF against GDAL's polygonize (issue 31 item 2).

The raster: smoothed noise (three box blurs, about a Gaussian of σ ≈ ``--blur`` × 0.6 pixels) quantized into
``--classes`` classes of equal area, ``--size``² pixels, UTM 33N with 10 m pixels, uint8, tiled.

Compared, each ``--runs`` times (the median is printed):

* **mrm**: ``mrm polygonize land.tif -o mrm.gpkg`` — the whole process (start-up, reading, polygonizing,
  writing the GeoPackage), kernels warm;
* **GDAL**: ``gdal_polygonize.py land.tif -f GPKG gdal.gpkg`` when it is installed, else the same work in
  one Python process: ``rasterio.features.shapes`` (which is GDALPolygonize) on the band, written to a
  GeoPackage with pyogrio.

Then both layers are read back and burnt with ``rasterio.features.rasterize`` (GDAL's centre rule) on the
raster's grid, and the pixels whose burnt class differs from the raster's are counted; mrm's polygons are
also checked with mrm's exact discretization D_gauss, polygon by polygon. Vertices are counted the same way
for both (coordinates minus each ring's closing one).

Run: ``python benchmarks/polygonize_gdal.py [--size 4096] [--classes 8] [--runs 3]``.
"""

from __future__ import annotations

import argparse
import json
import shutil
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np


def classified(size: int, classes: int, blur: int, seed: int) -> np.ndarray:
    """Smoothed noise quantized into ``classes`` classes of equal area (uint8, 1..classes)."""
    rng = np.random.default_rng(seed)
    a = rng.random((size, size), dtype=np.float32)
    for _ in range(3):  # three box blurs along each axis: close to a Gaussian
        for axis in (0, 1):
            c = np.cumsum(np.pad(a, [(blur, blur) if ax == axis else (0, 0) for ax in (0, 1)], mode="wrap"),
                          axis=axis, dtype=np.float64)  # fmt: skip
            lo = np.take(c, np.arange(0, size), axis=axis)
            hi = np.take(c, np.arange(2 * blur, 2 * blur + size), axis=axis)
            a = ((hi - lo) / (2 * blur)).astype(np.float32)
    edges = np.quantile(a, np.linspace(0, 1, classes + 1)[1:-1])
    return (np.searchsorted(edges, a) + 1).astype(np.uint8)


def write_tif(path: Path, cls: np.ndarray) -> tuple:
    import rasterio
    from rasterio.transform import from_origin

    t = from_origin(500_000.0, 4_200_000.0, 10.0, 10.0)
    profile = dict(driver="GTiff", width=cls.shape[1], height=cls.shape[0], count=1, dtype="uint8")
    with rasterio.open(
        path, "w", **profile, transform=t, crs="EPSG:32633", tiled=True, compress="deflate"
    ) as ds:
        ds.write(cls, 1)
    return t


def run_mrm(tif: Path, out: Path) -> tuple[float, dict]:
    t0 = time.perf_counter()
    cmd = [sys.executable, "-m", "mrm", "polygonize", str(tif), "-o", str(out), "--json", "-q"]
    done = subprocess.run(cmd, capture_output=True, text=True)
    wall = time.perf_counter() - t0
    if done.returncode != 0:
        raise SystemExit(f"mrm polygonize failed: {done.stderr.strip()}")
    return wall, json.loads(done.stdout)


def run_gdal(tif: Path, out: Path) -> tuple[float, str]:
    exe = shutil.which("gdal_polygonize.py") or shutil.which("gdal_polygonize")
    if out.exists():
        out.unlink()
    t0 = time.perf_counter()
    if exe is not None:
        subprocess.run([exe, "-q", str(tif), "-f", "GPKG", str(out), "layer", "label"], check=True)
        return time.perf_counter() - t0, "gdal_polygonize.py"
    code = (
        "import sys, numpy as np, rasterio, shapely, pyogrio\n"
        "from rasterio.features import shapes\n"
        "from shapely.geometry import shape\n"
        "with rasterio.open(sys.argv[1]) as ds:\n"
        "    band = ds.read(1); t = ds.transform; crs = ds.crs.to_string()\n"
        "feats = list(shapes(band, transform=t, connectivity=4))\n"
        "geoms = shapely.to_wkb([shape(g) for g, _ in feats])\n"
        "vals = np.array([int(v) for _, v in feats], dtype=np.int64)\n"
        "pyogrio.raw.write(sys.argv[2], geoms, field_data=[vals], fields=['label'],\n"
        "                  geometry_type='Polygon', crs=crs, driver='GPKG')\n"
    )
    subprocess.run([sys.executable, "-c", code, str(tif), str(out)], check=True)
    return time.perf_counter() - t0, "rasterio.features.shapes (GDALPolygonize) + pyogrio"


def vertices(geoms: np.ndarray) -> int:
    import shapely

    rings = shapely.get_num_interior_rings(geoms).sum() + len(geoms)
    return int(shapely.get_num_coordinates(geoms).sum() - rings)


def burnt_wrong(path: Path, cls: np.ndarray, t) -> tuple[int, int, np.ndarray]:
    """(features, pixels whose burnt class differs, the geometries) of a layer."""
    import pyogrio
    import shapely
    from rasterio.features import rasterize

    _, _, wkb, data = pyogrio.raw.read(path)
    geoms = shapely.from_wkb(wkb)
    burnt = rasterize(zip(geoms, np.asarray(data[0]).tolist(), strict=True), out_shape=cls.shape, transform=t,
                      fill=0, dtype="uint8")  # fmt: skip
    return len(geoms), int((burnt != cls).sum()), geoms


def exact_wrong(geoms: np.ndarray, labels: np.ndarray, cls: np.ndarray, t) -> int:
    """Pixels wrong when each polygon is discretized by mrm's exact D_gauss (in grid coordinates)."""
    import shapely

    from mrm.geometry.discretize import discretize

    h = cls.shape[0]
    inv = ~t  # world -> (col, row); grid (u, v) = (col − ½, h − ½ − row)
    image = np.zeros(cls.shape, dtype=np.uint8)

    def to_grid(c: np.ndarray) -> np.ndarray:
        col = inv.a * c[:, 0] + inv.b * c[:, 1] + inv.c
        row = inv.d * c[:, 0] + inv.e * c[:, 1] + inv.f
        return np.column_stack((col - 0.5, h - 0.5 - row))

    for g, lab in zip(shapely.transform(geoms, to_grid), labels.tolist(), strict=True):
        ps = discretize(g, "gauss", limit=None)
        pts = ps.points()
        image[h - 1 - pts[:, 1], pts[:, 0]] = lab
    return int((image != cls).sum())


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--size", type=int, default=4096)
    ap.add_argument("--classes", type=int, default=8)
    ap.add_argument("--blur", type=int, default=12)
    ap.add_argument("--runs", type=int, default=3)
    ap.add_argument("--seed", type=int, default=0)
    ap.add_argument("--no-exact", action="store_true", help="skip the (slow) exact D check of mrm's polygons")
    args = ap.parse_args()
    with tempfile.TemporaryDirectory() as tmp:
        d = Path(tmp)
        cls = classified(args.size, args.classes, args.blur, args.seed)
        t = write_tif(d / "land.tif", cls)
        mrm_times, gdal_times, summary, how = [], [], {}, ""
        for _ in range(args.runs):
            wall, summary = run_mrm(d / "land.tif", d / "mrm.gpkg")
            mrm_times.append(wall)
            wall, how = run_gdal(d / "land.tif", d / "gdal.gpkg")
            gdal_times.append(wall)
        n_m, wrong_m, g_m = burnt_wrong(d / "mrm.gpkg", cls, t)
        n_g, wrong_g, g_g = burnt_wrong(d / "gdal.gpkg", cls, t)
        exact = "—"
        if not args.no_exact:
            import pyogrio

            labels = np.asarray(pyogrio.raw.read(d / "mrm.gpkg")[3][0])
            exact = str(exact_wrong(g_m, labels, cls, t))
        print(
            f"{args.size}² pixels, {args.classes} classes (blur {args.blur}), {args.runs} runs; GDAL: {how}"
        )
        print(f"mrm: {summary['regions']} regions; polygonization alone {summary['seconds']:.2f} s")
        print("| | median wall (s) | features | vertices | pixels wrong (GDAL burn) | pixels wrong (mrm D) |")
        print("|---|---|---|---|---|---|")
        med = statistics.median(mrm_times)
        print(f"| mrm polygonize | {med:.2f} | {n_m} | {vertices(g_m)} | {wrong_m} | {exact} |")
        print(f"| GDAL | {statistics.median(gdal_times):.2f} | {n_g} | {vertices(g_g)} | {wrong_g} | — |")


if __name__ == "__main__":
    main()
