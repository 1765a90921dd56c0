"""Reference values of `pedesis validate`: exact results and published equations of state.

Units: k_B = 1, sigma is a particle diameter, eta the packing (area or volume) fraction.
Each function names its source; docs/validation.md lists them with the cases.
"""
import math

import numpy as np
from scipy.linalg import eigh_tridiagonal
from scipy.optimize import brentq

# (the transport coefficients of hard particles live with the analysis functions they are
# compared with; validation cases take them from here with the rest)
from ..analyze.transport_theory import chapman_enskog_dilute, enskog_transport, yeh_hummer  # noqa: F401

# Reduced virial coefficients B_n / B_2^(n-1) of hard disks, n = 2..10 (Clisby & McCoy,
# J. Stat. Phys. 122, 15 (2006), table 1; n = 3, 4 exact).
HARD_DISK_VIRIAL = (1.0, 0.78200443, 0.53223180, 0.33355604, 0.1988425, 0.1148728, 0.0649930,
                    0.0362193, 0.0199537)


def hard_disk_z_virial(eta):
    """Z = P / (rho T) of hard disks from the virial series to B_10: Z = 1 + sum_n b_n
    (2 eta)^(n-1), since rho B_2 = 2 eta. Returns (Z, truncation bound): the terms fall
    by a factor ~0.55 x 2 eta each, so the rest of the series is bounded by the last
    term times 2 eta / (1 - 2 eta) (1e-4 at eta = 0.3)."""
    x = 2.0 * eta
    terms = [b * x ** (n + 1) for n, b in enumerate(HARD_DISK_VIRIAL)]
    return 1.0 + sum(terms), terms[-1] * x / (1.0 - x)


def hard_disk_z_henderson(eta):
    """Henderson's hard-disk equation of state (Mol. Phys. 30, 971 (1975)): Z = (1 +
    eta^2/8) / (1 - eta)^2, good to ~0.1-0.5 % in the fluid."""
    return (1.0 + eta * eta / 8.0) / (1.0 - eta) ** 2


def hard_sphere_z_csk(eta):
    """The Carnahan-Starling-Kolafa equation of state (Boublik & Nezbeda, Collect. Czech.
    Chem. Commun. 51, 2301 (1986)): Z = (1 + eta + eta^2 - (2/3) eta^3 (1 + eta)) /
    (1 - eta)^3. It meets the reference points of HOOMD-blue's validation suite, Z =
    4.2952 at rho sigma^3 = 0.6 and 6.6566 at 0.75, to 3e-5 and 2e-4 (Kolafa, Labik &
    Malijevsky's own fit, PCCP 6, 2335 (2004), is not used here); Carnahan-Starling is
    0.27 % low at eta = 0.3."""
    return (1.0 + eta + eta ** 2 - 2.0 / 3.0 * eta ** 3 * (1.0 + eta)) / (1.0 - eta) ** 3


def contact_value(dimension, eta, z):
    """g(sigma+) from Z by the virial theorem: Z = 1 + 2^(d-1) eta g(sigma+)."""
    return (z - 1.0) / (2 ** (dimension - 1) * eta)


def collision_frequency(dimension, density, sigma, temperature, mass, g_contact):
    """Collisions per particle per unit time of hard particles in equilibrium, exact given
    the contact value (Enskog's expression; see Lue, J. Chem. Phys. 122, 044513 (2005)):
    2D omega = 2 sigma rho g sqrt(pi T/m), 3D omega = 4 sigma^2 rho g sqrt(pi T/m)."""
    prefactor = 2.0 * sigma if dimension == 2 else 4.0 * sigma * sigma
    return prefactor * density * g_contact * math.sqrt(math.pi * temperature / mass)


def haff_temperature(t, t0_temperature, omega0, restitution, dimension):
    """Haff's law: T(t) = T0 / (1 + t / t_H)^2, t_H = 2 d / ((1 - xi^2) omega0)."""
    t_h = 2.0 * dimension / ((1.0 - restitution ** 2) * omega0)
    return t0_temperature / (1.0 + np.asarray(t) / t_h) ** 2


