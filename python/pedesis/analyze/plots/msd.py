#!/usr/bin/python3
"""Mean squared displacement of a run (log.csv's msd column); for a brownian or langevin
run, against the exact MSD of free active Brownian particles with its parameters:

    MSD(t) = 2 d D_t t + 2 v0^2 tau^2 (t/tau - 1 + exp(-t/tau)),  tau = 1/((d-1) D_r),

v0 = alpha/gamma, D_t = T/gamma (brownian or langevin integrator), D_r = T_r/gamma_r
(brownian_rotation), from RUN_DIR/config.toml. Log-log axes.

Usage: msd.py RUN_DIR [--out FILE]   (default RUN_DIR/msd.png)
"""

import numpy as np

from . import figure
from .run_dir import InputError


def free_abp_msd(t, dim, Dt, v0, Dr):
    """The free-ABP MSD; with D_r = 0 the directors never turn and the active part is
    ballistic, v0^2 t^2 (the tau -> infinity limit)."""
    t = np.asarray(t, dtype=float)
    if Dr == 0:
        return 2 * dim * Dt * t + v0 * v0 * t * t
    tau = 1.0 / ((dim - 1) * Dr)
    x = t / tau
    # x - 1 + e^-x loses every digit to cancellation for small x; its series does not
    small = x < 1e-3
    g = np.where(small, x * x / 2 - x ** 3 / 6 + x ** 4 / 24, x + np.expm1(-np.where(small, 0, x)))
    return 2 * dim * Dt * t + 2 * v0 * v0 * tau * tau * g


class Parameters:
    """D_t, v0 and D_r of one species (or of all, when no parameter is per species)."""

    def __init__(self, name, Dt, v0, Dr):
        self.name, self.Dt, self.v0, self.Dr = name, Dt, v0, Dr

    def text(self, dim):
        tau = "inf" if self.Dr == 0 else f"{1.0 / ((dim - 1) * self.Dr):.4g}"
        who = "" if self.name is None else f"{self.name}: "
        return f"{who}D_t = {self.Dt:.4g}, v0 = {self.v0:.4g}, D_r = {self.Dr:.4g}, tau = {tau}"


def value(x, species, where):
    """A per-species parameter's value for one species (species None: the value is the
    same for all)."""
    if isinstance(x, dict):
        if species is None or species not in x:
            raise InputError(f"{where}: no value for species {species}")
        x = x[species]
    try:
        return float(x)
    except (TypeError, ValueError):
        raise InputError(f"{where}: a parameter is not a number: {x!r}") from None


def parameters(run, config_path):
    """The Parameters of each species, with the weights (shares of N) the log's MSD, a
    mean over all particles, averages their curves with; a single entry for all species
    when no parameter is given per species."""
    position = run.plugin("integrator", run.dynamics)
    if position is None:
        raise InputError(f"{config_path}: no [[integrator]] named '{run.dynamics}'")
    rotation = run.plugin("integrator", "brownian_rotation")
    propulsion = [f for f in run.plugins("force") if f.get("name") == "self_propulsion"]
    entries = [position.get("T"), position.get("gamma")] + [p.get("alpha") for p in propulsion]
    if rotation:
        entries += [rotation.get("T"), rotation.get("gamma")]
    if any(e is None for e in entries):
        raise InputError(f"{config_path}: an integrator or self_propulsion lacks T, gamma "
                         "or alpha")
    per_species = any(isinstance(e, dict) for e in entries)
    names, weights = [None], [1.0]
    if per_species:
        names, weights = species_weights(run)

    out = []
    for s in names:
        gamma = value(position["gamma"], s, config_path)
        Dt = value(position["T"], s, config_path) / gamma
        # several self_propulsion entries add up (docs/engines.md)
        v0 = sum(value(p["alpha"], s, config_path) for p in propulsion) / gamma
        Dr = 0.0
        if rotation:
            Dr = value(rotation["T"], s, config_path) / value(rotation["gamma"], s, config_path)
        out.append(Parameters(s, Dt, v0, Dr))
    return out, weights


