"""pedesis.analyze against exact cases: each quantity on a configuration whose answer is
known without the code (a lattice, an ideal gas, a random walk, an analytic g(r)), at a
tolerance that the configuration's size makes fair."""
import re
import subprocess

import numpy as np
import pytest

import pedesis.analyze as pa


def triangular(nx, ny, a=1.0):
    """A perfect triangular lattice of spacing a filling a periodic nx by ny box (ny even)."""
    j, i = np.meshgrid(np.arange(ny), np.arange(nx), indexing="ij")
    x = (i + 0.5 * (j % 2)) * a
    y = j * a * np.sqrt(3.0) / 2.0
    return np.stack([x.ravel(), y.ravel()], axis=1), pa.Box((nx * a, ny * a * np.sqrt(3.0) / 2.0))


def fcc(n, a=1.0):
    """n^3 cubic cells of 4 sites: nearest neighbours at a/sqrt(2) (12), then a (6)."""
    cells = np.stack(np.meshgrid(*[np.arange(n)] * 3, indexing="ij"), axis=-1).reshape(-1, 3)
    basis = np.array([[0, 0, 0], [0.5, 0.5, 0], [0.5, 0, 0.5], [0, 0.5, 0.5]])
    return ((cells[:, None, :] + basis[None]) * a).reshape(-1, 3), pa.Box((n * a,) * 3)


def coordination(r, g, density, dimension, lo, hi):
    """Neighbours between lo and hi: rho * sum of g over the shells there (rho of the
    other particles: (N - 1) / V within one species, as g is normalised by N (N - 1))."""
    dr = r[1] - r[0]
    edges = np.concatenate([r - dr / 2, [r[-1] + dr / 2]])
    shell = np.pi * np.diff(edges ** 2) if dimension == 2 else 4 / 3 * np.pi * np.diff(edges ** 3)
    inside = (r > lo) & (r < hi)
    return density * (g * shell)[inside].sum()


@pytest.mark.parametrize("dimension,walls", [(2, False), (3, False), (2, True), (3, True)])
def test_rdf_of_an_ideal_gas_is_one_within_its_noise(dimension, walls):
    # 20 frames' worth of uniform points: each bin past r = 1 holds >= 1e4 pairs, so g
    # deviates from 1 by ~1 %; 5 standard deviations of the pair count bound each bin,
    # and walls must not bend g (the set covariance in the normalisation)
    rng = np.random.default_rng(1)
    L = 30.0 if dimension == 2 else 14.0
    box = pa.Box((L,) * dimension, (not walls,) * dimension)
    n = 3000
    r_max = 5.0
    g_sum, frames = 0.0, 20
    for _ in range(frames):
        r, g = pa.rdf(rng.uniform(0, L, (n, dimension)), box, r_max=r_max, bins=25)
        g_sum = g_sum + g
    g = g_sum / frames
    dr = r_max / 25
    shell = 2 * np.pi * r * dr if dimension == 2 else 4 * np.pi * r ** 2 * dr
    expected_pairs = frames * 0.5 * n * (n - 1) / L ** dimension * shell
    bound = 5 / np.sqrt(expected_pairs)
    if walls:
        bound = bound * 1.5  # fewer pairs near walls
    far = r > 1.0
    assert np.all(np.abs(g[far] - 1) < bound[far]), (g[far], bound[far])


def test_rdf_of_a_triangular_lattice_has_its_shells_at_a_sqrt3a_2a_with_six_each():
    x, box = triangular(40, 46)
    r, g = pa.rdf(x, box, r_max=2.5, bins=500)
    rho = (len(x) - 1) / box.volume
    for centre in (1.0, np.sqrt(3.0), 2.0):
        assert coordination(r, g, rho, 2, centre - 0.02, centre + 0.02) == pytest.approx(6.0, rel=1e-9)
    # nothing between the shells, nor below a
    between = (r < 0.98) | ((r > 1.02) & (r < 1.71)) | ((r > 1.75) & (r < 1.98))
    assert np.all(g[between] == 0)


def test_rdf_of_fcc_has_12_neighbours_at_a_over_root2_and_6_at_a():
    x, box = fcc(8)
    r, g = pa.rdf(x, box, r_max=1.2, bins=600)
    rho = (len(x) - 1) / box.volume
    assert coordination(r, g, rho, 3, 0.69, 0.73) == pytest.approx(12.0, rel=1e-9)
    assert coordination(r, g, rho, 3, 0.98, 1.02) == pytest.approx(6.0, rel=1e-9)


