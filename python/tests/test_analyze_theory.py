"""The theory curves of the analysis plots (pedesis.analyze.plots, `pedesis analyze`) against
independent results: the equilibrium speed distributions of speed.py (normalisation,
moments, mode and median by quadrature, the CDF as the integral of the PDF), its
Kolmogorov-Smirnov distance and critical value, the free-ABP MSD of msd.py (the
integral of the velocity autocorrelation, the ballistic and diffusive limits) and the
parameters msd.py reads from a config, and the equation-of-state line of thermo.py
(Henderson in 2D, Carnahan-Starling in 3D, from formulas written here).

The plot modules are imported directly (they only define functions at import; `python3
-m pedesis.analyze KIND` runs their main()). Quadrature is
Gauss-Legendre from numpy, so the test needs only the declared dependencies (numpy,
matplotlib is not imported); tolerances are near rounding, since all of these are
exact formulas.

(The plots have no Haff's-law curve: thermo.py plots the log's temperature
without a cooling law, so there is nothing of that kind to test here.)
"""
import math

import numpy as np
import pytest

from pedesis.analyze.plots import msd, speed, thermo
from pedesis.analyze.plots.run_dir import Run

# --- quadrature ----------------------------------------------------------------------

_NODES, _WEIGHTS = np.polynomial.legendre.leggauss(100)


def integrate(f, a, b, pieces=40):
    """Composite 100-point Gauss-Legendre over `pieces` equal intervals of [a, b]: exact
    to rounding for the smooth integrands below."""
    edges = np.linspace(a, b, pieces + 1)
    total = 0.0
    for lo, hi in zip(edges[:-1], edges[1:]):
        half = 0.5 * (hi - lo)
        x = 0.5 * (hi + lo) + half * _NODES
        total += half * float(np.sum(_WEIGHTS * f(x)))
    return total


CASES = [(2, 1.0, 1.0), (2, 2.25, 2.0), (2, 0.3, 5.0), (3, 1.0, 1.0), (3, 0.6667, 3.0),
         (3, 4.0, 0.5)]


def top(T, m):
    """Upper limit of the speed integrals: 14 thermal speeds, where the densities are
    below e^-98 of their peak."""
    return 14.0 * math.sqrt(T / m)


# --- speed.py: Rayleigh (2D) and Maxwell (3D) ----------------------------------------


@pytest.mark.parametrize("dim,T,m", CASES)
def test_speed_pdf_is_normalised_with_the_kinetic_theory_moments(dim, T, m):
    pdf = lambda v: speed.speed_pdf(dim, v, T, m)  # noqa: E731
    vmax = top(T, m)
    assert integrate(pdf, 0.0, vmax) == pytest.approx(1.0, rel=1e-12)
    # mean speed: sqrt(pi T / 2m) in 2D, sqrt(8 T / pi m) in 3D
    mean = math.sqrt(math.pi * T / (2 * m)) if dim == 2 else math.sqrt(8 * T / (math.pi * m))
    assert integrate(lambda v: v * pdf(v), 0.0, vmax) == pytest.approx(mean, rel=1e-12)
    # equipartition: <m v^2> = d T
    assert integrate(lambda v: m * v * v * pdf(v), 0.0, vmax) == pytest.approx(dim * T,
                                                                              rel=1e-12)
    # <v^4> = 8 (T/m)^2 in 2D, 15 (T/m)^2 in 3D
    assert integrate(lambda v: v ** 4 * pdf(v), 0.0, vmax) == pytest.approx(
        (8 if dim == 2 else 15) * (T / m) ** 2, rel=1e-11)
    # the most probable speed: sqrt(T/m) in 2D, sqrt(2 T/m) in 3D
    mode = math.sqrt((1 if dim == 2 else 2) * T / m)
    grid = np.linspace(0.0, 3 * mode, 300001)
    assert grid[np.argmax(pdf(grid))] == pytest.approx(mode, abs=2 * (grid[1] - grid[0]))
    assert np.all(pdf(np.array([0.0, 50 * mode])) < 1e-300 + 1e-12 * pdf(mode))


