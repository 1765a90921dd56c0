"""Frames of a Gas or of an Evolver's System, kept as the run goes (pedesis.Recording).

    gas = pedesis.Gas(config)
    movie = gas.record(time=0.5)      # the state now, then every 0.5 time units of run()
    gas.run(time=50)
    movie.positions.shape             # (101, N, 2): no hand-written loop
    movie                             # a notebook cell ending with it: the particles, inline
    movie.save("gas.gsd")             # a GSD trajectory (".xyz": extended XYZ)

    e = pedesis.Evolver(s)
    frames = e.record(steps=10, file="abp.gsd")   # every 10 steps of run() and evolve()

Frames are dicts laid out as Simulation.frame() gives them (numpy arrays in tag order).
A recording with a file writes it whole, by the engines' own writers, each time run()
or evolve() returns with new frames: the file is then complete, and the frames stay in
memory (about 2 dim x 8 bytes per particle and frame). Each write costs all the frames
so far, so a file grows quadratically in work when evolve() is called step by step. A long run meant for disk is a Simulation with
a GSDWriter (docs/python.md), which writes as it goes.
"""
import functools
import math
import os
import pathlib
import tempfile
import weakref

import numpy as np

from . import _pedesis

__all__ = ["Recording"]

_FORMATS = {".gsd": "gsd", ".xyz": "xyz"}


def _format_of(path, format):
    if format is not None:
        return format
    suffix = pathlib.Path(path).suffix.lower()
    if suffix not in _FORMATS:
        raise _pedesis.InputError(f"{path}: the format is named by the suffix, .gsd or .xyz "
                                  "(or give format=)")
    return _FORMATS[suffix]


class Recording:
    """Frames kept in memory, the first the state when recording began. `frames` is the
    list of frame dicts; `times`, `steps`, `positions`, `velocities` (and `directors` for
    a System) stack them as arrays. save(path) writes a GSD or XYZ trajectory; in a
    notebook the recording draws itself (pedesis.show). stop() ends the recording."""

    def __init__(self, file=None, format=None):
        self.frames = []
        self.file = None if file is None else os.fspath(file)
        self._format = None if file is None else _format_of(self.file, format)
        if self.file is not None:
            parent = os.path.dirname(os.path.abspath(self.file))
            if not os.path.isdir(parent):
                raise FileNotFoundError(f"{self.file}: no such directory {parent}")
        self.recording = True
        self._saved = 0  # frames in the file

    def _take(self, frame):
        if self.recording:
            self.frames.append(frame)

    def _written(self):
        # (only when frames came since the last write: an evolve() loop that took none
        # must not rewrite the file at every step)
        if self.file is not None and self.frames and len(self.frames) != self._saved:
            self.save(self.file, self._format)
            self._saved = len(self.frames)

    def stop(self):
        """Takes no more frames (the file, if any, keeps those taken)."""
        self.recording = False

    def __len__(self):
        return len(self.frames)

    def __getitem__(self, index):
        return self.frames[index]

    def __iter__(self):
        return iter(self.frames)

    def _stack(self, key):
        if not self.frames or key not in self.frames[0]:
            raise AttributeError(f"the frames hold no {key!r}")
        return np.stack([f[key] for f in self.frames])

    @property
    def times(self):
        return np.array([f["time"] for f in self.frames])

    @property
    def steps(self):
        return np.array([f["step"] for f in self.frames], dtype=np.uint64)

    @property
    def positions(self):
        """(frames, N, dim)"""
        return self._stack("position")

    @property
    def velocities(self):
        return self._stack("velocity")

    @property
    def directors(self):
        return self._stack("director")

    def save(self, path, format=None):
        """Writes every frame as a GSD (HOOMD-blue's format) or extended-XYZ trajectory,
        by the suffix or `format`; the file appears complete or not at all."""
        _pedesis._write_frames(os.fspath(path), _format_of(path, format), self.frames)

    def show(self, max_bytes=None, height=560, every=None):
        """The frames inline in a notebook (pedesis.show on a run directory holding them)."""
        from .show import DEFAULT_MAX_BYTES, show
        with tempfile.TemporaryDirectory(prefix="pedesis_recording_") as run_dir:
            self.save(os.path.join(run_dir, "trajectory.gsd"))
            _write_log(self.frames, os.path.join(run_dir, "log.csv"))
            return show(run_dir, max_bytes or DEFAULT_MAX_BYTES, height, every)

    def _repr_html_(self):
        return self.show()._repr_html_() if self.frames else None

    def __repr__(self):
        what = f", written to {self.file}" if self.file else ""
        span = (f", t = {self.frames[0]['time']:g} to {self.frames[-1]['time']:g}"
                if self.frames else "")
        return f"<pedesis.Recording: {len(self.frames)} frames{span}{what}>"


