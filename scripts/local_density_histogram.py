#!/usr/bin/python3
"""Phase-separation diagnostics for a 2D pedesis soft run (e.g. examples/abp_mips.toml).

usage: scripts/local_density_histogram.py TRAJECTORY.gsd [options]

For one frame of a GSD trajectory (by default the last) it prints

  * the histogram of the LOCAL AREA FRACTION: the box is cut into square cells of
    about --cell particle diameters, and each cell's area fraction is
    sum(pi r_i^2) / (cell area) over the particles whose centres lie in it.
    A homogeneous fluid gives one peak near the mean area fraction; motility-induced
    phase separation gives two (a dilute gas and a dense, nearly close-packed phase).
  * the peaks of that histogram and whether it is bimodal;
  * the LARGEST-CLUSTER FRACTION: particles i and j are bonded when their centres are
    closer than --contact times their contact distance r_i + r_j. A particle with at
    least --min-neighbours bonds (default 5; a close-packed disk has 6) is "dense", and
    the script reports the share of all particles in the largest connected cluster of
    dense particles (periodic box). (With --min-neighbours 0 every particle counts; at
    area fractions near 0.6 such plain contact clusters percolate even in a homogeneous
    active fluid, so they do not tell the phases apart.)
  * the polar order |sum n_i| / N of the directors (from the quaternions).

With --every K it prints one line of these numbers for every K-th frame instead (a
time series), and the full histogram of the last frame.  --plot FILE.png draws the
histogram and a picture of the frame (needs Debian's python3-matplotlib).

Needs Debian's python3-gsd and python3-numpy only.  The time of a frame is its step
times dt; dt is read from config.toml next to the trajectory (the run directory), or
given with --dt.

Examples:
  scripts/local_density_histogram.py runs/abp_mips/trajectory.gsd
  scripts/local_density_histogram.py runs/abp_mips/trajectory.gsd --every 5
  scripts/local_density_histogram.py runs/abp_mips/trajectory.gsd --frame 0 --plot f0.png
"""

import argparse
import signal
import os
import sys

try:
    import numpy as np
    import gsd.hoomd
except ImportError as e:  # pragma: no cover
    sys.exit(f"{sys.argv[0]}: {e}; install Debian's python3-numpy and python3-gsd")


def read_dt(gsd_path):
    """dt from the run directory's config.toml, or None."""
    cfg = os.path.join(os.path.dirname(os.path.abspath(gsd_path)), "config.toml")
    if not os.path.exists(cfg):
        return None
    try:
        import tomllib
    except ImportError:
        return None
    try:
        with open(cfg, "rb") as f:
            return float(tomllib.load(f)["run"]["dt"])
    except (KeyError, ValueError, OSError, tomllib.TOMLDecodeError):
        return None


def frame_arrays(frame):
    dims = int(frame.configuration.dimensions)
    if dims != 2:
        sys.exit("this script analyses 2D trajectories only")
    box = np.asarray(frame.configuration.box[:2], dtype=float)
    pos = np.asarray(frame.particles.position[:, :2], dtype=float)
    diam = np.asarray(frame.particles.diameter, dtype=float)
    q = np.asarray(frame.particles.orientation, dtype=float)
    # director = q x q^* (the body x axis); in 2D q = (w, 0, 0, z)
    w, z = q[:, 0], q[:, 3]
    n = np.stack([w * w - z * z, 2.0 * w * z], axis=1)
    return box, pos, diam, n


def local_area_fraction(box, pos, diam, cell):
    """Area fraction of each cell of a grid of cells of side about `cell`."""
    m = np.maximum(1, np.floor(box / cell).astype(int))
    side = box / m
    idx = np.floor((pos + 0.5 * box) / side).astype(int)
    idx = np.minimum(np.maximum(idx, 0), m - 1)
    area = np.zeros((m[0], m[1]))
    np.add.at(area, (idx[:, 0], idx[:, 1]), 0.25 * np.pi * diam**2)
    return (area / (side[0] * side[1])).ravel(), side


