"""Structure of a run's last frames: the radial distribution function g(r), averaged over
up to 10 frames, and the static structure factor S(q), directly from the last frame (a
periodic box) and from g(r).

Usage: structure RUN_DIR [--out FILE]   (default RUN_DIR/structure.png)
"""
import numpy as np

from .. import rdf, structure_factor, structure_factor_from_rdf
from . import figure
from .run_dir import read_trajectory

FRAMES = 10


def main():
    a, run = figure.open_run(__doc__.split("\n")[0], "structure.png")
    # the starting state (often a lattice) is no sample of the run's structure
    traj = read_trajectory(run, most=FRAMES, last=FRAMES, skip_start=True)
    positions = traj.positions
    box, d = traj.box, traj.box.dimension
    n = positions.shape[1]
    density = n / box.volume
    spacing = density ** (-1.0 / d)
    periodic = [L for L, p in zip(box.lengths, box.periodic) if p]
    r_max = min(0.499 * min(periodic) if periodic else 0.25 * min(box.lengths), 8.0 * spacing)
    curves = [rdf(x, box, r_max, bins=200) for x in positions]
    r = curves[0][0]
    g = np.mean([c[1] for c in curves], axis=0)
    q_max = 25.0 / spacing
    q = np.linspace(0.5 * q_max / 100, q_max, 200)

    plt = figure.pyplot()
    fig, (left, right) = plt.subplots(1, 2, figsize=(11, 4.4))
    left.plot(r, g, lw=1.2)
    left.axhline(1.0, color="gray", lw=0.7, ls="--")
    left.set_xlabel("r [length]")
    left.set_ylabel("g(r)")
    peak = r[np.argmax(g)]
    left.set_title(f"g(r) over the last {len(curves)} frames; highest peak at r = {peak:.3g}")
    if all(box.periodic):
        qd, sd = structure_factor(positions[-1], box, q_max, bins=100)
        right.plot(qd, sd, ".", ms=3, label="direct sum, last frame")
    right.plot(q, structure_factor_from_rdf(r, g, density, q, d), lw=1.2,
               label="from g(r) (truncated at r_max)")
    right.set_xlabel("q [1/length]")
    right.set_ylabel("S(q)")
    right.legend()
    figure.title(fig, run, "Structure")
    fig.tight_layout()
    print(f"g(r): highest peak at r = {peak:.4g}, g = {g.max():.4g} ({len(curves)} frames)")
    return figure.save(fig, a.out)