@pytest.mark.parametrize("dim,T,m", CASES)
def test_speed_cdf_is_the_integral_of_the_pdf(dim, T, m):
    scale = math.sqrt(T / m)
    v = scale * np.array([0.05, 0.3, 0.7, 1.0, 1.5, 2.2, 3.0, 4.5, 6.0])
    F = speed.speed_cdf(dim, v, T, m)
    for vk, Fk in zip(v, F):
        ref = integrate(lambda x: speed.speed_pdf(dim, x, T, m), 0.0, vk)
        assert Fk == pytest.approx(ref, rel=1e-11, abs=1e-15), vk
    assert np.all(np.diff(F) > 0)
    assert speed.speed_cdf(dim, np.array([0.0]), T, m)[0] == 0.0
    assert speed.speed_cdf(dim, np.array([40 * scale]), T, m)[0] == pytest.approx(1.0,
                                                                                  abs=1e-15)


def test_speed_cdf_medians():
    # 2D: F(v) = 1 - exp(-m v^2 / 2T), so the median is sqrt(2 ln 2 T / m)
    T, m = 1.7, 0.8
    median = math.sqrt(2 * math.log(2) * T / m)
    assert speed.speed_cdf(2, np.array([median]), T, m)[0] == pytest.approx(0.5, rel=1e-14)
    # 3D: the median of the chi distribution with 3 degrees of freedom (in units of
    # sqrt(T/m)): the root of erf(x/sqrt 2) - sqrt(2/pi) x e^(-x^2/2) = 1/2, found with
    # mpmath at 30 digits when the test was written
    x = 1.5381722544550523
    assert speed.speed_cdf(3, np.array([x * math.sqrt(T / m)]), T, m)[0] == pytest.approx(
        0.5, abs=1e-14)


def test_speed_cdf_3d_keeps_its_digits_at_small_speeds():
    # F(x) = sqrt(2/pi) (x^3/3 - x^5/10 + x^7/56 - ...) for x = v sqrt(m/T) -> 0; the
    # formula erf - x e^(-x^2/2) cancels to ~1e-16 absolute, fine down to x ~ 1e-3
    x = np.array([1e-3, 3e-3, 1e-2, 0.1])
    series = math.sqrt(2 / math.pi) * (x ** 3 / 3 - x ** 5 / 10 + x ** 7 / 56 - x ** 9 / 432)
    np.testing.assert_allclose(speed.speed_cdf(3, x, 1.0, 1.0), series, rtol=1e-7)


def test_species_sample_temperature_is_the_width_of_the_speeds():
    v = np.array([0.5, 1.0, 2.0, 0.1])
    s = speed.SpeciesSample("A", v, 3.0, 2)
    assert s.T == pytest.approx(3.0 * np.sum(v ** 2) / (2 * 4), rel=1e-15)
    assert s.n == 4


# --- speed.py: Kolmogorov-Smirnov ----------------------------------------------------


def uniform_cdf(v):
    return np.clip(np.asarray(v, dtype=float), 0.0, 1.0)


def test_ks_distance_by_hand():
    # one point at 0.5: F_n jumps from 0 to 1 there, |F_n - F| = 0.5 on both sides
    assert speed.ks_distance(np.array([0.5]), uniform_cdf) == pytest.approx(0.5)
    # points 0.2 and 0.9: the largest gap is just below 0.9, F = 0.9 against F_n = 0.5
    assert speed.ks_distance(np.array([0.9, 0.2]), uniform_cdf) == pytest.approx(0.4)
    # points 0.1, 0.2, 0.3: above 0.3, F_n = 1 against F = 0.3
    assert speed.ks_distance(np.array([0.3, 0.1, 0.2]), uniform_cdf) == pytest.approx(0.7)


def test_ks_distance_is_the_sup_over_a_dense_grid():
    rng = np.random.default_rng(5)
    T, m = 1.3, 2.0
    v = rng.rayleigh(math.sqrt(T / m), 500) * 1.05  # slightly too wide
    cdf = lambda x: speed.speed_cdf(2, x, T, m)  # noqa: E731
    # sup |F_n - F| from both one-sided limits of F_n at every sample point, computed
    # with searchsorted
    s = np.sort(v)
    n = len(s)
    F = cdf(s)
    right = np.searchsorted(s, s, side="right") / n
    left = np.searchsorted(s, s, side="left") / n
    brute = max(np.max(np.abs(right - F)), np.max(np.abs(left - F)))
    assert speed.ks_distance(v, cdf) == pytest.approx(brute, rel=1e-14)
    assert speed.ks_distance(v, cdf) > 0.02  # the width error is visible


