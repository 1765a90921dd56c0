"""pedesis.Simulation: any engine's run from a config file, driven by the same loop as
`pedesis run` (the same log, frames, checkpoints and summary), with writers and
callbacks of the script's own on triggers.

    sim = pedesis.Simulation.from_file("examples/kob_andersen.toml", out="runs/ka")
    sim.writers.append(pedesis.GSDWriter("runs/ka/extra.gsd", pedesis.Periodic(steps=500)))
    sim.callbacks.append(pedesis.Callback(lambda: print(sim.log["temperature"]),
                                          pedesis.Periodic(time=1.0)))
    sim.run(steps=1000)   # 1000 more steps (or until the config's stop condition)
    sim.run()             # on to the config's stop condition, then the end of the run
"""
import math
import numbers
from dataclasses import dataclass
from typing import Callable, Optional

from . import _pedesis


def _count(value, what, positive):
    """value as an int (> 0 if positive, else >= 0), or InputError naming `what`: a bool or
    2.5 is no count of steps."""
    if isinstance(value, bool) or not isinstance(value, numbers.Integral):
        raise _pedesis.InputError(f"{what} must be a whole number of time steps (an int), "
                                  f"not {value!r}")
    if value < 0 or (positive and value == 0):
        raise _pedesis.InputError(f"{what} must be {'positive' if positive else '>= 0'}, "
                                  f"not {value!r}")
    return int(value)


def _duration(value, what, positive):
    """value as a finite float (> 0 if positive, else >= 0), or InputError naming `what`."""
    if isinstance(value, bool) or not isinstance(value, numbers.Real):
        raise _pedesis.InputError(f"{what} must be a number of time units, not {value!r}")
    value = float(value)
    if not math.isfinite(value) or value < 0 or (positive and value == 0):
        bound = "positive finite number" if positive else "finite number >= 0"
        raise _pedesis.InputError(f"{what} must be a {bound}, not {value!r}")
    return value


@dataclass(frozen=True)
class Periodic:
    """Fires every `steps` time steps or every `time` of simulated time (one of them), on a
    grid anchored at step 0 / t = 0. The event engine has no steps: give it time."""
    steps: Optional[int] = None
    time: Optional[float] = None

    def __post_init__(self):
        # refused when made, not later when appended to a Simulation, where the mistake
        # would be far from the line that made it
        if (self.steps is None) == (self.time is None):
            raise _pedesis.InputError("Periodic: give steps or time, one of them (got "
                                      f"steps={self.steps!r}, time={self.time!r})")
        if self.steps is not None:
            object.__setattr__(self, "steps", _count(self.steps, "Periodic: steps", True))
        else:
            object.__setattr__(self, "time", _duration(self.time, "Periodic: time", True))


@dataclass(frozen=True)
class GSDWriter:
    """A GSD trajectory (HOOMD-blue's format) of the script's own: a frame at the start, at
    each firing and, as the run's own trajectory, at the end of the run."""
    path: str
    trigger: Periodic


@dataclass(frozen=True)
class XYZWriter:
    """An extended-XYZ trajectory of the script's own: a frame at the start, at each firing
    and, as the run's own trajectory, at the end of the run."""
    path: str
    trigger: Periodic


@dataclass(frozen=True)
class Callback:
    """Calls fn() at each firing (not at the run's stop, like the run's own frames)."""
    fn: Callable[[], None]
    trigger: Periodic


class _Registered(list):
    """A list whose append registers the item with the run at once."""

    def __init__(self, register):
        super().__init__()
        self._register = register

    def append(self, item):
        self._register(item)
        super().append(item)


