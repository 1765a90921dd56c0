"""Bond orientational order in 3D: Steinhardt's q_l (q4, q6), per particle."""
import numpy as np
from scipy.spatial import cKDTree
from scipy.special import sph_harm

from .box import Box


def steinhardt(positions, box, l, neighbours=12):
    """q_l of each particle over its ``neighbours`` nearest: q_l = sqrt(4 pi / (2l + 1)
    sum_m |q_lm|^2), q_lm = the mean of Y_lm over the bonds. FCC (12 neighbours): q4 =
    0.19094, q6 = 0.57452; simple cubic (6): q4 = 0.76376, q6 = 0.35355. Returns (N,)."""
    box = box if isinstance(box, Box) else Box(box)
    if box.dimension != 3:
        raise ValueError("steinhardt is for 3D frames")
    x = box.wrap(np.asarray(positions, dtype=float))
    _, idx = cKDTree(x, boxsize=box.tree_size()).query(x, k=neighbours + 1)
    bond = box.minimum_image(x[idx[:, 1:]] - x[:, None, :])
    r = np.linalg.norm(bond, axis=2)
    polar = np.arccos(np.clip(bond[..., 2] / r, -1.0, 1.0))
    azimuth = np.arctan2(bond[..., 1], bond[..., 0])
    total = np.zeros(len(x))
    for m in range(-l, l + 1):
        qlm = sph_harm(m, l, azimuth, polar).mean(axis=1)
        total += np.abs(qlm) ** 2
    return np.sqrt(4.0 * np.pi / (2 * l + 1) * total)
