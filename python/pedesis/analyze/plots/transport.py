#!/usr/bin/python3
"""Transport coefficients of a run with a [transport] table: each coefficient's running
estimate (transport.csv) against the lag, the fit window, the value with its error and,
for one-species hard particles, Enskog's value (summary.json's "transport").

Prints one line per coefficient (value +- error, Enskog beside it) and the fit window.

Usage: transport.py RUN_DIR [--out FILE]   (default RUN_DIR/transport.png)
"""
import math

from . import figure
from .run_dir import InputError
from .transport_files import COEFFICIENTS, read_curves, read_summary

SYMBOLS = {"diffusion": "D", "shear_viscosity": "eta", "bulk_viscosity": "kappa",
           "thermal_conductivity": "lambda"}


def units(name, dimension):
    """The axis unit of a coefficient (k_B = 1)."""
    size = "area" if dimension == 2 else "volume"
    return {"diffusion": "length^2/time", "shear_viscosity": f"energy time/{size}",
            "bulk_viscosity": f"energy time/{size}",
            "thermal_conductivity": f"k_B/{'time' if dimension == 2 else '(length time)'}"}[name]


def text_lines(summary):
    """The printed result: a line per coefficient of summary.json, then the window."""
    lines = []
    for name, c in summary["coefficients"].items():
        if c["value"] is None:
            lines.append(f"{name}: not measured ({c['why']})")
            continue
        notes = [] if c["error"] is not None else ["no error: fewer than 2 blocks"]
        enskog = summary["enskog"].get(name)
        if enskog is not None:
            notes.append(f"Enskog {enskog:.5g}, ratio {c['value'] / enskog:.3f}")
        if name == "diffusion_infinite":
            notes.append("Yeh-Hummer, the infinite system")
        error = f" +- {c['error']:.2g}" if c["error"] is not None else ""
        lines.append(f"{name}: {c['value']:.5g}{error}"
                     + (f" ({'; '.join(notes)})" if notes else ""))
    if "fit_window" in summary:
        low, high = summary["fit_window"]
        extra = [f"{summary['blocks']:g} blocks"] if "blocks" in summary else []
        if "interval" in summary:
            extra.append(f"interval {summary['interval']:g}")
        lines.append(f"fit window: lag {low:g} to {high:g}"
                     + (f" ({', '.join(extra)})" if extra else ""))
    return lines


def main():
    a, run = figure.open_run(__doc__.split("\n")[0], "transport.png")
    curves = read_curves(run.path / "transport.csv")
    summary = read_summary(run)
    coefficients = summary["coefficients"]
    shown = [n for n in COEFFICIENTS if n in curves or (
        n in coefficients and coefficients[n]["value"] is not None)]
    if not shown:
        reasons = "; ".join(f"{n}: {c['why']}" for n, c in coefficients.items()) or "none given"
        raise InputError(f"{run.path}: no transport coefficient to draw: transport.csv has no "
                         f"curve and summary.json no value ({reasons})")
    for line in text_lines(summary):
        print(line)

    plt = figure.pyplot()
    cols = 1 if len(shown) == 1 else 2
    rows = math.ceil(len(shown) / cols)
    fig, axes = plt.subplots(rows, cols, figsize=(6.5 * cols, 4.2 * rows + 0.8), squeeze=False)
    for ax in axes.flat[len(shown):]:
        ax.set_visible(False)
    for ax, name in zip(axes.flat, shown):
        _panel(ax, name, curves, summary, run.dimension)
    figure.title(fig, run, "Transport coefficients")
    fig.tight_layout()
    return figure.save(fig, a.out)


def _panel(ax, name, curves, summary, dimension):
    symbol = SYMBOLS[name]
    c = summary["coefficients"].get(name, {"value": None, "error": None,
                                           "why": "summary.json has no entry"})
    drawn = False
    if name in curves:
        lag, _, running = curves[name]
        keep = lag > 0
        ax.plot(lag[keep], running[keep], "-", color="C0", lw=1.5,
                label="running estimate (local slope of the moment)")
        drawn = keep.any()
    if name == "diffusion" and "velocity_autocorrelation" in curves:
        lag, _, running = curves["velocity_autocorrelation"]
        keep = lag > 0
        ax.plot(lag[keep], running[keep], "-", color="C1", lw=1.2,
                label="(1/d) int <v(0).v(t)> dt (velocity autocorrelation)")
        drawn = drawn or keep.any()
    if "fit_window" in summary:
        ax.axvspan(*summary["fit_window"], color="gray", alpha=0.15, label="fit window")
    if c["value"] is not None:
        v, e = c["value"], c["error"]
        if e is not None:
            ax.axhspan(v - e, v + e, color="C2", alpha=0.25)
        ax.axhline(v, color="C2", lw=1.5, label=f"{symbol} = {v:.4g}"
                   + (f" +- {e:.2g}" if e is not None else " (no error)"))
        ax.set_title(name.replace("_", " "))
    else:
        ax.set_title(f"{name.replace('_', ' ')}: not measured ({c['why']})")
    enskog = summary["enskog"].get(name)
    if enskog is not None:
        ax.axhline(enskog, color="k", ls="--", lw=1.2, label=f"Enskog {enskog:.4g}")
    infinite = summary["coefficients"].get("diffusion_infinite", {}).get("value")
    if name == "diffusion" and infinite is not None:
        ax.axhline(infinite, color="C3", ls=":", lw=1.5,
                   label=f"Yeh-Hummer D_inf {infinite:.4g}")
    ax.set_xscale("log")
    if not drawn:
        # no curve: the window, or a decade, gives the log axis its range
        low, high = summary.get("fit_window", (0.1, 1.0))
        ax.set_xlim(max(low, high / 100) / 3, high * 3)
    ax.set_xlabel("lag [time]")
    ax.set_ylabel(f"{symbol} [{units(name, dimension)}]")
    ax.grid(alpha=0.3, which="both")
    ax.legend(loc="best")