class Simulation:
    """A run of any engine (event, stepped, brownian, langevin, nve) from a config file.

    The run directory is the CLI's: log.csv, the config's frame formats, checkpoint.bin,
    summary.json. run() goes on to the config's stop condition and writes the end of the
    run; run(steps=...) or run(time=...) advance that much more (never past the stop
    condition); close() writes the end of a run stopped early. `log` is the last log row
    by quantity name, `frame()` the current state as numpy arrays in id order.
    """

    def __init__(self, run):
        self._run = run
        self.writers = _Registered(self._add_writer)
        self.callbacks = _Registered(self._add_callback)

    @classmethod
    def from_file(cls, config, out=None, restart=None, quiet=True):
        """The run of a TOML config (docs/config.md). out: the run directory (default
        runs/<config name>); restart: a checkpoint.bin to continue from; quiet: no
        console lines (the CLI prints them)."""
        import os
        if out is None:
            out = os.path.join("runs", os.path.splitext(os.path.basename(str(config)))[0])
        sim = cls(_pedesis._Run(str(config), str(out), None if restart is None else
                                str(restart), quiet))
        sim.out_dir = out
        return sim

    out_dir = None  # the run directory (from_file's out)

    # What a script may assign; anything else raises, since a run's parameters live in
    # the engine: sim.temperature = 2 would otherwise change nothing, silently.
    _settable = ("_run", "writers", "callbacks", "out_dir")

    def __setattr__(self, name, value):
        if name not in self._settable:
            steer = (f"; change a running parameter with sim.set({name!r}, {value!r})"
                     if name in self._run.steerable else
                     "; set() changes what `steerable` lists, the config file the rest")
            raise AttributeError(f"Simulation has no setting {name!r}{steer}")
        object.__setattr__(self, name, value)

    def _repr_html_(self):
        """A notebook cell ending with the simulation shows its run directory as it is
        now: the frames written so far (pedesis.show); before the first frame, the usual
        text."""
        from .show import show
        if self.out_dir is None:
            return None
        try:
            return show(self)._repr_html_()
        except (FileNotFoundError, RuntimeError):
            return None  # (nothing to draw yet: IPython falls back to repr)

    def _add_writer(self, w):
        formats = {GSDWriter: "gsd", XYZWriter: "xyz"}
        if type(w) not in formats:
            raise _pedesis.InputError(f"Simulation.writers: {w!r} is not a GSDWriter or "
                                      "XYZWriter")
        import pathlib
        folder = pathlib.Path(w.path).parent.absolute()
        if self.out_dir is not None and folder.is_relative_to(pathlib.Path(self.out_dir).absolute()):
            # a file in the run directory, which run() makes: made now, for the writer
            folder.mkdir(parents=True, exist_ok=True)
        self._run.add_trajectory(str(w.path), formats[type(w)], w.trigger.steps,
                                 w.trigger.time)

    def _add_callback(self, c):
        if not isinstance(c, Callback):
            raise _pedesis.InputError(f"Simulation.callbacks: {c!r} is not a Callback")
        self._run.add_callback(c.fn, c.trigger.steps, c.trigger.time)

    def run(self, steps=None, time=None):
        """Without arguments: on to the config's stop condition, then the end of the run
        (last frame, checkpoint, summary). With steps or time: that much more, or less if
        the stop condition comes first (then the end of the run too). Returns the stop
        condition's name once it is met, else None. The GIL is released; Ctrl-C stops the
        engine within a step and raises KeyboardInterrupt, with the state intact (run()
        goes on from there, close() ends the run directory)."""
        if steps is not None and time is not None:
            raise _pedesis.InputError("Simulation.run: give steps or time, not both")
        if steps is not None:
            steps = _count(steps, "Simulation.run: steps", False)
        if time is not None:
            time = _duration(time, "Simulation.run: time", False)
        why = self._run.advance(steps, time)
        if why is not None and not self._run.closed:
            self._run.close("")
        return why

    def set(self, parameter, value):
        """Changes a parameter of the running simulation from the next step on, as the
        sliders of `pedesis run --view` do: "temperature" (of the position integrator,
        every species), "alpha" (self-propulsion) or "J" (polar alignment); see
        `steerable`. The change is recorded in the run directory's steering.csv, so that
        `pedesis run CONFIG --steering steering.csv` reproduces the run bit for bit.
        Raises ValueError for an unknown parameter or a bad value."""
        self._run.set(parameter, float(value))

    steerable = property(lambda self: self._run.steerable,
                         doc="what set() can change, with the current values")

    def close(self):
        """Writes the end of the run (last frame, checkpoint, summary) if not done yet."""
        if not self._run.closed:
            self._run.close("script")

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        if exc[0] is None:
            self.close()
        return False

    @property
    def summary(self):
        """The run directory's summary.json as a dict once the run has ended (run() to its
        stop condition, or close()); None before."""
        import json
        import os
        if not self._run.closed or self.out_dir is None:
            return None
        with open(os.path.join(str(self.out_dir), "summary.json")) as f:
            return json.load(f)

    @property
    def transport(self):
        """The transport coefficients of a run with [transport] (summary.json's
        "transport": {"diffusion": {"value": ..., "error": ...}, "shear_viscosity",
        "bulk_viscosity", "thermal_conductivity", ...}, docs/formats.md) once the run has
        ended; None before, or without [transport]."""
        summary = self.summary
        return None if summary is None else summary.get("transport")

    @property
    def log(self):
        """The last row of log.csv as {quantity: value} (empty before the first)."""
        return dict(zip(self._run.log_names, self._run.last_log_row))

    def frame(self):
        """The current state: dict of numpy arrays in id order (position, velocity, type,
        radius, mass, image, and director for soft runs) plus time, step, box, species."""
        return self._run.frame()

    step = property(lambda self: self._run.step, doc="time steps so far (collisions for "
                    "the event engine)")
    time = property(lambda self: self._run.time, doc="simulated time")
    dimension = property(lambda self: self._run.dimension)
    stopped_by = property(lambda self: self._run.stopped_by,
                          doc="the config's stop condition once met, else None")
