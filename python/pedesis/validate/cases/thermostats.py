"""The NVT thermostats of the soft engine (bussi, nose_hoover): the canonical
distribution of the kinetic energy and the conserved quantity."""
import numpy as np

from ..checks import CaseResult, Check
from ..configs import soft_run, table
from ..stats import block_mean


def nvt_thermostats(ctx):
    """A 3D LJ liquid (N = 256, rho = 0.8442, T = 0.72, cutoff 2.5 shifted) under each
    thermostat. In the canonical ensemble K is independent of the positions and
    Gamma-distributed with shape f/2 and scale T: the instantaneous temperature 2K/f has
    mean T and variance 2 T^2 / f (f = 3N - 3, the momentum is conserved). And the log's
    conserved_energy stays flat while the bath exchanges energy with the particles."""
    count, rho, temperature, dt = 256, 0.8442, 0.72, 0.005
    length = (count / rho) ** (1.0 / 3.0)
    equilibration, every = 2000, 10
    production = ctx.pick(20000, 200000)
    blocks = 20
    freedom = 3 * count - 3
    forces = table("force", "lj", epsilon=1.0, cutoff=2.5, shift=True)
    extra = 'velocities = "maxwell_boltzmann"\ntemperature = 0.72'
    checks, series = [], {}
    time = production * dt
    for name, tau in (("bussi", 0.1), ("nose_hoover", 0.2)):
        integrators = table("integrator", name, T=temperature, tau=tau)
        config = soft_run(3, name, count, length, 5, equilibration + production, dt, every,
                          equilibration + production, forces=forces, integrators=integrators,
                          positions="fcc", extra=extra)
        log = ctx.log(ctx.run("nvt_thermostats", name, config))
        keep = log["step"] > equilibration
        t = log["temperature"][keep]
        mean, mean_err = block_mean(t, blocks)
        # the variance about the run's mean, per block, and its scatter over the blocks
        ratio, ratio_err = block_mean((t - t.mean()) ** 2 * freedom / (2.0 * temperature ** 2),
                                      blocks)
        h = log["conserved_energy"][keep]
        ts = log["time"][keep]
        drift = abs(np.polyfit(ts, h, 1)[0]) / count
        exchanged = np.ptp(log["total_energy"][keep])
        series[name] = (log["time"], log["conserved_energy"] / count)
        why = (f"N = {count}, t = {time:g} after {equilibration * dt:g}, {blocks} blocks "
               "(each many relaxation times of K)")
        checks += [
            Check.near(f"{name}: mean of 2K/f", mean, mean_err, temperature, 0.01 * temperature,
                       "the bath's T (canonical <K> = f T / 2)", why),
            Check.near(f"{name}: f var(2K/f) / (2 T^2)", ratio, ratio_err, 1.0,
                       ctx.pick(0.2, 0.06), "canonical var K = f T^2 / 2 (Gamma of shape f/2)",
                       why),
            Check(f"{name}: conserved_energy drift per particle per unit time", drift, 0.0,
                  "< 1e-4", "velocity Verlet's bounded error (no drift of its own)", 0.0, 1e-4,
                  f"the total energy K + U itself moves by {exchanged:.3g} over the run"),
        ]

    def plot(ax):
        for name, (t, h) in series.items():
            ax.plot(t, h - h[0], lw=0.7, label=name)
        ax.set(xlabel="time", ylabel="conserved_energy / N (from its start)")
        ax.legend()

    ran = (f"3D LJ, N = {count}, rho = {rho}, T = {temperature}, cutoff 2.5 (shifted), "
           f"{production} steps of dt = {dt} per thermostat (bussi tau = 0.1, nose_hoover "
           "tau = 0.2, chain 3)")
    return CaseResult("nvt_thermostats", "NVT thermostats: canonical kinetic energy",
                      ran, checks, plot)
