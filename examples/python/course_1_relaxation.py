# Course problem 1 (seed 000): a 2D event-driven gas of equal hard disks, all started at
# speed 1 in random directions, relaxes to Rayleigh: p(v) = (m v / T) exp(-m v^2 / 2T).
import argparse, os
import matplotlib; matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np
import pedesis

ap = argparse.ArgumentParser(description="2D hard-disk gas relaxing to the Rayleigh law")
ap.add_argument("--out", default="runs/python_course_1_relaxation", help="output folder")
ap.add_argument("--quick", action="store_true", help="fewer disks, shorter run (CI)")
args = ap.parse_args()
os.makedirs(args.out, exist_ok=True)
n, L, t_end = (1000, 87.0, 100.0) if args.quick else (3000, 150.0, 200.0)
gas = pedesis.Gas(f"""seed = 2026
box = {{ length = {L}, boundary = "wall" }}
species = [{{ count = {n}, radius = 0.5, mass = 1.0, velocities = "equal_speed", speed = 1.0 }}]""")
speeds = []  # the first half of the run relaxes the gas; snapshots of the second are pooled
for t in np.linspace(t_end / 2, t_end, 51):
    gas.run(time=t); speeds.append(gas.speeds)
v = np.concatenate(speeds); T = np.mean(v**2) / 2  # m = 1, 2 degrees of freedom
plt.hist(v, bins=50, density=True, alpha=0.6, label=f"simulation, t = {t_end/2:g} to {t_end:g}")
u = np.linspace(0, v.max(), 300)
plt.plot(u, u / T * np.exp(-u**2 / (2 * T)), "k-", label="2D Maxwell-Boltzmann at measured T")
plt.xlabel("speed v (initial speed = 1)"); plt.ylabel("probability density p(v)")
plt.title(f"{n} disks, radius 0.5, mass 1, walled box {L:g} x {L:g}; T = {T:.4f}")
plt.legend(fontsize="small"); plt.savefig(os.path.join(args.out, "speed_distribution.png"), dpi=120)
print(f"T = {T:.4f}, {gas.collisions / n:.1f} collisions per disk, figure in {args.out}")
