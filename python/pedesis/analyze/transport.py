"""Transport coefficients from trajectories and logs made elsewhere: the self-diffusion
coefficient from the mean squared displacement and a Green-Kubo coefficient (the shear
viscosity from the pressure tensor) from the Einstein form of its integrated flux.

The fit rule is the one pedesis's own [transport] measurement uses (docs/analyze.md):
the series is split into ``blocks`` contiguous blocks of equal length; in each, the mean
square increment of the moment (the positions, or the time integral of the flux) is
taken over every time origin; with the block's duration t_b (its first sample to its
last), tau_max = t_b / 10 and the fit window is [tau_max / 4, tau_max]; a least-squares
line (slope and intercept) through the increments at the lags inside the window gives the
slope, and the coefficient is the slope over 2d (diffusion) or times V / (2 T) (Green-
Kubo). The value is the mean of the blocks' coefficients and the error their standard
deviation (ddof 1) over sqrt(blocks); None for one block.
"""
import csv
import math
from pathlib import Path

import numpy as np

from .dynamics import msd_of_paths
from .paths import check_unwrapped, unwrap

# The columns of the off-diagonal pressure tensor in pedesis logs (docs/formats.md).
OFF_DIAGONAL = ("pressure_xy", "pressure_xz", "pressure_yz")


def diffusion_coefficient(positions, dt, box=None, blocks=8):
    """The self-diffusion coefficient D = slope / (2 d) of the MSD, by the fit rule of
    this module (its docstring): the frames cut into ``blocks`` contiguous blocks, in each
    a least-squares line through the MSD over the window [tau_max/4, tau_max], tau_max a
    tenth of a block's duration; the mean of the blocks' D and its standard error.

    ``positions``: (T, N, d) at times k * dt, unwrapped; with ``box`` they may be wrapped
    and are unwrapped first (each particle to its nearest image between consecutive
    frames, pa.unwrap: right while no particle moves half a box length between frames).
    Without a box, positions that look wrapped raise ValueError (as pa.msd does).

    Returns {"value", "error", "fit_window": (from, to) in time, "msd": (lags in time,
    MSD summed over the axes, the mean of the blocks')}."""
    x = np.asarray(positions, dtype=float)
    if x.ndim != 3 or x.shape[2] not in (2, 3):
        raise ValueError(f"diffusion_coefficient: positions must be (frames, N, d) with d = 2 "
                         f"or 3, not of shape {x.shape}")
    if box is not None:
        x = unwrap(x, box)
    else:
        check_unwrapped(x, None, "diffusion_coefficient")
    length = _block_length(x.shape[0], blocks, "diffusion_coefficient")
    curves = np.array([msd_of_paths(x[b * length:(b + 1) * length]) for b in range(blocks)])
    return _fit_blocks(curves, dt, 1.0 / (2 * x.shape[2]))


def green_kubo(flux, dt, volume, temperature, blocks=8, remove_drift=False):
    """A Green-Kubo coefficient (V / T) int_0^inf <dJ(0) dJ(t)> dt of ``flux`` (T, k): k
    equivalent components of a flux sampled every ``dt`` (for the shear viscosity the
    off-diagonal pressure P_xy, P_xz, P_yz, whose mean is zero; for the bulk viscosity
    the pressure with remove_drift). It uses the Einstein form: G(t) = dt sum_{j < t/dt}
    J_j, <[G(t + tau) - G(t)]^2> -> 2 tau int_0^inf <J(0) J(t)> dt, so the coefficient is
    V / (2 T) times the slope of the mean square increment of G, fitted by this module's
    rule (its docstring: blocks contiguous blocks, the window [tau_max/4, tau_max] with
    tau_max a tenth of a block's duration, the mean and standard error of the blocks'
    values), the components averaged. ``remove_drift``: each component's mean over the
    series (its first blocks * L samples) is subtracted from it first, and the mean
    square increment at lag m divided by 1 - m/(blocks L): a moment whose flux has had
    its sample mean removed is a bridge, <dG^2> = 2 D m dt (1 - m/(blocks L)) while the
    increments are diffusive, so the division leaves no bias (fitting the variance of
    the increments over each block's origins instead, <dG^2> - <dG>^2, is 14 % low with
    8 blocks). (A log of hard particles gives each row's pressure as the mean over the
    interval since the row before: dt times it is the exact increment of the Helfand
    moment.)

    Returns {"value", "error", "fit_window": (from, to) in time, "running": (lags in
    time, the running coefficient: V / (2 T) times the local slope of the blocks' mean
    square increment, which equals (V / T) int_0^tau <J(0) J(t)> dt)}."""
    j = np.asarray(flux, dtype=float)
    if j.ndim == 1:
        j = j[:, None]
    if j.ndim != 2:
        raise ValueError(f"green_kubo: the flux must be (T,) or (T, k), not of shape {j.shape}")
    if volume <= 0 or temperature <= 0:
        raise ValueError("green_kubo: the volume and the temperature must be positive")
    # a block of L samples makes a moment of L + 1 values, G(0) = 0 to G(L dt), whose
    # fit window is what must hold enough lags
    length = _block_length(j.shape[0] + blocks, blocks, "green_kubo") - 1
    scale = volume / (2.0 * temperature)
    used = blocks * length
    bridge = np.ones(length + 1)
    if remove_drift:
        j = j[:used] - j[:used].mean(axis=0)
        bridge = 1.0 - np.arange(length + 1) / used
    curves = []
    for b in range(blocks):
        part = j[b * length:(b + 1) * length]
        moment = np.concatenate([np.zeros((1, part.shape[1])), np.cumsum(part, axis=0)]) * dt
        # each component a one-dimensional path, averaged as msd averages particles; (one
        # block with remove_drift: the whole span's increment is 0 by construction, 0/0)
        with np.errstate(divide="ignore", invalid="ignore"):
            curves.append(msd_of_paths(moment[:, :, None]) / bridge)
    result = _fit_blocks(np.array(curves), dt, scale)
    lags, mean = result.pop("msd")
    result["running"] = (lags, scale * np.gradient(mean, lags))
    return result


