"""Dilute ideal particles sedimenting onto a wall floor (issue 50): the far-field decay
rate of the density of active Brownian particles against its exact value, the passive
barometric rate, and the walls carrying the whole weight."""
import json

import numpy as np
from scipy.optimize import brentq

from ...analyze import read_frames
from .. import theory
from ..checks import CaseError, CaseResult, Check
from ..configs import soft_run, table
from ..stats import block_mean
from .active_models import _log_after

WIDTH, HEIGHT, DT = 20.0, 60.0, 0.01  # periodic x, walls at y = +-30; v0 dt = 0.01
FLOOR = 0.5  # the harmonic wall (sigma = the radius) acts on centres closer than this
# (name, v0, D_r, D_t, weight, window of heights above the floor face, relaxation time,
# steps quick and full, tolerance): the active run has mu w / v0 = 0.3, where the
# first-order rate mu w / (D_t + v0^2 / (2 D_r)) = 0.5 is 9 % below the exact 0.5475;
# its window starts where the next decaying solution of the far-field equation (rate
# 3.44) is down by e^(-(3.44 - 0.55) 2.5) ~ 1e-3 on the wall layer, and it relaxes for
# about the sediment's slowest time 4 / (lambda^2 (D_t + v0^2 / (2 D_r))) = 22. The passive
# profile is exactly e^(-w h / T) beyond the wall's reach, even for the Euler-Maruyama
# step (Gaussian steps with a constant drift leave it invariant), and relaxes in 8
RUNS = (("active", 1.0, 1.0, 0.1, 0.3, (3.0, 15.0), 20.0, (12000, 33000), 0.03),
        ("passive", 0.0, 0.0, 0.5, 0.5, (1.0, 9.0), 10.0, (7000, 20000), 0.03))


def _start_file(folder, name, count, rate, seed):
    """A JSON start with x uniform and the heights drawn from the exponential profile of
    ``rate`` above the floor (directors random): only the wall layer and the directors
    are left to relax. Returns the file's name, relative to the run's config."""
    rng = np.random.default_rng(seed)
    x = rng.uniform(-WIDTH / 2, WIDTH / 2, count)
    y = np.minimum(-HEIGHT / 2 + FLOOR + rng.exponential(1.0 / rate, count), HEIGHT / 2 - 1.0)
    particles = [{"id": i, "r": [float(x[i]), float(y[i])]} for i in range(count)]
    folder.mkdir(parents=True, exist_ok=True)
    path = folder / f"{name}_start.json"
    path.write_text(json.dumps({"system": {"box": {"Lx": WIDTH, "Ly": HEIGHT},
                                           "particles": particles}}))
    return path.name


def truncated_exponential_rate(heights, length):
    """The maximum-likelihood rate of an exponential density ~ e^(-lambda h) seen on
    [0, length): the root of mean(h) = 1/lambda - length / (e^(lambda length) - 1)."""
    mean = float(np.mean(heights))
    if not 0.0 < mean < length / 2:
        raise CaseError(f"the window's mean height {mean:g} of {length:g} is no decaying profile")

    def gap(rate):
        return 1.0 / rate - length / np.expm1(rate * length) - mean
    # the right side falls from length / 2 (rate -> 0) to ~1 / rate: 200 / length is far
    # beyond any window this case uses
    return brentq(gap, 1e-6 / length, 200.0 / length, xtol=1e-12)


def _decay_rate(heights, window, blocks=10):
    """The rate fitted to each of ``blocks`` consecutive runs of frames, their mean and
    its standard error."""
    low, high = window
    rates = []
    for block in np.array_split(heights[: len(heights) - len(heights) % blocks], blocks):
        h = block.ravel()
        rates.append(truncated_exponential_rate(h[(h >= low) & (h < high)] - low, high - low))
    return float(np.mean(rates)), float(np.std(rates, ddof=1) / np.sqrt(blocks))


