"""Voxel masks shared by the 3D region and safety-net tests: known shapes and seeded random masks."""

from __future__ import annotations

import numpy as np


def ball(r: float, n: int) -> np.ndarray:
    z, y, x = np.mgrid[0:n, 0:n, 0:n] - (n - 1) / 2
    return x * x + y * y + z * z <= r * r


def solid_torus(n: int = 15, big: float = 4.5, small: float = 2.0) -> np.ndarray:
    z, y, x = np.mgrid[0:n, 0:n, 0:n] - (n - 1) / 2
    return (np.hypot(x, y) - big) ** 2 + z * z <= small * small


def hollow(n: int = 9) -> np.ndarray:
    return ball(n / 2 - 0.5, n) & ~ball(n / 2 - 2.5, n)


def random_mask(seed: int, shape: tuple[int, int, int], density: float) -> np.ndarray:
    return np.random.default_rng(seed).random(shape) < density
