"""`pedesis analyze clusters` takes its contact distance from the run's pair potential:
a dense WCA cluster whose particles sit just beyond 1.1 diameters apart (as active WCA
particles at alpha = epsilon = 1 do) was reported as 0.003 of the particles."""
import math
import re

import gsd.hoomd
import numpy as np
import pytest

import pedesis.analyze as pa
from pedesis.analyze.plots.contact import contact_distances

WCA_RUN = """dimension = 2
dynamics = "brownian"
seed = 1
[box]
length = 60.0
[[species]]
name = "A"
count = {count}
radius = 0.5
[[force]]
name = "wca"
epsilon = 1.0
[[force]]
name = "self_propulsion"
alpha = 1.0
[[integrator]]
name = "brownian"
T = 0.01
gamma = 1.0
[[integrator]]
name = "brownian_rotation"
T = 0.01
gamma = 1.0
[run]
steps = 2
dt = 0.001
"""


def hexagonal_cluster_in_a_gas(spacing=1.11, rows=20, gas=200, seed=4):
    """A rows x rows triangular patch of the given spacing in a 60 x 60 box, and a dilute
    gas that keeps 3 away from it and 1.5 from one another."""
    j, i = np.meshgrid(np.arange(rows), np.arange(rows), indexing="ij")
    patch = np.stack([(i + 0.5 * (j % 2)) * spacing, j * spacing * math.sqrt(3) / 2], axis=-1)
    patch = patch.reshape(-1, 2) + 5.0
    rng = np.random.default_rng(seed)
    loose = []
    while len(loose) < gas:
        p = rng.uniform(0, 60, 2)
        if np.min(np.linalg.norm(patch - p, axis=1)) > 3 and all(
                np.linalg.norm(p - q) > 1.5 for q in loose):
            loose.append(p)
    return np.concatenate([patch, loose])


def write_run(folder, x):
    folder.mkdir()
    (folder / "config.toml").write_text(WCA_RUN.format(count=len(x)))
    with gsd.hoomd.open(str(folder / "trajectory.gsd"), "wb") as f:
        for step in (0, 1, 2):
            frame = gsd.hoomd.Snapshot()
            frame.configuration.step = step
            frame.configuration.box = [60.0, 60.0, 0.0, 0, 0, 0]
            frame.configuration.dimensions = 2
            frame.particles.N = len(x)
            frame.particles.types = ["A"]
            frame.particles.typeid = np.zeros(len(x), np.uint32)
            frame.particles.diameter = np.ones(len(x), np.float32)
            frame.particles.position = np.column_stack([x, np.zeros(len(x))]).astype(np.float32)
            f.append(frame)


def test_clusters_of_a_wca_run_use_the_wca_cutoff_by_default(tmp_path, run_cli):
    x = hexagonal_cluster_in_a_gas()
    write_run(tmp_path / "run", x)
    # the particles with 5 or more neighbours within 2^(1/6) (the interior of the patch)
    d = np.linalg.norm(x[:, None] - x[None], axis=2)
    dense = (((d < 2 ** (1 / 6)) & (d > 0)).sum(axis=1) >= 5).sum() / len(x)
    assert dense > 0.5
    out = run_cli("analyze", "clusters", tmp_path / "run", "--out", tmp_path / "c.png").stdout
    assert "clusters: contact distance 1.122 (wca's cutoff 2^(1/6) sigma; --contact overrides)" in out
    largest = [float(line.split()[-1]) for line in out.splitlines() if re.match(r"\s+[012] ", line)]
    assert largest == pytest.approx([dense] * 3, abs=1e-9)  # was 0.000: 1.1 < 1.11
    # --contact keeps its meaning: diameters
    out = run_cli("analyze", "clusters", tmp_path / "run", "--contact", "1.05",
                  "--out", tmp_path / "c.png").stdout
    assert "clusters: contact distance 1.05 (--contact 1.05 diameters of 1)" in out
    assert [float(line.split()[-1]) for line in out.splitlines()
            if re.match(r"\s+[012] ", line)] == [0.0] * 3


def test_contact_distances_follow_each_potential_pair_by_pair():
    names, radii = ["A", "B"], [0.5, 0.3]
    wca, why = contact_distances({"dynamics": "brownian", "force": [{"name": "wca", "epsilon": 1.0}]},
                                 names, radii)
    assert why == "wca's cutoff 2^(1/6) sigma"
    np.testing.assert_allclose(wca, 2 ** (1 / 6) * np.array([[1.0, 0.8], [0.8, 0.6]]))
    harmonic, why = contact_distances({"dynamics": "langevin", "force": [
        {"name": "harmonic", "k": 5.0, "a": {"A": 1.0, "B": 0.64}}]}, names, radii)
    assert why == "harmonic's range a"
    np.testing.assert_allclose(harmonic, [[1.0, 0.8], [0.8, 0.64]])  # geometric mixing
    # Kob-Andersen: per-pair sigma from [[force.pairs]], first shell 1.5 sigma
    lj, why = contact_distances({"dynamics": "nve", "force": [
        {"name": "lj", "epsilon": 1.0, "sigma": 1.0, "cutoff": 2.5,
         "pairs": [{"species": ["B", "A"], "sigma": 0.8}, {"species": ["B", "B"], "sigma": 0.88}]}]},
        names, radii)
    assert why == "lj's first shell 1.5 sigma"
    np.testing.assert_allclose(lj, 1.5 * np.array([[1.0, 0.8], [0.8, 0.88]]))
    arithmetic, _ = contact_distances({"dynamics": "nve", "force": [
        {"name": "lj", "epsilon": 1.0, "sigma": {"A": 1.0, "B": 0.6}, "mixing": "arithmetic",
         "cutoff": 1.2}]}, names, radii)
    np.testing.assert_allclose(arithmetic, 1.2 * np.array([[1.0, 0.8], [0.8, 0.6]]))  # the cutoff
    both, why = contact_distances({"dynamics": "brownian", "force": [
        {"name": "wca", "epsilon": 1.0, "sigma": 0.5}, {"name": "harmonic", "k": 1.0},
        {"name": "self_propulsion", "alpha": 1.0}]}, names, radii)
    assert why == "the largest of harmonic's range a, wca's cutoff 2^(1/6) sigma"
    np.testing.assert_allclose(both, [[1.0, 0.8], [0.8, 0.6]])
    hard, why = contact_distances({"dynamics": "event"}, names, radii)
    assert why == "hard particles: 1.1 (r_i + r_j)"
    np.testing.assert_allclose(hard, 1.1 * np.array([[1.0, 0.8], [0.8, 0.6]]))


def test_clusters_with_a_contact_distance_per_pair_of_species():
    # A-A pairs 1.0 apart count (cutoff 1.05); B-B pairs as far apart do not (0.7)
    x = np.array([[0.0, 0.0], [1.0, 0.0], [10.0, 0.0], [11.0, 0.0], [1.0, 0.6]])
    types = np.array([0, 0, 1, 1, 1])
    cutoff = np.array([[1.05, 0.7], [0.7, 0.7]])
    labels, sizes = pa.clusters(x, pa.Box((30.0, 30.0)), cutoff, types=types)
    assert list(sizes) == [3, 1, 1]
    assert labels[0] == labels[1] == labels[4] and labels[2] != labels[3]
    with pytest.raises(ValueError, match="needs types"):
        pa.clusters(x, pa.Box((30.0, 30.0)), cutoff)