def abp_sedimentation(ctx):
    """Dilute ideal ABPs (2D) under gravity above a harmonic wall floor: the far-field
    density decay rate against the exact root of the Mathieu eigenproblem (and a passive
    control against the barometric w / T), and the walls carrying the whole weight."""
    count = ctx.pick(6000, 10000)
    every = 100  # frames every t = 1
    folder = ctx.workdir / "abp_sedimentation"
    checks, profiles = [], {}
    for name, v0, d_r, d_t, weight, window, t0, steps, tolerance in RUNS:
        steps = ctx.pick(*steps)
        rate = theory.active_sedimentation_rate(v0, d_r, d_t, weight)
        forces = (table("force", "wall", potential="harmonic", k=20.0)
                  + table("force", "gravity", force=weight))
        integrators = table("integrator", "brownian", T=d_t, gamma=1.0)
        if v0 > 0.0:
            forces += table("force", "self_propulsion", alpha=v0)
            integrators += table("integrator", "brownian_rotation", T=d_r, gamma=1.0)
        # (the skin bounds a step: the passive noise, sqrt(2 T dt) = 0.1 per axis, would
        # exceed the default 0.5 somewhere in 10^8 draws and stop the run as a blow-up)
        start = _start_file(folder, name, count, rate, 11)
        config = soft_run(2, "brownian", count, [WIDTH, HEIGHT], 5, steps, DT, 10, every,
                          forces=forces, integrators=integrators, positions="random",
                          extra=f'file = "{start}"\n\n[neighbor_list]\nskin = 2.0\n',
                          boundary=["periodic", "wall"])
        run = ctx.run("abp_sedimentation", name, config)
        traj = read_frames(str(run))
        heights = traj.positions[traj.steps * DT >= t0][:, :, 1] + HEIGHT / 2
        measured, error = _decay_rate(heights, window)
        profiles[name] = (np.histogram(heights.ravel(), bins=60, range=(0.0, 15.0))[0]
                          / (len(heights) * 0.25 * count), rate)
        why = (f"N = {count} started on the exact profile, {len(heights)} frames after t = "
               f"{t0:g}; the maximum-likelihood rate on heights {window[0]:g}-{window[1]:g}, "
               "its error from 10 blocks of frames (each particle's height decorrelates in "
               f"~1 / (lambda^2 D_eff) = {1.0 / (rate ** 2 * (d_t + (v0 ** 2 / (2 * d_r) if v0 else 0))):.2g}): "
               f"~{0.5 if v0 else 0.4} % error")
        if v0 > 0.0:
            first = weight / (d_t + v0 ** 2 / (2.0 * d_r))
            checks.append(Check.near(
                f"far-field decay rate, ABPs (v0 = {v0:g}, D_r = {d_r:g}, D_t = {d_t:g}, "
                f"w = {weight:g})", measured, error, rate, tolerance * rate,
                "Enculescu & Stark 2011: top Mathieu eigenvalue = lambda (mu w - D_t lambda), "
                f"solved here (first order: {first:.4g})",
                why + "; dt = 0.005 and 0.01 gave the same rate (0.5451 +- 0.0025 and 0.5447 "
                "+- 0.0017, N = 10000 to t = 430); 3 %, a third of the first-order "
                "formula's gap"))
        else:
            checks.append(Check.near(
                f"far-field decay rate, passive (T = {d_t:g}, w = {weight:g})", measured,
                error, rate, tolerance * rate, "barometric law: lambda = mu w / T (exact)",
                why + "; no step bias; 3 %"))
        pressure, p_err = block_mean(_log_after(ctx, run, "wall_pressure_y", t0))
        per_area = count * weight / (2.0 * WIDTH)
        noise = (f"the swimmers' push v0 sum_i n_y,i ({100 * v0 / (weight * np.sqrt(2 * count)):.1f} "
                 "% of the weight) decorrelates in 1 / D_r = 1" if v0 else "")
        checks.append(Check.near(
            f"wall_pressure_y / (N w / (2 L_x)), {name}", pressure / per_area,
            p_err / per_area, 1.0, 0.02,
            "force balance: the walls carry the weight (torque-free walls leave <n_y> = 0)",
            "exact at any dt (the step's mean displacement vanishes in the steady state; "
            f"the ceiling, {HEIGHT - 2 * FLOOR:g} up, carries nothing); "
            + (noise + ", so " if noise else "") + "~0.2-0.5 % error from 10 blocks of "
            "the log rows; 2 %"))

    def plot(ax):
        centres = np.linspace(0.0, 15.0, 61)
        centres = 0.5 * (centres[1:] + centres[:-1])
        for label, (profile, rate) in profiles.items():
            shown = np.where(profile > 0, profile, np.nan)  # (empty bins far up)
            line, = ax.semilogy(centres, shown, label=f"{label} pedesis")
            tail = (centres >= 3.0) & (profile > 0)
            ref = np.exp(np.mean(np.log(profile[tail]) + rate * centres[tail]))
            ax.semilogy(centres, ref * np.exp(-rate * centres), "--", color=line.get_color(),
                        label=f"e^(-{rate:.4g} h)")
        ax.set(xlabel="height h above the floor", ylabel="density")
        ax.legend(fontsize=8)

    times = ", ".join(f"{r[0]} to t = {ctx.pick(*r[7]) * DT:g}" for r in RUNS)
    ran = (f"2D ideal particles, N = {count} in {WIDTH:g} x {HEIGHT:g}, walls on y (harmonic, "
           f"k = 20), gravity; ABPs v0 = 1, D_r = 1, D_t = 0.1, w = 0.3; passive T = 0.5, "
           f"w = 0.5; dt = {DT}, {times}")
    return CaseResult("abp_sedimentation", "Active sedimentation", ran, checks, plot)