def species_weights(run):
    """Species names and their share of N, from [[species]] counts or else the final
    frame's particle types."""
    species = run.config.get("species", [])
    counts = [s.get("count") for s in species]
    if species and all(isinstance(c, int) for c in counts):
        names = run.species_names()[:len(species)]
        total = sum(counts)
        return names, [c / total for c in counts]
    frame = run.final_frame()
    kinds, counts = np.unique(frame.types, return_counts=True)
    return [frame.names[k] for k in kinds], list(counts / counts.sum())


def main():
    a, run = figure.open_run(__doc__.split("\n")[0], "msd.png")
    out = a.out
    log_path = run.path / "log.csv"
    elsewhere = None if run.soft else (
        f"this '{run.dynamics}' run was made before event and stepped runs logged the MSD; "
        "run it again, or from frames written often enough, "
        "pa.msd(pa.unwrap(traj.positions, traj.box)) in Python, docs/analyze.md")
    log = run.log(("time", "msd"), "msd", elsewhere)
    keep = (log["time"] > 0) & (log["msd"] > 0)
    if not keep.any():
        raise InputError(f"{log_path}: no row with t > 0 and msd > 0 to draw on log axes")
    t, msd = log["time"][keep], log["msd"][keep]
    dim = run.dimension

    reference = run.dynamics in ("brownian", "langevin")
    params, weights = parameters(run, run.path / "config.toml") if reference else ([], [])
    interactions = sorted({p.get("name", "?") for p in run.plugins("force")
                           if p.get("name") != "self_propulsion"} |
                          {p.get("name", "?") for p in run.plugins("torque")})

    plt = figure.pyplot()
    fig, (ax, ax_ratio) = plt.subplots(2, 1, figsize=(7.5, 7.0), sharex=True,
                                       gridspec_kw={"height_ratios": [3, 1]})
    ax.loglog(t, msd, "o", ms=3.5, color="C0", label="measured (log.csv)")
    if reference:
        tt = np.geomspace(t.min(), t.max(), 400)
        curve = sum(w * free_abp_msd(tt, dim, p.Dt, p.v0, p.Dr) for p, w in zip(params, weights))
        at_t = sum(w * free_abp_msd(t, dim, p.Dt, p.v0, p.Dr) for p, w in zip(params, weights))
        what = ("free-particle reference (the run has interactions: "
                f"{', '.join(interactions)})" if interactions else "free ABP, exact")
        if run.dynamics == "langevin":
            what += "; overdamped limit, valid for t >> m/gamma"
        ax.loglog(tt, curve, "k-", lw=1.5, label=what)
        for p in params:
            ax.plot([], [], " ", label=p.text(dim))
            if p.Dr > 0 and len(params) == 1:
                tau = 1.0 / ((dim - 1) * p.Dr)
                if t.min() <= tau <= t.max():
                    ax.axvline(tau, color="gray", ls=":", lw=1)
                    ax.text(tau, ax.get_ylim()[0], " tau", color="gray", va="bottom")
        with np.errstate(divide="ignore", invalid="ignore"):
            ax_ratio.semilogx(t, msd / at_t, "o", ms=3, color="C0")
        ax_ratio.axhline(1.0, color="k", lw=1)
        ax_ratio.set_ylabel("measured / reference")
    else:
        why = ("hard particles: their D is measured by [transport]"
               if run.dynamics in ("event", "stepped") else
               f"'{run.dynamics}' dynamics has no friction, so no free-ABP diffusion")
        ax.plot([], [], " ", label=f"no reference curve: {why}")
        ax_ratio.set_visible(False)
        ax.tick_params(labelbottom=True)
        ax.set_xlabel("time t [time]")
    ax.set_ylabel("mean squared displacement [length^2]")
    ax.legend(loc="upper left")
    ax.grid(alpha=0.3, which="both")
    ax_ratio.set_xlabel("time t [time]")
    ax_ratio.grid(alpha=0.3, which="both")
    figure.title(fig, run, "Mean squared displacement")
    fig.tight_layout()
    return figure.save(fig, out)
