"""Frames from a pedesis run directory or any GSD file (through the gsd package)."""
import os
from dataclasses import dataclass

import numpy as np

from .box import Box


@dataclass
class Trajectory:
    """Frames as arrays: positions (T, N, d) wrapped as stored, images (T, N, d) integer
    box crossings (zeros where the file has none), velocities (T, N, d) or None, types
    (N,) species indices, type_names, steps (T,), and the box (that of frame 0)."""

    positions: np.ndarray
    images: np.ndarray
    velocities: object
    types: np.ndarray
    type_names: list
    steps: np.ndarray
    box: Box

    def unwrapped(self):
        """Positions plus image * L: continuous paths, for the MSD."""
        return self.positions + self.images * np.array(self.box.lengths)


def _periodicity(run_dir, dimension):
    """The run's [box] boundary from its config.toml: walls or periodic, per axis."""
    config = os.path.join(run_dir, "config.toml")
    if not os.path.exists(config):
        return None
    import tomllib

    with open(config, "rb") as f:
        boundary = tomllib.load(f).get("box", {}).get("boundary", "periodic")
    if isinstance(boundary, str):
        boundary = [boundary] * dimension
    return tuple(b != "wall" for b in boundary[:dimension])


def read_frames(source, frames=None):
    """A Trajectory from a run directory (its trajectory.gsd; the periodicity from its
    config.toml) or a GSD file. ``frames``: a slice or indices (default: all)."""
    import gsd.hoomd

    path, periodic = source, None
    if os.path.isdir(source):
        path = os.path.join(source, "trajectory.gsd")
        if not os.path.exists(path):
            raise FileNotFoundError(f"{source}: no trajectory.gsd (set formats = [\"gsd\"])")
    with gsd.hoomd.open(path, "rb") as traj:
        chosen = range(len(traj))[frames] if isinstance(frames, slice) else (
            range(len(traj)) if frames is None else list(frames))
        snaps = [traj[int(k)] for k in chosen]
    if not snaps:
        raise ValueError(f"{path}: no frames")
    first = snaps[0]
    d = int(first.configuration.dimensions)
    if os.path.isdir(source):
        periodic = _periodicity(source, d)
    box = Box(tuple(first.configuration.box[:d]), periodic)
    pos = np.stack([s.particles.position[:, :d] for s in snaps]).astype(float)
    img = np.stack([s.particles.image[:, :d] for s in snaps]).astype(float)
    vel = np.stack([s.particles.velocity[:, :d] for s in snaps]).astype(float)
    if not vel.any():
        vel = None
    return Trajectory(positions=pos, images=img, velocities=vel,
                      types=np.asarray(first.particles.typeid), type_names=list(first.particles.types),
                      steps=np.array([s.configuration.step for s in snaps]), box=box)
