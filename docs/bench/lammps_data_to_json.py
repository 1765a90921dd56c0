#!/usr/bin/python3
"""Convert a LAMMPS data file (written by `write_data`) into pedesis' initial-configuration
JSON (the ABP tutorial's layout, docs/formats.md "Initial-configuration JSON input").

Used by docs/bench/lammps_side_by_side.sh so that LAMMPS and pedesis start from the same
configuration, bit for bit: LAMMPS builds the start (create_atoms, velocity create) and
writes it with write_data; this script turns that file into the `[initial] file` of the
pedesis config. Only the Python standard library is used.

What is converted:
  * box: Lx, Ly (and Lz in 3D) = xhi - xlo, ...; positions are shifted by the box centre
    (pedesis' box is centred at the origin) and wrapped into [-L/2, L/2); the z
    coordinate of a 2D system is dropped;
  * ids: LAMMPS' 1..N become 0..N-1; types: 1.. become 0..;
  * velocities: from the Velocities section (vx vy [vz]); omitted with --no-velocities;
  * radius: --radius, or half the per-atom diameter of a sphere style;
  * mass: --mass, or the per-type mass of the Masses section (1 if there is none);
  * director n: the dipole moment (mux, muy[, muz]) of a dipole style, normalised by
    pedesis; omitted otherwise (pedesis then draws directors from its seed).
Numbers are written with Python's repr (the shortest text that reads back to the same
double), so no digit of write_data's output is lost.

Atom styles (the `Atoms # STYLE` comment of the data file is checked against --style):
  atomic         id type x y z [ix iy iz]
  sphere-dipole  id type x y z diameter density q mux muy muz [ix iy iz]
                 (`atom_style hybrid sphere dipole`, written by LAMMPS as "# hybrid")

With --toml-tables PATH it also writes the [box] and [[species]] tables that describe
the same box and the single species (name "A", its count, radius and mass) as TOML, for
appending to a pedesis config: a run restarted from a checkpoint (--restart) then need not
read the JSON file again for them (docs/config.md, "Restarting a soft run").

Usage:
  lammps_data_to_json.py --dim 2|3 --style atomic|sphere-dipole [--radius R] [--mass M]
                         [--no-velocities] [--toml-tables PATH] DATA OUT.json
"""

import argparse
import json
import math
import os
import sys


def fail(msg):
    sys.stderr.write("lammps_data_to_json: error: %s\n" % msg)
    sys.exit(2)


