"""A Lennard-Jones liquid state point against the NIST Standard Reference Simulation
Website's Monte Carlo data."""
import numpy as np
from scipy.spatial import cKDTree

from ...analyze import read_frames
from ..checks import CaseResult, Check
from ..configs import soft_run, table
from ..stats import block_mean

# NIST SRSW, LJ fluid, NVT Monte Carlo, cutoff 3 sigma with analytic long-range
# corrections (https://mmlapps.nist.gov/srs/LJ_PURE/mc.htm): T* = 0.9, rho* = 0.776.
NIST_T, NIST_RHO = 0.9, 0.776
NIST_ENERGY, NIST_ENERGY_ERROR = -5.4689, 4.20e-4
NIST_PRESSURE = 0.24056


def pairs_within(frame, lengths, cutoff):
    """The number of pairs closer than ``cutoff`` in one periodic frame."""
    x = np.mod(np.asarray(frame, dtype=float), lengths)
    return len(cKDTree(x, boxsize=lengths).query_pairs(cutoff))


def reweighted_block_mean(values, weights, blocks=10):
    """The weighted mean of a time series and its standard error from ``blocks``
    consecutive blocks' weighted means (as stats.block_mean)."""
    x, w = np.asarray(values, dtype=float), np.asarray(weights, dtype=float)
    usable = len(x) - len(x) % blocks
    xs, ws = x[:usable].reshape(blocks, -1), w[:usable].reshape(blocks, -1)
    means = (xs * ws).sum(axis=1) / ws.sum(axis=1)
    return float(means.mean()), float(means.std(ddof=1) / np.sqrt(blocks))


def lennard_jones(ctx):
    """Langevin dynamics of LJ atoms cut at 3 sigma (unshifted energy, the cutoff of the
    reference), with the long-range corrections NIST adds made by the engine itself
    ([[force]] tail = true: U and P of the log include them).

    Dynamics sees only forces, which the cut truncates the same way whether the energy is
    shifted or not, so it samples the potential shifted at the cutoff: exp(-U_s / T).
    NIST's Monte Carlo samples the truncated one, U_t = U_s + n_c u(r_c), n_c the pairs
    inside the cutoff. The frames are reweighted by exp(-u(r_c) n_c / T) (exact importance
    sampling; u(r_c) = -0.0055 and n_c varies by about 40, so the weights stay within a
    factor of a few). The log's U is U_t already. The pressure's ideal part is n T of the
    bath: BAOAB samples the configurations well at this dt but its kinetic temperature
    runs about 0.2 % cold."""
    count, cutoff = 500, 3.0
    length = (count / NIST_RHO) ** (1.0 / 3.0)
    dt, equilibration, every = 0.005, 4000, 100
    production = ctx.pick(80000, 200000)
    blocks = 20
    forces = table("force", "lj", epsilon=1.0, cutoff=cutoff, tail=True)
    integrators = table("integrator", "langevin", T=NIST_T, gamma=1.0)
    config = soft_run(3, "langevin", count, length, 3, equilibration + production, dt, 20,
                      every, forces=forces, integrators=integrators, positions="fcc")
    run = ctx.run("lennard_jones", "run", config)
    log = ctx.log(run)
    keep = log["step"] > equilibration
    temperature, temperature_err = block_mean(log["temperature"][keep], blocks)

    traj = read_frames(str(run))
    lengths = np.asarray(traj.box.lengths, dtype=float)
    row_of = {int(s): k for k, s in enumerate(log["step"])}
    frames = [f for f, s in enumerate(traj.steps) if s > equilibration]
    rows = np.array([row_of[int(traj.steps[f])] for f in frames])
    n_c = np.array([pairs_within(traj.positions[f], lengths, cutoff) for f in frames], float)
    u_cut = 4.0 * (cutoff ** -12 - cutoff ** -6)
    weights = np.exp(-u_cut * (n_c - n_c.mean()) / NIST_T)
    # the log's energy is U_t already (the energy is not shifted); the pressure takes the
    # bath's ideal part
    energy_t = log["potential_energy"][rows] / count
    pressure_t = (log["pressure"][rows] - log["pressure_ideal"][rows]
                  + NIST_RHO * NIST_T)
    energy, energy_err = reweighted_block_mean(energy_t, weights, blocks)
    pressure, pressure_err = reweighted_block_mean(pressure_t, weights, blocks)
    plain_pressure, _ = block_mean(log["pressure"][keep], blocks)
    time = production * dt
    why = (f"N = {count}, t = {time:g} after {equilibration * dt:g} (blocks of {time / blocks:g}, "
           f"many structural relaxation times); frames every {every} steps reweighted from the "
           "shifted potential the dynamics samples to the truncated one of NIST's Monte Carlo "
           "(by exp(-u(rc) n_c / T)), ideal part n T of the bath; without these the mean "
           f"pressure is {plain_pressure:.4f}")
    checks = [
        Check.near("potential energy per particle (truncated)", energy, energy_err,
                   NIST_ENERGY, 0.01,
                   "NIST SRSW LJ Monte Carlo (rc = 3, long-range corrected)", why),
        Check.near("pressure", pressure, pressure_err, NIST_PRESSURE, ctx.pick(0.05, 0.02),
                   "NIST SRSW LJ Monte Carlo (rc = 3, long-range corrected)", why),
        Check.near("kinetic temperature", temperature, temperature_err, NIST_T, 0.01,
                   "the Langevin bath's T", "the thermostat's own target; its dt^2 bias is "
                   "below 1 %"),
    ]

    def plot(ax):
        t = log["time"]
        ax.plot(t, log["potential_energy"] / count, lw=0.7, label="U/N (with the tail)")
        ax.axhline(NIST_ENERGY, color="C1", label="NIST")
        ax.set(xlabel="time", ylabel="potential energy per particle")
        ax.legend()

    ran = (f"3D LJ, N = {count}, rho = {NIST_RHO}, T = {NIST_T} (Langevin, gamma = 1), cutoff "
           f"{cutoff}, {production} steps of dt = {dt}")
    return CaseResult("lennard_jones", "Lennard-Jones liquid state point", ran, checks, plot)
