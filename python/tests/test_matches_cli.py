"""A script and `pedesis run` of the same config give the same trajectory, bit for bit:
the Python module drives the same C++ evolver, and keeping its arrays in tag order
between calls (restore_tag_order, NeighborList::reorder) must not change a single
floating-point operation of the steps."""
import json
import os
import re
import subprocess
import sys

import numpy as np
import pedesis
import pytest

TUTORIAL = """
dimension = {dim}
dynamics = "{dynamics}"
seed = {seed}

[initial]
file = "{init}"

[neighbor_list]
r_cut = 3.0
pad = 0.5

{terms}

[run]
steps = {steps}
dt = {dt}

[output]
log_every = 100
formats = ["json"]
progress = false
"""

ABP_TERMS = """
[[force]]
name = "harmonic"
k = 10.0
a = 2.0

[[force]]
name = "self_propulsion"
alpha = 1.0

[[torque]]
name = "polar_align"
J = 1.0
a = 2.0

[[integrator]]
name = "brownian"
T = 0.0
gamma = 1.0

[[integrator]]
name = "brownian_rotation"
T = 0.1
gamma = 1.0
"""

NVE_TERMS = """
[[force]]
name = "harmonic"
k = 10.0
a = 2.0

[[integrator]]
name = "nve"
"""


def final_frame(out_dir):
    frames = sorted((out_dir / "snapshots").glob("frame_*.json"))
    doc = json.loads(frames[-1].read_text())["system"]
    parts = sorted(doc["particles"], key=lambda p: p["id"])
    return (np.array([p["r"] for p in parts]), np.array([p["n"] for p in parts]),
            np.array([p["v"] for p in parts]))


def tutorial_script(init, seed, every, steps, dt):
    s = pedesis.System(rcut=3.0, pad=0.5, seed=seed)
    s.read_init(str(init))
    e = pedesis.Evolver(s)
    e.add_force(pedesis.HarmonicForce(s, 10.0, 2.0))
    e.add_force(pedesis.SelfPropulsion(s, 1.0))
    e.add_torque(pedesis.PolarAlign(s, 1.0, 2.0))
    e.add_integrator(pedesis.BrownianIntegrator(s, T=0.0, gamma=1.0))
    e.add_integrator(pedesis.BrownianRotIntegrator(s, T=0.1, gamma=1.0))
    seen = []
    if every:
        # reads the arrays at every callback, as a script recording observables would
        e.run(steps, dt, every=every, callback=lambda step: seen.append(s.polar_order()))
    else:
        for _ in range(steps):
            e.evolve(dt)
    return s, seen


# 1000 steps cross the space-filling-curve sort at step 500, which is where keeping the
# arrays in tag order for Python could have changed the summation order of the forces.
@pytest.mark.parametrize("every", [0, 10, 7])
def test_tutorial_example_is_bit_identical_to_the_cli(tmp_path, run_cli, every):
    init = tmp_path / "init.json"
    pedesis.builder.random_init(0.4, 50, rcut=1.0, outfile=init, seed=3)
    cfg = tmp_path / "abp.toml"
    cfg.write_text(TUTORIAL.format(dim=2, dynamics="brownian", seed=5, init=init.name,
                                   terms=ABP_TERMS, steps=1000, dt=0.01))
    run_cli("run", cfg, "--out", tmp_path / "cli")
    r_cli, n_cli, _ = final_frame(tmp_path / "cli")

    s, seen = tutorial_script(init, seed=5, every=every, steps=1000, dt=0.01)
    assert s.step == 1000
    assert np.array_equal(s.positions, r_cli)
    assert np.array_equal(s.directors, n_cli)
    if every:
        assert len(seen) == 1000 // every


def nve_case(tmp_path):
    """A 3D harmonic gas under velocity Verlet: its start and the CLI's config."""
    init = tmp_path / "init.json"
    pedesis.builder.random_init(0.05, 20, rcut=1.8, outfile=init, seed=4, dim=3)
    cfg = tmp_path / "nve.toml"
    cfg.write_text(TUTORIAL.format(dim=3, dynamics="nve", seed=2, init=init.name,
                                   terms=NVE_TERMS, steps=600, dt=0.005))
    return init, cfg


def test_velocity_verlet_3d_is_bit_identical_to_the_cli(tmp_path, run_cli):
    """The inertial integrator reads the forces of the previous step in its pre-step;
    callbacks that only read the arrays must not make the module recompute them."""
    init, cfg = nve_case(tmp_path)
    run_cli("run", cfg, "--out", tmp_path / "cli")
    r_cli, _, v_cli = final_frame(tmp_path / "cli")

    s = pedesis.System(rcut=3.0, pad=0.5, seed=2)
    s.read_init(str(init))
    assert s.dim == 3
    e = pedesis.Evolver(s)
    e.add_force(pedesis.HarmonicForce(s, 10.0, 2.0))
    e.add_integrator(pedesis.NVEIntegrator(s))
    energies = []
    e.run(600, 0.005, every=50, callback=lambda step: energies.append(s.kinetic_energy()))
    assert np.array_equal(s.positions, r_cli)
    assert np.array_equal(s.velocities, v_cli)


# The script of nve_case in a process of its own, which reads PEDESIS_SIMD once.
NVE_SCRIPT = """
import sys
import numpy as np
import pedesis
s = pedesis.System(rcut=3.0, pad=0.5, seed=2)
s.read_init(sys.argv[1])
e = pedesis.Evolver(s)
e.add_force(pedesis.HarmonicForce(s, 10.0, 2.0))
e.add_integrator(pedesis.NVEIntegrator(s))
e.run(600, 0.005)
np.save(sys.argv[2], np.stack([s.positions, s.velocities]))
"""


def test_every_kernel_set_runs_the_cli_and_a_script_alike(tmp_path, pedesis_bin):
    """Sets may differ from each other in the last bits (docs/engines.md, "CPU kernel
    sets"), but within one the CLI and a script run the same kernels. The CLI's copy of
    the AVX2 and AVX-512 kernels once called each row's last, partial group of four out of
    line, compiled for SSE2 without fused multiply-adds, and the module's did not: the
    CLI then differed from the script under those sets only."""
    version = subprocess.run([pedesis_bin, "--version"], capture_output=True, text=True)
    found = re.search(r"this CPU runs: ([a-z0-9, ]+);", version.stdout)
    assert found, version.stdout
    sets = found.group(1).split(", ")
    assert sets[0] == "sse2", sets
    init, cfg = nve_case(tmp_path)
    for kernels in sets:
        env = dict(os.environ, PEDESIS_SIMD=kernels)
        out = tmp_path / f"cli_{kernels}"
        r = subprocess.run([pedesis_bin, "run", str(cfg), "--out", str(out)],
                           capture_output=True, text=True, env=env)
        assert r.returncode == 0, r.stderr
        assert f"CPU kernels: {kernels}" in r.stdout, r.stdout
        r_cli, _, v_cli = final_frame(out)
        saved = tmp_path / f"script_{kernels}.npy"
        r = subprocess.run([sys.executable, "-c", NVE_SCRIPT, str(init), str(saved)],
                           capture_output=True, text=True, env=env)
        assert r.returncode == 0, r.stderr
        r_script, v_script = np.load(saved)
        assert np.array_equal(r_script, r_cli), f"positions differ under {kernels}"
        assert np.array_equal(v_script, v_cli), f"velocities differ under {kernels}"