def kolmogorov_sf(x):
    """P(sqrt(n) D > x) for n -> infinity: 2 sum_k (-1)^(k-1) exp(-2 k^2 x^2)."""
    return 2.0 * sum((-1) ** (k - 1) * math.exp(-2.0 * k * k * x * x) for k in range(1, 101))


@pytest.mark.parametrize("alpha", [0.1, 0.05, 0.01, 1e-3, 1e-6])
def test_ks_critical_is_the_kolmogorov_quantile(alpha):
    lo, hi = 0.5, 5.0
    for _ in range(200):  # bisection on the decreasing survival function
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if kolmogorov_sf(mid) > alpha else (lo, mid)
    for n in (10, 2000):
        # the script keeps the first term of the series, exact to (alpha/2)^3 relatively
        assert speed.ks_critical(n, alpha) == pytest.approx(lo / math.sqrt(n), rel=2e-4)


# --- msd.py: free active Brownian particles ------------------------------------------


def abp_msd_by_quadrature(t, dim, Dt, v0, Dr):
    """2 d Dt t + 2 int_0^t (t - s) C(s) ds with the swim velocity autocorrelation
    C(s) = v0^2 exp(-(d - 1) Dr s) (the directors' correlation in d dimensions)."""
    if t == 0:
        return 0.0
    rate = (dim - 1) * Dr
    # beyond 60 / rate the integrand is below e^-60 of its start: leave it out
    end = t if rate == 0 else min(t, 60.0 / rate)
    active = integrate(lambda s: (t - s) * np.exp(-rate * s), 0.0, end)
    return 2 * dim * Dt * t + 2 * v0 * v0 * active


PARAMS = [(2, 0.1, 1.0, 0.5), (2, 0.0, 2.0, 2.0), (3, 0.05, 1.5, 0.3), (3, 0.0, 1.0, 1.0)]


@pytest.mark.parametrize("dim,Dt,v0,Dr", PARAMS)
def test_free_abp_msd_is_the_integral_of_the_velocity_autocorrelation(dim, Dt, v0, Dr):
    tau = 1.0 / ((dim - 1) * Dr)
    t = tau * np.geomspace(1e-6, 1e3, 40)
    got = msd.free_abp_msd(t, dim, Dt, v0, Dr)
    ref = np.array([abp_msd_by_quadrature(x, dim, Dt, v0, Dr) for x in t])
    np.testing.assert_allclose(got, ref, rtol=1e-10)
    assert msd.free_abp_msd(np.array([0.0]), dim, Dt, v0, Dr)[0] == 0.0


@pytest.mark.parametrize("dim,Dt,v0,Dr", PARAMS)
def test_free_abp_msd_ballistic_and_diffusive_limits(dim, Dt, v0, Dr):
    tau = 1.0 / ((dim - 1) * Dr)
    # short times: the active part is ballistic, v0^2 t^2 (1 - x/3 + x^2/12 - x^3/60 + ...),
    # x = t / tau
    for x in (1e-7, 1e-5, 1e-3, 1e-2):
        t = x * tau
        active = msd.free_abp_msd(np.array([t]), dim, Dt, v0, Dr)[0] - 2 * dim * Dt * t
        assert active == pytest.approx(v0 * v0 * t * t * (1 - x / 3 + x * x / 12 - x ** 3 / 60),
                                       rel=1e-9)
    # long times: diffusive with D_eff = Dt + v0^2 tau / d, i.e. v0^2 / (2 Dr) in 2D and
    # v0^2 / (6 Dr) in 3D, offset by -2 v0^2 tau^2 (exact once e^(-t/tau) is negligible)
    D_eff = Dt + v0 * v0 / ((2 if dim == 2 else 6) * Dr)
    for x in (50.0, 1e3, 1e6):
        t = x * tau
        expect = 2 * dim * D_eff * t - 2 * v0 * v0 * tau * tau
        assert msd.free_abp_msd(np.array([t]), dim, Dt, v0, Dr)[0] == pytest.approx(
            expect, rel=1e-12)


def test_free_abp_msd_series_branch_is_continuous():
    # x - 1 + e^-x by its Taylor series (exact to rounding for x <= 1), across the
    # script's switch from the series to the closed form at x = 1e-3
    x = np.concatenate([np.geomspace(1e-9, 1.0, 200), [1e-3 * (1 - 1e-12), 1e-3]])
    g = np.array([math.fsum((-xi) ** k / math.factorial(k) for k in range(2, 40)) for xi in x])
    Dr, v0 = 0.7, 1.3
    tau = 1.0 / Dr
    got = msd.free_abp_msd(x * tau, 2, 0.0, v0, Dr)
    np.testing.assert_allclose(got, 2 * v0 * v0 * tau * tau * g, rtol=1e-9)


