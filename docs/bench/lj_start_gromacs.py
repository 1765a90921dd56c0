#!/usr/bin/python3
"""The common start of docs/bench/gromacs_side_by_side.sh: in.lj's system in reduced units
(pedesis' initial-configuration JSON) and the same system in GROMACS units (.gro, .top).

Two subcommands, standard library only:

  fcc   --cells C --rho RHO --temp T --seed S OUT.json
        An fcc lattice of C^3 unit cells of 4 atoms at number density RHO (LAMMPS'
        `lattice fcc RHO`, basis (0,0,0) (1/2,1/2,0) (1/2,0,1/2) (0,1/2,1/2)), the box
        centred at the origin (pedesis' convention), mass 1, radius 0.5; Gaussian
        velocities from Python's Mersenne Twister seeded with S, the centre-of-mass
        velocity removed, scaled to temperature T exactly with 3N - 3 degrees of freedom
        (the count of pedesis' nve and of GROMACS with comm-mode Linear). Used when LAMMPS
        is not installed; otherwise the script takes LAMMPS' start (lammps_lj3d.in,
        `velocity create 1.44 87287 loop geom`) through lammps_data_to_json.py, the start
        of lammps_side_by_side.sh's lj3d.

  gro   --sigma NM --epsilon KJMOL --mass U IN.json OUT.gro OUT.top
        The start IN.json (reduced units: sigma = epsilon = 1, the mass given in the file,
        1 for in.lj) in GROMACS units: lengths times sigma (nm), velocities times
        sigma / tau (nm/ps) with tau = sigma sqrt(m / epsilon) (ps: 1 u nm^2 ps^-2 is
        1 kJ/mol exactly), positions shifted by half the box (GROMACS' box starts at 0)
        and wrapped into [0, L). The .gro is written with 12 decimals per field (GROMACS
        reads the precision from the spacing of the decimal points of the first atom
        line, fileio/groio.cpp), so the start loses nothing that double precision keeps
        beyond about 1e-12 nm. The .top has one atom type AR (sigma, epsilon with
        combination rule 2, charge 0) and one single-atom molecule type, N copies.
"""

import argparse
import json
import math
import os
import random
import sys


def fail(msg):
    sys.stderr.write("lj_start_gromacs: error: %s\n" % msg)
    sys.exit(2)


def write_atomic(path, text):
    tmp = path + ".tmp.%d" % os.getpid()
    with open(tmp, "w") as f:
        f.write(text)
    os.replace(tmp, path)


def cmd_fcc(a):
    if a.cells < 1 or a.rho <= 0 or a.temp <= 0:
        fail("--cells must be >= 1, --rho and --temp > 0")
    lat = (4.0 / a.rho) ** (1.0 / 3.0)
    L = a.cells * lat
    basis = ((0.0, 0.0, 0.0), (0.5, 0.5, 0.0), (0.5, 0.0, 0.5), (0.0, 0.5, 0.5))
    pos = []
    for i in range(a.cells):
        for j in range(a.cells):
            for k in range(a.cells):
                for b in basis:
                    pos.append([(i + b[0]) * lat - 0.5 * L, (j + b[1]) * lat - 0.5 * L,
                                (k + b[2]) * lat - 0.5 * L])
    n = len(pos)
    rng = random.Random(a.seed)
    vel = [[rng.gauss(0.0, 1.0) for _ in range(3)] for _ in range(n)]
    com = [sum(v[d] for v in vel) / n for d in range(3)]
    for v in vel:
        for d in range(3):
            v[d] -= com[d]
    t_now = sum(x * x for v in vel for x in v) / (3 * n - 3)
    scale = math.sqrt(a.temp / t_now)
    particles = []
    for i in range(n):
        particles.append({"id": i, "r": pos[i], "type": 0, "radius": 0.5, "mass": 1.0,
                          "v": [x * scale for x in vel[i]]})
    doc = {"system": {"box": {"Lx": L, "Ly": L, "Lz": L}, "particles": particles}}
    write_atomic(a.out, json.dumps(doc, separators=(",", ":")) + "\n")
    sys.stderr.write("lj_start_gromacs: fcc %d^3 cells, %d atoms, L = %r, T = %r -> %s\n"
                     % (a.cells, n, L, a.temp, a.out))


