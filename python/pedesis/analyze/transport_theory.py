"""Kinetic theory of the transport coefficients of hard disks and spheres: the dilute
Chapman-Enskog values, Enskog's dense-gas values and the Yeh-Hummer finite-size
correction of the diffusion coefficient (formulas: ../shared/PHYSICS.md, section
"Transport coefficients of hard particles"; docs/analyze.md).

Units: k_B = 1; ``sigma`` the diameter, ``mass`` the particle mass, ``temperature`` T,
``density`` the number density n (per area in 2D, per volume in 3D). The published
formulas are in reduced units sigma = m = T = 1; they carry their dimensions as

    D ~ sigma sqrt(T/m) / (n sigma^d),   eta, kappa ~ sqrt(m T) / sigma^(d-1),
    lambda ~ sqrt(T/m) / sigma^(d-1)   (the heat flux per temperature gradient, k_B = 1),

so each reduced value below is multiplied by its unit. In 3D the dilute values carry
the converged Sonine factors (1.018954 for D, 1.016034 for eta, 1.025218 for lambda);
in 2D they are the first Sonine approximation.
"""
import math

# Converged Sonine factors of the 3D dilute values (Chapman & Cowling; Pieprzyk et al.).
_SONINE_3D = {"diffusion": 1.018954, "shear_viscosity": 1.016034,
              "thermal_conductivity": 1.025218}

# The Yeh-Hummer constant of a cubic periodic box (Yeh & Hummer, J. Phys. Chem. B 108,
# 15873 (2004)): D_inf = D_L + xi T / (6 pi eta L).
YEH_HUMMER_XI = 2.837297


def packing_fraction(dimension, density, sigma=1.0):
    """phi = pi n sigma^2 / 4 (2D) or pi n sigma^3 / 6 (3D)."""
    _check_dimension(dimension)
    return math.pi * density * sigma ** dimension / (4.0 if dimension == 2 else 6.0)


def contact_value(dimension, packing):
    """g(sigma+) of one-component hard particles: Henderson (1 - 7 phi/16)/(1 - phi)^2 in
    2D, Carnahan-Starling (1 - phi/2)/(1 - phi)^3 in 3D."""
    _check_dimension(dimension)
    if not 0.0 <= packing < 1.0:
        raise ValueError(f"the packing fraction must lie in [0, 1), not {packing!r}")
    if dimension == 2:
        return (1.0 - 7.0 * packing / 16.0) / (1.0 - packing) ** 2
    return (1.0 - packing / 2.0) / (1.0 - packing) ** 3


def chapman_enskog_dilute(dimension, density, sigma=1.0, mass=1.0, temperature=1.0):
    """The dilute-gas (Boltzmann, chi -> 1, n -> 0) coefficients:
    3D  D0 = 1.018954 * 3/(8 n sigma^2) sqrt(T/(pi m)),  eta0 = 1.016034 * 5/(16 sigma^2)
        sqrt(m T/pi),  lambda0 = 1.025218 * 75/(64 sigma^2) sqrt(T/(pi m));
    2D  D0 = 1/(2 n sigma) sqrt(T/(pi m)),  eta0 = 1/(2 sigma) sqrt(m T/pi),
        lambda0 = 2/sigma sqrt(T/(pi m))  (first Sonine).
    The bulk viscosity of a dilute gas of hard particles is 0. Returns a dict with the
    keys diffusion, shear_viscosity, bulk_viscosity, thermal_conductivity."""
    d_unit, eta_unit, lambda_unit = _units(dimension, density, sigma, mass, temperature)
    root_pi = math.sqrt(math.pi)
    if dimension == 2:
        reduced = (1.0 / (2.0 * root_pi), 1.0 / (2.0 * root_pi), 2.0 / root_pi)
    else:
        reduced = (_SONINE_3D["diffusion"] * 3.0 / (8.0 * root_pi),
                   _SONINE_3D["shear_viscosity"] * 5.0 / (16.0 * root_pi),
                   _SONINE_3D["thermal_conductivity"] * 75.0 / (64.0 * root_pi))
    return {"diffusion": reduced[0] * d_unit, "shear_viscosity": reduced[1] * eta_unit,
            "bulk_viscosity": 0.0, "thermal_conductivity": reduced[2] * lambda_unit}