def test_rdf_per_species_pair_of_two_interleaved_lattices():
    # two square lattices offset by half a cell: A-B neighbours at a/sqrt(2) (4 of them),
    # A-A at a (4); g_AB vanishes at a, g_AA at a/sqrt(2)
    n = 30
    i, j = np.meshgrid(np.arange(n), np.arange(n), indexing="ij")
    a_sites = np.stack([i.ravel(), j.ravel()], axis=1).astype(float)
    x = np.concatenate([a_sites, a_sites + 0.5])
    types = np.repeat([0, 1], n * n)
    box = pa.Box((n, n))
    r, g_ab = pa.rdf(x, box, r_max=1.2, bins=240, types=types, pair=(0, 1))
    _, g_aa = pa.rdf(x, box, r_max=1.2, bins=240, types=types, pair=(0, 0))
    rho_b, rho_other_a = n * n / box.volume, (n * n - 1) / box.volume
    assert coordination(r, g_ab, rho_b, 2, 0.69, 0.73) == pytest.approx(4.0, rel=1e-9)
    assert coordination(r, g_aa, rho_other_a, 2, 0.98, 1.02) == pytest.approx(4.0, rel=1e-9)
    assert coordination(r, g_ab, rho_b, 2, 0.98, 1.02) == 0
    assert coordination(r, g_aa, rho_b, 2, 0.69, 0.73) == 0


def test_structure_factor_of_a_square_lattice_is_n_at_its_bragg_peak_and_zero_between():
    n = 20
    i, j = np.meshgrid(np.arange(n), np.arange(n), indexing="ij")
    x = np.stack([i.ravel(), j.ravel()], axis=1).astype(float)
    box = pa.Box((n, n))
    q, s = pa.structure_factor(x, box, q_max=2 * np.pi * 1.05, binned=False)
    # the reciprocal lattice vectors (2 pi, 0), (0, 2 pi) and their negatives: S = N;
    # every other allowed wave vector (|q| = 2 pi too for n = (16, 12)): the phases cancel
    bragg = np.all(np.isclose(np.mod(q / (2 * np.pi) + 0.5, 1.0), 0.5), axis=1)
    assert bragg.sum() == 4
    assert s[bragg] == pytest.approx(np.full(4, n * n), rel=1e-9)
    assert np.all(s[~bragg] < 1e-9 * n * n)
    # binned: the bin of |q| = 2 pi averages the 4 Bragg vectors with the 8 of n = (16, 12)
    qb, sb = pa.structure_factor(x, box, q_max=2 * np.pi * 1.05, bins=400)
    assert sb.max() == pytest.approx(n * n * 4 / 12, rel=1e-9)


def test_structure_factor_from_an_analytic_rdf():
    # g(r) = 1 - exp(-r^2 / s^2) in 3D: S(q) = 1 - rho pi^(3/2) s^3 exp(-q^2 s^2 / 4)
    s, rho = 0.8, 0.5
    r = np.linspace(0, 12, 6001)
    g = 1 - np.exp(-(r / s) ** 2)
    q = np.array([0.5, 1.0, 2.0, 4.0])
    got = pa.structure_factor_from_rdf(r, g, rho, q, 3)
    want = 1 - rho * np.pi ** 1.5 * s ** 3 * np.exp(-(q * s) ** 2 / 4)
    assert got == pytest.approx(want, abs=1e-5)  # trapezoids of dr = 0.002
    # 2D: 1 - rho pi s^2 exp(-q^2 s^2 / 4)
    got2 = pa.structure_factor_from_rdf(r, g, rho, q, 2)
    assert got2 == pytest.approx(1 - rho * np.pi * s ** 2 * np.exp(-(q * s) ** 2 / 4), abs=1e-5)


def test_fft_msd_equals_the_direct_sum():
    rng = np.random.default_rng(2)
    x = np.cumsum(rng.normal(size=(300, 40, 3)), axis=0)
    assert pa.msd(x) == pytest.approx(pa.msd_direct(x), rel=1e-9, abs=1e-9)