def _write_log(frames, path):
    """A log.csv for the viewer's plot: the time, the temperature 2K/(dN) and the mean
    speed of each frame, from the frames themselves."""
    with open(path, "w") as out:
        out.write("step,time,kinetic_energy,mean_speed\n")
        for f in frames:
            v = f.get("velocity")
            if v is None:
                continue
            moving = np.isfinite(f["mass"])
            speed2 = np.sum(v * v, axis=1)
            kinetic = 0.5 * float(np.sum(f["mass"][moving] * speed2[moving]))
            mean_speed = float(np.mean(np.sqrt(speed2))) if len(speed2) else math.nan
            out.write(f"{f['step']},{f['time']!r},{kinetic!r},{mean_speed!r}\n")


# Who records what: a Gas or Evolver -> its recordings (weak: a recording does not keep
# its source alive).
_recordings = weakref.WeakKeyDictionary()


def _system_frame(system):
    table = system.species
    types = np.array(system.types, copy=True)
    radius = np.array([sp["radius"] for sp in table], dtype=float)
    mass = np.array([sp["mass"] for sp in table], dtype=float)
    return {"time": system.time, "step": system.step, "box": system.box,
            "species": [sp["name"] for sp in table], "type": types,
            "position": np.array(system.positions, copy=True),
            "velocity": np.array(system.velocities, copy=True),
            "director": np.array(system.directors, copy=True),
            "image": np.array(system.images, copy=True),
            "radius": radius[types], "mass": mass[types]}


def gas_record(gas, time=None, steps=None, file=None, format=None):
    """Gas.record: the state now, then a frame each `time` of simulated time (or each
    `steps` steps, stepped engine) on a grid anchored at t = 0, in every later run();
    returns the Recording. file: also written as a trajectory when each run() returns."""
    rec = Recording(file, format)
    gas._add_recording(rec._take, steps=steps, time=time)  # (checks the trigger first)
    rec._take(gas.frame())
    _recordings.setdefault(gas, []).append(rec)
    return rec


def evolver_record(evolver, steps, file=None, format=None):
    """Evolver.record: the state now, then a frame at each step that is a multiple of
    `steps`, in every later run() and evolve(); returns the Recording. file: also written
    as a trajectory when each run() or evolve() returns."""
    if not (isinstance(steps, int) and steps > 0):
        raise _pedesis.InputError(f"Evolver.record: steps must be a positive integer, got "
                                  f"{steps!r}")
    rec = Recording(file, format)
    rec._take(_system_frame(evolver.system))
    _recordings.setdefault(evolver, []).append((steps, rec))
    return rec


def _write_files(owner):
    for entry in _recordings.get(owner, []):
        (entry[1] if isinstance(entry, tuple) else entry)._written()


def recording_gas_run(run):
    @functools.wraps(run)
    def wrapped(self, *args, **kwargs):
        try:
            return run(self, *args, **kwargs)
        finally:  # (also after Ctrl-C: the state is whole, and so are the frames)
            _write_files(self)
    return wrapped


def recording_evolver_run(run):
    """Evolver.run with its recordings served: the C++ loop calls back at the multiples of
    the greatest common divisor of `every` and the recordings' intervals, and each call
    goes to those whose multiple it is."""
    @functools.wraps(run)
    def wrapped(self, steps, dt, every=0, callback=None):
        taking = [(n, rec) for n, rec in _recordings.get(self, []) if rec.recording]
        if not taking:
            return run(self, steps, dt, every, callback)
        if callback is not None and every <= 0:
            raise _pedesis.InputError("Evolver.run: a callback needs every > 0 (steps)")
        stride = every if callback is not None else 0
        for n, _ in taking:
            stride = math.gcd(stride, n)

        def serve(step):
            if any(step % n == 0 for n, _ in taking):
                frame = _system_frame(self.system)
                for n, rec in taking:
                    if step % n == 0:
                        rec._take(frame)
            if callback is not None and step % every == 0:
                callback(step)
        try:
            return run(self, steps, dt, stride, serve)
        finally:
            _write_files(self)
    return wrapped


def recording_evolve(evolve):
    @functools.wraps(evolve)
    def wrapped(self, dt):
        try:
            evolve(self, dt)
            step = self.system.step
            for n, rec in _recordings.get(self, []):
                if rec.recording and step % n == 0:
                    rec._take(_system_frame(self.system))
        finally:
            _write_files(self)
    return wrapped


def _now(frame):
    rec = Recording()
    rec._take(frame)
    return rec


def latest_recording(source):
    """A Gas's latest recording, else its state now; a System's state now."""
    if isinstance(source, _pedesis.System):
        return _now(_system_frame(source))
    recs = [r for r in _recordings.get(source, []) if isinstance(r, Recording)]
    return recs[-1] if recs else _now(source.frame())


def gas_repr_html(gas):
    """A Gas ending a notebook cell: its latest recording, else the state now."""
    return latest_recording(gas)._repr_html_()


def system_repr_html(system):
    """A System ending a notebook cell: the state now (an Evolver's record() keeps the
    frames of a run)."""
    try:
        frame = _system_frame(system)
    except _pedesis.InputError:  # (no particles read yet: IPython shows the repr)
        return None
    return _now(frame)._repr_html_()
