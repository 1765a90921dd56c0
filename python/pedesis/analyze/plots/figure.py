"""What every analyze plot shares: the command line, the title that says which run is
shown (N, dimension, dynamics, key parameters), matplotlib set-up and the atomic save.
"""
import argparse
import os
import textwrap
from pathlib import Path

from .run_dir import InputError, Run

DPI = 150
FORMATS = (".png", ".pdf", ".svg")


def open_run(description, default_name, options=None, check=None):
    """What every figure does first: its command line (see parse), ``check(args)`` for
    options of its own (raising InputError), the output checked before any work, and the
    run directory opened. Returns (args, Run)."""
    a = parse(description, default_name, options)
    if check is not None:
        check(a)
    check_output(a.out)
    return a, Run(a.run_dir)


def parse(description, default_name, options=None):
    """The arguments: RUN_DIR, --out (default RUN_DIR/default_name) and what
    ``options(parser)`` adds. argparse itself exits with 2 on a usage error, the status of
    bad input."""
    p = argparse.ArgumentParser(description=description)
    p.add_argument("run_dir", type=Path, help="a pedesis run directory")
    p.add_argument("--out", type=Path, help=f"output file (default RUN_DIR/{default_name})")
    if options is not None:
        options(p)
    a = p.parse_args()
    if a.out is None:
        a.out = a.run_dir / default_name
    return a


def check_output(out):
    """Refuses an output the save would fail on, before any work is done."""
    if out.suffix.lower() not in FORMATS:
        raise InputError(f"{out}: the output must end in .png, .pdf or .svg")
    folder = out.parent if str(out.parent) else Path(".")
    if not folder.is_dir():
        raise InputError(f"{out}: the folder {folder} does not exist")


def pyplot():
    """matplotlib.pyplot on the file-only Agg backend (no display needed)."""
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError as e:
        raise InputError(f"the plots need Debian's python3-matplotlib ({e}); "
                         "apt-get install python3-matplotlib") from None
    plt.rcParams.update({"font.size": 10, "axes.titlesize": 10, "legend.fontsize": 8,
                         "figure.titlesize": 11})
    return plt


def save(fig, out):
    """Writes NAME.tmp.EXT beside the output and renames it over it, so a reader never
    sees a half-written plot; returns the path, which a figure's main() returns for
    main_guard to print last."""
    tmp = out.with_name(f"{out.stem}.tmp{out.suffix}")
    try:
        fig.savefig(tmp, dpi=DPI, format=out.suffix[1:].lower())
        os.replace(tmp, out)
    except OSError as e:
        tmp.unlink(missing_ok=True)
        raise InputError(f"{out}: cannot be written: {e.strerror or e}") from None
    return out


# --- titles --------------------------------------------------------------------------


def number(x):
    """Short text for a config value: a number, or a per-species table."""
    if isinstance(x, dict):
        return "(" + ", ".join(f"{k} {number(v)}" for k, v in x.items()) + ")"
    if isinstance(x, float):
        return f"{x:g}"
    return str(x)


def describe(run):
    """Two title lines: what the system is, and the parameters that shape the curves."""
    d = run.dimension
    n = run.particle_count()
    n_text = f"N = {n}" if n is not None else "N = ?"
    if not run.soft:
        what = f"hard {'disks' if d == 2 else 'spheres'}, {d}D, {run.dynamics} dynamics"
        return f"{n_text} {what}", _hard_parameters(run)
    active = run.plugin("force", "self_propulsion") is not None
    what = f"{'active' if active else 'soft'} particles, {d}D, {run.dynamics} dynamics"
    return f"{n_text} {what}", _soft_parameters(run)


def _box_text(run):
    box = run.config.get("box")
    if not box:
        return None
    d = run.dimension
    lengths = box.get("lengths") or [box.get("length")] * d
    bound = box.get("boundary", "periodic")
    bound = bound if isinstance(bound, str) else "/".join(bound)
    return "box " + " x ".join(number(x) for x in lengths) + f" ({bound})"


def _hard_parameters(run):
    parts = []
    box = _box_text(run)
    if box:
        parts.append(box)
    eta = run.summary().get("packing_fraction")
    if eta is not None:
        parts.append(f"packing fraction {eta:.3g}")
    species = run.config.get("species", [])
    if species:
        parts.append("; ".join(
            f"{s.get('name', chr(65 + k))}: m {number(s.get('mass', 1.0))}, "
            f"r {number(s.get('radius', 0.5))}" for k, s in enumerate(species)))
    xi = run.config.get("event", {}).get("restitution")
    if xi is not None and xi != 1:
        parts.append(f"restitution {number(xi)}")
    # the stepped engine keeps its time step in its own table
    dt = run.config.get("run", {}).get("dt", run.config.get(run.dynamics, {}).get("dt"))
    if dt is not None:
        parts.append(f"dt {number(dt)}")
    return ", ".join(parts)


def _value(v):
    """A plug-in parameter as the config gives it: a number, a per-species table, a flag."""
    if isinstance(v, bool):
        return "on" if v else "off"
    return number(v)


def _soft_parameters(run):
    parts = []
    for table in ("force", "torque", "integrator"):
        for p in run.plugins(table):
            # every parameter the config gives, by its config key (the plug-in catalogue's
            # names, docs/engines.md), so that no second list of plug-ins lives here
            name = p.get("name", "?")
            keys = [f"{k} {_value(v)}" for k, v in p.items()
                    if k not in ("name", "pairs") and isinstance(v, (int, float, dict))]
            if p.get("pairs"):
                keys.append(f"{len(p['pairs'])} pair(s) set apart")
            parts.append(name + (" " + ", ".join(keys) if keys else ""))
    dt = run.config.get("run", {}).get("dt")
    if dt is not None:
        parts.append(f"dt {number(dt)}")
    return "; ".join(parts)


def title(fig, run, headline):
    """The figure title: the plot's own headline, then the system and its parameters."""
    system, params = describe(run)
    # about 11 characters of the title font per inch of figure width
    lines = [f"{headline}: {system}"] + textwrap.wrap(params, int(10.5 * fig.get_figwidth()))
    fig.suptitle("\n".join(lines))
