"""Active Brownian particles: free-particle dynamics and swim pressure against exact
results, and motility-induced phase separation."""
import numpy as np

from ...analyze import (Box, fraction_bins, histogram_peaks, local_area_fraction,
                         phase_fractions, read_frames)
from .. import theory
from ..checks import CaseResult, Check
from ..configs import box_length, soft_run, table
from ..stats import sample_mean


def _free_abp_config(dimension, count, length, steps, dt, every):
    """Free ABPs: self-propulsion alpha = 1, gamma = 1 (v0 = 1), D_r = 1, D_t = 0.1."""
    forces = table("force", "self_propulsion", alpha=1.0)
    integrators = (table("integrator", "brownian", T=0.1, gamma=1.0)
                   + table("integrator", "brownian_rotation", T=1.0, gamma=1.0))
    return soft_run(dimension, "brownian", count, length, 5, steps, dt, every, every,
                    forces=forces, integrators=integrators)


def free_abp(ctx):
    """MSD, orientation correlation and swim pressure of free ABPs (2D; 3D in the full
    suite), each from the per-particle values of the GSD frames, so that every check has
    the standard error of its mean over particles."""
    count = ctx.pick(20000, 50000)
    dt, steps, every = 0.002, 2500, 250  # t = 5, frames every 0.5
    checks, curves = [], {}
    for dimension in ctx.pick((2,), (2, 3)):
        length = 100.0
        run = ctx.run("free_abp", f"{dimension}d",
                      _free_abp_config(dimension, count, length, steps, dt, every))
        traj = read_frames(str(run))
        t = traj.steps * dt
        x = traj.unwrapped()
        n = traj.directors
        tau = 1.0 / (dimension - 1)
        dr2 = ((x - x[:1]) ** 2).sum(axis=2)
        dot = (n * n[:1]).sum(axis=2)
        swim = (n * (x - x[:1])).sum(axis=2) * count / (dimension * length ** dimension)
        msd_m = [sample_mean(dr2[k]) for k in range(len(t))]
        curves[dimension] = (t, np.array([m for m, _ in msd_m]))
        why_msd = (f"N = {count}: one particle's r^2 has a relative spread ~1, so the mean's "
                   f"error is ~{100 / np.sqrt(count):.1f} %; Euler-Maruyama's bias is "
                   f"O((d-1) D_r dt) = {100 * (dimension - 1) * dt:.1f} %; 3 %")
        for k in (1, 2, len(t) - 1):  # t = 0.5, 1 and 5 tau (2D)
            ref = float(theory.free_abp_msd(t[k], dimension, 0.1, 1.0, 1.0))
            checks.append(Check.near(f"{dimension}D MSD at t = {t[k]:g}", msd_m[k][0], msd_m[k][1],
                                     ref, 0.03 * ref, "ten Hagen et al. 2011 (exact)", why_msd))
        k = 2
        m, e = sample_mean(dot[k])
        spread = 0.7 / np.sqrt(count)
        checks.append(Check.near(f"{dimension}D <n(t).n(0)> at t = {t[k]:g}", m, e,
                                 float(theory.free_abp_orientation(t[k], dimension, 1.0)),
                                 4 * spread, "rotational diffusion (exact)",
                                 f"N = {count}: standard error below 0.7/sqrt(N) = "
                                 f"{spread:.4f}, the tolerance 4 of them; the step's own bias "
                                 "is below 1e-6 here (2D exact, 3D second order in D_r dt)"))
        density = count / length ** dimension
        k = len(t) - 1
        m, e = sample_mean(swim[k])
        ref = float(theory.swim_pressure(t[k], dimension, density, 1.0, 1.0, 1.0))
        checks.append(Check.near(
            f"{dimension}D swim pressure at t = {t[k]:g} (= {t[k] / tau:g} tau_R)", m, e, ref,
            0.05 * ref, "Takatori, Yan & Brady 2014; steady value "
            f"{density / (dimension * (dimension - 1)):.4g}",
            f"N = {count}: n.dr has a spread ~1.6 v0 tau against a mean ~v0 tau, so the mean's "
            f"error is ~{160 / np.sqrt(count):.1f} %; 5 % holds it 3 times and the "
            "integrator's O(D_r dt) bias"))

    def plot(ax):
        for dim, (tt, msd) in curves.items():
            fine = np.linspace(0.0, tt[-1], 200)
            ax.plot(fine, theory.free_abp_msd(fine, dim, 0.1, 1.0, 1.0), label=f"{dim}D theory")
            ax.plot(tt, msd, "o", label=f"{dim}D pedesis")
        ax.set(xlabel="time", ylabel="MSD")
        ax.legend()

    ran = (f"free ABPs, N = {count}, v0 = 1, D_r = 1, D_t = 0.1, dt = {dt}, t = 5 "
           f"({', '.join(f'{d}D' for d in curves)})")
    return CaseResult("free_abp", "Free active Brownian particles", ran, checks, plot)


