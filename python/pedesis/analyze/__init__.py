"""pedesis.analyze: analysis of particle trajectories, as functions of numpy arrays.

Each function takes positions (an (N, d) array, d = 2 or 3, or (T, N, d) for a
trajectory) and a :class:`Box`, and returns numpy arrays; plotting is left to the caller.
Frames come from pedesis run directories or any GSD file through :func:`read_frames`.
Neighbour searches use scipy's cKDTree (periodic boxes through its ``boxsize``), never an
O(N^2) loop. Lengths are in the units of the positions; times in those of the frames.

Structure: :func:`rdf` (g(r), per species pair), :func:`structure_factor` (direct, on
the box's reciprocal lattice), :func:`structure_factor_from_rdf`.
Dynamics: :func:`msd` (FFT method), :func:`msd_direct` (the O(T^2) sum it must equal),
:func:`self_intermediate_scattering`, :func:`velocity_autocorrelation`; :func:`unwrap`
(continuous paths for frames without image counts).
Order: :func:`psi6` (2D bond order, global and per particle), :func:`steinhardt` (q4,
q6 in 3D), :func:`clusters`.
Transport: :func:`diffusion_coefficient` (from the MSD), :func:`green_kubo` and
:func:`shear_viscosity` (from a flux, or a log's pressure tensor), and the kinetic theory
they are compared with, :func:`enskog_transport`, :func:`chapman_enskog_dilute`,
:func:`yeh_hummer`.
Active matter: :func:`polar_order`, :func:`polar_correlation`, :func:`local_area_fraction`
with :func:`histogram_peaks` and :func:`phase_fractions` (MIPS bimodality and the
coexisting fractions), :func:`swim_pressure`.

Example::

    import pedesis.analyze as pa
    traj = pa.read_frames("runs/demo")
    r, g = pa.rdf(traj.positions[-1], traj.box, r_max=5.0, bins=200)
"""
from .active import (fraction_bins, histogram_peaks, local_area_fraction, phase_fractions, polar_correlation,
                     polar_order, swim_pressure)
from .box import Box
from .dynamics import msd, msd_direct, self_intermediate_scattering, velocity_autocorrelation
from .frames import Trajectory, read_frames
from .order import clusters, psi6
from .paths import unwrap
from .steinhardt import steinhardt
from .structure import rdf, structure_factor, structure_factor_from_rdf
from .transport import diffusion_coefficient, green_kubo, shear_viscosity
from .transport_theory import chapman_enskog_dilute, enskog_transport, yeh_hummer

__all__ = [
    "Box", "Trajectory", "read_frames", "rdf", "structure_factor", "structure_factor_from_rdf",
    "msd", "msd_direct", "unwrap", "self_intermediate_scattering", "velocity_autocorrelation", "psi6",
    "clusters", "steinhardt", "polar_order", "polar_correlation", "local_area_fraction",
    "fraction_bins", "histogram_peaks", "phase_fractions", "swim_pressure",
    "diffusion_coefficient", "green_kubo", "shear_viscosity", "enskog_transport",
    "chapman_enskog_dilute", "yeh_hummer",
]