def bonds(box, pos, diam, contact):
    """Bonded pairs (i, j), each once: centres closer than contact * (r_i + r_j)
    (minimum image), found with a padded cell list."""
    cut = contact * diam.max()
    m = np.maximum(1, np.floor(box / cut).astype(int))
    if np.any(m < 3):  # small box: all pairs
        i, j = np.triu_indices(len(pos), 1)
        d = pos[i] - pos[j]
        d -= box * np.round(d / box)
        ok = (d**2).sum(1) < (contact * 0.5 * (diam[i] + diam[j])) ** 2
        return i[ok], j[ok]
    c = np.floor((pos + 0.5 * box) / (box / m)).astype(int) % m
    cid = c[:, 0] * m[1] + c[:, 1]
    order = np.argsort(cid, kind="stable")
    counts = np.bincount(cid, minlength=m[0] * m[1])
    start = np.concatenate([[0], np.cumsum(counts)[:-1]])
    width = counts.max()
    table = -np.ones((m[0] * m[1], width), dtype=np.int64)
    slot = np.arange(len(pos)) - start[cid[order]]
    table[cid[order], slot] = order
    cx, cy = np.divmod(np.arange(m[0] * m[1]), m[1])
    out_i, out_j = [], []
    for dx, dy in ((0, 0), (1, -1), (1, 0), (1, 1), (0, 1)):  # half stencil
        other = ((cx + dx) % m[0]) * m[1] + (cy + dy) % m[1]
        a = table[:, :, None]
        b = table[other][:, None, :]
        a, b = np.broadcast_arrays(a, b)
        ok = (a >= 0) & (b >= 0)
        if (dx, dy) == (0, 0):
            ok &= a < b
        a, b = a[ok], b[ok]
        d = pos[a] - pos[b]
        d -= box * np.round(d / box)
        close = (d**2).sum(1) < (contact * 0.5 * (diam[a] + diam[b])) ** 2
        out_i.append(a[close])
        out_j.append(b[close])
    return np.concatenate(out_i), np.concatenate(out_j)


def cluster_sizes(n, i, j):
    """Sizes of the connected components of the graph with edges (i, j)."""
    parent = np.arange(n)

    def find(x):
        root = x
        while parent[root] != root:
            root = parent[root]
        while parent[x] != root:
            parent[x], x = root, parent[x]
        return root

    for a, b in zip(i.tolist(), j.tolist()):
        ra, rb = find(a), find(b)
        if ra != rb:
            parent[max(ra, rb)] = min(ra, rb)
    roots = np.array([find(x) for x in range(n)])
    return np.bincount(roots)[np.unique(roots)]


def histogram_peaks(phi, edges):
    """Histogram (share of cells per bin) and its peaks: local maxima of the lightly
    smoothed histogram holding at least 8 % of the cells within +-1 bin, at least 0.25
    in area fraction from a neighbouring peak and separated from it by a dip below 60 %
    of the lower of the two (else the higher of the two is kept)."""
    h, _ = np.histogram(phi, bins=edges)
    h = h / max(1, len(phi))
    s = np.convolve(np.pad(h, 1, mode="edge"), [0.25, 0.5, 0.25], mode="valid")
    centres = 0.5 * (edges[1:] + edges[:-1])
    cand = [k for k in range(len(s))
            if s[k] > 0 and (k == 0 or s[k] >= s[k - 1]) and (k == len(s) - 1 or s[k] > s[k + 1])
            and h[max(0, k - 1):k + 2].sum() >= 0.08]
    peaks = []
    for k in cand:
        if peaks:
            p = peaks[-1]
            dip = s[p:k + 1].min()
            if dip >= 0.6 * min(s[p], s[k]) or centres[k] - centres[p] < 0.25:
                if s[k] > s[p]:
                    peaks[-1] = k
                continue
        peaks.append(k)
    return h, centres, [centres[k] for k in peaks]


