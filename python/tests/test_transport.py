"""pedesis.analyze's transport functions (docs/analyze.md): the kinetic theory of hard
particles against the numbers of ../shared/PHYSICS.md and its dimensions, and the
estimators against processes whose coefficients are known exactly: a Gaussian random
walk (D) and an Ornstein-Uhlenbeck flux (its Green-Kubo integral sigma^2 tau)."""
import math

import numpy as np
import pytest
from scipy.signal import lfilter

import pedesis.analyze as pa
from pedesis.validate import theory

KEYS = ("diffusion", "shear_viscosity", "bulk_viscosity", "thermal_conductivity")


# --- kinetic theory ----------------------------------------------------------------


@pytest.mark.parametrize("phi, d_e, eta_e, lambda_e", [
    (0.1, 0.8662, 0.2232, 0.9526), (0.3, 0.1518, 0.7311, 3.082), (0.45, 0.05385, 2.355, 9.359)])
def test_enskog_3d_gives_the_tabulated_values(phi, d_e, eta_e, lambda_e):
    # PHYSICS.md, "Transport coefficients of hard particles": Carnahan-Starling chi and
    # the Sonine factors, sigma = m = T = 1
    e = pa.enskog_transport(3, 6 * phi / math.pi)
    assert e["diffusion"] == pytest.approx(d_e, rel=2e-3)
    assert e["shear_viscosity"] == pytest.approx(eta_e, rel=2e-3)
    assert e["thermal_conductivity"] == pytest.approx(lambda_e, rel=2e-3)


def test_enskog_3d_bulk_viscosity():
    # kappa_E = (4/9) sqrt(pi) n^2 chi at phi = 0.3: n = 1.8/pi, chi = 0.85 / 0.343
    n, chi = 1.8 / math.pi, 0.85 / 0.343
    assert pa.enskog_transport(3, n)["bulk_viscosity"] == pytest.approx(
        4 / 9 * math.sqrt(math.pi) * n * n * chi, rel=1e-12)


def test_enskog_2d_at_phi_0_3():
    # PHYSICS.md's 2D formulas (Henderson chi, first Sonine) worked out with bc:
    # D_E = D0/chi, eta_E = eta0 [1/chi + 2 phi + (1 + 8/pi) phi^2 chi], lambda_E likewise
    e = pa.enskog_transport(2, 1.2 / math.pi)
    assert e["diffusion"] == pytest.approx(0.416547907407, rel=1e-9)
    assert e["shear_viscosity"] == pytest.approx(0.488003514594, rel=1e-9)
    assert e["thermal_conductivity"] == pytest.approx(2.286343497837, rel=1e-9)


@pytest.mark.parametrize("phi", [0.1, 0.3, 0.6])
def test_enskog_2d_bulk_viscosity_is_twice_the_collisional_term_of_eta(phi):
    # eta_E = (eta0/chi)(1 + phi chi)^2 + (d/(d+2)) kappa_E in 2D: the (8/pi) phi^2 chi
    # eta0 of PHYSICS.md's eta_E is kappa_E / 2
    n = 4 * phi / math.pi
    chi = (1 - 7 * phi / 16) / (1 - phi) ** 2
    eta0 = 1 / (2 * math.sqrt(math.pi))
    e = pa.enskog_transport(2, n)
    assert e["shear_viscosity"] - eta0 / chi * (1 + phi * chi) ** 2 == pytest.approx(
        e["bulk_viscosity"] / 2, rel=1e-12)


