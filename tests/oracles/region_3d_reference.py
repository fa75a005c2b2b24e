"""Reference region quantities of a voxel set with the (6, 26) topology, by their definitions.

- components: ``scipy.ndimage.label`` with the 6-connectivity structure;
- cavities: ``scipy.ndimage.label`` of the complement in the padded box with the 26-connectivity structure,
  the components touching the padding being the unbounded one;
- Euler characteristic: counted on the cubical complex of the (6, 26) pair — vertices at voxel centres, edges
  between 6-adjacent voxels, squares for planar 2×2 blocks, cubes for 2×2×2 blocks — as χ = V − E + F − C
  over the whole array at once.

Nothing here is shared with mrm.geometry.topology (which sums a 2×2×2 configuration table at run ends).
"""

from __future__ import annotations

import numpy as np
import scipy.ndimage as ndi

S6 = ndi.generate_binary_structure(3, 1)
S26 = np.ones((3, 3, 3), bool)


def components(mask: np.ndarray) -> tuple[np.ndarray, int]:
    """The 6-connected components: (labels, n)."""
    lab, n = ndi.label(mask, S6)
    return lab, int(n)


def cavities(mask: np.ndarray) -> tuple[np.ndarray, int]:
    """The bounded 26-components of the complement: (labels over the mask's box with 0 elsewhere, n)."""
    lab, n = ndi.label(np.pad(~mask.astype(bool), 1, constant_values=True), S26)
    outside = set(np.unique(lab[0])) | set(np.unique(lab[-1]))
    outside |= set(np.unique(lab[:, 0])) | set(np.unique(lab[:, -1]))
    outside |= set(np.unique(lab[:, :, 0])) | set(np.unique(lab[:, :, -1]))
    inner = lab[1:-1, 1:-1, 1:-1].copy()
    inner[np.isin(inner, sorted(outside))] = 0
    kept = np.unique(inner[inner > 0])
    relabel = np.zeros(int(n) + 1, np.int64)
    relabel[kept] = np.arange(1, kept.size + 1)
    return relabel[inner], int(kept.size)


def euler(mask: np.ndarray) -> int:
    """χ = V − E + F − C of the cubical complex of the voxels (6-adjacency)."""
    m = np.pad(mask.astype(bool), 1)
    v = int(m.sum())
    e = 0
    f = 0
    for a in (m, m.transpose(1, 2, 0), m.transpose(2, 0, 1)):  # each axis in turn as the first one
        e += int((a[:-1] & a[1:]).sum())
        f += int((a[:, :-1, :-1] & a[:, 1:, :-1] & a[:, :-1, 1:] & a[:, 1:, 1:]).sum())
    c = m[:-1, :-1, :-1].copy()
    for dz in (0, 1):
        for dy in (0, 1):
            for dx in (0, 1):
                c &= m[dz : m.shape[0] - 1 + dz, dy : m.shape[1] - 1 + dy, dx : m.shape[2] - 1 + dx]
    return v - e + f - int(c.sum())
