"""Cost of e.run() from Python against `pedesis run` of the same config (issue 5's
benchmark): the ABP tutorial's model at N = 36,000 (phi = 0.4, L = 300), 1000 steps.

    OMP_NUM_THREADS=1 /usr/bin/python3 docs/bench/python_vs_cli.py --bin build/pedesis

Both sides are timed around the steps only: the CLI's wall time from its own progress
line (particle-steps per second over the run) and Python's around e.run(). The two
alternate `--repeats` times in one sitting; the ratio of the medians is what counts on
a shared machine. Whole-process times (start-up, reading, writing) are printed too.
"""
import argparse
import os
import re
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "..", "build", "python"))
import pedesis  # noqa: E402

CONFIG = """dimension = 2
dynamics = "brownian"
seed = 1
[initial]
file = "{init}"
[neighbor_list]
r_cut = 3.0
pad = 0.5
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
[run]
steps = {steps}
dt = 0.01
[output]
log_every = {steps}
formats = ["gsd"]
"""


def cli_run(binary, cfg, out, n, steps):
    t0 = time.perf_counter()
    r = subprocess.run([binary, "run", cfg, "--out", out], capture_output=True, text=True,
                       check=True)
    total = time.perf_counter() - t0
    rates = [float(x) for x in re.findall(r"([0-9.e+]+) particle-steps/s", r.stdout)]
    return n * steps / rates[-1], total


def python_run(init, steps):
    t0 = time.perf_counter()
    s = pedesis.System(rcut=3.0, pad=0.5, seed=1)
    s.read_init(init)
    e = pedesis.Evolver(s)
    e.add_force(pedesis.HarmonicForce(s, 10.0, 2.0))
    e.add_force(pedesis.SelfPropulsion(s, 1.0))
    e.add_torque(pedesis.PolarAlign(s, 1.0, 2.0))
    e.add_integrator(pedesis.BrownianIntegrator(s, T=0.0, gamma=1.0))
    e.add_integrator(pedesis.BrownianRotIntegrator(s, T=0.1, gamma=1.0))
    t1 = time.perf_counter()
    e.run(steps, 0.01)
    t2 = time.perf_counter()
    return t2 - t1, t2 - t0


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--bin", default=os.path.join(HERE, "..", "..", "build", "pedesis"))
    ap.add_argument("--steps", type=int, default=1000)
    ap.add_argument("--repeats", type=int, default=3)
    args = ap.parse_args()
    with tempfile.TemporaryDirectory() as tmp:
        init = os.path.join(tmp, "init.json")
        pedesis.builder.random_init(0.4, 300, rcut=1.0, outfile=init, seed=1)
        cfg = os.path.join(tmp, "bench.toml")
        with open(cfg, "w") as f:
            f.write(CONFIG.format(init=init, steps=args.steps))
        n = 36000
        cli, py = [], []
        for k in range(args.repeats):
            cli.append(cli_run(args.bin, cfg, os.path.join(tmp, f"cli{k}"), n, args.steps))
            py.append(python_run(init, args.steps))
            print(f"repeat {k}: cli steps {cli[-1][0]:.3f} s (process {cli[-1][1]:.3f} s), "
                  f"python e.run {py[-1][0]:.3f} s (script {py[-1][1]:.3f} s)")
        med = lambda v: sorted(v)[len(v) // 2]  # noqa: E731
        c, p = med([x[0] for x in cli]), med([x[0] for x in py])
        print(f"N = {n}, {args.steps} steps, OMP_NUM_THREADS={os.environ.get('OMP_NUM_THREADS', '-')}")
        print(f"cli_steps_seconds: {c:.3f}")
        print(f"python_run_seconds: {p:.3f}")
        print(f"python_over_cli: {p / c:.3f}")


if __name__ == "__main__":
    main()