def cmd_gro(a):
    if a.sigma <= 0 or a.epsilon <= 0 or a.mass <= 0:
        fail("--sigma, --epsilon and --mass must be > 0")
    with open(a.json) as f:
        doc = json.load(f)
    try:
        box = doc["system"]["box"]
        L = [box["Lx"], box["Ly"], box["Lz"]]
        particles = sorted(doc["system"]["particles"], key=lambda p: p["id"])
    except (KeyError, TypeError):
        fail("%s: not a 3D pedesis initial file with system.box.Lx/Ly/Lz and particles" % a.json)
    masses = {p.get("mass", 1.0) for p in particles}
    if len(masses) != 1:
        fail("%s: one mass for all particles expected, found %d" % (a.json, len(masses)))
    m_red = masses.pop()
    # a reduced mass m_red (in units of the mass unit, here a.mass) changes tau's mass
    tau = a.sigma * math.sqrt(a.mass / a.epsilon)
    vfac = a.sigma / tau
    n = len(particles)
    if n >= 100000:
        fail("%d atoms: the .gro's atom number field has 5 digits" % n)
    Lnm = [x * a.sigma for x in L]
    lines = ["in.lj in GROMACS units: sigma %r nm, epsilon %r kJ/mol, m %r u, tau %r ps"
             % (a.sigma, a.epsilon, a.mass * m_red, tau), "%d" % n]
    for i, p in enumerate(particles):
        r = []
        for d in range(3):
            x = (p["r"][d] + 0.5 * L[d]) * a.sigma
            x -= math.floor(x / Lnm[d]) * Lnm[d]
            if x >= Lnm[d]:
                x -= Lnm[d]
            r.append(x)
        v = [x * vfac for x in p.get("v", [0.0, 0.0, 0.0])]
        lines.append("%5d%-5s%5s%5d%17.12f%17.12f%17.12f%17.12f%17.12f%17.12f"
                     % ((i + 1) % 100000, "AR", "AR", (i + 1) % 100000, r[0], r[1], r[2],
                        v[0], v[1], v[2]))
    lines.append("%.12f %.12f %.12f" % tuple(Lnm))
    write_atomic(a.gro, "\n".join(lines) + "\n")
    top = """; in.lj (LAMMPS bench/in.lj) in GROMACS units, written by lj_start_gromacs.py
; sigma %r nm, epsilon %r kJ/mol, m %r u, no charges
[ defaults ]
; nbfunc  comb-rule  gen-pairs
  1       2          no

[ atomtypes ]
; name  mass  charge  ptype  sigma  epsilon
  AR    %r   0.0     A      %r   %r

[ moleculetype ]
; name  nrexcl
  AR    0

[ atoms ]
; nr  type  resnr  residue  atom  cgnr  charge  mass
  1   AR    1      AR       AR    1     0.0     %r

[ system ]
in.lj

[ molecules ]
AR  %d
""" % (a.sigma, a.epsilon, a.mass * m_red, a.mass * m_red, a.sigma, a.epsilon,
       a.mass * m_red, n)
    write_atomic(a.top, top)
    sys.stderr.write("lj_start_gromacs: %d atoms, box %.6f nm, tau %r ps -> %s, %s\n"
                     % (n, Lnm[0], tau, a.gro, a.top))


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    sub = ap.add_subparsers(dest="cmd", required=True)
    f = sub.add_parser("fcc")
    f.add_argument("--cells", type=int, default=20)
    f.add_argument("--rho", type=float, default=0.8442)
    f.add_argument("--temp", type=float, default=1.44)
    f.add_argument("--seed", type=int, default=87287)
    f.add_argument("out")
    g = sub.add_parser("gro")
    g.add_argument("--sigma", type=float, default=0.34)
    g.add_argument("--epsilon", type=float, default=0.996)
    g.add_argument("--mass", type=float, default=39.948)
    g.add_argument("json")
    g.add_argument("gro")
    g.add_argument("top")
    a = ap.parse_args()
    if a.cmd == "fcc":
        cmd_fcc(a)
    else:
        cmd_gro(a)


if __name__ == "__main__":
    main()