def read_data(path):
    """Return (header dict, {section name: [token lists]}, atoms style comment)."""
    with open(path) as f:
        lines = f.read().split("\n")
    header = {}
    sections = {}
    atoms_comment = None
    known = {"Atoms", "Velocities", "Masses", "Pair Coeffs", "PairIJ Coeffs"}
    i = 1  # the first line is a title
    current = None
    while i < len(lines):
        raw = lines[i]
        line = raw.split("#", 1)[0].strip()
        i += 1
        if not line:
            continue
        name = line
        if name in known or name.endswith("Coeffs"):
            current = name
            sections[current] = []
            if name == "Atoms" and "#" in raw:
                atoms_comment = raw.split("#", 1)[1].strip()
            continue
        toks = line.split()
        if current is None:
            if line.endswith("xlo xhi"):
                header["x"] = (float(toks[0]), float(toks[1]))
            elif line.endswith("ylo yhi"):
                header["y"] = (float(toks[0]), float(toks[1]))
            elif line.endswith("zlo zhi"):
                header["z"] = (float(toks[0]), float(toks[1]))
            elif line.endswith("xy xz yz"):
                if any(float(t) != 0.0 for t in toks[:3]):
                    fail("%s: triclinic boxes are not supported" % path)
            elif line.endswith(" atoms"):
                header["atoms"] = int(toks[0])
            elif line.endswith("atom types"):
                header["types"] = int(toks[0])
            continue
        sections[current].append(toks)
    return header, sections, atoms_comment


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--dim", type=int, choices=(2, 3), required=True)
    ap.add_argument("--style", choices=("atomic", "sphere-dipole"), required=True)
    ap.add_argument("--radius", type=float, help="radius written for every particle")
    ap.add_argument("--mass", type=float, help="mass written for every particle")
    ap.add_argument("--no-velocities", action="store_true")
    ap.add_argument("--toml-tables", metavar="PATH",
                    help="also write [box] and [[species]] as TOML to PATH")
    ap.add_argument("data")
    ap.add_argument("out")
    a = ap.parse_args()

    header, sections, comment = read_data(a.data)
    for k in ("atoms", "x", "y", "z"):
        if k not in header:
            fail("%s: no '%s' line in the header" % (a.data, k))
    if "Atoms" not in sections:
        fail("%s: no Atoms section" % a.data)
    want_comment = {"atomic": "atomic", "sphere-dipole": "hybrid"}[a.style]
    if comment is not None and comment.split()[0] != want_comment:
        fail("%s: Atoms section is '# %s', expected '# %s' for --style %s"
             % (a.data, comment, want_comment, a.style))
    ncols = {"atomic": 5, "sphere-dipole": 11}[a.style]

    axes = "xyz"[: a.dim]
    lo = [header[c][0] for c in axes]
    hi = [header[c][1] for c in axes]
    L = [h - l for l, h in zip(lo, hi)]
    centre = [0.5 * (l + h) for l, h in zip(lo, hi)]

    masses = {}
    for toks in sections.get("Masses", []):
        masses[int(toks[0])] = float(toks[1])

    vel = {}
    if not a.no_velocities:
        for toks in sections.get("Velocities", []):
            vel[int(toks[0])] = [float(t) for t in toks[1 : 1 + a.dim]]

    atoms = sections["Atoms"]
    if len(atoms) != header["atoms"]:
        fail("%s: header says %d atoms, Atoms section has %d lines"
             % (a.data, header["atoms"], len(atoms)))
    particles = []
    for toks in atoms:
        if len(toks) not in (ncols, ncols + 3):
            fail("%s: Atoms line '%s' has %d columns, expected %d or %d for --style %s"
                 % (a.data, " ".join(toks), len(toks), ncols, ncols + 3, a.style))
        aid, typ = int(toks[0]), int(toks[1])
        r = []
        for k in range(a.dim):
            x = float(toks[2 + k]) - centre[k]
            if x >= 0.5 * L[k]:
                x -= L[k]
            elif x < -0.5 * L[k]:
                x += L[k]
            r.append(x)
        p = {"id": aid - 1, "r": r, "type": typ - 1}
        if a.style == "sphere-dipole":
            radius = 0.5 * float(toks[5])
            mu = [float(t) for t in toks[8 : 8 + a.dim]]
            if math.hypot(*mu) > 0.0:
                p["n"] = mu
        else:
            radius = None
        if a.radius is not None:
            radius = a.radius
        if radius is not None:
            p["radius"] = radius
        mass = a.mass if a.mass is not None else masses.get(typ, 1.0)
        p["mass"] = mass
        if aid in vel:
            p["v"] = vel[aid]
        particles.append(p)
    particles.sort(key=lambda p: p["id"])

    box = {"Lx": L[0], "Ly": L[1]}
    if a.dim == 3:
        box["Lz"] = L[2]
    doc = {"system": {"box": box, "particles": particles}}
    tmp = a.out + ".tmp.%d" % os.getpid()
    with open(tmp, "w") as f:
        json.dump(doc, f, separators=(",", ":"))
        f.write("\n")
    os.replace(tmp, a.out)
    if a.toml_tables:
        kinds = {(p["type"], p.get("radius", 1.0), p["mass"]) for p in particles}
        if len(kinds) != 1:
            fail("--toml-tables needs one type with one radius and mass, found %d" % len(kinds))
        typ, radius, mass = kinds.pop()
        if typ != 0:
            fail("--toml-tables: the type must be 1 in LAMMPS (0 in pedesis), got %d" % (typ + 1))
        with open(a.toml_tables, "w") as f:
            f.write("\n# from %s by lammps_data_to_json.py: the box and species of %s\n"
                    % (os.path.basename(a.data), os.path.basename(a.out)))
            f.write("[box]\nlengths = [%s]\n\n" % ", ".join(repr(x) for x in L))
            f.write('[[species]]\nname = "A"\ncount = %d\nradius = %r\nmass = %r\n'
                    % (len(particles), radius, mass))
    sys.stderr.write("lammps_data_to_json: %d particles, %dD box %s -> %s\n"
                     % (len(particles), a.dim, " x ".join(repr(x) for x in L), a.out))


if __name__ == "__main__":
    main()
