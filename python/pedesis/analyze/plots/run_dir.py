"""Reading a pedesis run directory (docs/formats.md) for the analyze scripts.

Every fault raises InputError with the file named; `main_guard` turns it into one line
on stderr and exit status 2, the project's code for bad input (docs/analyze.md).
numpy is the only dependency here, so a script can check its input before paying for
the matplotlib import.
"""
import csv
import json
import math
import re
import sys
import tomllib
from pathlib import Path

import numpy as np  # (python -m pedesis.analyze names the package if it is missing)

SOFT_DYNAMICS = ("brownian", "langevin", "nve")


class InputError(Exception):
    """Bad or missing input; the message names the file."""


def main_guard(main):
    """Runs a figure's main(), which returns the file it wrote, and prints `wrote PATH`
    after the figure's own lines, in one place so that every figure ends the same way
    (docs/analyze.md); maps InputError to exit status 2 with one line on stderr."""
    try:
        out = main()
    except InputError as e:
        sys.stderr.write(f"pedesis: error: {e}\n")
        return 2
    print(f"wrote {out}")
    return 0


class Run:
    """A run directory: its config copy, log, summary and frames, read on demand."""

    def __init__(self, path):
        self.path = Path(path)
        if not self.path.exists():
            raise InputError(f"{self.path}: no such run directory")
        if not self.path.is_dir():
            raise InputError(f"{self.path}: not a directory (give the run directory)")
        self.config = self._read_config()
        self._summary = None

    # --- config.toml -----------------------------------------------------------------

    def _read_config(self):
        path = self.path / "config.toml"
        if not path.is_file():
            raise InputError(f"{path}: missing (is {self.path} a pedesis run directory?)")
        try:
            with path.open("rb") as f:
                return tomllib.load(f)
        except (tomllib.TOMLDecodeError, UnicodeDecodeError) as e:
            raise InputError(f"{path}: not valid TOML: {e}") from None
        except OSError as e:
            raise InputError(f"{path}: cannot be read: {e.strerror}") from None

    @property
    def dimension(self):
        return int(self.config.get("dimension", 2))

    @property
    def dynamics(self):
        return str(self.config.get("dynamics", "event"))

    @property
    def soft(self):
        return self.dynamics in SOFT_DYNAMICS

    def species_names(self):
        """Names by species index: [[species]] names, or A, B, ... as the engines name
        the types of an initial file when the config has no [[species]]."""
        entries = self.config.get("species", [])
        if entries:
            return [str(s.get("name", chr(ord("A") + k))) for k, s in enumerate(entries)]
        return [chr(ord("A") + k) for k in range(26)]

    def plugins(self, table):
        """The [[force]], [[torque]] or [[integrator]] entries (table = 'force', ...)."""
        return list(self.config.get(table, []))

    def plugin(self, table, name):
        """The first entry of that name, or None."""
        return next((p for p in self.plugins(table) if p.get("name") == name), None)

    # --- summary.json ----------------------------------------------------------------

    def summary(self):
        """summary.json as a dict, or {} when the run did not finish (it is optional)."""
        if self._summary is None:
            path = self.path / "summary.json"
            self._summary = {}
            if path.is_file():
                try:
                    self._summary = json.loads(path.read_text())
                except (ValueError, OSError) as e:
                    raise InputError(f"{path}: not valid JSON: {e}") from None
        return self._summary

    def particle_count(self):
        """N from summary.json, else from the config's species counts, else None."""
        n = self.summary().get("particles")
        if n is not None:
            return int(n)
        counts = [s.get("count") for s in self.config.get("species", [])]
        if counts and all(isinstance(c, int) for c in counts):
            return sum(counts)
        return None

    # --- log.csv ---------------------------------------------------------------------

    def log(self, needs=("time",), figure="this figure", elsewhere=None):
        """log.csv (see read_log) with the columns ``needs`` that ``figure`` draws, time
        first. ``elsewhere``: why this run's engine logs none of needs[1:] (a soft run's
        column asked of an event run), said when they are missing. Otherwise a missing
        column was left out by the run's [log] quantities, and the message says so."""
        path = self.path / "log.csv"
        log = read_log(path)
        if elsewhere is not None:
            require_columns(log, path, needs[1:], elsewhere)
        missing = [c for c in needs if c not in log]
        if not missing:
            return log
        needed = (f"{figure} needs the column{'s' if len(needs) > 1 else ''} "
                  f"{_and(needs)}")
        if "quantities" in self.config.get("log", {}):
            columns = _and(repr(c) for c in missing)
            toml_names = _and('"' + c + '"' for c in missing)
            raise InputError(f"{path}: no column {columns}: the run's [log] quantities left "
                             f"out {_and(missing)}, and {needed}; add {toml_names} to [log] "
                             "quantities and run again")
        require_columns(log, path, missing, needed)  # (raises: missing is not empty)

    # --- frames ----------------------------------------------------------------------

    def final_frame(self):
        """The last frame of the run: see read_final_frame."""
        return read_final_frame(self)


