"""Active models beyond free ABPs (issue 50), each against an exact result: ideal ABPs
between walls (Solon et al.'s wall pressure), ABPs in a harmonic trap (<r^2>), and the
free MSD of chiral ABPs, run-and-tumble particles and active Ornstein-Uhlenbeck
particles."""
import numpy as np

from ...analyze import read_frames
from .. import theory
from ..checks import CaseError, CaseResult, Check
from ..configs import soft_run, table
from ..stats import block_mean, ratio_error, sample_mean

V0, D_T = 1.0, 0.01  # swim speed (alpha = gamma = 1) and translational diffusion


def _integrators(d_t, d_r=None):
    rotation = "" if d_r is None else table("integrator", "brownian_rotation", T=d_r, gamma=1.0)
    return table("integrator", "brownian", T=d_t, gamma=1.0) + rotation


def _log_after(ctx, run, column, t0):
    log = ctx.log(run)
    if column not in log:
        raise CaseError(f"{run}/log.csv has no column {column}")
    return log[column][log["time"] >= t0]


def abp_walls(ctx):
    """Ideal ABPs between two flat walls: the pressure on the walls (wall_pressure_x) against
    Solon et al.'s n_bulk (D_t + v0^2 / (d (d-1) D_r)) / mu for a torque-free wall, WCA
    and harmonic, and below it for a wall that turns the swimmers away."""
    count, height = ctx.pick((2000, 80.0), (8000, 320.0))
    width, d_r, dt, steps, t0 = 20.0, 0.5, 0.005, 40000, 50.0  # t = 200
    every = 500  # a frame every t = 2.5
    checks, profiles = [], {}
    walls = (("wca", {}, 0.0), ("harmonic", {"k": 20.0}, 0.0), ("harmonic", {"k": 20.0}, 1.0))
    for potential, keys, torque in walls:
        name = f"{potential}{'_torque' if torque else ''}"
        wall = table("force", "wall", potential=potential, **keys,
                     **({"torque": torque} if torque else {}))
        config = soft_run(2, "brownian", count, [width, height], 1, steps, dt, 20, every,
                          forces=table("force", "self_propulsion", alpha=V0) + wall,
                          integrators=_integrators(D_T, d_r), boundary=["wall", "periodic"])
        run = ctx.run("abp_walls", name, config)
        pressure, p_err = block_mean(_log_after(ctx, run, "wall_pressure_x", t0))
        traj = read_frames(str(run))
        x = traj.positions[traj.steps * dt >= t0][:, :, 0]
        bulk, b_err = block_mean((np.abs(x) < width / 4).sum(axis=1) / (0.5 * width * height))
        per_bulk = theory.active_wall_pressure(2, 1.0, D_T, V0, d_r, 1.0)
        ratio, r_err = ratio_error(pressure, p_err, bulk * per_bulk, b_err * per_bulk)
        profiles[name] = np.histogram(x.ravel(), bins=40, range=(-width / 2, width / 2))[0] / (
            len(x) * width / 40 * height)
        label = f"{potential} wall{', torque c = 1' if torque else ''}"
        why = (f"N = {count}, {len(x)} frames after t = {t0:g} (the wall layers fill by "
               f"diffusion across the channel, L^2 / D_eff ~ 100): ~1 % error from 10 "
               "blocks of the log rows and of the middle's density (|x| < L/4); the "
               "step's bias is O(D_r dt) = 0.25 %")
        if torque:
            checks.append(Check(f"P / Solon's value, {label}", ratio, r_err, "below 0.85",
                                "Solon et al. 2015: walls that exert torques break the "
                                "equation of state", 0.0, 0.85,
                                why + "; c = 1 turns a swimmer pressing on the wall away "
                                "within ~1 / (c alpha) = 1, faster than D_r", 0.05))
        else:
            checks.append(Check.near(f"P / (n_bulk (D_t + v0^2 / (2 D_r)) / mu), {label}", ratio,
                                     r_err, 1.0, 0.05, "Solon et al., Nature Physics 11, 673 "
                                     "(2015) (exact for ideal ABPs)", why))

    def plot(ax):
        centres = np.linspace(-width / 2, width / 2, 41)
        centres = 0.5 * (centres[1:] + centres[:-1])
        for label, profile in profiles.items():
            ax.plot(centres, profile, label=label)
        ax.set(xlabel="x (walls at +-10)", ylabel="density")
        ax.legend()

    ran = (f"2D ideal ABPs, N = {count} in {width:g} x {height:g}, walls on x, v0 = 1, "
           f"D_r = {d_r}, D_t = {D_T}, dt = {dt}, t = {steps * dt:g}")
    return CaseResult("abp_walls", "Active pressure on walls", ran, checks, plot)


