#!/usr/bin/python3
"""Plot a run's speed_histogram.csv against the equilibrium curve it carries.

Usage: plot_speed_histogram.py RUN_DIR [OUT.png]
Uses Debian's python3-matplotlib (hence /usr/bin/python3, not the first python3 on PATH).
"""
import csv
import json
import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def main() -> int:
    if len(sys.argv) < 2:
        print(__doc__, file=sys.stderr)
        return 2
    run = Path(sys.argv[1])
    out = Path(sys.argv[2]) if len(sys.argv) > 2 else run / "speed_distribution.png"
    table = run / "speed_histogram.csv"
    if not table.is_file():
        print(f"{table}: no such file (is {run} a pedesis run directory?)", file=sys.stderr)
        return 2
    summary = json.loads((run / "summary.json").read_text())
    rows = list(csv.DictReader(table.open()))
    fig, ax = plt.subplots(figsize=(6, 4), dpi=120)
    for name in dict.fromkeys(r["species"] for r in rows):
        sel = [r for r in rows if r["species"] == name]
        lo = [float(r["v_lo"]) for r in sel]
        width = float(sel[0]["v_hi"]) - lo[0]
        ax.bar(lo, [float(r["density"]) for r in sel], width=width, align="edge", alpha=0.5,
               label=f"{name}: simulation")
        mid = [x + width / 2 for x in lo]
        label = "Rayleigh" if summary["dimension"] == 2 else "Maxwell"
        ax.plot(mid, [float(r["theory"]) for r in sel], "k-",
                label=f"{name}: {label}, T = {float(sel[0]['temperature']):.3g}")
    ax.set_xlabel("speed v")
    ax.set_ylabel("probability density f(v)")
    ax.set_title(f"{summary['particles']} hard {'disks' if summary['dimension'] == 2 else 'spheres'}, "
                 f"eta = {summary['packing_fraction']:.3f}, "
                 f"{summary['collisions_per_particle']:.0f} collisions per particle")
    ax.legend()
    fig.tight_layout()
    tmp = out.with_name(out.name + ".tmp.png")
    fig.savefig(tmp)
    tmp.replace(out)
    print(f"wrote {out}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