@pytest.mark.parametrize("dimension", [2, 3])
def test_dilute_values_and_the_low_density_limit(dimension):
    root_pi = math.sqrt(math.pi)
    if dimension == 3:
        expected = {"diffusion": 1.018954 * 3 / (8 * root_pi), "shear_viscosity":
                    1.016034 * 5 / (16 * root_pi), "thermal_conductivity": 1.025218 * 75 / (64 * root_pi)}
    else:
        expected = {"diffusion": 1 / (2 * root_pi), "shear_viscosity": 1 / (2 * root_pi),
                    "thermal_conductivity": 2 / root_pi}
    n = 1e-7
    dilute = pa.chapman_enskog_dilute(dimension, n)
    # D0 n, eta0 and lambda0 do not depend on the density
    assert dilute["diffusion"] * n == pytest.approx(expected["diffusion"], rel=1e-12)
    assert dilute["shear_viscosity"] == pytest.approx(expected["shear_viscosity"], rel=1e-12)
    assert dilute["thermal_conductivity"] == pytest.approx(expected["thermal_conductivity"],
                                                           rel=1e-12)
    assert dilute["bulk_viscosity"] == 0.0
    enskog = pa.enskog_transport(dimension, n)
    for key in ("diffusion", "shear_viscosity", "thermal_conductivity"):
        assert enskog[key] == pytest.approx(dilute[key], rel=1e-5), key
    assert enskog["bulk_viscosity"] < 1e-12


@pytest.mark.parametrize("dimension", [2, 3])
def test_each_coefficient_scales_as_its_dimensions(dimension):
    # D ~ sigma sqrt(T/m) / (n sigma^d), eta and kappa ~ sqrt(m T) / sigma^(d-1), lambda ~
    # sqrt(T/m) / sigma^(d-1); doubling sigma at the same packing (n / 2^d) keeps chi
    d = dimension
    n, r2 = 0.4, math.sqrt(2)
    base = pa.enskog_transport(d, n)
    factors = {
        "sigma": ({"diffusion": 2.0, "shear_viscosity": 2.0 ** (1 - d),
                   "bulk_viscosity": 2.0 ** (1 - d), "thermal_conductivity": 2.0 ** (1 - d)},
                  pa.enskog_transport(d, n / 2 ** d, sigma=2.0)),
        "mass": ({"diffusion": 1 / r2, "shear_viscosity": r2, "bulk_viscosity": r2,
                  "thermal_conductivity": 1 / r2}, pa.enskog_transport(d, n, mass=2.0)),
        "temperature": ({k: r2 for k in KEYS}, pa.enskog_transport(d, n, temperature=2.0)),
    }
    for what, (factor, scaled) in factors.items():
        for key in KEYS:
            assert scaled[key] == pytest.approx(factor[key] * base[key], rel=1e-12), (what, key)


def test_yeh_hummer():
    # D + 2.837297 T / (6 pi eta L), worked out with bc: 0.05 + 2.837297/(6 pi 2 10)
    assert pa.yeh_hummer(0.05, 1.0, 2.0, 10.0) == pytest.approx(0.057526164042, rel=1e-10)
    # the correction is linear in T and falls as 1/(eta L)
    assert pa.yeh_hummer(0.0, 2.0, 4.0, 5.0) == pytest.approx(
        2 * pa.yeh_hummer(0.0, 1.0, 2.0, 10.0), rel=1e-12)


def test_theory_is_in_the_validation_references_too():
    assert theory.enskog_transport is pa.enskog_transport
    assert theory.chapman_enskog_dilute is pa.chapman_enskog_dilute
    assert theory.yeh_hummer is pa.yeh_hummer


@pytest.mark.parametrize("call", [
    lambda: pa.enskog_transport(4, 0.1), lambda: pa.enskog_transport(3, -0.1),
    lambda: pa.enskog_transport(3, 2.0), lambda: pa.yeh_hummer(0.1, 1.0, 0.0, 10.0)])
def test_impossible_arguments_raise(call):
    # (n = 2 in 3D is a packing fraction above 1)
    with pytest.raises(ValueError):
        call()


# --- estimators ----------------------------------------------------------------------


