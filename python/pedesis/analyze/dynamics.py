"""Dynamics: mean squared displacement, self-intermediate scattering function, velocity
autocorrelation, over a trajectory of T frames equally spaced in time."""
import numpy as np
from scipy.special import j0

from .paths import check_unwrapped


def _autocorrelation(x):
    """sum_k x(k) x(k + m) for every lag m, along axis 0, by FFT (zero-padded)."""
    T = x.shape[0]
    f = np.fft.rfft(x, n=2 * T, axis=0)
    return np.fft.irfft(f * np.conj(f), n=2 * T, axis=0)[:T]


def msd(positions, box=None):
    """The mean squared displacement MSD(m) = < |r(k + m) - r(k)|^2 > over particles and
    every time origin k, for lags m = 0 .. T-1, by the FFT method (O(T log T) per
    particle): MSD(m) = S1(m) - 2 S2(m) with S2 the autocorrelation of the positions and
    S1(m) = (1/(T-m)) sum_k [r(k)^2 + r(k+m)^2].

    ``positions``: (T, N, d), unwrapped (add image * L to wrapped positions first).
    Raises ValueError where they look wrapped: a particle moves more than half a box
    length between consecutive frames along a periodic axis of ``box`` (without a box:
    more than half the extent of the positions along an axis); see paths.check_unwrapped.
    """
    check_unwrapped(positions, box, "msd")
    return msd_of_paths(positions)


def msd_of_paths(positions):
    """msd without the check that the positions are paths (for callers that made them
    paths, or that check the whole series once before taking its parts)."""
    x = np.asarray(positions)
    T, N = x.shape[0], x.shape[1]
    out = np.zeros(T)
    # particles a block at a time: the transforms of all 10^5 particles of 1,000 frames
    # at once would take gigabytes
    block = max(1, 1_000_000 // max(T, 1))
    for first in range(0, N, block):
        out += _msd_sum(np.asarray(x[:, first:first + block], dtype=float))
    return out / N


def _msd_sum(x):
    """sum over the particles of x (T, n, d) of their MSD(m)."""
    T = x.shape[0]
    # one row per particle and axis, time along the row: the transforms run over
    # contiguous memory; each path from its start (smaller numbers, less cancellation)
    rows = np.ascontiguousarray(np.moveaxis(x - x[:1], 0, -1)).reshape(-1, T)
    f = np.fft.rfft(rows, n=2 * T, axis=1)
    s2 = np.fft.irfft(f * np.conj(f), n=2 * T, axis=1)[:, :T].sum(axis=0) / (T - np.arange(T))
    d2 = (rows ** 2).sum(axis=0)  # (T,): summed over particles and axes
    # S1(m) = (1/(T-m)) sum_{k < T-m} [r(k)^2 + r(k+m)^2]: drop one frame at each end per lag
    total = 2.0 * d2.sum()
    s1 = np.empty(T)
    for m in range(T):
        s1[m] = total / (T - m)
        total -= d2[m] + d2[T - 1 - m]
    return s1 - 2.0 * s2


def msd_direct(positions):
    """The same MSD by its definition, O(T^2): the reference the FFT method must equal."""
    x = np.asarray(positions, dtype=float)
    T = x.shape[0]
    return np.array([((x[m:] - x[:T - m]) ** 2).sum(axis=2).mean() for m in range(T)])


def self_intermediate_scattering(positions, q, lags=None, box=None):
    """F_s(q, t) = < exp(i q . (r(k + m) - r(k))) >, isotropically averaged over the
    directions of q: < sin(q dr)/(q dr) > in 3D, < J0(q dr) > in 2D, over particles and
    every time origin. ``positions`` (T, N, d), unwrapped (checked as msd checks them);
    ``lags`` the m to compute (default all). Returns the lags and F_s at each."""
    check_unwrapped(positions, box, "self_intermediate_scattering")
    x = np.asarray(positions, dtype=float)
    T, _, d = x.shape
    lags = np.arange(T) if lags is None else np.asarray(lags, int)
    out = np.empty(len(lags))
    for k, m in enumerate(lags):
        dr = np.linalg.norm(x[m:] - x[:T - m], axis=2) * q
        out[k] = (np.sinc(dr / np.pi) if d == 3 else j0(dr)).mean()
    return lags, out


def velocity_autocorrelation(velocities):
    """Z(m) = < v(k) . v(k + m) > over particles and time origins, by FFT; (T, N, d)."""
    v = np.asarray(velocities, dtype=float)
    T = v.shape[0]
    return (_autocorrelation(v).sum(axis=2) / (T - np.arange(T))[:, None]).mean(axis=1)