def test_random_walk_msd_and_self_intermediate_scattering_against_diffusion():
    # Gaussian steps of variance 2 D per axis and frame: MSD = 2 d D t exactly on average,
    # F_s(q, t) = exp(-q^2 D t); 4000 walkers make both agree to ~1 % (bound 3 %)
    rng = np.random.default_rng(3)
    D, d = 0.05, 2
    x = np.cumsum(rng.normal(scale=np.sqrt(2 * D), size=(60, 4000, d)), axis=0)
    lags = np.arange(1, 40)
    assert pa.msd(x)[lags] == pytest.approx(2 * d * D * lags, rel=0.03)
    _, fs = pa.self_intermediate_scattering(x, q=2.0, lags=lags)
    assert fs == pytest.approx(np.exp(-4.0 * D * lags), rel=0.03, abs=0.01)


def test_velocity_autocorrelation_of_constant_velocities_is_v_squared():
    v = np.tile(np.array([[3.0, 4.0]]), (50, 10, 1))
    assert pa.velocity_autocorrelation(v) == pytest.approx(np.full(50, 25.0))


def test_psi6_is_one_on_a_triangular_lattice_and_small_for_a_gas():
    x, box = triangular(30, 36)
    total, local = pa.psi6(x, box)
    assert total == pytest.approx(1.0, abs=1e-12)
    assert np.abs(local) == pytest.approx(np.ones(len(x)), abs=1e-12)
    gas = np.random.default_rng(4).uniform(0, 40, (4000, 2))
    assert pa.psi6(gas, pa.Box((40, 40)))[0] < 5 / np.sqrt(4000)


@pytest.mark.parametrize("walls", [False, True])
def test_voronoi_psi6_is_one_on_a_triangular_lattice_and_zero_on_a_square_one(walls):
    # every Voronoi cell of a triangular lattice is a regular hexagon (6 equal edges); a
    # square lattice's cells are squares, whose 4 bonds cancel in exp(6 i theta), and the
    # diagonal neighbours share a vertex only (weight 0). With walls the outer cells are
    # open: their finite edges still point along lattice bonds
    x, box = triangular(30, 36)
    if walls:
        box = pa.Box(box.lengths, (False, False))
    total, local = pa.psi6(x, box, weighting="voronoi")
    inner = np.ones(len(x), dtype=bool)
    if walls:  # the outermost rows and columns have open cells
        inner = (x[:, 0] > 1.5) & (x[:, 0] < 28) & (x[:, 1] > 1.5) & (x[:, 1] < 29)
    assert np.abs(local[inner]) == pytest.approx(np.ones(inner.sum()), abs=1e-9)
    if not walls:
        assert total == pytest.approx(1.0, abs=1e-9)
    j, i = np.meshgrid(np.arange(30), np.arange(30), indexing="ij")
    square = np.stack([i.ravel(), j.ravel()], axis=1) + 0.5
    assert np.abs(pa.psi6(square, pa.Box((30.0, 30.0)), weighting="voronoi")[1]).max() < 1e-9
    gas = np.random.default_rng(4).uniform(0, 40, (4000, 2))
    assert pa.psi6(gas, pa.Box((40, 40)), weighting="voronoi")[0] < 5 / np.sqrt(4000)


def test_clusters_of_two_patches_and_loose_particles():
    # a 100-particle patch at 21.5..29.6 (spacing 0.9 < cutoff 1), a 64-particle one at
    # 2..6.5, two loose particles, and one at x = 0.3 that touches the big patch only across
    # the periodic edge (0.7 away through it, 29.3 directly)
    i, j = np.meshgrid(np.arange(10), np.arange(10), indexing="ij")
    patch = np.stack([i.ravel(), j.ravel()], axis=1) * 0.9
    x = np.concatenate([patch[:64] + 2.0, patch + 21.5, [[15.0, 2.0], [2.0, 15.0], [0.3, 21.5]]])
    labels, sizes = pa.clusters(x, pa.Box((30.0, 30.0)), cutoff=1.0)
    assert list(sizes) == [101, 64, 1, 1]
    assert labels[-1] == 0 and labels[64] == 0 and labels[0] == 1
    assert set(labels[-3:-1]) == {2, 3}
    # with walls the edge no longer joins it
    _, walled = pa.clusters(x, pa.Box((30.0, 30.0), (False, False)), cutoff=1.0)
    assert list(walled) == [100, 64, 1, 1, 1]