def test_free_abp_msd_without_rotational_noise_is_ballistic():
    t = np.array([0.0, 0.1, 1.0, 10.0, 1e4])
    for dim in (2, 3):
        np.testing.assert_allclose(msd.free_abp_msd(t, dim, 0.25, 1.5, 0.0),
                                   2 * dim * 0.25 * t + 1.5 ** 2 * t * t, rtol=1e-15)


def write_config(tmp_path, text):
    (tmp_path / "config.toml").write_text(text)
    return Run(tmp_path)


def test_msd_parameters_from_the_config(tmp_path):
    run = write_config(tmp_path, """
dimension = 2
dynamics = "brownian"
[[species]]
name = "A"
count = 30
[[force]]
name = "self_propulsion"
alpha = 1.0
[[force]]
name = "self_propulsion"
alpha = 0.5
[[integrator]]
name = "brownian"
T = 0.2
gamma = 2.0
[[integrator]]
name = "brownian_rotation"
T = 0.3
gamma = 0.6
""")
    params, weights = msd.parameters(run, tmp_path / "config.toml")
    assert weights == [1.0]
    (p,) = params
    assert p.Dt == pytest.approx(0.2 / 2.0)  # D = T / gamma
    assert p.v0 == pytest.approx((1.0 + 0.5) / 2.0)  # the alphas add up; v0 = alpha / gamma
    assert p.Dr == pytest.approx(0.3 / 0.6)


def test_msd_parameters_per_species(tmp_path):
    run = write_config(tmp_path, """
dimension = 3
dynamics = "langevin"
[[species]]
name = "A"
count = 30
[[species]]
name = "B"
count = 10
[[force]]
name = "self_propulsion"
alpha = { A = 1.0, B = 2.0 }
[[integrator]]
name = "langevin"
T = 1.0
gamma = { A = 1.0, B = 4.0 }
""")
    params, weights = msd.parameters(run, tmp_path / "config.toml")
    assert weights == pytest.approx([0.75, 0.25])
    a, b = params
    assert (a.name, a.Dt, a.v0, a.Dr) == ("A", pytest.approx(1.0), pytest.approx(1.0), 0.0)
    assert (b.name, b.Dt, b.v0, b.Dr) == ("B", pytest.approx(0.25), pytest.approx(0.5), 0.0)


# --- thermo.py: the equation of state line -------------------------------------------


def henderson(eta):
    return (1 + eta * eta / 8) / (1 - eta) ** 2


def carnahan_starling(eta):
    return (1 + eta + eta * eta - eta ** 3) / (1 - eta) ** 3


class RecordingAxes:
    def __init__(self):
        self.lines = []

    def plot(self, x, y, **style):
        self.lines.append((np.asarray(x), np.asarray(y), style))


@pytest.mark.parametrize("dim,count,length", [(2, 60, 14.0), (3, 80, 9.0)])
def test_thermo_equation_of_state_line(tmp_path, run_cli, dim, count, length):
    # a short elastic run in a walled box; the line is Z(eta) x pressure_ideal
    (tmp_path / "gas.toml").write_text(f"""
dimension = {dim}
seed = 3
[box]
length = {length}
boundary = "wall"
[[species]]
name = "A"
count = {count}
radius = 0.5
[run]
time = 3.0
[output]
log_interval = 0.5
formats = []
progress = false
""")
    run_cli("run", "gas.toml", "--out", "out", cwd=tmp_path)
    run = Run(tmp_path / "out")
    log = run.log()
    ax = RecordingAxes()
    thermo._equation_of_state(run, log, log["time"], ax)
    assert len(ax.lines) == 1
    x, y, style = ax.lines[0]
    if dim == 2:
        eta = count * math.pi * 0.25 / length ** 2
        Z, name = henderson(eta), "Henderson"
    else:
        eta = count * math.pi / 6 / length ** 3
        Z, name = carnahan_starling(eta), "Carnahan-Starling"
    np.testing.assert_allclose(x, log["time"])
    np.testing.assert_allclose(y, Z * log["pressure_ideal"], rtol=1e-12)
    assert name in style["label"]
    assert f"Z = {Z:.4g}" in style["label"]
