#!/usr/bin/python3
"""Turns a LAMMPS run of in.start into the files of the in.lj regression test.

    lmp -in in.start -log log.lammps && /usr/bin/python3 make_reference.py

start.json: LAMMPS's start (dump of step 0: its fcc positions, shifted into pedesis'
box centred at 0, and its velocities) in the initial-configuration layout.
reference.json: means of LAMMPS's T, U/N and P over steps 1000-6000 (thermo every 10
steps) and their standard errors from 10 block means.
"""
import json
import statistics

with open("start.dump") as f:
    lines = f.read().split("\n")
bounds = [float(x) for x in lines[5].split()]
lo, hi = bounds
half = 0.5 * (hi - lo)
particles = []
for line in lines[9:]:
    if not line.strip():
        continue
    fields = line.split()
    tag = int(fields[0]) - 1
    r = [float(x) - lo - half for x in fields[1:4]]
    v = [float(x) for x in fields[4:7]]
    particles.append({"id": tag, "r": r, "v": v})
L = hi - lo
with open("start.json", "w") as f:
    json.dump({"system": {"box": {"Lx": L, "Ly": L, "Lz": L}, "particles": particles}}, f,
              separators=(",", ":"))

rows = []
with open("log.lammps") as f:
    inside = False
    for line in f:
        if line.startswith("Step Temp PotEng Press"):
            inside = True
            continue
        if inside:
            if line.startswith("Loop time"):
                break
            step, temp, pe, press = line.split()
            if int(step) >= 1000:
                rows.append((float(temp), float(pe), float(press)))
blocks = 10
size = len(rows) // blocks
reference = {"source": "LAMMPS 20220106 (Debian), in.start, steps 1000-6000, thermo every 10",
             "rows": len(rows)}
for k, name in enumerate(["temperature", "potential_energy_per_particle", "pressure"]):
    means = [statistics.fmean(r[k] for r in rows[b * size:(b + 1) * size]) for b in range(blocks)]
    reference[name] = {"mean": statistics.fmean(r[k] for r in rows),
                       "standard_error": statistics.stdev(means) / blocks ** 0.5}
with open("reference.json", "w") as f:
    json.dump(reference, f, indent=1)
print(json.dumps(reference, indent=1))
