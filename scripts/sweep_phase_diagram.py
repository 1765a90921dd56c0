#!/usr/bin/python3
"""Phase diagram of a pedesis sweep of 2D soft runs: local-density bimodality per point.

usage: scripts/sweep_phase_diagram.py SWEEP_DIR --x KEY --y KEY [--plot FILE.png]

SWEEP_DIR is the directory of `pedesis sweep` (it holds sweep.csv and one run directory
per point); KEY are two of its varied keys (the column names of sweep.csv). For each
finished point's trajectory.gsd it computes, with pedesis.analyze (as `pedesis analyze
clusters` does for one run):

  * the peaks of the histogram of the local area fraction (cells of --cell diameters),
    pooled over the frames of the second half of the run: two peaks, a dilute gas and
    a dense phase, are motility-induced phase separation;
  * the largest-cluster fraction of dense particles (>= 5 neighbours within 1.1
    diameters), averaged over those frames.

It prints one line per point and, with --plot, draws the (x, y) grid coloured by the
largest-cluster fraction, each point marked by its mean area fraction and its peaks
(in bold where there are two). Example (examples/sweeps/mips_phase_diagram.toml):

  scripts/sweep_phase_diagram.py runs/mips_phase_diagram --x force.self_propulsion.alpha \\
      --y box.length --plot runs/mips_phase_diagram/phase_diagram.png

Needs Debian's python3-gsd, python3-numpy, python3-scipy and (for --plot)
python3-matplotlib; the pedesis package is taken from the source tree's python/.
"""

import argparse
import csv
import os
import sys

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "python"))
import pedesis.analyze as pa  # noqa: E402


def read_points(sweep_dir, x, y):
    """The rows of sweep.csv that are done, with their x and y values as floats."""
    path = os.path.join(sweep_dir, "sweep.csv")
    with open(path, newline="") as f:
        rows = list(csv.DictReader(f))
    for key in (x, y):
        if rows and key not in rows[0]:
            sys.exit(f"{path}: no column '{key}' (the varied keys are the columns after 'name')")
    return [dict(r, _x=float(r[x]), _y=float(r[y])) for r in rows if r["status"] == "done"]


def analyse_point(sweep_dir, row, cell):
    """The frames of the second half of the run, pooled: one frame of a small system
    shows spurious peaks; the cells of several frames make a smooth histogram."""
    run = os.path.join(sweep_dir, row["name"])
    traj = pa.read_frames(run)
    diameter = float(np.mean(traj.diameters))
    frames = traj.positions[len(traj.positions) // 2:]
    cells = [pa.local_area_fraction(x, 0.5 * traj.diameters, traj.box, cell * diameter)
             for x in frames]
    grid = pa.fraction_bins(0.5 * diameter, traj.box, cell * diameter)
    peaks = pa.histogram_peaks(np.concatenate(cells), *grid, min_share=0.05, smooth=5)[0]
    largest = [pa.clusters(x, traj.box, 1.1 * diameter, min_neighbours=5)[1] for x in frames]
    area = np.pi / 4 * np.sum(traj.diameters ** 2) / traj.box.volume
    return dict(phi_mean=float(area), peaks=sorted(peaks), frames=len(frames),
                largest=float(np.mean([s[0] / len(traj.types) if len(s) else 0.0
                                       for s in largest])))


def plot(points, results, x, y, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    xs = sorted({p["_x"] for p in points})
    ys = sorted({p["_y"] for p in points})
    grid = np.full((len(ys), len(xs)), np.nan)
    fig, ax = plt.subplots(figsize=(6.4, 5.2))
    for p, r in zip(points, results):
        i, j = ys.index(p["_y"]), xs.index(p["_x"])
        grid[i, j] = r["largest"]
        peaks = " | ".join(f"{c:.2f}" for c in r["peaks"])
        ax.text(j, i, f"φ={r['phi_mean']:.2f}\npeaks {peaks}", ha="center", va="center",
                fontsize=7.5, fontweight="bold" if len(r["peaks"]) >= 2 else "normal",
                color="white" if r["largest"] < 0.5 else "black")
    im = ax.imshow(grid, origin="lower", cmap="viridis", vmin=0, vmax=1)
    ax.set_xticks(range(len(xs)), [f"{v:g}" for v in xs])
    ax.set_yticks(range(len(ys)), [f"{v:g}" for v in ys])
    ax.set_xlabel(x)
    ax.set_ylabel(y)
    fig.colorbar(im, label="largest dense cluster / N")
    ax.set_title("local area fraction peaks, second half of each run (bold: two peaks)",
                 fontsize=10)
    fig.tight_layout()
    tmp = path + ".tmp.png"
    fig.savefig(tmp, dpi=120)
    os.replace(tmp, path)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("sweep_dir")
    ap.add_argument("--x", required=True, help="varied key for the horizontal axis")
    ap.add_argument("--y", required=True, help="varied key for the vertical axis")
    ap.add_argument("--cell", type=float, default=5.0, help="cell side in diameters")
    ap.add_argument("--plot", help="write the phase diagram to this PNG file")
    a = ap.parse_args()
    points = read_points(a.sweep_dir, a.x, a.y)
    if not points:
        sys.exit(f"{a.sweep_dir}: no finished point in sweep.csv")
    results = [analyse_point(a.sweep_dir, p, a.cell) for p in points]
    print(f"{'point':<10} {a.x:>12} {a.y:>12}  phi   peaks            largest cluster")
    for p, r in zip(points, results):
        peaks = ", ".join(f"{c:.2f}" for c in r["peaks"])
        print(f"{p['name']:<10} {p['_x']:>12g} {p['_y']:>12g}  {r['phi_mean']:.2f}  "
              f"{peaks:<16} {r['largest']:.2f}")
    if a.plot:
        plot(points, results, a.x, a.y, a.plot)
        print(f"phase diagram: {a.plot}")


if __name__ == "__main__":
    main()
