#!/usr/bin/python3
"""Energies, temperatures and pressures of a run's log.csv against time, and, for
hard-particle runs, against collisions per particle as well. Plots whatever of these
columns the log has (event, stepped and soft runs log different ones).

Usage: thermo.py RUN_DIR [--out FILE]   (default RUN_DIR/thermo.png)
"""

from . import figure
from .run_dir import InputError


# the pressure tensor's components: a panel of their own
_TENSOR = {f"pressure_{a}{b}" for a in "xyz" for b in "xyz"}


def panels(log, dim):
    """(title, y label, columns) for each quantity the log has, in a fixed order."""
    density = "energy/area" if dim == 2 else "energy/volume"
    groups = [
        ("kinetic energy", "kinetic energy K [energy]", "kinetic_energy"),
        ("potential energy", "potential energy U [energy]", "potential_energy"),
        ("temperature", "temperature T [energy] (k_B = 1)", "temperature"),
        ("pressure", f"pressure P [{density}]", "pressure"),
    ]
    out = []
    for title, ylabel, prefix in groups:
        cols = [c for c in log
                if (c == prefix or c.startswith(prefix + "_")) and c not in _TENSOR]
        if prefix in ("kinetic_energy", "temperature") and len(cols) == 2 and prefix in cols:
            cols = [prefix]  # one species: its column repeats the total
        if cols:
            out.append((title, ylabel, cols))
    tensor = [c for c in log if c in _TENSOR]
    if tensor:
        out.append(("pressure tensor", f"P_ab [{density}]", tensor))
    return out


# what the pressure columns of docs/formats.md are, for the legend
_PRESSURE_LABELS = {
    "pressure": "P (total)",
    "pressure_ideal": "ideal gas, N T / V",
    "pressure_virial": "virial of the pair forces",
    "pressure_active": "active (swim) pressure",
    "pressure_running": "running mean since t = 0",
}


def label(column, prefix_title):
    """'temperature_A' -> 'A' (a species); the bare column is the total."""
    if column in _PRESSURE_LABELS:
        return _PRESSURE_LABELS[column]
    if column in _TENSOR:
        return "P_" + column[len("pressure_"):]
    prefix = prefix_title.replace(" ", "_")
    return "total" if column == prefix else column[len(prefix) + 1:]


def main():
    a, run = figure.open_run(__doc__.split("\n")[0], "thermo.png")
    out = a.out
    log_path = run.path / "log.csv"
    log = run.log(("time",), "thermo")
    rows = panels(log, run.dimension)
    if not rows:
        raise InputError(f"{log_path}: none of the columns thermo plots (kinetic_energy*, "
                         f"potential_energy, temperature*, pressure*); the log has: "
                         f"{', '.join(log)}")
    # hard-particle logs give the pressure of the interval since the previous row, 0 in
    # the first row by definition: draw it as steps over its interval, and leave out
    # row 0 of every pressure measured from collisions
    interval_pressure = "collisions" in log
    axes_x = [("time", "time t [time]")]
    if "collisions_per_particle" in log:
        axes_x.append(("collisions_per_particle", "pair collisions per particle"))

    plt = figure.pyplot()
    ncols, nrows = len(rows), len(axes_x)
    fig, axes = plt.subplots(nrows, ncols, figsize=(4.3 * ncols + 0.5, 3.4 * nrows + 1.0),
                             squeeze=False)
    marker = "." if len(log["time"]) < 40 else None
    for r, (xcol, xlabel) in enumerate(axes_x):
        x = log[xcol]
        for c, (title, ylabel, cols) in enumerate(rows):
            ax = axes[r][c]
            for k, col in enumerate(cols):
                y = log[col]
                style = dict(color="k" if k == 0 else f"C{k - 1}", lw=1.6 if k == 0 else 1.1,
                             label=label(col, title))
                skip_first = (title.startswith("pressure") and interval_pressure
                              and col != "pressure_ideal")
                if skip_first and col == "pressure":
                    ax.step(x[1:], y[1:], where="pre", **style)
                elif skip_first:
                    ax.plot(x[1:], y[1:], marker=marker, **style)
                else:
                    ax.plot(x, y, marker=marker, **style)
            if title == "pressure":
                _equation_of_state(run, log, x, ax)
            ax.set_xlabel(xlabel)
            ax.set_ylabel(ylabel)
            if r == 0:
                ax.set_title(title + (" (mean over each log interval)"
                                      if title.startswith("pressure") and interval_pressure
                                      else ""))
            if len(cols) > 1:
                ax.legend()
            ax.grid(alpha=0.3)
    figure.title(fig, run, "Thermodynamics")
    fig.tight_layout()
    return figure.save(fig, out)


def _equation_of_state(run, log, x, ax):
    """The hard-particle equation of state Z(eta) N T / V of summary.json, the pressure
    the collisions should give in equilibrium (walls shift it by O(sigma/L))."""
    Z = run.summary().get("compressibility_equation_of_state")
    if Z is None or "pressure_ideal" not in log:
        return
    name = "Henderson" if run.dimension == 2 else "Carnahan-Starling"
    ax.plot(x, Z * log["pressure_ideal"], color="gray", ls="--", lw=1.2,
            label=f"{name} equation of state, Z = {Z:.4g}")
