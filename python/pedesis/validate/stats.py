"""Means and their standard errors from correlated series (block averaging)."""
import numpy as np


def block_mean(values, blocks=10):
    """The mean of a time series and its standard error from ``blocks`` consecutive block
    means: when a block is much longer than the series' correlation time its means are
    close to independent, so their scatter / sqrt(blocks) is the error of the mean.
    Returns (mean, standard error)."""
    x = np.asarray(values, dtype=float)
    usable = len(x) - len(x) % blocks
    if usable < blocks:
        raise ValueError(f"block_mean: {len(x)} values cannot make {blocks} blocks")
    means = x[:usable].reshape(blocks, -1).mean(axis=1)
    return float(means.mean()), float(means.std(ddof=1) / np.sqrt(blocks))


def ratio_error(a, a_err, b, b_err):
    """a / b and its error, for independent a and b (first order)."""
    r = a / b
    return r, abs(r) * float(np.hypot(a_err / a, b_err / b))


def sample_mean(values):
    """The mean of independent values and its standard error."""
    x = np.asarray(values, dtype=float)
    return float(x.mean()), float(x.std(ddof=1) / np.sqrt(len(x)))