def read_log(path):
    """log.csv as {column: float array}, in the order of the header. Refuses ragged rows,
    text that is not a number, and a log without rows."""
    if not path.is_file():
        part = path.with_name(path.name + ".part")
        hint = (f" ({part.name} exists: the run is still going, or was killed)"
                if part.exists() else "")
        raise InputError(f"{path}: missing{hint}")
    rows = read_csv_rows(path)
    if not rows or not rows[0]:
        raise InputError(f"{path}: empty (no header line)")
    # (no column is required here: [log] quantities chooses them; Run.log checks a
    # figure's own)
    header = [h.strip() for h in rows[0]]
    if len(set(header)) != len(header):
        raise InputError(f"{path}: a column name appears twice in the header")
    data = []
    for line, row in enumerate(rows[1:], start=2):
        if not row:
            continue
        if len(row) != len(header):
            raise InputError(f"{path}: line {line} has {len(row)} fields, "
                             f"the header has {len(header)}")
        try:
            data.append([float(x) for x in row])
        except ValueError:
            bad = next(x for x in row if not _is_number(x))
            raise InputError(f"{path}: line {line}: '{bad}' is not a number") from None
    if not data:
        raise InputError(f"{path}: has a header but no rows")
    table = np.array(data, dtype=float)
    return {name: table[:, k] for k, name in enumerate(header)}


def read_csv_rows(path):
    """The rows of a CSV file as lists of strings; its faults as InputError naming it."""
    try:
        with path.open(newline="") as f:
            return list(csv.reader(f))
    except (OSError, UnicodeDecodeError, csv.Error) as e:
        raise InputError(f"{path}: cannot be read as CSV: {e}") from None


def _is_number(text):
    try:
        float(text)
        return True
    except ValueError:
        return False


def _and(names):
    """'a', 'a and b', 'a, b and c'."""
    names = list(names)
    return names[0] if len(names) == 1 else f"{', '.join(names[:-1])} and {names[-1]}"


def require_columns(log, path, columns, why):
    missing = [c for c in columns if c not in log]
    if missing:
        have = ", ".join(log)
        raise InputError(f"{path}: no column {', '.join(repr(c) for c in missing)}; {why} "
                         f"(the log has: {have})")


# --- frames --------------------------------------------------------------------------


class Frame:
    """One state: per-particle species index, mass and velocity (N x d), and where it
    came from (`source`, said in the output so a reader knows which state is shown)."""

    def __init__(self, time, types, mass, velocity, names, source):
        self.time = time
        self.types = types
        self.mass = mass
        self.velocity = velocity
        self.names = names
        self.source = source


def read_final_frame(run):
    """The final state, from the first frame source the run has: snapshots/*.json (full
    precision), trajectory.xyz (full precision), trajectory.gsd (float32)."""
    json_frames = _numbered_json_frames(run.path / "snapshots")
    if json_frames:
        return _final_json_frame(run, json_frames)
    xyz = run.path / "trajectory.xyz"
    if xyz.is_file():
        return _last_xyz_frame(run, xyz)
    gsd_path = run.path / "trajectory.gsd"
    if gsd_path.is_file():
        return _last_gsd_frame(run, gsd_path)
    raise InputError(f"{run.path}: no frames to take velocities from (snapshots/frame_*.json, "
                     "trajectory.xyz or trajectory.gsd); add \"json\" to [output] formats")


def _numbered_json_frames(folder):
    if not folder.is_dir():
        return []
    found = []
    for p in folder.glob("frame_*.json"):
        m = re.fullmatch(r"frame_(\d+)\.json", p.name)
        if m:
            found.append((int(m.group(1)), p))
    return [p for _, p in sorted(found)]


def _log_end_time(run):
    """The time of the log's last row, or None: it tells the run's own final frame from
    a later-numbered one an earlier, longer run left in the directory."""
    path = run.path / "log.csv"
    if not path.is_file():
        return None
    try:
        return float(read_log(path)["time"][-1])
    except (InputError, KeyError):
        return None


def _final_json_frame(run, frames):
    end = _log_end_time(run)
    newest = None
    for path in reversed(frames):
        frame = _read_json_frame(run, path)
        newest = newest or frame
        if end is None or math.isclose(frame.time, end, rel_tol=1e-9, abs_tol=1e-12):
            return frame
    sys.stderr.write(f"pedesis: warning: no frame in {run.path / 'snapshots'} has the time of "
                     f"the last row of log.csv (t = {end:g}); using {newest.source}\n")
    return newest