def mips(ctx):
    """Motility-induced phase separation of repulsive ABPs at area fraction 0.6 and Peclet
    number v0 / (D_r sigma) = 100: the histogram of local area fractions must have a gas
    peak and a dense peak; the same system at Pe = 5 (a twentieth of the swim force) must
    stay homogeneous, with one."""
    count, t_end = ctx.pick((2000, 120.0), (10000, 300.0))
    phi, dt = 0.6, 0.002
    length = box_length(2, count, 0.5, phi)
    steps = int(round(t_end / dt))
    frames = 10
    integrators = (table("integrator", "brownian", T=0.00333, gamma=1.0)
                   + table("integrator", "brownian_rotation", T=0.01, gamma=1.0))

    def cells_of(name, alpha):
        forces = table("force", "harmonic", k=50.0) + table("force", "self_propulsion", alpha=alpha)
        config = soft_run(2, "brownian", count, length, 1, steps, dt, steps // 100,
                          steps // (2 * frames), forces=forces, integrators=integrators,
                          extra="min_distance = 0.8\n")
        traj = read_frames(str(ctx.run("mips", name, config)))
        return [local_area_fraction(x, 0.5, traj.box, 5.0) for x in traj.positions[-frames:]]

    cells = cells_of("pe100", 1.0)
    grid = fraction_bins(0.5, Box((length, length)), 5.0)
    _, centres, density = histogram_peaks(np.concatenate(cells), *grid)
    phases = phase_fractions(cells, *grid)
    why = (f"the last {frames} frames (t > {t_end / 2:g}, after coarsening to a few clusters): "
           "their pooled histogram's two peaks and the minimum between them split the cells "
           "of each frame into the phases; the scatter of each phase's mean over the frames "
           "is the error")
    source = "Stenhammar et al. 2014, Digregorio et al. 2018: coexisting gas and dense phases"
    checks = []
    for k, (label, lower, upper) in enumerate((("gas", 0.0, 0.35), ("dense", 0.75, 1.1))):
        m, e = (float("nan"), float("inf")) if phases is None else sample_mean(phases[k])
        checks.append(Check(f"mean local area fraction of the {label} phase", m, e,
                            f"{lower:g} to {upper:g}", source, lower, upper, why, max_error=0.05))
    threshold = None if phases is None else phases[2]
    control = cells_of("pe5", 0.05)
    control_peaks = len(histogram_peaks(np.concatenate(control), *grid, min_share=0.05,
                                        smooth=5)[0])
    checks.append(Check("peaks of the local area fraction at Pe = 5", control_peaks, 0.0, "1",
                        "a homogeneous active fluid below the MIPS threshold (Pe ~ 40)", 1, 1,
                        "the same histogram as above, which must not find two phases where "
                        "there are none"))

    def plot(ax):
        ax.plot(centres, density)
        if threshold is not None:
            ax.axvline(threshold, color="grey", lw=0.5, label="phase boundary")
        ax.set(xlabel="local area fraction (cells of 5 sigma)", ylabel="probability density")

    ran = (f"2D ABPs, N = {count}, area fraction {phi}, harmonic k = 50, Pe = v0/(D_r sigma) = "
           f"100, t = {t_end:g}")
    return CaseResult("mips", "Motility-induced phase separation", ran, checks, plot)