def test_dense_clusters_keep_only_particles_with_enough_neighbours():
    # a triangular patch (interior particles have 6 neighbours at distance 1, its rim 2-4)
    # in a dilute gas: with min_neighbours = 5 one cluster of exactly the particles with
    # 5 or more neighbours, counted here by brute force; the gas and the rim get -1
    patch, _ = triangular(12, 12)
    rng = np.random.default_rng(2)
    gas = rng.uniform(20, 60, (40, 2))
    x = np.concatenate([patch + 2.0, gas])
    d = np.linalg.norm(x[:, None] - x[None], axis=2)
    degree = ((d < 1.1) & (d > 0)).sum(axis=1)
    labels, sizes = pa.clusters(x, pa.Box((80.0, 80.0)), cutoff=1.1, min_neighbours=5)
    assert sizes[0] == (degree >= 5).sum() > 80
    assert np.array_equal(labels == 0, degree >= 5)
    assert np.all(labels[degree < 5] == -1) and len(sizes) == 1


def test_dense_clusters_of_a_gas_without_a_dense_phase_are_none():
    # no particle of a dilute gas has 5 neighbours within 1.1: every label -1, no sizes
    # (this raised IndexError on the empty set of clusters)
    gas = np.random.default_rng(3).uniform(0, 40, (50, 2))
    labels, sizes = pa.clusters(gas, pa.Box((40.0, 40.0)), cutoff=1.1, min_neighbours=5)
    assert len(labels) == 50 and np.all(labels == -1)
    assert len(sizes) == 0
    labels, sizes = pa.clusters(np.zeros((0, 2)), pa.Box((40.0, 40.0)), cutoff=1.1)
    assert len(labels) == 0 and len(sizes) == 0


def test_read_frames_of_a_run_unwraps_to_the_logged_msd(tmp_path, run_cli):
    # a soft run's MSD since step 0, measured from its GSD frames (wrapped positions plus
    # image counts), is the log's msd column at each frame (float32 positions: 1e-5)
    cfg = tmp_path / "abp.toml"
    cfg.write_text(
        'dimension = 2\ndynamics = "brownian"\nseed = 4\n[box]\nlength = 8.0\n'
        '[[species]]\nname = "A"\ncount = 30\nradius = 0.5\n[initial]\npositions = "random"\n'
        '[[force]]\nname = "harmonic"\nk = 10.0\n[[force]]\nname = "self_propulsion"\nalpha = 2.0\n'
        '[[integrator]]\nname = "brownian"\nT = 0.2\ngamma = 1.0\n'
        '[[integrator]]\nname = "brownian_rotation"\nT = 0.2\ngamma = 1.0\n'
        '[run]\ndt = 0.01\nsteps = 400\n[output]\nlog_every = 50\nsnapshot_every = 50\n'
        'formats = ["gsd"]\nprogress = false\n[log]\nquantities = ["msd"]\n')
    run_cli("run", cfg, "--out", tmp_path / "run")
    traj = pa.read_frames(tmp_path / "run")
    assert traj.positions.shape == (9, 30, 2) and traj.box.lengths == (8.0, 8.0)
    assert traj.box.periodic == (True, True)
    x = traj.unwrapped()
    measured = ((x - x[0]) ** 2).sum(axis=2).mean(axis=1)
    rows = (tmp_path / "run" / "log.csv").read_text().splitlines()
    col = rows[0].split(",").index("msd")
    logged = np.array([float(r.split(",")[col]) for r in rows[1:]])
    assert np.abs(traj.images).max() > 0  # the swimmers crossed the edges
    assert measured == pytest.approx(logged, rel=1e-5, abs=1e-5)


def test_polar_order_of_aligned_and_random_directors():
    aligned = np.tile([[0.6, 0.8]], (500, 1))
    assert pa.polar_order(aligned) == pytest.approx(1.0)
    t = np.random.default_rng(5).uniform(0, 2 * np.pi, 10000)
    assert pa.polar_order(np.stack([np.cos(t), np.sin(t)], axis=1)) < 5 / np.sqrt(10000)


def test_polar_correlation_of_a_plane_wave_is_bessel_j0():
    # n = (cos kx, sin kx) on a uniform gas: n_i . n_j = cos(k dx), and over the pairs at
    # distance r (isotropic) < cos(k r cos(theta)) > = J0(k r); ~4000 pairs a bin at r > 1
    # bound the noise by 0.05
    from scipy.special import j0
    rng = np.random.default_rng(6)
    L, n = 40.0, 6000
    x = rng.uniform(0, L, (n, 2))
    k = 2 * np.pi / L * 6  # a whole number of waves: periodic
    d = np.stack([np.cos(k * x[:, 0]), np.sin(k * x[:, 0])], axis=1)
    r, c, count = pa.polar_correlation(x, d, pa.Box((L, L)), r_max=6.0, bins=30)
    far = r > 1.0
    assert np.all(count[far] > 1000)
    assert c[far] == pytest.approx(j0(k * r[far]), abs=0.05)


