# The kinetic-theory notebook (seed 003): molecules in a walled box, time-stepped, each
# velocity component drawn from a normal distribution; the walls reflect the molecules
# and count the momentum they receive, which gives the pressure. As in the notebook the
# run prints the iteration, time, v_rms and the running wall pressure; at the end the
# average pressure is compared with the ideal-gas law P = N T / V, in 2D and in 3D.
#
# The gases are dilute (packing fraction below 1%), so P / P_ideal is 1 to within a few
# per cent. What remains is the molecules' own size: hard-core collisions raise P by the
# second virial coefficient, B2 n = 2^(d-1) eta, and the walls keep centres a radius
# away, which raises it by L / (L - 2r). The script prints that estimate too.
#
#   python3 kinetic_gas_pressure.py [--out DIR] [--quick]
import argparse
import os

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np

import pedesis

ap = argparse.ArgumentParser(description="Wall pressure of a dilute hard-particle gas")
ap.add_argument("--out", default="runs/python_kinetic_gas_pressure", help="output folder")
ap.add_argument("--quick", action="store_true", help="shorter runs (CI)")
args = ap.parse_args()
os.makedirs(args.out, exist_ok=True)


def simulate(dim, N, L, t_end, radius=0.5, dt=0.04, samples=100, prints=10):
    gas = pedesis.Gas(f"""
dimension = {dim}
dynamics = "stepped"
seed = 2024

[box]
length = {L}
boundary = "wall"

[[species]]
name = "molecule"
count = {N}
radius = {radius}
mass = 1.0

[initial]
positions = "random"
velocities = "normal"         # the notebook's default start
sigma = 1.0                   # each component: T = m sigma^2 = 1

[stepped]
dt = {dt}

""")
    V = L**dim
    eta = N * (np.pi * radius**2 if dim == 2 else 4 / 3 * np.pi * radius**3) / V
    print(f"\n{dim}D: {N} molecules of radius {radius} in a walled box of side {L:g} "
          f"(packing fraction {eta:.4f}), dt = {dt}")
    times, pressures = [], []

    def average():  # the intervals' pressures weighted by their lengths: the run average
        return np.average(pressures, weights=np.diff(times, prepend=0.0))

    for k in range(1, samples + 1):
        gas.run(time=k * t_end / samples)
        times.append(gas.time)
        pressures.append(gas.pressure())  # wall pressure since the previous call
        if k % (samples // prints) == 0:
            # The notebook's "V_RMS" is really the mean speed; this is the root mean square.
            v_rms = np.sqrt(np.mean(gas.speeds**2))
            print(f"Iteration: {gas.steps:<8d}Time: {gas.time:.4E}  V_RMS: {v_rms:.4E}  "
                  f"Wall Pressure: {average():.6f}")
    P, P_err = average(), np.std(pressures) / np.sqrt(samples)
    T = 2 * gas.kinetic_energy() / (dim * N)  # constant: every collision is elastic
    P_ideal = N * T / V
    Z_size = (1 + 2 ** (dim - 1) * eta) * L / (L - 2 * radius)
    print(f"Average pressure on wall: {P:.6f} +- {P_err:.6f}")
    print(f"Ideal gas N T / V = {P_ideal:.6f} (T = {T:.4f}): P / P_ideal = "
          f"{P / P_ideal:.4f} +- {P_err / P_ideal:.4f}; "
          f"molecular size alone predicts {Z_size:.4f}")
    return dict(dim=dim, N=N, L=L, eta=eta, T=T, times=np.array(times),
                pressures=np.array(pressures), P_ideal=P_ideal, Z_size=Z_size)


# The 2D box gets about 5 wall hits per unit time, the 3D one about 40: the 2D run is
# longer, so that both averages come within about 0.5% (a few per cent with --quick).
scale = 0.05 if args.quick else 1.0
runs = [simulate(2, 1000, 300.0, t_end=4000 * scale),
        simulate(3, 1000, 60.0, t_end=1200 * scale)]

fig, axes = plt.subplots(1, 2, figsize=(12, 4.5))
for ax, r in zip(axes, runs):
    t, p = r["times"], r["pressures"]
    running = np.cumsum(p * np.diff(t, prepend=0.0)) / t
    ax.plot(t, p, ".", color="lightgray", label=f"each interval of {t[0]:g} time units")
    ax.plot(t, running, "b-", label="running average (printed)")
    ax.axhline(r["P_ideal"], color="k", ls="--", label="ideal gas N T / V")
    ax.axhline(r["P_ideal"] * r["Z_size"], color="r", ls=":",
               label="with molecular size (B2 and wall layer)")
    ax.set_xlabel("time (simulation units)")
    ax.set_ylabel("wall pressure (force per unit " + ("length)" if r["dim"] == 2 else "area)"))
    ax.set_title(f"{r['dim']}D: N = {r['N']}, L = {r['L']:g}, packing {r['eta']:.4f}, "
                 f"T = {r['T']:.3f}", fontsize=10)
    ax.set_ylim(0.6 * r["P_ideal"], 1.4 * r["P_ideal"])
    ax.legend(fontsize="small")
fig.tight_layout()
png = os.path.join(args.out, "pressure.png")
fig.savefig(png, dpi=120)
print(f"\nfigure: {png}")
