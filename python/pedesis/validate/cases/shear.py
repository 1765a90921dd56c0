"""Lees-Edwards shear of hard spheres in the event engine (issue 51): the viscosity of the
sheared fluid (NEMD) against the equilibrium Einstein-Helfand estimator, and the uniform
shear flow of an inelastic gas against the Navier-Stokes balance of viscous heating and
collisional cooling with Enskog's coefficients."""
import csv
import math

import numpy as np

from ..checks import CaseError, CaseResult, Check
from ..configs import hard_gas
from ..theory import collision_frequency, contact_value, enskog_transport, hard_sphere_z_csk
from .transport import _summary, _value


def _sheared(ctx, case, name, count, density, rate, time, seed, event_keys, restitution=1.0):
    """A sheared event-driven run, log rows every time unit; ``event_keys`` go in [event]."""
    length = (count / density) ** (1.0 / 3.0)
    config = hard_gas(3, [("A", count, 0.5, 1.0)], length, seed, time, 1.0, positions="fcc",
                      restitution=restitution, extra=event_keys)
    config = config.replace('boundary = "periodic"', f'boundary = "periodic"\nshear_rate = {rate}')
    return ctx.run(case, name, config), length


def hard_sphere_shear(ctx):
    """1372 hard spheres at n = 0.5 sheared at rates 0.1 and 0.2 under the rescaling
    thermostat (T = 1): eta = -<P_xy>/rate against [transport]'s equilibrium eta of the same
    fluid, and the laboratory velocity profile against the imposed flow."""
    count, density = 1372, 0.5
    time_eq, time_shear = 8000.0, 400.0
    rates = (0.1, 0.2)
    length = (count / density) ** (1.0 / 3.0)
    eq_config = hard_gas(3, [("A", count, 0.5, 1.0)], length, 11, time_eq, time_eq / 4,
                         positions="fcc", extra="[transport]\n")
    eq = _summary(ctx.run("hard_sphere_shear", "equilibrium", eq_config))
    eta_eq, eta_eq_err = _value(eq["transport"], "shear_viscosity")
    thermostat = 'thermostat = "rescale"\ntemperature = 1.0\n'
    checks, measured, profiles = [], [], []
    for k, rate in enumerate(rates):
        run, _ = _sheared(ctx, "hard_sphere_shear", f"rate{rate:g}", count, density, rate,
                          time_shear, 21 + k, thermostat)
        nemd = _summary(run)["shear"]["viscosity"]
        if nemd["value"] is None or nemd["error"] is None:
            raise CaseError(f"the run at rate {rate:g} gave no viscosity")
        measured.append((rate, nemd["value"], nemd["error"]))
        checks.append(Check.near(
            f"eta = -<P_xy>/rate at rate {rate:g} (NEMD)", nemd["value"], nemd["error"], eta_eq,
            0.1 * eta_eq,
            f"[transport]'s equilibrium Einstein-Helfand eta of the same fluid: {eta_eq:.4g} +- "
            f"{eta_eq_err:.2g} (t = {time_eq:g})",
            "linear response: reduced rates of 0.1 and 0.2 thin a hard-sphere fluid at this "
            "density by less than the statistical errors; 10 % is about three times the "
            "combined error"))
        profiles.append(np.genfromtxt(run / "velocity_profile.csv", delimiter=",", names=True))
    rate, profile = rates[0], profiles[0]
    slope = np.polyfit(profile["y"], profile["velocity_x"], 1)[0]
    residual = profile["velocity_x"] - slope * profile["y"]
    checks.append(Check.near(
        f"slope of the velocity profile at rate {rate:g}", float(slope),
        float(np.std(residual) / np.sqrt(len(residual)) / np.std(profile["y"])), rate,
        0.05 * rate, "the imposed Lees-Edwards flow v_x = rate y",
        "the laboratory v_x of every logged row, in bins of y; 5 %"))

    def plot(ax):
        ax.errorbar([r for r, _, _ in measured], [v for _, v, _ in measured],
                    yerr=[e for _, _, e in measured], fmt="o", label="NEMD -<P_xy>/rate")
        ax.axhspan(eta_eq - eta_eq_err, eta_eq + eta_eq_err, color="C1", alpha=0.3,
                   label="equilibrium Einstein-Helfand")
        ax.axhline(enskog_transport(3, density)["shear_viscosity"], color="k", ls=":",
                   label="Enskog")
        ax.set(xlabel="shear rate", ylabel="eta", xlim=(0, 0.22), title="hard spheres, n = 0.5")
        ax.legend()

    ran = (f"3D, N = {count}, n = {density:g}; equilibrium t = {time_eq:g} with [transport], "
           f"sheared at rates {', '.join(f'{r:g}' for r in rates)} for t = {time_shear:g} each "
           "(event engine, rescaling thermostat T = 1)")
    return CaseResult("hard_sphere_shear", "Hard-sphere viscosity: NEMD against equilibrium", ran,
                      checks, plot)


