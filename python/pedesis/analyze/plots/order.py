#!/usr/bin/python3
"""Polar order parameter P = |sum_i n_i| / N of a soft/active run (log.csv's
polar_order column) against time, with the level 1/sqrt(N) of random directors.

Usage: order.py RUN_DIR [--out FILE]   (default RUN_DIR/order.png)
"""
import math

from . import figure
from .run_dir import InputError


def main():
    a, run = figure.open_run(__doc__.split("\n")[0], "order.png")
    out = a.out
    log = run.log(("time", "polar_order"), "order", None if run.soft else (
        f"the polar order is logged by soft/active runs only (dynamics brownian, langevin or "
        f"nve; this run's dynamics is '{run.dynamics}')"))
    t, P = log["time"], log["polar_order"]
    n = run.particle_count()
    if n is None:
        n = len(run.final_frame().types)
    if n <= 0:
        raise InputError(f"{run.path}: the run has no particles")

    plt = figure.pyplot()
    fig, ax = plt.subplots(figsize=(8, 4.8))
    ax.plot(t, P, "-", marker="." if len(t) < 60 else None, color="C0", lw=1.5,
            label="P = |sum n_i| / N (log.csv)")
    # i.i.d. uniform unit vectors: <P^2> = 1/N, so disorder sits near this level
    ax.axhline(1 / math.sqrt(n), color="gray", ls="--", lw=1,
               label=f"random directors, 1/sqrt(N) = {1 / math.sqrt(n):.3g}")
    ax.set_xlabel("time t [time]")
    ax.set_ylabel("polar order parameter P (dimensionless)")
    ax.set_ylim(0, 1.02)
    ax.set_xlim(t.min(), t.max() if t.max() > t.min() else t.min() + 1)
    ax.grid(alpha=0.3)
    ax.legend(loc="best")
    ax.set_title(f"final P = {P[-1]:.3f}, mean of the rows after the first: "
                 f"{P[1:].mean() if len(P) > 1 else P[0]:.3f}")
    figure.title(fig, run, "Polar order")
    fig.tight_layout()
    return figure.save(fig, out)
