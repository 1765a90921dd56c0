#!/usr/bin/python3
"""How fast pedesis.analyze is on one core (issue 17's targets): g(r) and clusters of 10^6
particles (target < 10 s each), the MSD over 1,000 frames of 10^5 particles (< 30 s); and
psi6 of 10^6 disks, nearest neighbours and Voronoi-weighted (no target).
Uniform random disks at area fraction 0.5 (g(r) to 5 diameters, 100 bins; clusters at
contact), and a random walk for the MSD. Prints seconds; fails on nothing.

    OMP_NUM_THREADS=1 PYTHONPATH=build/python /usr/bin/python3 scripts/bench_analyze.py
"""
import time

import numpy as np

import pedesis.analyze as pa


def timed(what, fn):
    t0 = time.process_time()
    fn()
    print(f"{what}: {time.process_time() - t0:.2f} s CPU")


def main():
    rng = np.random.default_rng(1)
    n = 1_000_000
    L = np.sqrt(n * np.pi * 0.25 / 0.5)  # unit diameters at area fraction 0.5
    x = rng.uniform(0, L, (n, 2))
    box = pa.Box((L, L))
    timed("g(r), 10^6 disks, r < 5, 100 bins", lambda: pa.rdf(x, box, r_max=5.0, bins=100))
    timed("clusters, 10^6 disks, cutoff 1", lambda: pa.clusters(x, box, cutoff=1.0))
    timed("psi6, 10^6 disks, 6 nearest", lambda: pa.psi6(x, box))
    timed("psi6, 10^6 disks, Voronoi-weighted", lambda: pa.psi6(x, box, weighting="voronoi"))
    walk = np.cumsum(rng.normal(scale=0.1, size=(1000, 100_000, 2)).astype(np.float32), axis=0)
    timed("MSD, 1000 frames of 10^5 particles (FFT)", lambda: pa.msd(walk))


if __name__ == "__main__":
    main()
