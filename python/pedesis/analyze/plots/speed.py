#!/usr/bin/python3
"""Speed distribution of a run's final frame, per species, over the equilibrium curve
(Rayleigh in 2D, Maxwell in 3D) at each species' measured temperature, with the
Kolmogorov-Smirnov distance printed per species:

    ks_distance NAME: D (N = n, T = T, m = m)

Usage: speed.py RUN_DIR [--out FILE]   (default RUN_DIR/speed_distribution.png)
"""
import csv
import math

import numpy as np

from . import figure
from .run_dir import InputError


def speed_cdf(dim, v, T, m):
    """Equilibrium CDF of the speed, the F of docs/formats.md's speed_histogram.csv."""
    x2 = m * v * v / T
    if dim == 2:
        return -np.expm1(-0.5 * x2)
    x = np.sqrt(x2)
    erf = np.array([math.erf(t / math.sqrt(2.0)) for t in x])
    return erf - math.sqrt(2.0 / math.pi) * x * np.exp(-0.5 * x2)


def speed_pdf(dim, v, T, m):
    a = m / T
    if dim == 2:
        return a * v * np.exp(-0.5 * a * v * v)
    return 4.0 * math.pi * v * v * (a / (2.0 * math.pi)) ** 1.5 * np.exp(-0.5 * a * v * v)


def ks_distance(speeds, cdf):
    """sup |F_n - F| of the sample against the CDF, over both sides of each step."""
    v = np.sort(speeds)
    n = len(v)
    F = cdf(v)
    k = np.arange(n)
    return float(max(np.max(F - k / n), np.max((k + 1) / n - F)))


def ks_critical(n, alpha):
    """Asymptotic critical KS distance at significance alpha, as pedesis::theory has it.
    With T fitted from the same sample the test is conservative (Lilliefors)."""
    return math.sqrt(-0.5 * math.log(alpha / 2.0)) / math.sqrt(n)


class SpeciesSample:
    """The speeds of one species' mobile particles and their temperature
    T = sum m v^2 / (d N), the temperature the theory curve is drawn at."""

    def __init__(self, name, speeds, mass, dim):
        self.name = name
        self.speeds = speeds
        self.mass = mass
        self.n = len(speeds)
        self.T = float(mass * np.sum(speeds ** 2) / (dim * self.n))


def samples(frame, dim):
    out = []
    for k in np.unique(frame.types):
        mine = (frame.types == k) & np.isfinite(frame.mass)
        if not mine.any():
            continue  # fixed obstacles have no speed distribution
        name = frame.names[k] if k < len(frame.names) else f"type {k}"
        masses = np.unique(frame.mass[mine])
        if len(masses) != 1:
            raise InputError(f"{frame.source}: species {name} has several masses {masses}")
        speeds = np.linalg.norm(frame.velocity[mine], axis=1)
        out.append(SpeciesSample(name, speeds, float(masses[0]), dim))
    if not out:
        raise InputError(f"{frame.source}: no mobile particle (all masses are infinite)")
    return out


def main():
    a, run = figure.open_run(__doc__.split("\n")[0], "speed_distribution.png")
    out = a.out
    dim = run.dimension
    frame = run.final_frame()
    if frame.velocity.shape[1] != dim:
        raise InputError(f"{run.path / frame.source}: velocities have "
                         f"{frame.velocity.shape[1]} components, config.toml says {dim}D")
    print(f"speed: velocities of {frame.source}, t = {frame.time:g} (the final frame)")
    law = "Rayleigh" if dim == 2 else "Maxwell"
    groups = samples(frame, dim)
    for s in groups:
        if s.T > 0:
            s.ks = ks_distance(s.speeds, lambda v: speed_cdf(dim, v, s.T, s.mass))
            print(f"ks_distance {s.name}: {s.ks:.10f} (N = {s.n}, T = {s.T:.8g}, m = {s.mass:g})")
        else:
            s.ks = None
            print(f"speed: species {s.name} is at rest (T = 0): no {law} curve to compare with")

    plt = figure.pyplot()
    fig, (ax_pdf, ax_cdf) = plt.subplots(1, 2, figsize=(11, 4.8))
    vmax = 1.05 * max(float(s.speeds.max()) for s in groups) or 1.0
    grid = np.linspace(0.0, vmax, 400)
    for k, s in enumerate(groups):
        c = f"C{k}"
        # about sqrt(N) bins over this species' own range: a heavy species is slower
        bins = int(np.clip(np.sqrt(s.n), 8, 50))
        edges = np.linspace(0.0, 1.02 * float(s.speeds.max()) or 1.0, bins + 1)
        ax_pdf.hist(s.speeds, bins=edges, density=True, histtype="stepfilled", alpha=0.35,
                    color=c, label=f"{s.name} (m = {s.mass:g}): {s.n} speeds")
        v = np.sort(s.speeds)
        ax_cdf.step(v, np.arange(1, s.n + 1) / s.n, where="post", color=c, lw=1.2,
                    label=f"{s.name}: empirical")
        if s.ks is None:
            continue
        ax_pdf.plot(grid, speed_pdf(dim, grid, s.T, s.mass), color=c, lw=1.8,
                    label=f"{law}, T = {s.T:.4g}")
        ax_cdf.plot(grid, speed_cdf(dim, grid, s.T, s.mass), color="k" if len(groups) == 1
                    else c, lw=1.0, ls="--", label=f"{law}, T = {s.T:.4g}: KS D = {s.ks:.4f} "
                    f"(5 % level {ks_critical(s.n, 0.05):.4f})")
    _time_averaged_histogram(run, ax_pdf, {s.name: f"C{k}" for k, s in enumerate(groups)})
    ax_pdf.set_xlabel("speed |v| [length/time]")
    ax_pdf.set_ylabel("probability density f(v) [time/length]")
    ax_pdf.set_xlim(0, vmax)
    ax_pdf.legend()
    ax_cdf.set_xlabel("speed |v| [length/time]")
    ax_cdf.set_ylabel("cumulative distribution F(v)")
    ax_cdf.set_xlim(0, vmax)
    ax_cdf.set_ylim(0, 1.02)
    ax_cdf.legend(loc="lower right")
    note = ("\n(brownian: v = step displacement / dt, noise included)"
            if run.dynamics == "brownian" else "")
    ax_pdf.set_title(f"{frame.source}, t = {frame.time:g}{note}")
    ax_cdf.set_title("T measured per species: T = sum m v^2 / (d N)")
    figure.title(fig, run, "Speed distribution")
    fig.tight_layout()
    return figure.save(fig, out)


def _time_averaged_histogram(run, ax, colours):
    """speed_histogram.csv, when the run sampled it over many states
    ([output] histogram_start), as an outline: smoother than one frame's histogram."""
    start = run.config.get("output", {}).get("histogram_start")
    path = run.path / "speed_histogram.csv"
    if start is None or not path.is_file():
        return
    try:
        with path.open(newline="") as f:
            rows = list(csv.DictReader(f))
        by_species = {}
        for r in rows:
            by_species.setdefault(r["species"], []).append(
                (float(r["v_lo"]), float(r["v_hi"]), float(r["density"])))
    except (OSError, KeyError, ValueError, TypeError) as e:
        raise InputError(f"{path}: not a pedesis speed histogram ({e})") from None
    for name, bins in by_species.items():
        lo = [b[0] for b in bins] + [bins[-1][1]]
        dens = [b[2] for b in bins] + [bins[-1][2]]
        ax.step(lo, dens, where="post", color=colours.get(name, "k"), lw=1.0, ls=":",
                label=f"{name}: all states t >= {start:g} ({path.name})")
