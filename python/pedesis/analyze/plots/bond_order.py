"""Bond orientational order of a run's frames: in 2D the hexatic order |<psi6>| with
Voronoi weights against time and the last frame coloured by each particle's |psi6|; in
3D the Steinhardt q4 and q6 averaged over the particles against time.

Usage: bond_order RUN_DIR [--out FILE]   (default RUN_DIR/bond_order.png)
"""
import numpy as np

from .. import psi6, steinhardt
from . import figure
from .run_dir import read_trajectory


def main():
    a, run = figure.open_run(__doc__.split("\n")[0], "bond_order.png")
    traj = read_trajectory(run, most=100)
    t = traj.times
    plt = figure.pyplot()
    if traj.box.dimension == 2:
        values = [psi6(x, traj.box, weighting="voronoi") for x in traj.positions]
        order = np.array([v[0] for v in values])
        fig, (left, right) = plt.subplots(1, 2, figsize=(11, 4.6))
        left.plot(t, order, ".-")
        left.set_ylabel("|< psi6 >| (Voronoi-weighted)")
        x = traj.positions[-1]
        dots = right.scatter(x[:, 0], x[:, 1], c=np.abs(values[-1][1]), s=4, cmap="viridis",
                             vmin=0, vmax=1)
        right.set_aspect("equal")
        right.set_title("last frame: |psi6| of each particle")
        fig.colorbar(dots, ax=right)
        final = f"|<psi6>| = {order[-1]:.4f}"
    else:
        q4 = np.array([steinhardt(x, traj.box, 4).mean() for x in traj.positions])
        q6 = np.array([steinhardt(x, traj.box, 6).mean() for x in traj.positions])
        fig, left = plt.subplots(figsize=(8, 4.6))
        left.plot(t, q4, ".-", label="<q4>")
        left.plot(t, q6, ".-", label="<q6>")
        left.axhline(0.575, color="gray", ls="--", lw=0.7, label="fcc q6 = 0.575")
        left.legend()
        left.set_ylabel("Steinhardt order (12 nearest neighbours)")
        final = f"<q4> = {q4[-1]:.4f}, <q6> = {q6[-1]:.4f}"
    left.set_xlabel("time [time]")
    left.set_title(f"last frame: {final}")
    figure.title(fig, run, "Bond order")
    fig.tight_layout()
    print(f"last frame: {final} ({len(t)} frames)")
    return figure.save(fig, a.out)