def enskog_transport(dimension, density, sigma=1.0, mass=1.0, temperature=1.0):
    """Enskog's coefficients of one-component hard particles, chi = contact_value:
    3D (y = 4 phi chi): D_E = D0/chi, eta_E = (eta0/chi)(1 + 0.8 y + 0.7615 y^2),
       lambda_E = (lambda0/chi)(1 + 1.2 y + 0.7575 y^2), kappa_E = (4/9) n^2 sigma^4 chi
       sqrt(pi m T);
    2D D_E = D0/chi, eta_E = eta0 [1/chi + 2 phi + (1 + 8/pi) phi^2 chi],
       lambda_E = lambda0 [1/chi + 3 phi + (9/4 + 4/pi) phi^2 chi],
       kappa_E = (1/2) n^2 sigma^3 chi sqrt(pi m T)
    with D0, eta0, lambda0 of chapman_enskog_dilute. The bulk viscosity is Enskog's
    kappa = (2^(2d+1) / (pi (d + 2))) * 2 phi^2 chi eta0 (Garzo & Dufty, Phys. Rev. E 59,
    5895 (1999), elastic limit; 2D: Gass, J. Chem. Phys. 54, 1898 (1971)): in 3D it is
    the (4/9) formula above, and in 2D it is the term (8/pi) phi^2 chi eta0 = kappa/2 of
    eta_E (eta = (eta0/chi)(1 + phi chi)^2 + (d/(d+2)) kappa). Returns a dict with the
    keys diffusion, shear_viscosity, bulk_viscosity, thermal_conductivity."""
    phi = packing_fraction(dimension, density, sigma)
    chi = contact_value(dimension, phi)
    dilute = chapman_enskog_dilute(dimension, density, sigma, mass, temperature)
    eta0, lambda0 = dilute["shear_viscosity"], dilute["thermal_conductivity"]
    _, eta_unit, _ = _units(dimension, density, sigma, mass, temperature)
    if dimension == 2:
        eta = eta0 * (1.0 / chi + 2.0 * phi + (1.0 + 8.0 / math.pi) * phi * phi * chi)
        conductivity = lambda0 * (1.0 / chi + 3.0 * phi + (2.25 + 4.0 / math.pi) * phi * phi * chi)
        bulk_reduced = 0.5 * math.sqrt(math.pi)
    else:
        y = 4.0 * phi * chi
        eta = eta0 / chi * (1.0 + 0.8 * y + 0.7615 * y * y)
        conductivity = lambda0 / chi * (1.0 + 1.2 * y + 0.7575 * y * y)
        bulk_reduced = 4.0 / 9.0 * math.sqrt(math.pi)
    # n^2 sigma^(d+1) sqrt(m T) = (n sigma^d)^2 * sqrt(m T) / sigma^(d-1)
    bulk = bulk_reduced * (density * sigma ** dimension) ** 2 * chi * eta_unit
    return {"diffusion": dilute["diffusion"] / chi, "shear_viscosity": eta,
            "bulk_viscosity": bulk, "thermal_conductivity": conductivity}


def yeh_hummer(d_pbc, temperature, shear_viscosity, box_length):
    """The diffusion coefficient of an infinite system from that of a cubic periodic box
    of edge L: D_inf = D_L + 2.837297 T / (6 pi eta L) (3D; k_B = 1)."""
    if shear_viscosity <= 0 or box_length <= 0:
        raise ValueError("yeh_hummer: the shear viscosity and the box length must be positive")
    return d_pbc + YEH_HUMMER_XI * temperature / (6.0 * math.pi * shear_viscosity * box_length)


def _units(dimension, density, sigma, mass, temperature):
    """The units of D, of eta (and kappa), and of lambda that the reduced values multiply."""
    _check_dimension(dimension)
    if density <= 0 or sigma <= 0 or mass <= 0 or temperature <= 0:
        raise ValueError("the density, sigma, mass and temperature must be positive")
    speed = math.sqrt(temperature / mass)
    return (sigma * speed / (density * sigma ** dimension),
            math.sqrt(mass * temperature) / sigma ** (dimension - 1),
            speed / sigma ** (dimension - 1))


def _check_dimension(dimension):
    if dimension not in (2, 3):
        raise ValueError(f"the dimension must be 2 or 3, not {dimension!r}")
