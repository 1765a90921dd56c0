#!/usr/bin/python3
"""Weak and strong scaling of the soft engine's MPI domain decomposition (issue 15).

Runs the ABP tutorial's model (the system of `pedesis bench abp`: radius 1, harmonic
repulsion k = 10, self-propulsion alpha = 1, Brownian T = 0.1, number density 0.4,
dt = 0.01, skin 1.0, sorted every 200 steps) with `pedesis run`, one thread per
process, alternating one process (no mpirun) and two (mpirun -np 2): A B A B ...
so that the host's noise falls on both alike. Prints, per pair, each run's
particle-steps per second over its stepping (summary.json's steps x N /
stepping_seconds: the start, log rows and the final checkpoint excluded), and then the
median and range of the per-pair ratios, the parallel efficiency, the share of the
stepping time the processes spent in MPI calls (waiting included) and the bytes sent
per step.

  weak:   N = 36,000 per process (box 300 x 300 for one, 600 x 300 for two)
  strong: N = 1,000,000 on one and on two processes (box 1581 x 1581), sorted every
          20 steps instead of 200 (its 100 steps would otherwise run mostly unsorted)

Usage: scripts/bench_mpi_scaling.py [--pairs 6] [--weak-steps 1000]
       [--strong-steps 100] [--only weak|strong] [--binary build/pedesis]
"""
import argparse
import json
import math
import os
import statistics
import subprocess
import sys
import tempfile

CONFIG = """dimension = 2
dynamics = "brownian"
seed = 1
[box]
lengths = [{lx}, {ly}]
[[species]]
name = "A"
count = {n}
radius = 1.0
[initial]
positions = "random"
[[force]]
name = "harmonic"
k = 10.0
[[force]]
name = "self_propulsion"
alpha = 1.0
[[integrator]]
name = "brownian"
T = 0.1
gamma = 1.0
[[integrator]]
name = "brownian_rotation"
T = 0.1
gamma = 1.0
[neighbor_list]
skin = 1.0
sort_every = {sort_every}
[run]
dt = 0.01
steps = {steps}
[output]
log_every = {steps}
formats = []
progress = false
"""


def run(binary, config, out, processes):
    env = dict(os.environ, OMP_NUM_THREADS="1")
    command = [binary, "run", config, "--out", out]
    if processes > 1:
        command = ["mpirun", "--allow-run-as-root", "-np", str(processes), "--bind-to", "core"] + command
    subprocess.run(command, check=True, env=env, stdout=subprocess.DEVNULL)
    with open(os.path.join(out, "summary.json")) as f:
        return json.load(f)


def series(name, binary, work, configs, pairs):
    """configs: {processes: path}; alternates 1 and 2 processes `pairs` times."""
    rates = {1: [], 2: []}
    comm_share, bytes_per_step = [], []
    print(f"\n{name}")
    for k in range(pairs):
        for p in (1, 2):
            s = run(binary, configs[p], os.path.join(work, f"{name}_{p}_{k}"), p)
            rates[p].append(s["steps"] * s["particles"] / s["stepping_seconds"])
            if p == 2:
                comm_share.append(s["mpi"]["communication_seconds_mean"] / s["stepping_seconds"])
                bytes_per_step.append(s["mpi"]["bytes_sent_per_step"])
        print(f"  pair {k + 1}: 1 process {rates[1][-1]:.4g}, 2 processes {rates[2][-1]:.4g} "
              f"particle-steps/s (ratio {rates[2][-1] / rates[1][-1]:.3f})", flush=True)
    ratios = [b / a for a, b in zip(rates[1], rates[2])]
    return ratios, statistics.median(comm_share), statistics.median(bytes_per_step)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--pairs", type=int, default=6)
    ap.add_argument("--weak-steps", type=int, default=1000)
    ap.add_argument("--strong-steps", type=int, default=100)
    ap.add_argument("--only", choices=["weak", "strong"])
    ap.add_argument("--binary", default=os.path.join(os.path.dirname(__file__), "..", "build", "pedesis"))
    a = ap.parse_args()
    binary = os.path.abspath(a.binary)
    density = 0.4
    with tempfile.TemporaryDirectory() as work:
        def write(name, n, lx, ly, steps, sort_every=200):
            path = os.path.join(work, name + ".toml")
            with open(path, "w") as f:
                f.write(CONFIG.format(n=n, lx=lx, ly=ly, steps=steps, sort_every=sort_every))
            return path

        if a.only in (None, "weak"):
            side = math.sqrt(36000 / density)
            configs = {1: write("weak1", 36000, side, side, a.weak_steps),
                       2: write("weak2", 72000, 2 * side, side, a.weak_steps)}
            ratios, share, volume = series("weak", binary, work, configs, a.pairs)
            # weak: the same work per process, so the ideal rate ratio is 2
            eff = [r / 2 for r in ratios]
            print(f"weak scaling, N = 36,000 per process: rate(2)/rate(1) median "
                  f"{statistics.median(ratios):.3f} (range {min(ratios):.3f}-{max(ratios):.3f}); "
                  f"efficiency {statistics.median(eff):.2f} ({min(eff):.2f}-{max(eff):.2f}); "
                  f"time in MPI {100 * share:.1f} %; {volume / 1e3:.1f} kB sent per step")
        if a.only in (None, "strong"):
            side = math.sqrt(1_000_000 / density)
            # sorted every 20 steps: the random start is in random memory order, and a
            # short run would otherwise be timed mostly before the first sort
            path = write("strong", 1_000_000, side, side, a.strong_steps, sort_every=20)
            ratios, share, volume = series("strong", binary, work, {1: path, 2: path}, a.pairs)
            eff = [r / 2 for r in ratios]
            print(f"strong scaling, N = 1,000,000: speed-up median {statistics.median(ratios):.3f} "
                  f"(range {min(ratios):.3f}-{max(ratios):.3f}); efficiency "
                  f"{statistics.median(eff):.2f} ({min(eff):.2f}-{max(eff):.2f}); "
                  f"time in MPI {100 * share:.1f} %; {volume / 1e3:.1f} kB sent per step")


if __name__ == "__main__":
    sys.exit(main())