def _partial_cooling_rate(i, temperatures, masses, fractions, restitution, dimension):
    """zeta_i of a binary mixture of equal-sized inelastic hard particles with Gaussian
    velocity distributions (the Gaussian approximation of Garzo & Dufty, PRE 60, 5706
    (1999), written out for equal diameters and one restitution), up to a factor common
    to both species:
    zeta_i ~ (1/T_i) sum_j x_j (1+xi) (T_i/m_i + T_j/m_j)^(3/2) m_ij
             [ (T_i - T_j) / (M (T_i/m_i + T_j/m_j)) + mu_ji (1 - xi) / 2 ]
    with M = m_i + m_j, m_ij = m_i m_j / M, mu_ji = m_j / M (the common factor holds the
    density, the contact value and sigma^(d-1), and d only through pi^((d-1)/2)/Gamma)."""
    total = 0.0
    for j in range(2):
        a = temperatures[i] / masses[i] + temperatures[j] / masses[j]
        M = masses[i] + masses[j]
        reduced = masses[i] * masses[j] / M
        bracket = (temperatures[i] - temperatures[j]) / (M * a) + 0.5 * masses[j] / M * (1.0 - restitution)
        total += fractions[j] * (1.0 + restitution) * a ** 1.5 * reduced * bracket
    return total / temperatures[i]


def garzo_dufty_temperature_ratio(masses, fractions, restitution, dimension):
    """T_2 / T_1 in the homogeneous cooling state of a binary mixture of equal-sized
    inelastic hard particles: the ratio at which both species cool at the same rate,
    zeta_1 = zeta_2 (Garzo & Dufty 1999, Gaussian approximation). 1 when elastic or when
    the masses are equal."""
    def gap(ratio):
        t = (1.0, ratio)
        return (_partial_cooling_rate(0, t, masses, fractions, restitution, dimension)
                - _partial_cooling_rate(1, t, masses, fractions, restitution, dimension))

    if restitution == 1.0 or masses[0] == masses[1]:
        return 1.0
    return brentq(gap, 0.05, 20.0, xtol=1e-12)


def free_abp_msd(t, dimension, d_t, v0, d_r):
    """Mean squared displacement of a free active Brownian particle: 2 d D_t t + 2 v0^2
    tau^2 (t/tau - 1 + exp(-t/tau)), tau = 1 / ((d - 1) D_r) (ten Hagen, van Teeffelen &
    Lowen, J. Phys.: Condens. Matter 23, 194119 (2011))."""
    t = np.asarray(t, dtype=float)
    tau = 1.0 / ((dimension - 1) * d_r)
    return 2.0 * dimension * d_t * t + 2.0 * v0 ** 2 * tau ** 2 * (t / tau - 1.0 + np.exp(-t / tau))


def free_abp_orientation(t, dimension, d_r):
    """< n(t) . n(0) > = exp(-(d - 1) D_r t) for rotational diffusion on the circle or sphere."""
    return np.exp(-(dimension - 1) * d_r * np.asarray(t, dtype=float))


def swim_pressure(t, dimension, density, alpha, gamma, d_r):
    """The swim pressure of free ABPs, measured from the start: Pi(t) = n alpha v0 tau
    (1 - exp(-t/tau)) / d, v0 = alpha / gamma, tau = 1/((d-1) D_r); its steady value
    n alpha^2 / (gamma d (d-1) D_r) is Takatori, Yan & Brady's (PRL 113, 028103 (2014))
    n zeta U0^2 tau_R / (d (d-1))."""
    tau = 1.0 / ((dimension - 1) * d_r)
    v0 = alpha / gamma
    return density * alpha * v0 * tau * (1.0 - np.exp(-np.asarray(t, dtype=float) / tau)) / dimension


def chiral_abp_msd(t, d_t, v0, d_r, omega):
    """Mean squared displacement of a free 2D chiral ABP (active angular velocity omega):
    4 D_t t + (2 v0^2 / K) [D_r t - (D_r^2 - w^2) / K + e^(-D_r t) ((D_r^2 - w^2) cos wt
    - 2 D_r w sin wt) / K], K = D_r^2 + w^2 (van Teeffelen & Lowen, PRE 78, 020101 (2008))."""
    t = np.asarray(t, dtype=float)
    k = d_r ** 2 + omega ** 2
    c = d_r ** 2 - omega ** 2
    wave = np.exp(-d_r * t) * (c * np.cos(omega * t) - 2.0 * d_r * omega * np.sin(omega * t))
    return 4.0 * d_t * t + 2.0 * v0 ** 2 / k * (d_r * t - c / k + wave / k)