def abp_trap(ctx):
    """Ideal ABPs in an isotropic harmonic trap: the stationary <r^2> (from the log's
    trap_energy) against d D_t / kappa + v0^2 / (kappa (kappa + (d - 1) D_r))
    (2D; 3D in the full suite)."""
    count, kappa, d_r, dt, steps, t0 = 2000, 1.0, 0.2, 0.01, 5000, 20.0  # t = 50
    checks, series = [], {}
    for dimension in ctx.pick((2,), (2, 3)):
        forces = (table("force", "self_propulsion", alpha=V0)
                  + table("force", "harmonic_trap", k=kappa))
        config = soft_run(dimension, "brownian", count, 20.0, 1, steps, dt, 50, steps,
                          forces=forces, integrators=_integrators(2 * D_T, d_r))
        run = ctx.run("abp_trap", f"{dimension}d", config)
        log = ctx.log(run)
        if "trap_energy" not in log:
            raise CaseError(f"{run}/log.csv has no column trap_energy")
        r2 = 2.0 * log["trap_energy"] / (kappa * count)
        series[dimension] = (log["time"], r2)
        m, e = block_mean(r2[log["time"] >= t0])
        ref = theory.trapped_abp_r2(dimension, 2 * D_T, V0, d_r, kappa)
        checks.append(Check.near(
            f"{dimension}D <r^2>", m, e, ref, 0.02 * ref,
            "closed form (the position filters the director's exponential correlation)",
            f"N = {count}, t = {t0:g} to {steps * dt:g}: error ~0.3 % from 10 blocks; "
            f"Euler-Maruyama's bias is O(kappa dt / 2) = {50 * kappa * dt:.1f} %; 2 %"))

    def plot(ax):
        for dim, (t, r2) in series.items():
            ax.plot(t, r2, label=f"{dim}D pedesis")
            ax.axhline(theory.trapped_abp_r2(dim, 2 * D_T, V0, d_r, kappa), ls="--",
                       color="grey")
        ax.set(xlabel="time", ylabel="<r^2>", ylim=(0, 2))
        ax.legend()

    ran = (f"ideal ABPs, N = {count}, trap kappa = {kappa}, v0 = 1, D_r = {d_r}, "
           f"D_t = {2 * D_T}, dt = {dt}, t = {steps * dt:g}")
    return CaseResult("abp_trap", "ABPs in a harmonic trap", ran, checks, plot)


def _free_msd(ctx, case, extra_terms, reference, times, label, dimension=2,
              active=table("force", "self_propulsion", alpha=V0), prefix=""):
    """Runs free swimmers (2D unless ``dimension``, N = 20000, t = 10, frames every 0.5)
    driven by the ``active`` [[force]] tables, with the given extra [[torque]] /
    [[integrator]] tables, and checks the MSD at ``times`` against ``reference(t)``, each
    with its standard error over particles (``prefix`` opens their names); returns the
    checks and the curve."""
    count, dt, steps, every = 20000, 0.01, 1000, 50
    config = soft_run(dimension, "brownian", count, 400.0 if dimension == 2 else 60.0, 3,
                      steps, dt, every, every, forces=active,
                      integrators=_integrators(D_T) + extra_terms)
    traj = read_frames(str(ctx.run(case, f"{dimension}d", config)))
    t = traj.steps * dt
    x = traj.unwrapped()
    dr2 = ((x - x[:1]) ** 2).sum(axis=2)
    checks = []
    for when in times:
        k = int(np.argmin(np.abs(t - when)))
        m, e = sample_mean(dr2[k])
        ref = float(reference(t[k]))
        checks.append(Check.near(f"{prefix}MSD at t = {t[k]:g}", m, e, ref, 0.03 * ref, label,
                                 f"N = {count}: one particle's r^2 has a relative spread "
                                 f"~1, so ~{100 / np.sqrt(count):.1f} % error; the step's "
                                 "bias is O(dt) = 1 %; 3 %"))
    return checks, (t, np.array([dr2[k].mean() for k in range(len(t))]))


