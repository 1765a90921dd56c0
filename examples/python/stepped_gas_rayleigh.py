# A 2D gas of hard disks in a walled box on the time-stepped engine (seed 002): every
# step moves the disks by v dt, finds the pairs that overlap, rewinds each to the moment
# of contact and collides it elastically (collisions "a posteriori"), with a cell grid
# so that only nearby disks are compared. The velocity components start uniform in
# [-s, s], far from equilibrium; after a few collisions per disk the speeds follow the
# Rayleigh distribution f(v) = (m v / T) exp(-m v^2 / 2T), the 2D Maxwell-Boltzmann law.
# The script pools speeds over time and measures the agreement with the
# Kolmogorov-Smirnov distance D = max |F_sampled(v) - F_Rayleigh(v)|.
#
#   python3 stepped_gas_rayleigh.py [--out DIR] [--quick]
import argparse
import os

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np

import pedesis

ap = argparse.ArgumentParser(description="Stepped 2D hard-disk gas vs the Rayleigh law")
ap.add_argument("--out", default="runs/python_stepped_gas_rayleigh", help="output folder")
ap.add_argument("--quick", action="store_true", help="shorter sampling (CI)")
args = ap.parse_args()
os.makedirs(args.out, exist_ok=True)

N, L, dt = 1000, 100.0, 0.02
t_relax = 30.0  # each disk collides about 12 times by then, forgetting the square start
t_end = 60.0 if args.quick else 330.0
gas = pedesis.Gas(f"""
dimension = 2
dynamics = "stepped"
seed = 2024

[box]
length = {L}
boundary = "wall"

[[species]]
name = "disk"
count = {N}
radius = 0.5
mass = 1.0

[initial]
velocities = "uniform"        # each component uniform in [-speed, speed]
speed = 1.7320508075688772    # sqrt(3): T = m speed^2 / 3 = 1

[stepped]
dt = {dt}                     # the fastest disks move about a fifth of a radius per step

""")


def ks_distance(v, T, m=1.0):
    """Largest gap between the empirical distribution function of the speeds v and the
    Rayleigh one, F(v) = 1 - exp(-m v^2 / 2T)."""
    v = np.sort(v)
    F = 1.0 - np.exp(-m * v**2 / (2 * T))
    n = len(v)
    return max(np.max(np.arange(1, n + 1) / n - F), np.max(F - np.arange(n) / n))


start = gas.speeds
gas.run(time=t_relax)
# Snapshots one time unit apart (each disk collides about 0.4 times in between) are far
# from independent, but pooling many of them smooths the histogram.
samples = []
for t in np.arange(t_relax, t_end + dt / 2, 1.0):
    gas.run(time=t)
    samples.append(gas.speeds)
v = np.concatenate(samples)
T = np.mean(v**2) / 2  # m = 1 and two degrees of freedom: T = m <v^2> / 2

D_start, D_eq, D_last = ks_distance(start, T), ks_distance(v, T), ks_distance(samples[-1], T)
print(f"{N} disks, eta = {N * np.pi * 0.25 / L**2:.3f}, dt = {dt}, t = {gas.time:g} "
      f"({gas.steps} steps, {gas.collisions / N:.1f} pair collisions per disk), T = {T:.4f}")
print(f"Kolmogorov-Smirnov distance to Rayleigh: start {D_start:.4f}, "
      f"last snapshot {D_last:.4f}, {len(samples)} snapshots pooled {D_eq:.4f}")
# The mean of the Kolmogorov distribution, 0.87, sets the scale of D for honest samples.
print(f"(for {N} independent speeds from the Rayleigh law itself D is typically "
      f"{0.87 / np.sqrt(N):.4f})")

bins = np.linspace(0, 4.5, 46)
h_start, _, _ = plt.hist(start, bins=bins, density=True, histtype="step", color="gray",
                         label=f"start, t = 0 (components uniform), D = {D_start:.3f}")
plt.hist(v, bins=bins, density=True, alpha=0.6,
         label=f"t = {t_relax:g} to {t_end:g}, {len(samples)} snapshots, D = {D_eq:.4f}")
u = np.linspace(0, bins[-1], 300)
plt.plot(u, u / T * np.exp(-u**2 / (2 * T)), "k-", label=f"Rayleigh, T = {T:.3f} (measured)")
plt.xlabel("speed v (simulation units; mass 1, radius 0.5)")
plt.ylabel("probability density f(v)")
plt.title(f"Stepped 2D gas: {N} disks (radius 0.5) in a walled {L:g} x {L:g} box, dt = {dt}",
          fontsize=10)
plt.ylim(0, 1.35 * h_start.max())  # room for the legend above the curves
plt.legend(fontsize="small", loc="upper right")
png = os.path.join(args.out, "speed_distribution.png")
plt.savefig(png, dpi=120)
print(f"figure: {png}")
