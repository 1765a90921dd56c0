"""Phase separation of a 2D or 3D run (motility-induced phase separation of active
particles, or any coexistence): per frame, the peaks of the histogram of the local area
(volume) fraction, in cells of --cell diameters, and the share of all particles in the
largest cluster of dense particles (those with at least --min-neighbours others closer than
--contact diameters); the histogram of the second half of the run, pooled; and the cluster
sizes of the last frame. Two peaks, a gas and a dense phase, mean phase separation.
The contact distance comes from the run's pair potential (contact.py), unless --contact
gives it in diameters; the first line says which.

Usage: clusters RUN_DIR [--out FILE] [--cell C] [--contact F] [--min-neighbours K]
       (default RUN_DIR/clusters.png)
"""
import numpy as np

from .. import clusters, fraction_bins, histogram_peaks, local_area_fraction, phase_fractions, polar_order
from . import figure
from .contact import contact_distances, describe
from .run_dir import InputError, read_trajectory


def options(p):
    p.add_argument("--cell", type=float, default=5.0,
                   help="cell edge for the local fractions, in particle diameters (default 5)")
    p.add_argument("--contact", type=float, default=None,
                   help="neighbours are closer than this many diameters (default: the "
                        "contact distance of the run's pair potential)")
    p.add_argument("--min-neighbours", type=int, default=5,
                   help="neighbours that make a particle dense (default 5; 0: every particle)")


def check_options(a):
    if a.cell <= 0 or (a.contact is not None and a.contact <= 0) or a.min_neighbours < 0:
        raise InputError("--cell and --contact must be positive, --min-neighbours >= 0")


def contact(run, traj, a):
    """(distance, the printed line): --contact diameters, or the distance per pair of
    species from the run's potential."""
    diameter = float(np.mean(traj.diameters))
    if a.contact is not None:
        distance = a.contact * diameter
        return distance, (f"clusters: contact distance {distance:.4g} (--contact {a.contact:g} "
                          f"diameters of {diameter:.4g})")
    names = traj.type_names
    radii = [0.5 * float(traj.diameters[np.argmax(traj.types == k)]) if (traj.types == k).any()
             else 0.5 * diameter for k in range(len(names))]
    try:
        distances, reason = contact_distances(run.config, names, radii)
    except (KeyError, TypeError, ValueError) as e:
        raise InputError(f"{run.path / 'config.toml'}: a pair force's parameters do not give "
                         f"a contact distance for the species {names} ({type(e).__name__}: "
                         f"{e}); give --contact") from None
    return distances, describe(distances, names, reason)


def frame_numbers(x, traj, a, distance):
    """The local fractions of one frame's cells and the largest dense cluster's share."""
    diameter = float(np.mean(traj.diameters))
    fractions = local_area_fraction(x, 0.5 * traj.diameters, traj.box, a.cell * diameter)
    _, sizes = clusters(x, traj.box, distance, a.min_neighbours, traj.types)
    return fractions, sizes[0] / len(x) if len(sizes) else 0.0


def phase_columns(fractions, threshold):
    """The gas and dense columns of a row: the mean fraction of the cells on either side
    of the phase boundary; "one phase" where the histogram has one peak, "-" for a side
    with no cell in this frame."""
    if threshold is None:
        return f"{'one phase':>13}"
    sides = (fractions[fractions < threshold], fractions[fractions >= threshold])
    return " ".join(f"{side.mean():6.3f}" if len(side) else f"{'-':>6}" for side in sides)


def main():
    a, run = figure.open_run(__doc__.split("\n")[0], "clusters.png", options, check_options)
    traj = read_trajectory(run, most=50)
    if not np.all(traj.diameters > 0):
        raise InputError(f"{run.path}/trajectory.gsd: the particles have no diameters")
    distance, line = contact(run, traj, a)
    print(line)
    rows = [frame_numbers(x, traj, a, distance) for x in traj.positions]
    half = len(rows) // 2
    pooled = np.concatenate([r[0] for r in rows[half:]])
    grid = fraction_bins(0.5 * float(np.mean(traj.diameters)), traj.box,
                         a.cell * float(np.mean(traj.diameters)))
    peaks, centres, density = histogram_peaks(pooled, *grid, min_share=0.05, smooth=5)
    # the phase boundary of the second half, applied to every frame
    phases = phase_fractions([r[0] for r in rows[half:]], *grid)
    threshold = None if phases is None else phases[2]
    print(f"{'time':>10} {'gas':>6} {'dense':>6} {'largest dense cluster':>22}"
          + ("  polar order" if traj.directors is not None else ""))
    for k, (fractions, largest) in enumerate(rows):
        polar = f"  {polar_order(traj.directors[k]):11.3f}" if traj.directors is not None else ""
        print(f"{traj.times[k]:10.4g} {phase_columns(fractions, threshold)} {largest:22.3f}{polar}")
    print("(gas, dense: mean local fraction of the cells on either side of the second half's "
          f"phase boundary{'' if threshold is None else f' {threshold:.2f}'}; \"one phase\" if "
          "its histogram has one peak)")
    _, sizes = clusters(traj.positions[-1], traj.box, distance, a.min_neighbours, traj.types)

    plt = figure.pyplot()
    fig, (left, middle, right) = plt.subplots(1, 3, figsize=(14, 4.4))
    left.plot(centres, density, "-")
    if threshold is not None:
        left.axvline(threshold, color="gray", lw=0.7, ls="--", label="phase boundary")
    left.set_xlabel(f"local fraction (cells of {a.cell:g} diameters)")
    left.set_ylabel("probability density")
    verdict = ("one peak: homogeneous" if phases is None else
               f"phase separated: gas {np.nanmean(phases[0]):.2f}, dense {np.nanmean(phases[1]):.2f}")
    left.set_title(f"second half of the run, pooled; {verdict}")
    middle.plot(traj.times, [r[1] for r in rows], ".-")
    middle.set_xlabel("time [time]")
    middle.set_ylabel("largest dense cluster / N")
    middle.set_ylim(0, 1)
    # (the printed line without its reason: "contact distance 1.122")
    middle.set_title(f">= {a.min_neighbours} neighbours within "
                     f"{line.split(' (')[0].removeprefix('clusters: ')}")
    if len(sizes):
        values, counts = np.unique(sizes, return_counts=True)
        right.loglog(values, counts, "o")
    right.set_xlabel("cluster size")
    right.set_ylabel("clusters (last frame)")
    figure.title(fig, run, "Clusters and local density")
    fig.tight_layout()
    print(f"second half, pooled: peaks at {', '.join(f'{p:.2f}' for p in sorted(peaks))}; "
          f"{verdict}")
    return figure.save(fig, a.out)
