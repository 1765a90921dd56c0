"""Structure: the radial distribution function g(r) and the static structure factor S(q)."""
import numpy as np
from scipy.special import j0

from .box import Box


def _directions(dimension, count=4096):
    """Unit vectors spread evenly over the circle or (Fibonacci) sphere."""
    if dimension == 2:
        t = (np.arange(count) + 0.5) * 2.0 * np.pi / count
        return np.stack([np.cos(t), np.sin(t)], axis=1)
    k = np.arange(count) + 0.5
    z = 1.0 - 2.0 * k / count
    phi = np.pi * (1.0 + 5.0 ** 0.5) * k
    s = np.sqrt(1.0 - z * z)
    return np.stack([s * np.cos(phi), s * np.sin(phi), z], axis=1)


def _pair_volume(box, r):
    """The mean over directions u of the set covariance gamma(r u): the volume of points x
    of the box with x + r u in it too (L - r|u_a| on a walled axis, L on a periodic one).
    Ideal-gas pairs at separation r are N(N-1)/V^2 of it per unit of separation volume:
    V on a periodic box, less near walls."""
    u = np.abs(_directions(box.dimension))
    out = np.empty(len(r))
    for k, rk in enumerate(r):
        g = np.ones(len(u))
        for a, (L, p) in enumerate(zip(box.lengths, box.periodic)):
            g *= L if p else np.clip(L - rk * u[:, a], 0.0, None)
        out[k] = g.mean()
    return out


def _shell_volumes(edges, dimension):
    if dimension == 2:
        return np.pi * np.diff(edges ** 2)
    return 4.0 / 3.0 * np.pi * np.diff(edges ** 3)


def rdf(positions, box, r_max, bins=200, types=None, pair=None):
    """The radial distribution function g(r) of one frame.

    g(r) = n_pairs(r) / n_ideal(r): the pairs at distance in [r, r + dr] over those of an
    ideal gas of the same numbers in the same box, N(N-1)/(2 V^2) * shell volume * the mean
    set covariance (V in a periodic box; smaller near walls, so that g = 1 for an ideal
    gas in a walled box too). ``types`` (N integers) and ``pair`` (a, b) restrict it to
    the pairs of species a and b (g_ab, counting each unordered pair once).

    Returns (r, g): the bin centres and g there. r_max must be below half the shortest
    periodic edge (the minimum image).
    """
    box = box if isinstance(box, Box) else Box(box)
    x = box.wrap(np.asarray(positions, dtype=float))
    periodic_edges = [L for L, p in zip(box.lengths, box.periodic) if p]
    if periodic_edges and r_max > 0.5 * min(periodic_edges):
        raise ValueError(f"rdf: r_max = {r_max} exceeds half the shortest periodic edge")
    edges = np.linspace(0.0, r_max, bins + 1)
    if pair is None:
        a = b = x
        same = True
    else:
        types = np.asarray(types)
        a, b = x[types == pair[0]], x[types == pair[1]]
        same = pair[0] == pair[1]
    # the pairs by distance, through pedesis's cell list (each pair once); imported here,
    # so that the rest of pedesis.analyze works where the compiled module is not built
    from .. import _pedesis

    counts = _pedesis.pair_histogram(a, b, same, list(box.lengths), list(box.periodic), r_max, bins)
    pairs = 0.5 * len(a) * (len(a) - 1) if same else float(len(a) * len(b))
    centres = 0.5 * (edges[1:] + edges[:-1])
    ideal = pairs / box.volume ** 2 * _shell_volumes(edges, box.dimension) * _pair_volume(box, centres)
    return centres, counts / ideal


def structure_factor(positions, box, q_max, bins=100, max_vectors=20000, seed=0, binned=True):
    """The static structure factor S(q) = |sum_j exp(-i q . r_j)|^2 / N, directly, on the
    wave vectors of a periodic box (q = 2 pi n / L, n integer, 0 < |q| <= q_max), averaged
    over the vectors in each bin of |q|. More than ``max_vectors`` vectors: a random
    subset of them (fixed seed). Returns (q, S) for the bins that hold vectors, or with
    ``binned=False`` the wave vectors (M, d) and S at each.
    """
    box = box if isinstance(box, Box) else Box(box)
    if not all(box.periodic):
        raise ValueError("structure_factor: the direct sum needs a periodic box")
    x = np.asarray(positions, dtype=float)
    n_max = [int(q_max * L / (2.0 * np.pi)) for L in box.lengths]
    grids = np.meshgrid(*[np.arange(-m, m + 1) for m in n_max], indexing="ij")
    n = np.stack([g.ravel() for g in grids], axis=1)
    q = 2.0 * np.pi * n / np.array(box.lengths)
    norm = np.linalg.norm(q, axis=1)
    keep = (norm > 0) & (norm <= q_max)
    q, norm = q[keep], norm[keep]
    if len(q) > max_vectors:
        pick = np.random.default_rng(seed).choice(len(q), max_vectors, replace=False)
        q, norm = q[pick], norm[pick]
    s = np.empty(len(q))
    for start in range(0, len(q), 256):  # a few MB of phases at a time
        phase = x @ q[start:start + 256].T
        s[start:start + 256] = (np.cos(phase).sum(axis=0) ** 2 + np.sin(phase).sum(axis=0) ** 2)
    s /= len(x)
    if not binned:
        return q, s
    edges = np.linspace(0.0, q_max, bins + 1)
    which = np.clip(np.digitize(norm, edges) - 1, 0, bins - 1)
    total = np.bincount(which, weights=s, minlength=bins)
    count = np.bincount(which, minlength=bins)
    held = count > 0
    return 0.5 * (edges[1:] + edges[:-1])[held], total[held] / count[held]


def structure_factor_from_rdf(r, g, density, q, dimension):
    """S(q) = 1 + rho * integral of (g(r) - 1) times exp(i q . r) over space: in 3D
    4 pi rho int (g - 1) r^2 sin(qr)/(qr) dr, in 2D 2 pi rho int (g - 1) r J0(qr) dr
    (trapezoids over the given r; g must have reached 1 at the last r)."""
    r, g, q = np.asarray(r, float), np.asarray(g, float), np.atleast_1d(np.asarray(q, float))
    qr = np.outer(q, r)
    if dimension == 3:
        kernel = 4.0 * np.pi * r ** 2 * np.sinc(qr / np.pi)
    else:
        kernel = 2.0 * np.pi * r * j0(qr)
    return 1.0 + density * np.trapz(kernel * (g - 1.0), r, axis=1)