def random_walk(seed, dimension, D, dt, frames=2000, particles=400):
    """A Gaussian random walk, each step N(0, 2 D dt) per axis: MSD = 2 d D t exactly."""
    rng = np.random.default_rng(seed)
    steps = rng.normal(0.0, math.sqrt(2 * D * dt), (frames, particles, dimension))
    return np.cumsum(steps, axis=0) + rng.uniform(0, 10, (1, particles, dimension))


@pytest.mark.parametrize("dimension", [2, 3])
def test_diffusion_of_a_random_walk(dimension):
    D, dt = 0.7, 0.01
    r = pa.diffusion_coefficient(random_walk(1, dimension, D, dt), dt)
    # 8 blocks of 250 frames: duration 2.49, tau_max 0.249, window [0.06225, 0.249]
    assert r["fit_window"] == pytest.approx((0.06225, 0.249), rel=1e-12)
    assert abs(r["value"] - D) < 4 * r["error"], r
    # the error is that of 400 particles x d axes x 8 blocks (under 1 %): not vacuous
    assert r["error"] < 0.01 * D
    lags, curve = r["msd"]
    assert lags[1] == pytest.approx(dt) and len(lags) == 250
    assert curve[100] == pytest.approx(2 * dimension * D * lags[100], rel=0.03)


def test_a_wrapped_walk_in_its_box_gives_the_same_d():
    D, dt, L = 0.7, 0.01, 6.0
    paths = random_walk(2, 3, D, dt)
    wrapped = np.mod(paths, L)
    box = pa.Box([L, L, L])
    direct = pa.diffusion_coefficient(paths, dt)
    assert pa.diffusion_coefficient(wrapped, dt, box=box)["value"] == pytest.approx(
        direct["value"], rel=1e-9)
    # without the box, wrapped positions are refused, not fitted (their MSD levels off)
    with pytest.raises(ValueError, match="look like wrapped positions"):
        pa.diffusion_coefficient(wrapped, dt)


def ornstein_uhlenbeck(seed, samples, components, dt, tau, sigma):
    """Stationary OU paths sampled every dt, exactly (AR(1) with a = exp(-dt/tau)):
    <J(0) J(t)> = sigma^2 exp(-t/tau), whose integral is sigma^2 tau."""
    rng = np.random.default_rng(seed)
    a = math.exp(-dt / tau)
    kicks = rng.normal(0.0, sigma * math.sqrt(1 - a * a), (samples, components))
    kicks[0] = rng.normal(0.0, sigma, components)
    return lfilter([1.0], [1.0, -a], kicks, axis=0)


def test_green_kubo_of_an_ornstein_uhlenbeck_flux():
    tau, sigma, dt, volume, temperature = 1.0, 1.3, 0.05, 2.0, 0.5
    flux = ornstein_uhlenbeck(3, 40000, 32, dt, tau, sigma)
    r = pa.green_kubo(flux, dt, volume, temperature)
    exact = volume / temperature * sigma ** 2 * tau  # 6.76
    # (the sampled sum dt sum J differs from the integral by (dt/tau)^2/12 = 2e-4)
    assert abs(r["value"] - exact) < 4 * r["error"], r
    assert r["error"] < 0.05 * exact
    # blocks of 5000 samples: a moment of 5001 values, duration 250, window [6.25, 25]
    assert r["fit_window"] == pytest.approx((6.25, 25.0), rel=1e-12)
    lags, running = r["running"]
    # the running coefficient (V/T) int_0^t sigma^2 e^(-s/tau) ds: half way at t = tau ln 2
    at = np.searchsorted(lags, tau * math.log(2))
    assert running[at] == pytest.approx(exact / 2, rel=0.1)
    assert np.mean(running[(lags > 5) & (lags < 25)]) == pytest.approx(exact, rel=0.1)