def _read_json_frame(run, path):
    try:
        system = json.loads(path.read_text())["system"]
        particles = system["particles"]
        time = float(system.get("time", 0.0))
        n = len(particles)
        types = np.array([int(p.get("type", 0)) for p in particles], dtype=int)
        mass = np.array([float(p.get("mass", 1.0)) for p in particles], dtype=float)
        velocity = np.array([p["v"] for p in particles], dtype=float).reshape(n, -1)
    except (OSError, ValueError, KeyError, TypeError, AttributeError) as e:
        raise InputError(f"{path}: not a pedesis snapshot ({type(e).__name__}: {e})") from None
    if n == 0:
        raise InputError(f"{path}: has no particles")
    return Frame(time, types, mass, velocity, run.species_names(),
                 f"{path.relative_to(run.path)}")


def _last_xyz_frame(run, path):
    """The last frame of an extended XYZ trajectory written by pedesis (species name,
    pos 3, velo 3, radius, mass, id)."""
    try:
        lines = path.read_text().splitlines()
    except (OSError, UnicodeDecodeError) as e:
        raise InputError(f"{path}: cannot be read: {e}") from None
    start, k = None, 0
    while k < len(lines):
        try:
            n = int(lines[k])
        except ValueError:
            raise InputError(f"{path}: line {k + 1}: expected a particle count") from None
        if k + 2 + n > len(lines):
            break  # a torn last frame: keep the last whole one
        start, k = k, k + 2 + n
    if start is None:
        raise InputError(f"{path}: no complete frame")
    comment = lines[start + 1]
    m = re.search(r"Time=(\S+)", comment)
    names, types, mass, velocity = [], [], [], []
    try:
        for line in lines[start + 2:start + 2 + int(lines[start])]:
            f = line.split()
            if f[0] not in names:
                names.append(f[0])
            types.append(names.index(f[0]))
            velocity.append([float(x) for x in f[4:7]])
            mass.append(float(f[8]))
        time = float(m.group(1)) if m else float("nan")
    except (ValueError, IndexError):
        raise InputError(f"{path}: frame at line {start + 1} is not pedesis extended XYZ") from None
    # species order of the config, so colours and names match the other plots
    order = [n for n in run.species_names() if n in names] + [n for n in names
                                                              if n not in run.species_names()]
    types = np.array([order.index(names[t]) for t in types], dtype=int)
    return Frame(time, types, np.array(mass), np.array(velocity)[:, :run.dimension], order,
                 f"{path.name} (last frame, line {start + 1})")


def _last_gsd_frame(run, path):
    try:
        import gsd.hoomd
    except ImportError:
        raise InputError(f"{path}: reading GSD needs Debian's python3-gsd") from None
    try:
        with gsd.hoomd.open(str(path)) as traj:
            if len(traj) == 0:
                raise InputError(f"{path}: no frames")
            frame = traj[len(traj) - 1]
            step = int(frame.configuration.step)
            velocity = np.asarray(frame.particles.velocity, dtype=float)[:, :run.dimension]
            mass = np.asarray(frame.particles.mass, dtype=float)
            types = np.asarray(frame.particles.typeid, dtype=int)
            names = list(frame.particles.types)
            logged_time = frame.log.get("time")
    except InputError:
        raise
    except Exception as e:  # gsd raises several kinds on a corrupt file
        raise InputError(f"{path}: cannot be read as GSD: {e}") from None
    dt = run.config.get("run", {}).get("dt")
    if logged_time is not None:  # log/time, which pedesis writes in every frame
        time = float(np.asarray(logged_time).reshape(-1)[0])
    else:
        time = step * float(dt) if dt is not None else float("nan")
    return Frame(time, types, mass, velocity, names,
                 f"{path.name} (last frame, step {step}; float32 velocities)")


def read_trajectory(run, most=200, last=None, skip_start=False):
    """The run's trajectory.gsd as a pedesis.analyze Trajectory: at most ``most`` frames
    evenly spread over the run (or over its ``last`` frames), the last one included; its
    faults as InputError. ``skip_start``: the run's starting frame (the file's first) is
    left out when there are others, and only it: the ``last`` frames are counted after
    it."""
    import gsd.hoomd

    from ..frames import read_frames

    path = run.path / "trajectory.gsd"
    if not path.is_file():
        raise InputError(f"{path}: missing; this figure reads GSD frames: add \"gsd\" to "
                         "[output] formats and run again")
    try:
        with gsd.hoomd.open(str(path), "rb") as traj:
            count = len(traj)
        first = 0 if last is None else max(0, count - last)
        if skip_start and count > 1:
            first = max(first, 1)
        picks = [first + k for k in frame_picks(count - first, most)]
        return read_frames(str(run.path), picks)
    except (OSError, RuntimeError, ValueError, KeyError) as e:
        raise InputError(f"{path}: cannot be read as GSD: {e}") from None


def frame_picks(count, most):
    """At most ``most`` frame indices out of ``count``, evenly spread, the last included."""
    if count <= most:
        return list(range(count))
    return sorted({int(round(k)) for k in np.linspace(0, count - 1, most)})