def _steady_means(run, start):
    """Means and standard errors (8 blocks) of T and P_xy over the log rows at t > start."""
    with open(run / "log.csv") as f:
        rows = [r for r in csv.DictReader(f) if float(r["time"]) > start]
    if len(rows) < 16:
        raise CaseError(f"{run}/log.csv: too few rows after t = {start:g}")
    out = {}
    for key in ("temperature", "pressure_xy"):
        x = np.array([float(r[key]) for r in rows])
        blocks = np.array([b.mean() for b in np.array_split(x, 8)])
        out[key] = (float(x.mean()), float(blocks.std(ddof=1) / math.sqrt(8)))
    return out


def granular_usf(ctx):
    """Uniform shear flow of inelastic hard spheres (xi = 0.95, n = 0.25, no thermostat):
    the steady temperature where viscous heating meets collisional cooling, and the
    reduced viscosity there, against the Navier-Stokes balance with Enskog's coefficients."""
    count, density, xi, rate = 1372, 0.25, 0.95, 0.348
    time, start = 300.0, 100.0
    run, _ = _sheared(ctx, "granular_usf", "run", count, density, rate, time, 3, "",
                      restitution=xi)
    means = _steady_means(run, start)
    temperature, t_err = means["temperature"]
    p_xy, p_err = means["pressure_xy"]
    eta, eta_err = -p_xy / rate, p_err / rate
    # Navier-Stokes with T-independent reduced coefficients: eta = eta1 sqrt(T), the energy
    # lost per volume and time n T (1 - xi^2) omega1 sqrt(T) / 2 (Haff's cooling rate with
    # Enskog's collision frequency omega = omega1 sqrt(T)); heating eta rate^2 balances it at
    # T = 2 rate^2 eta1 / (n (1 - xi^2) omega1)
    phi = math.pi / 6.0 * density
    chi = contact_value(3, phi, hard_sphere_z_csk(phi))
    omega1 = collision_frequency(3, density, 1.0, 1.0, 1.0, chi)
    eta1 = enskog_transport(3, density)["shear_viscosity"]
    t_ns = 2.0 * rate ** 2 * eta1 / (density * (1.0 - xi ** 2) * omega1)
    source = ("Navier-Stokes balance of viscous heating and Haff's cooling, with Enskog's "
              "elastic eta and collision frequency (Carnahan-Starling chi); the granular "
              "corrections to eta and to the cooling rate at xi = 0.95 (Garzo & Dufty 1999; "
              "Brey, Ruiz-Montero & Moreno 1997, USF) and the Burnett terms at the reduced "
              f"rate {rate / omega1:.3f} are a few per cent")
    why = f"8 blocks of the log rows after t = {start:g} (the temperature relaxes in about 12)"
    checks = [
        Check.near("steady temperature of the sheared inelastic gas", temperature, t_err, t_ns,
                   0.1 * t_ns, source, why),
        Check.near("reduced viscosity -<P_xy> / (rate sqrt(T))", eta / math.sqrt(temperature),
                   eta_err / math.sqrt(temperature), eta1, 0.1 * eta1,
                   "Enskog's eta at T = 1 (eta scales as sqrt(T)); " + source, why)]
    with open(run / "log.csv") as f:
        rows = list(csv.DictReader(f))

    def plot(ax):
        ax.plot([float(r["time"]) for r in rows], [float(r["temperature"]) for r in rows],
                label="temperature")
        ax.axhline(t_ns, color="k", ls=":", label="Navier-Stokes + Enskog")
        ax.axvline(start, color="grey", lw=1)
        ax.set(xlabel="t", ylabel="T", title=f"USF, xi = {xi}, n = {density}, rate = {rate}")
        ax.legend()

    ran = (f"3D, N = {count}, n = {density:g}, xi = {xi}, shear rate {rate} (event engine, "
           f"Lees-Edwards, no thermostat), t = {time:g}")
    return CaseResult("granular_usf", "Uniform shear flow of an inelastic gas", ran, checks,
                      plot)
