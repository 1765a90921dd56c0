"""TOML configs of the validation runs, written as text (docs/config.md)."""
import math


def box_length(dimension, count, radius, packing):
    """Edge of the square/cubic box that ``count`` particles of ``radius`` fill to
    ``packing``."""
    one = math.pi * radius ** 2 if dimension == 2 else 4.0 / 3.0 * math.pi * radius ** 3
    return (count * one / packing) ** (1.0 / dimension)


def species_tables(species):
    """[[species]] tables from (name, count, radius, mass) tuples."""
    return "".join(f"[[species]]\nname = \"{n}\"\ncount = {c}\nradius = {r}\nmass = {m}\n\n"
                   for n, c, r, m in species)


def hard_gas(dimension, species, length, seed, time, log_interval, boundary="periodic",
             positions="random", dynamics="event", restitution=1.0, quantities=None,
             extra="", velocities="maxwell_boltzmann", stop=None):
    """A hard-particle run (event or stepped engine): a Maxwell-Boltzmann start at T = 1
    (or ``velocities``, speed 1), no frames, a log row every ``log_interval``, to ``time``
    (or the [run] line ``stop``). ``extra`` follows the [event] table's restitution: more
    [event] keys, or tables of their own."""
    log = "" if quantities is None else f"[log]\nquantities = {list(quantities)!r}\n"
    event = f"[event]\nrestitution = {restitution}\n" if dynamics == "event" else ""
    return f"""dimension = {dimension}
dynamics = "{dynamics}"
seed = {seed}

[box]
length = {length!r}
boundary = "{boundary}"

{species_tables(species)}[initial]
positions = "{positions}"
velocities = "{velocities}"
temperature = 1.0
speed = 1.0

{event}{extra}
[run]
{stop or f"time = {time}"}

[output]
log_interval = {log_interval}
formats = []
progress = false

{log}""".replace("'", '"')


def soft_run(dimension, dynamics, count, length, seed, steps, dt, log_every, snapshot_every,
             forces="", integrators="", positions="random", radius=0.5, extra="",
             boundary=None):
    """A soft/active run (brownian, langevin, nve): the [[force]] and [[integrator]]
    tables as given, GSD frames every ``snapshot_every`` steps. ``length`` is one edge or
    a list of one per axis; ``boundary`` (a list of "periodic" / "wall" per axis) walls
    axes, which then need a wall force; the default box is periodic."""
    edges = (f"lengths = {[float(x) for x in length]!r}" if isinstance(length, (list, tuple))
             else f"length = {length!r}")
    walls = "" if boundary is None else f"boundary = {list(boundary)!r}\n".replace("'", '"')
    return f"""dimension = {dimension}
dynamics = "{dynamics}"
seed = {seed}

[box]
{edges}
{walls}
[[species]]
name = "A"
count = {count}
radius = {radius}

[initial]
positions = "{positions}"
{extra}
{forces}
{integrators}
[run]
steps = {steps}
dt = {dt}

[output]
log_every = {log_every}
snapshot_every = {snapshot_every}
formats = ["gsd"]
progress = false
"""


def table(kind, name, **keys):
    """One [[kind]] table (force, torque, integrator) with its keys."""
    def toml(v):
        return ("true" if v else "false") if isinstance(v, bool) else repr(v).replace("'", '"')
    body = "".join(f"{k} = {toml(v)}\n" for k, v in keys.items())
    return f"[[{kind}]]\nname = \"{name}\"\n{body}\n"