def test_local_area_fraction_of_a_lattice_and_a_separated_system():
    # disks of radius 0.5 on a unit square lattice: every 2 x 2 cell holds 4 centres, an
    # area fraction of pi/4 exactly
    n = 20
    i, j = np.meshgrid(np.arange(n), np.arange(n), indexing="ij")
    lattice = np.stack([i.ravel(), j.ravel()], axis=1) + 0.25
    phi = pa.local_area_fraction(lattice, 0.5, pa.Box((n, n)), cell=2.0)
    assert phi == pytest.approx(np.full(100, np.pi / 4))
    # half the box that lattice, the other half a dilute gas: two peaks, near pi/4 and
    # near the gas's area fraction (40 disks in 200: 0.157)
    gas = np.random.default_rng(7).uniform([10, 0], [20, 20], (40, 2))
    mixed = np.concatenate([lattice[lattice[:, 0] < 10], gas])
    peaks, _, _ = pa.histogram_peaks(pa.local_area_fraction(mixed, 0.5, pa.Box((n, n)), cell=2.0),
                                     bins=20, min_share=0.1)
    assert len(peaks) >= 2
    assert min(abs(peaks - np.pi / 4)) < 0.05 and min(abs(peaks - 0.157)) < 0.12


def test_swim_pressure_of_free_active_brownian_particles():
    # 2D free ABPs (U0 = 1, zeta = 1, D_r = 1, no translational noise), Euler steps of
    # 0.01: Pi -> n zeta U0^2 / (2 D_r) = n / 2 after a few tau_R = 1; the mean over
    # t in [5, 20] of 2000 particles is within 5 % (its noise ~2 %)
    rng = np.random.default_rng(8)
    N, T, dt = 2000, 2000, 0.01
    theta = np.cumsum(rng.normal(scale=np.sqrt(2 * dt), size=(T, N)), axis=0)
    n = np.stack([np.cos(theta), np.sin(theta)], axis=2)
    x = np.concatenate([np.zeros((1, N, 2)), np.cumsum(n[:-1] * dt, axis=0)])
    volume = 100.0 ** 2
    pi = pa.swim_pressure(x, n, alpha=1.0, volume=volume)
    late = pi[500:].mean()
    assert late == pytest.approx(N / volume / 2, rel=0.05)


def test_steinhardt_q4_q6_of_fcc_and_simple_cubic():
    x, box = fcc(5)
    assert pa.steinhardt(x, box, 4) == pytest.approx(np.full(len(x), 0.19094), abs=1e-5)
    assert pa.steinhardt(x, box, 6) == pytest.approx(np.full(len(x), 0.57452), abs=1e-5)
    c = np.stack(np.meshgrid(*[np.arange(6.0)] * 3, indexing="ij"), axis=-1).reshape(-1, 3)
    sc = pa.Box((6.0, 6.0, 6.0))
    assert pa.steinhardt(c, sc, 4, neighbours=6) == pytest.approx(np.full(len(c), 0.76376), abs=1e-5)
    assert pa.steinhardt(c, sc, 6, neighbours=6) == pytest.approx(np.full(len(c), 0.35355), abs=1e-5)


