"""Frames from a pedesis run directory or any GSD file (through the gsd package)."""
import os
from dataclasses import dataclass

import numpy as np

from .box import Box
from .paths import check_images


@dataclass
class Trajectory:
    """Frames as arrays: positions (T, N, d) wrapped as stored, images (T, N, d) integer
    box crossings (zeros where the file has none), velocities (T, N, d) or None, types
    (N,) species indices, type_names, steps (T,), the box (that of frame 0), and directors
    (T, N, d): unit vectors, the file's orientations applied to the x axis (None where
    every orientation is the identity, as for hard particles), diameters (N,) of frame 0,
    and times (T,): the simulated time of each frame (log/time; the step where a file has
    none)."""

    positions: np.ndarray
    images: np.ndarray
    velocities: object
    types: np.ndarray
    type_names: list
    steps: np.ndarray
    box: Box
    directors: object = None
    diameters: object = None
    times: object = None
    # False where the frames' writer does not track box crossings (image counts of 0
    # that mean nothing); None where nothing says
    images_tracked: object = None
    source: str = "frames"  # the run directory or file, for messages

    def unwrapped(self):
        """Positions plus image * L: continuous paths, for the MSD. Raises ValueError
        where the image counts cannot give them (see paths.check_images)."""
        check_images(self.positions, self.images, self.box, self.images_tracked, self.source)
        return self.positions + self.images * np.array(self.box.lengths)


def _run_config(run_dir):
    """The run's config.toml as a dict, or None where the folder has none."""
    config = os.path.join(run_dir, "config.toml")
    if not os.path.exists(config):
        return None
    import tomllib

    with open(config, "rb") as f:
        return tomllib.load(f)


def _periodicity(config, dimension):
    """The run's [box] boundary: walls or periodic, per axis."""
    boundary = config.get("box", {}).get("boundary", "periodic")
    if isinstance(boundary, str):
        boundary = [boundary] * dimension
    return tuple(b != "wall" for b in boundary[:dimension])


def _gsd_path(source):
    """The GSD file of a run directory or the file itself; FileNotFoundError naming what
    read_frames takes where neither is there."""
    if os.path.isdir(source):
        path = os.path.join(source, "trajectory.gsd")
        if not os.path.exists(path):
            raise FileNotFoundError(f"{source}: no trajectory.gsd (set formats = [\"gsd\"])")
        return path
    if not os.path.exists(source):
        raise FileNotFoundError(f"{source}: no such run directory or file (read_frames takes a "
                                "run directory with trajectory.gsd, or a .gsd file)")
    return source


def read_frames(source, frames=None):
    """A Trajectory from a run directory (its trajectory.gsd) or a GSD file; the
    periodicity from the file's log/pedesis/periodic (pedesis writes it), else from the
    config.toml of the run directory (or of the file's folder), which also says whether
    the image counts are tracked. ``frames``: a slice or indices (default:
    all)."""
    import gsd.hoomd

    source = os.fspath(source)
    path = _gsd_path(source)
    try:
        with gsd.hoomd.open(path, "rb") as traj:
            chosen = range(len(traj))[frames] if isinstance(frames, slice) else (
                range(len(traj)) if frames is None else list(frames))
            snaps = [traj[int(k)] for k in chosen]
    except (OSError, RuntimeError) as e:
        raise ValueError(f"{path}: cannot be read as GSD ({e}); read_frames takes a run "
                         "directory with trajectory.gsd, or a .gsd file") from None
    if not snaps:
        raise ValueError(f"{path}: no frames")
    first = snaps[0]
    d = int(first.configuration.dimensions)
    config = _run_config(source if os.path.isdir(source) else os.path.dirname(path) or ".")
    periodic = None if config is None else _periodicity(config, d)
    flags = (first.log or {}).get("pedesis/periodic")  # the file's own walls come first
    if flags is not None:
        periodic = tuple(bool(p) for p in np.ravel(flags)[:d])
    # every engine counts box crossings (a frame written before the event and stepped
    # engines did stores 0: check_images then finds the jumps)
    tracked = None if config is None else True
    box = Box(tuple(first.configuration.box[:d]), periodic)
    pos = np.stack([s.particles.position[:, :d] for s in snaps]).astype(float)
    img = np.stack([s.particles.image[:, :d] for s in snaps]).astype(float)
    vel = np.stack([s.particles.velocity[:, :d] for s in snaps]).astype(float)
    if not vel.any():
        vel = None
    q = np.stack([s.particles.orientation for s in snaps]).astype(float)
    directors = None if np.all(q == (1.0, 0.0, 0.0, 0.0)) else _x_axis_rotated(q)[..., :d]
    return Trajectory(positions=pos, images=img, velocities=vel,
                      types=np.asarray(first.particles.typeid), type_names=list(first.particles.types),
                      steps=np.array([s.configuration.step for s in snaps]), box=box,
                      directors=directors, diameters=np.asarray(first.particles.diameter, float),
                      times=np.array([_time(s) for s in snaps]), images_tracked=tracked,
                      source=source)


def _time(snap):
    """A frame's simulated time: pedesis writes it as log/time."""
    value = (snap.log or {}).get("time")
    return float(np.ravel(value)[0]) if value is not None else float(snap.configuration.step)


def _x_axis_rotated(q):
    """The x axis rotated by unit quaternions q = (w, x, y, z) (..., 4): the first column
    of the rotation matrix, as HOOMD-blue and pedesis store a director."""
    w, x, y, z = np.moveaxis(q / np.linalg.norm(q, axis=-1, keepdims=True), -1, 0)
    return np.stack([1.0 - 2.0 * (y * y + z * z), 2.0 * (x * y + w * z), 2.0 * (x * z - w * y)],
                    axis=-1)