def analyse(frame, cell, contact, min_neighbours, bin_width):
    box, pos, diam, n = frame_arrays(frame)
    phi_cells, side = local_area_fraction(box, pos, diam, cell)
    if bin_width is None:
        # two particles of mean size per bin, bin edges half-way between particle
        # counts: equal-width bins of area fraction would alias the discrete counts
        unit = 0.25 * np.pi * np.mean(diam**2) / (side[0] * side[1])
        bin_width = 2 * unit
        edges = np.arange(-0.5 * unit, phi_cells.max() + bin_width + 1e-12, bin_width)
    else:
        edges = np.arange(0.0, phi_cells.max() + bin_width + 1e-12, bin_width)
    h, centres, peaks = histogram_peaks(phi_cells, edges)
    i, j = bonds(box, pos, diam, contact)
    z = np.bincount(i, minlength=len(pos)) + np.bincount(j, minlength=len(pos))
    dense = z >= min_neighbours
    keep = dense[i] & dense[j]
    sizes = cluster_sizes(len(pos), i[keep], j[keep])
    sizes = np.append(sizes[sizes > 1], 1 if dense.any() else 0)  # isolated dense particles
    phi_mean = 0.25 * np.pi * (diam**2).sum() / box.prod()
    return dict(
        N=len(pos), box=box, side=side, phi_mean=phi_mean, phi_cells=phi_cells, hist=h,
        centres=centres, peaks=peaks, largest=sizes.max() / len(pos),
        clusters_10=int((sizes >= 10).sum()), dense=dense.mean(), min_neighbours=min_neighbours, polar=np.linalg.norm(n.sum(0)) / len(pos),
        pos=pos, diam=diam)


def print_histogram(r, width=50):
    print(f"local area fraction in {len(r['phi_cells'])} cells of "
          f"{r['side'][0]:.3g} x {r['side'][1]:.3g} (mean area fraction {r['phi_mean']:.3f}):")
    if len(r["phi_cells"]) < 100:
        print(f"  (only {len(r['phi_cells'])} cells: the histogram is noisy; a smaller --cell "
              "gives more)")
    top = r["hist"].max()
    lo = np.nonzero(r["hist"])[0]
    first, last = (lo[0], lo[-1]) if len(lo) else (0, -1)
    step = r["centres"][1] - r["centres"][0]
    for k in range(first, last + 1):
        c = r["centres"][k]
        bar = "#" * int(round(width * r["hist"][k] / top)) if top > 0 else ""
        print(f"  {max(0.0, c - step / 2):5.2f}-{c + step / 2:4.2f} {100 * r['hist'][k]:5.1f} % {bar}")


def summary_line(r):
    peaks = ", ".join(f"{p:.2f}" for p in r["peaks"])
    mode = "bimodal" if len(r["peaks"]) >= 2 else "unimodal"
    phi = r["phi_cells"]
    gas, liquid = phi[phi < 0.3], phi[phi > 0.7]
    means = (f"mean area fraction of the cells below 0.3: "
             f"{gas.mean() if len(gas) else float('nan'):.3f} ({100 * len(gas) / len(phi):.0f} % of cells), "
             f"above 0.7: {liquid.mean() if len(liquid) else float('nan'):.3f} "
             f"({100 * len(liquid) / len(phi):.0f} % of cells)\n")
    return means + (f"{mode} (peaks at {peaks}); {100 * r['dense']:.1f} % of particles have >= "
            f"{r['min_neighbours']} neighbours in contact; largest cluster of them "
            f"{100 * r['largest']:.1f} % of all particles; polar order {r['polar']:.3f}")


def plot(r, path, title):
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        from matplotlib.collections import EllipseCollection
    except ImportError:
        sys.exit("--plot needs Debian's python3-matplotlib")
    fig, (a, b) = plt.subplots(1, 2, figsize=(11, 5))
    step = r["centres"][1] - r["centres"][0]
    a.bar(r["centres"], 100 * r["hist"], width=step, color="tab:blue")
    for p in r["peaks"]:
        a.axvline(p, color="tab:red", ls="--", lw=1)
    a.set_xlim(left=0)
    a.set_xlabel("local area fraction")
    a.set_ylabel("% of cells")
    a.set_title(title)
    box = r["box"]
    b.add_collection(EllipseCollection(r["diam"], r["diam"], 0, units="x", offsets=r["pos"],
                                       transOffset=b.transData, facecolor="k", linewidth=0))
    b.set_xlim(-box[0] / 2, box[0] / 2)
    b.set_ylim(-box[1] / 2, box[1] / 2)
    b.set_aspect("equal")
    b.set_title(f"largest dense cluster {100 * r['largest']:.0f} % of particles")
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    print(f"wrote {path}")