def test_remove_drift_cancels_a_mean_flux_without_bias():
    # the bulk viscosity's flux is the pressure, whose mean is not zero: its moment grows
    # as mean * t, and its mean square as (mean t)^2
    dt = 0.05
    flux = ornstein_uhlenbeck(6, 16000, 4, dt, 1.0, 1.0)
    assert pa.green_kubo(flux + 5.0, dt, 1.0, 1.0)["value"] > 10
    shifted = pa.green_kubo(flux + 5.0, dt, 1.0, 1.0, remove_drift=True)
    assert shifted["value"] == pytest.approx(
        pa.green_kubo(flux, dt, 1.0, 1.0, remove_drift=True)["value"], rel=1e-9)
    assert abs(shifted["value"] - 1.0) < 4 * shifted["error"]
    # i.i.d. samples of variance 1 around a mean of 5: with the sample mean of N samples
    # removed, a window of m of them sums to variance m (1 - m/N) exactly, so the
    # coefficient (V/2T) * dt = 1 needs the division by 1 - m/N; 2 blocks make that
    # 6 % (without it, or with <dG^2> - <dG>^2 per block, 0.94 or lower)
    rng = np.random.default_rng(7)
    white = rng.normal(5.0, 1.0, (3200, 1000))
    r = pa.green_kubo(white, 1.0, 2.0, 1.0, blocks=2, remove_drift=True)
    assert r["value"] == pytest.approx(1.0, abs=0.03)


def test_shear_viscosity_from_a_log_takes_its_off_diagonal_columns(tmp_path):
    tau, sigma, dt = 0.5, 2.0, 0.05
    flux = ornstein_uhlenbeck(4, 12001, 3, dt, tau, sigma)
    flux[0] = 0.0  # a hard-particle log's first row: the interval pressure is 0 by definition
    path = tmp_path / "log.csv"
    columns = {"time": dt * np.arange(len(flux)), "temperature": np.full(len(flux), 2.0),
               "pressure_xy": flux[:, 0], "pressure_xz": flux[:, 1], "pressure_yz": flux[:, 2],
               "pressure_xx": np.full(len(flux), 50.0)}
    np.savetxt(path, np.column_stack(list(columns.values())), delimiter=",",
               header=",".join(columns), comments="")
    r = pa.shear_viscosity(path, volume=8.0)
    same = pa.green_kubo(flux[1:], dt, 8.0, 2.0)
    assert r["value"] == pytest.approx(same["value"], rel=1e-9)
    assert abs(r["value"] - 8.0 / 2.0 * sigma ** 2 * tau) < 4 * r["error"]
    # a dict of columns does the same; 2D logs have pressure_xy alone
    two_d = {k: columns[k] for k in ("time", "temperature", "pressure_xy")}
    assert pa.shear_viscosity(two_d, 8.0)["value"] == pytest.approx(
        pa.green_kubo(flux[1:, :1], dt, 8.0, 2.0)["value"], rel=1e-12)
    with pytest.raises(ValueError, match="no column pressure_xy"):
        pa.shear_viscosity({"time": columns["time"]}, 8.0)
    uneven = dict(two_d, time=columns["time"] ** 2)
    with pytest.raises(ValueError, match="not evenly spaced"):
        pa.shear_viscosity(uneven, 8.0)


@pytest.mark.parametrize("call, message", [
    (lambda: pa.diffusion_coefficient(np.zeros((100, 5, 3)), 0.1, blocks=8), "too few"),
    (lambda: pa.diffusion_coefficient(np.zeros((100, 5, 4)), 0.1), "d = 2 or 3"),
    (lambda: pa.green_kubo(np.zeros((1000, 2)), 0.1, 1.0, 1.0, blocks=0), "positive integer"),
    (lambda: pa.green_kubo(np.zeros((1000, 2)), 0.1, -1.0, 1.0), "must be positive")])
def test_bad_input_raises_value_error(call, message):
    with pytest.raises(ValueError, match=message):
        call()


def test_one_block_has_no_error():
    r = pa.diffusion_coefficient(random_walk(5, 2, 1.0, 0.01, frames=400), 0.01, blocks=1)
    assert r["error"] is None and r["value"] > 0