def run_and_tumble_msd(t, dimension, d_t, v0, rate):
    """Mean squared displacement of a free run-and-tumble particle (tumble rate lambda, a
    new direction drawn uniformly): <v(t).v(0)> = v0^2 e^(-lambda t), so the ABP MSD with
    (d - 1) D_r replaced by lambda: 2 d D_t t + 2 v0^2 / lambda^2 (lambda t - 1 +
    e^(-lambda t))."""
    return free_abp_msd(t, dimension, d_t, v0, rate / (dimension - 1))


def trapped_abp_r2(dimension, d_t, v0, d_r, kappa):
    """Stationary <r^2> of an ABP in an isotropic harmonic trap (kappa = mobility x
    stiffness): d D_t / kappa + v0^2 / (kappa (kappa + (d - 1) D_r)) (the position is a
    linear filter of the director, whose correlation decays at (d - 1) D_r)."""
    return dimension * d_t / kappa + v0 ** 2 / (kappa * (kappa + (dimension - 1) * d_r))


def active_wall_pressure(dimension, bulk_density, d_t, v0, d_r, mobility):
    """Pressure of ideal ABPs on a torque-free wall of any stiffness: n_bulk (D_t + v0^2 /
    (d (d - 1) D_r)) / mu (Solon et al., Nature Physics 11, 673 (2015))."""
    return bulk_density * (d_t + v0 ** 2 / (dimension * (dimension - 1) * d_r)) / mobility


def aoup_msd(t, dimension, d_t, d_a, tau):
    """Mean squared displacement of a free active Ornstein-Uhlenbeck particle (tau dp =
    -p dt + sqrt(2 D_a) dW per axis, so <p_a(t) p_a(0)> = (D_a / tau) e^(-|t|/tau)):
    2 d D_t t + 2 d D_a [t - tau (1 - e^(-t/tau))] (../shared/PHYSICS.md)."""
    t = np.asarray(t, dtype=float)
    return 2.0 * dimension * (d_t * t + d_a * (t - tau * (1.0 - np.exp(-t / tau))))


def rotational_top_eigenvalue(d_r, a, modes=40):
    """The largest eigenvalue of D_r d^2/dtheta^2 + a cos(theta) on 2 pi-periodic
    functions (a Mathieu operator). In the Fourier basis e^(i m theta), m = -M..M, it is
    the symmetric tridiagonal matrix with diagonal -D_r m^2 and off-diagonal a / 2; the
    top eigenvector falls off like (a / D_r)^|m| / (m!)^2, so M = 40 is exact to
    rounding for a / D_r up to ~100."""
    m = np.arange(-modes, modes + 1, dtype=float)
    top = eigh_tridiagonal(-d_r * m * m, np.full(2 * modes, 0.5 * a), eigvals_only=True,
                           select="i", select_range=(2 * modes, 2 * modes))
    return float(top[0])


def active_sedimentation_rate(v0, d_r, d_t, weight, mobility=1.0):
    """The far-field decay rate lambda of the density of dilute ideal 2D ABPs under a
    force ``weight`` along -y, n(y) ~ e^(-lambda y): with P(y, theta) = e^(-lambda y)
    g(theta) the stationary Fokker-Planck equation reads D_r g'' + lambda v0 cos(theta) g
    = lambda (mu w - D_t lambda) g (theta from the upward axis), so lambda is the root in
    (0, mu w / D_t) of rotational_top_eigenvalue(D_r, lambda v0) = lambda (mu w - D_t
    lambda) (Enculescu & Stark, PRL 107, 058301 (2011)). It tends to mu w / (D_t +
    v0^2 / (2 D_r)) for mu w << v0 and is the barometric mu w / D_t for v0 = 0."""
    top_rate = mobility * weight / d_t
    if v0 == 0.0:
        return top_rate

    def gap(rate):
        return rotational_top_eigenvalue(d_r, rate * v0) - rate * (mobility * weight - d_t * rate)
    # the gap is ~ -mu w lambda just above 0 and >= 0 at mu w / D_t (the eigenvalue is >= 0)
    return brentq(gap, 1e-9 * top_rate, top_rate, xtol=1e-14 * top_rate)