def main():
    signal.signal(signal.SIGPIPE, signal.SIG_DFL)  # quiet when piped into head
    p = argparse.ArgumentParser(
        usage="%(prog)s TRAJECTORY.gsd [--frame N | --every K] [--cell C] [--contact F] "
              "[--min-neighbours Z] [--bins W] [--dt DT] [--plot PNG]",
        description=__doc__.split("\n", 3)[3],  # the text after the usage line
        formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("gsd", help="trajectory.gsd of a run directory")
    p.add_argument("--frame", type=int, default=-1,
                   help="frame to analyse (default: the last; negative counts from the end)")
    p.add_argument("--every", type=int, default=0, metavar="K",
                   help="print a time series of every K-th frame (and the last)")
    p.add_argument("--cell", type=float, default=5.0,
                   help="cell side in particle diameters for the local density (default 5)")
    p.add_argument("--contact", type=float, default=1.1,
                   help="bond if closer than this times r_i + r_j (default 1.1)")
    p.add_argument("--min-neighbours", type=int, default=5, metavar="Z",
                   help="a particle is dense with at least Z bonds (default 5; 0: all count)")
    p.add_argument("--bins", type=float, default=None, metavar="WIDTH",
                   help="histogram bin width in area fraction (default: the area fraction of "
                        "two particles in one cell, about 0.06 for cells of 5 diameters)")
    p.add_argument("--dt", type=float, default=None,
                   help="time step (default: [run] dt of config.toml next to the file)")
    p.add_argument("--plot", metavar="PNG", help="also draw the histogram and the frame")
    a = p.parse_args()
    if not os.path.exists(a.gsd):
        part = a.gsd + ".part"
        hint = f" ({part} exists: the run is still going or was stopped)" if os.path.exists(part) else ""
        p.error(f"{a.gsd}: no such file{hint}")
    if a.cell <= 0 or a.contact <= 0 or (a.bins is not None and a.bins <= 0):
        p.error("--cell, --contact and --bins must be positive")
    if a.min_neighbours < 0:
        p.error("--min-neighbours must be >= 0")
    dt = a.dt if a.dt is not None else read_dt(a.gsd)

    with gsd.hoomd.open(a.gsd) as traj:  # default mode: read (gsd 2 and 3)
        nframes = len(traj)
        if nframes == 0:
            sys.exit(f"{a.gsd}: no frames")
        d0 = float(np.mean(traj[0].particles.diameter))
        cell = a.cell * d0

        def when(fr):
            s = int(fr.configuration.step)
            return f"step {s}" + (f", t = {s * dt:g}" if dt else "")

        if a.every > 0:
            frames = list(range(0, nframes, a.every))
            if frames[-1] != nframes - 1:
                frames.append(nframes - 1)
            print(f"{'frame':>5} {'step':>9} {'time':>9} {'dense':>6} {'largest':>8} {'clusters':>8} "
                  f"{'polar':>6} {'cells<0.3':>9} {'cells>0.7':>9}  peaks")
            for k in frames:
                fr = traj[k]
                r = analyse(fr, cell, a.contact, a.min_neighbours, a.bins)
                s = int(fr.configuration.step)
                t = f"{s * dt:9.4g}" if dt else f"{'?':>9}"
                pk = ", ".join(f"{x:.2f}" for x in r["peaks"])
                print(f"{k:5d} {s:9d} {t} {100 * r['dense']:5.1f}% {100 * r['largest']:7.1f}% "
                      f"{r['clusters_10']:8d} {r['polar']:6.3f} "
                      f"{100 * np.mean(r['phi_cells'] < 0.3):8.1f}% "
                      f"{100 * np.mean(r['phi_cells'] > 0.7):8.1f}%  {pk}")
            print(f"(dense: share of particles with >= {a.min_neighbours} neighbours within "
                  f"{a.contact:g} contact distances; largest: share of all particles in the "
                  "largest cluster of dense particles; clusters: such clusters of >= 10 "
                  "particles; cells<0.3 / cells>0.7: share of cells with a local area fraction "
                  "below 0.3 / above 0.7; peaks: of the local area fraction histogram)")
            k = frames[-1]
        else:
            k = a.frame if a.frame >= 0 else nframes + a.frame
            if not 0 <= k < nframes:
                p.error(f"--frame {a.frame}: the file has {nframes} frames")
        fr = traj[k]
        r = analyse(fr, cell, a.contact, a.min_neighbours, a.bins)
        print(f"\n{a.gsd}: frame {k} of {nframes} ({when(fr)}), N = {r['N']}, "
              f"box {r['box'][0]:g} x {r['box'][1]:g}")
        print_histogram(r)
        print(summary_line(r))
        if a.plot:
            plot(r, a.plot, f"frame {k} ({when(fr)})")


if __name__ == "__main__":
    main()