@pytest.mark.parametrize("dimension", [2, 3])
def test_contact_value_of_hard_particles_gives_the_measured_pressure(tmp_path, run_cli, dimension):
    # the virial theorem for hard disks (spheres): Z = 1 + 2 eta g(sigma+) (1 + 4 eta
    # g(sigma+)); g(sigma+) extrapolated from the first bins of g(r) over the frames of an
    # event-driven run at eta = 0.3 must give the Z the engine measures from its
    # collisions, within 3 combined standard errors (8 blocks of frames, 8 of log rows)
    n = 400 if dimension == 2 else 500
    eta = 0.3
    volume_one = np.pi / 4 if dimension == 2 else np.pi / 6
    L = (n * volume_one / eta) ** (1 / dimension)
    cfg = tmp_path / "hard.toml"
    cfg.write_text(
        f"dimension = {dimension}\nseed = 11\n[box]\nlength = {L!r}\n"
        f'[[species]]\nname = "A"\ncount = {n}\nradius = 0.5\n'
        '[initial]\nvelocities = "normal"\nsigma = 1.0\n[run]\ntime = 400.0\n'
        '[output]\nlog_interval = 1.0\nsnapshot_interval = 0.5\nformats = ["gsd"]\nprogress = false\n')
    run_cli("run", cfg, "--out", tmp_path / "run")
    traj = pa.read_frames(tmp_path / "run")
    frames = traj.positions[40:]  # after t = 20
    r, _ = pa.rdf(frames[0], traj.box, r_max=1.5, bins=150)
    near = (r > 1.0) & (r < 1.08)

    def contact(block):
        g = np.mean([pa.rdf(x, traj.box, r_max=1.5, bins=150)[1] for x in block], axis=0)
        return np.polyval(np.polyfit(r[near], g[near], 2), 1.0)

    values = [contact(b) for b in np.array_split(frames, 8)]
    g_contact, g_error = np.mean(values), np.std(values, ddof=1) / np.sqrt(8)
    factor = 2 * eta if dimension == 2 else 4 * eta
    z_from_g = 1 + factor * g_contact
    rows = (tmp_path / "run" / "log.csv").read_text().splitlines()
    col = rows[0].split(",").index("compressibility")
    z_rows = np.array([float(row.split(",")[col]) for row in rows[21:]])  # t > 20
    z_blocks = [b.mean() for b in np.array_split(z_rows, 8)]
    z, z_error = np.mean(z_blocks), np.std(z_blocks, ddof=1) / np.sqrt(8)
    bound = 3 * np.hypot(factor * g_error, z_error)
    assert abs(z_from_g - z) < bound, (z_from_g, z, bound)


def _lattice_run(tmp_path, run_cli):
    """A 20 x 20 triangular lattice of spacing 1 (disks of diameter 0.9) that does not
    move: brownian dynamics at T = 0 with no force, two frames."""
    cfg = tmp_path / "lattice.toml"
    cfg.write_text(
        'dimension = 2\ndynamics = "brownian"\nseed = 1\n[box]\n'
        f'lengths = [20.0, {20 * np.sqrt(3) / 2!r}]\n'
        '[[species]]\nname = "A"\ncount = 400\nradius = 0.45\n[initial]\npositions = "hexagonal"\n'
        '[[integrator]]\nname = "brownian"\nT = 0.0\ngamma = 1.0\n'
        '[run]\ndt = 0.01\nsteps = 2\n[output]\nlog_every = 1\nsnapshot_every = 1\n'
        'formats = ["gsd"]\nprogress = false\n')
    run_cli("run", cfg, "--out", tmp_path / "run")
    return tmp_path / "run"


def test_analyze_figures_of_a_lattice_run(tmp_path, run_cli):
    # the CLI's structure, bond_order and clusters figures of a perfect lattice: g(r)'s
    # highest peak at the spacing 1 (within a bin of 0.04), |psi6| = 1, and every particle
    # in one dense cluster (6 neighbours within 1.2 diameters = 1.08) with no phase split
    run = _lattice_run(tmp_path, run_cli)
    out = run_cli("analyze", "structure", run).stdout
    peak = float(re.search(r"highest peak at r = ([0-9.]+)", out).group(1))
    assert abs(peak - 1.0) < 0.04
    assert (run / "structure.png").stat().st_size > 10000
    out = run_cli("analyze", "bond_order", run).stdout
    assert "|<psi6>| = 1.0000" in out
    out = run_cli("analyze", "clusters", run, "--contact", "1.2", "--out", tmp_path / "c.png").stdout
    last = [line for line in out.splitlines() if line.strip().startswith("0.02")][0].split()
    assert float(last[3]) == 1.0
    assert "one peak: homogeneous" in out
    # a row's gas and dense columns say so too (they printed "nan nan")
    assert last[1:3] == ["one", "phase"] and "nan" not in out
    assert "clusters: contact distance 1.08 (--contact 1.2 diameters of 0.9)" in out
    assert (tmp_path / "c.png").stat().st_size > 10000


def test_analyze_figures_refuse_bad_input(tmp_path, run_cli, pedesis_bin):
    run = _lattice_run(tmp_path, run_cli)
    r = subprocess.run([pedesis_bin, "analyze", "clusters", str(run), "--cell", "-1"],
                       capture_output=True, text=True)
    assert r.returncode == 2 and "--cell" in r.stderr and r.stderr.count("\n") == 1
    (run / "trajectory.gsd").unlink()
    r = subprocess.run([pedesis_bin, "analyze", "structure", str(run)], capture_output=True,
                       text=True)
    assert r.returncode == 2 and "trajectory.gsd: missing" in r.stderr