def _msd_plot(curve, reference):
    t, msd = curve

    def plot(ax):
        fine = np.linspace(0.0, t[-1], 300)
        ax.plot(fine, reference(fine), label="theory")
        ax.plot(t, msd, "o", label="pedesis")
        ax.set(xlabel="time", ylabel="MSD")
        ax.legend()
    return plot


def chiral_abp(ctx):
    """Free chiral ABPs (active_torque, omega = 1, D_r = 0.1): the MSD's circles and its
    diffusive rise against van Teeffelen & Lowen's closed form."""
    d_r, omega = 0.1, 1.0
    terms = (table("torque", "active_torque", torque=omega)
             + table("integrator", "brownian_rotation", T=d_r, gamma=1.0))

    def reference(t):
        return theory.chiral_abp_msd(t, D_T, V0, d_r, omega)
    checks, curve = _free_msd(ctx, "chiral_abp", terms, reference, (1.0, 3.0, 6.0, 10.0),
                              "van Teeffelen & Lowen, PRE 78, 020101 (2008) (exact)")
    ran = f"2D chiral ABPs, N = 20000, v0 = 1, omega = {omega}, D_r = {d_r}, D_t = {D_T}, t = 10"
    return CaseResult("chiral_abp", "Chiral active Brownian particles", ran, checks,
                      _msd_plot(curve, reference))


def run_and_tumble(ctx):
    """Free run-and-tumble particles (tumble rate 0.5): the MSD against the ABP form with
    (d - 1) D_r replaced by the tumble rate."""
    rate = 0.5

    def reference(t):
        return theory.run_and_tumble_msd(t, 2, D_T, V0, rate)
    checks, curve = _free_msd(ctx, "run_and_tumble",
                              table("integrator", "run_and_tumble", rate=rate), reference,
                              (1.0, 2.0, 5.0, 10.0),
                              "<v(t).v(0)> = v0^2 e^(-lambda t) (exact)")
    ran = f"2D run-and-tumble particles, N = 20000, v0 = 1, lambda = {rate}, D_t = {D_T}, t = 10"
    return CaseResult("run_and_tumble", "Run-and-tumble particles", ran, checks,
                      _msd_plot(curve, reference))


def aoup_msd(ctx):
    """Free active Ornstein-Uhlenbeck particles (active_ou, tau = 1, D_a = 0.5): the MSD
    against 2 d D_t t + 2 d D_a [t - tau (1 - e^(-t/tau))] (2D; 2D and 3D in the full
    suite)."""
    tau, d_a = 1.0, 0.5
    checks, curves = [], {}
    for dimension in ctx.pick((2,), (2, 3)):
        def reference(t, d=dimension):
            return theory.aoup_msd(t, d, D_T, d_a, tau)
        more, curves[dimension] = _free_msd(
            ctx, "aoup_msd", "", reference, (0.5, 1.0, 3.0, 10.0),
            "<p_a(t) p_a(0)> = (D_a / tau) e^(-t/tau) (exact)", dimension,
            table("force", "active_ou", tau=tau, D_a=d_a), f"{dimension}D ")
        checks += more

    def plot(ax):
        for dimension, curve in curves.items():
            t, msd = curve
            fine = np.linspace(0.0, t[-1], 300)
            line, = ax.plot(fine, theory.aoup_msd(fine, dimension, D_T, d_a, tau),
                            label=f"{dimension}D theory")
            ax.plot(t, msd, "o", color=line.get_color(), label=f"{dimension}D pedesis")
        ax.set(xlabel="time", ylabel="MSD")
        ax.legend()

    ran = (f"free AOUPs (brownian), N = 20000, tau = {tau}, D_a = {d_a}, D_t = {D_T}, dt = "
           f"0.01, t = 10, {' and '.join(f'{d}D' for d in ctx.pick((2,), (2, 3)))}")
    return CaseResult("aoup_msd", "Active Ornstein-Uhlenbeck particles", ran, checks, plot)
