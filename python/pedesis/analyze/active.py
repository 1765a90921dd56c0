"""Active matter: polar order and its correlation, local area fractions (motility-induced
phase separation), and the swim pressure."""
import numpy as np
from scipy.spatial import cKDTree

from .box import Box


def polar_order(directors):
    """|sum_i n_i| / N for unit directors (N, d): 1 when all point one way, ~1/sqrt(N) at
    random. For a trajectory (T, N, d), one value per frame."""
    n = np.asarray(directors, dtype=float)
    return np.linalg.norm(n.mean(axis=-2), axis=-1)


def polar_correlation(positions, directors, box, r_max, bins=50):
    """C(r) = < n_i . n_j > over the pairs at distance r (a bin of width r_max / bins).
    Returns (r, C, pairs): bin centres, C (NaN where a bin has no pair), pair counts."""
    box = box if isinstance(box, Box) else Box(box)
    x = box.wrap(np.asarray(positions, dtype=float))
    n = np.asarray(directors, dtype=float)
    pairs = cKDTree(x, boxsize=box.tree_size()).query_pairs(r_max, output_type="ndarray")
    r = np.linalg.norm(box.minimum_image(x[pairs[:, 1]] - x[pairs[:, 0]]), axis=1)
    dot = (n[pairs[:, 0]] * n[pairs[:, 1]]).sum(axis=1)
    edges = np.linspace(0.0, r_max, bins + 1)
    which = np.clip(np.digitize(r, edges) - 1, 0, bins - 1)
    count = np.bincount(which, minlength=bins)
    total = np.bincount(which, weights=dot, minlength=bins)
    with np.errstate(invalid="ignore", divide="ignore"):
        c = np.where(count > 0, total / np.maximum(count, 1), np.nan)
    return 0.5 * (edges[1:] + edges[:-1]), c, count


def local_area_fraction(positions, radii, box, cell):
    """The fraction of each cell of a grid of about ``cell`` wide that the particles whose
    centres lie in it cover: sum of pi r^2 (2D) or 4/3 pi r^3 (3D) over the cell's size.
    Returns the fractions of every cell, flat. A homogeneous fluid gives one peak in their
    histogram, motility-induced phase separation two (gas and dense phase)."""
    box = box if isinstance(box, Box) else Box(box)
    x = box.wrap(np.asarray(positions, dtype=float))
    radii = np.broadcast_to(np.asarray(radii, dtype=float), (len(x),))
    counts = [max(1, int(round(L / cell))) for L in box.lengths]
    index = np.zeros(len(x), dtype=np.int64)
    for a, (L, m) in enumerate(zip(box.lengths, counts)):
        index = index * m + np.minimum((x[:, a] / L * m).astype(np.int64), m - 1)
    size = radii ** box.dimension * (np.pi if box.dimension == 2 else 4.0 / 3.0 * np.pi)
    covered = np.bincount(index, weights=size, minlength=int(np.prod(counts)))
    return covered / (box.volume / np.prod(counts))


def fraction_bins(radius, box, cell, top=1.2):
    """Histogram bins for the local_area_fraction of equal particles of ``radius``:
    (bins, value_range) with edges halfway between whole particle counts and each bin a
    whole number (>= 2) of particles wide, at least 0.025. A cell's fraction is a whole
    multiple of one particle's share of it, and bins that do not line up with those
    multiples alias them into a comb of false peaks."""
    box = box if isinstance(box, Box) else Box(box)
    counts = [max(1, int(round(L / cell))) for L in box.lengths]
    one = np.pi * radius ** 2 if box.dimension == 2 else 4.0 / 3.0 * np.pi * radius ** 3
    share = one / (box.volume / np.prod(counts))
    width = share * max(2, int(np.ceil(0.025 / share)))
    bins = int(np.ceil((top + 0.5 * share) / width))
    return bins, (-0.5 * share, -0.5 * share + bins * width)


def histogram_peaks(values, bins=40, value_range=(0.0, 1.0), min_share=0.02, smooth=3):
    """The local maxima of the histogram of ``values`` (a count smoothed over ``smooth``
    bins) that hold at least ``min_share`` of the values, as bin centres, highest count
    first; two or more mean a bimodal distribution. Returns (peaks, centres, density)."""
    density, edges = np.histogram(values, bins=bins, range=value_range, density=True)
    centres = 0.5 * (edges[1:] + edges[:-1])
    smoothed = np.convolve(density, np.ones(smooth) / smooth, mode="same")
    width = edges[1] - edges[0]
    peaks = [k for k in range(bins)
             if smoothed[k] > 0 and smoothed[k] >= smoothed[max(k - 1, 0)]
             and smoothed[k] > smoothed[min(k + 1, bins - 1)]
             and smoothed[k] * width * smooth >= min_share]
    peaks.sort(key=lambda k: -smoothed[k])
    return centres[peaks], centres, density


def phase_fractions(fractions_per_frame, bins=40, value_range=(0.0, 1.2)):
    """The coexisting phases of frames of local fractions (one array of cells per frame):
    the pooled histogram's lowest and highest peaks (smoothed over 5 bins, each holding 5 %
    of the cells) and the histogram's minimum between them split the cells into a dilute
    and a dense phase; returns (gas, dense, threshold) with gas and dense (T,) the mean
    local fraction of each frame's cells on either side, or None if the pooled histogram
    has one peak. For equal particles take bins and value_range from fraction_bins."""
    pooled = np.concatenate(fractions_per_frame)
    peaks, centres, density = histogram_peaks(pooled, bins, value_range, min_share=0.05, smooth=5)
    if len(peaks) < 2:
        return None
    lo, hi = np.searchsorted(centres, [peaks.min(), peaks.max()])
    threshold = centres[lo + int(np.argmin(density[lo:hi + 1]))]
    gas = np.array([f[f < threshold].mean() if (f < threshold).any() else np.nan
                    for f in fractions_per_frame])
    dense = np.array([f[f >= threshold].mean() if (f >= threshold).any() else np.nan
                      for f in fractions_per_frame])
    return gas, dense, float(threshold)


def swim_pressure(unwrapped, directors, alpha, volume):
    """The swim pressure of active Brownian particles (Takatori & Brady 2014), per frame:
    Pi(t) = (1 / (d V)) sum_i alpha (r_i(t) - r_i(0)) . n_i(t), with alpha = zeta U0 the
    active force. For free particles it tends to n zeta U0^2 tau_R / d after a few
    tau_R = 1 / ((d - 1) D_r). ``unwrapped`` and ``directors``: (T, N, d)."""
    x = np.asarray(unwrapped, dtype=float)
    n = np.asarray(directors, dtype=float)
    d = x.shape[2]
    return alpha * ((x - x[:1]) * n).sum(axis=(1, 2)) / (d * volume)