def shear_viscosity(log, volume, temperature=None, dt=None, blocks=8):
    """The shear viscosity by green_kubo from a pedesis log: ``log`` a path to a log.csv,
    or a table of columns (a dict of arrays, a numpy structured array, a pandas
    DataFrame). It takes the columns pressure_xy (2D; 3D also pressure_xz and
    pressure_yz) and leaves out the first row (a hard-particle log's pressure is a mean
    over the interval since the row before, 0 in the first row). ``temperature``: default
    the mean of the log's temperature column after the first row; ``dt``: default the
    spacing of its time column, which must be even. Returns green_kubo's dict."""
    table = _read_csv(Path(log)) if isinstance(log, (str, Path)) else log
    names = _column_names(table)
    columns = [c for c in OFF_DIAGONAL if c in names]
    if not columns:
        raise ValueError("shear_viscosity: the log has no column pressure_xy (nor pressure_xz, "
                         "pressure_yz); log the pressure tensor, or give green_kubo the flux")
    flux = np.column_stack([np.asarray(table[c], dtype=float) for c in columns])[1:]
    if temperature is None:
        if "temperature" not in names:
            raise ValueError("shear_viscosity: the log has no temperature column; give "
                             "temperature=")
        temperature = float(np.mean(np.asarray(table["temperature"], dtype=float)[1:]))
    if dt is None:
        dt = _even_spacing(table, names)
    return green_kubo(flux, dt, volume, temperature, blocks)


# Each block needs this many lags in its fit window at least: a line through fewer
# is no fit.
MIN_WINDOW_LAGS = 3


def _window(length):
    """The lags (in samples) of the fit window of a block of ``length`` samples: its
    duration length - 1, tau_max a tenth of it, the window [tau_max / 4, tau_max]; (a lag
    on an edge within rounding is inside). Returns (mask over lags 0 .. length-1, from,
    to)."""
    tau_max = (length - 1) / 10.0
    lags = np.arange(length)
    inside = (lags >= tau_max / 4.0 - 1e-9) & (lags <= tau_max + 1e-9)
    return inside, tau_max / 4.0, tau_max


def _block_length(samples, blocks, who):
    """Samples per block; the last samples that do not fill a block are left out."""
    if isinstance(blocks, bool) or not isinstance(blocks, (int, np.integer)) or blocks < 1:
        raise ValueError(f"{who}: blocks must be a positive integer, not {blocks!r}")
    length = samples // blocks
    if length < 2 or _window(length)[0].sum() < MIN_WINDOW_LAGS:
        raise ValueError(f"{who}: {samples} samples in {blocks} blocks are too few: the fit "
                         f"window [tau_max/4, tau_max], tau_max a tenth of a block's duration, "
                         f"needs {MIN_WINDOW_LAGS} lags or more (about 30 samples per block)")
    return length


def _fit_blocks(curves, dt, factor):
    """The coefficient factor * slope of each block's curve (lags 0 .. length-1) in the
    fit window; the value, error and window as the module's docstring says."""
    inside, low, high = _window(curves.shape[1])
    lags = np.arange(curves.shape[1]) * dt
    values = np.array([factor * np.polyfit(lags[inside], c[inside], 1)[0] for c in curves])
    error = None
    if len(values) > 1:
        error = float(np.std(values, ddof=1) / math.sqrt(len(values)))
    return {"value": float(values.mean()), "error": error, "fit_window": (low * dt, high * dt),
            "msd": (lags, curves.mean(axis=0))}


def _read_csv(path):
    if not path.is_file():
        raise FileNotFoundError(f"{path}: no such log")
    with path.open(newline="") as f:
        rows = list(csv.reader(f))
    if len(rows) < 2:
        raise ValueError(f"{path}: no rows")
    header = [h.strip() for h in rows[0]]
    try:
        data = np.array([[float(v) for v in row] for row in rows[1:] if row], dtype=float)
    except ValueError as e:
        raise ValueError(f"{path}: {e}") from None
    if data.shape[1] != len(header):
        raise ValueError(f"{path}: the rows do not have the header's {len(header)} fields")
    return {name: data[:, k] for k, name in enumerate(header)}


def _column_names(table):
    names = getattr(getattr(table, "dtype", None), "names", None)  # structured array
    if names is None:
        names = table.columns if hasattr(table, "columns") else table.keys()
    return set(names)


def _even_spacing(table, names):
    if "time" not in names:
        raise ValueError("shear_viscosity: the log has no time column; give dt=")
    steps = np.diff(np.asarray(table["time"], dtype=float)[1:])
    if len(steps) == 0 or not np.allclose(steps, steps[0], rtol=1e-6, atol=0):
        raise ValueError("shear_viscosity: the log's rows are not evenly spaced in time "
                         "(log with [log] interval or every); give dt= for evenly spaced "
                         "samples")
    return float(steps[0])
