# The Kob-Andersen binary Lennard-Jones mixture (80:20, epsilon_AB = 1.5, sigma_AB = 0.8,
# epsilon_BB = 0.5, sigma_BB = 0.88, every pair cut at 2.5 sigma_ab and shifted) at
# density 1.2, from Python: NVT with a Langevin thermostat at T = 1, then NVE, where the
# total energy must stay constant. The config-file twin is examples/kob_andersen.toml.
#
#   python3 kob_andersen.py [--out DIR] [--quick]
import argparse
import json
import os

import numpy as np

import pedesis

ap = argparse.ArgumentParser(description="Kob-Andersen mixture: NVT then NVE")
ap.add_argument("--out", default="runs/python_kob_andersen", help="output folder")
ap.add_argument("--quick", action="store_true", help="fewer steps (CI)")
args = ap.parse_args()
os.makedirs(args.out, exist_ok=True)

# 10^3 sites of a slightly jittered cubic lattice at density 1.2; 200 of them, at random,
# are B particles (type 1). No two centres start closer than ~0.7 sigma.
n_side, rho = 10, 1.2
L = (n_side**3 / rho) ** (1 / 3)
a = L / n_side
rng = np.random.default_rng(3)
grid = np.stack(np.meshgrid(*[np.arange(n_side)] * 3, indexing="ij"), -1).reshape(-1, 3)
r = (grid + 0.5 + rng.uniform(-0.1, 0.1, grid.shape)) * a - L / 2
types = np.zeros(len(r), dtype=int)
types[rng.choice(len(r), 200, replace=False)] = 1
particles = [{"id": i, "type": int(t), "r": [float(x) for x in p],
              "radius": 0.5 if t == 0 else 0.44, "mass": 1.0}
             for i, (p, t) in enumerate(zip(r, types))]
init = os.path.join(args.out, "init.json")
with open(init, "w") as f:
    json.dump({"system": {"time": 0.0, "box": {"Lx": L, "Ly": L, "Lz": L},
                          "particles": particles}}, f)

s = pedesis.System(rcut=2.5, pad=0.3)
s.read_init(init)

# epsilon and sigma are those of A-A and of every pair not listed
lj = pedesis.LjForce(s, epsilon=1.0, sigma=1.0, cutoff=2.5, shift=True,
                     pairs={("A", "B"): {"epsilon": 1.5, "sigma": 0.8},
                            ("B", "B"): {"epsilon": 0.5, "sigma": 0.88}})

dt = 0.005
nvt_steps, nve_steps = (1000, 1000) if args.quick else (20000, 10000)

nvt = pedesis.Evolver(s)
nvt.add_force(lj)
nvt.add_integrator(pedesis.LangevinIntegrator(s, T=1.0, gamma=1.0))
nvt.run(nvt_steps, dt)
# kinetic temperature 2 K / (3 N - 3): the Langevin thermostat does not conserve momentum,
# but NVE below does, so the centre of mass keeps its 3 degrees of freedom out
print(f"NVT: {nvt_steps} steps at T = 1: T = {2 * s.kinetic_energy() / (3 * s.N - 3):.3f}, "
      f"U/N = {nvt.potential_energy() / s.N:.4f}")

nve = pedesis.Evolver(s)
nve.add_force(lj)
nve.add_integrator(pedesis.NVEIntegrator(s))
energies = []
nve.run(nve_steps, dt, every=100,
        callback=lambda step: energies.append(nve.potential_energy() + s.kinetic_energy()))
drift = (max(energies) - min(energies)) / abs(np.mean(energies))
print(f"NVE: {nve_steps} steps: total energy per particle {np.mean(energies) / s.N:.4f}, "
      f"spread {drift:.1e} of it")
pedesis.Dump(s).dump_json(os.path.join(args.out, "final.json"))
if drift > 1e-3:
    raise SystemExit(f"NVE energy not conserved: spread {drift:.1e} > 1e-3")
