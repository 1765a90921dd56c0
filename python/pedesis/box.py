"""The simulation box: an orthorhombic box with periodic or walled axes (pedesis.Box).

Gas.box, the "box" of every frame (Gas.frame(), Simulation.frame(), a Recording's frames)
and pedesis.analyze take it. It reads like the list of lengths it replaced (indexing,
len, iteration, numpy, equality with a list), so that scripts written for that list
keep working, and it carries the boundaries that the list lost."""
from dataclasses import dataclass, field

import numpy as np

__all__ = ["Box"]


@dataclass(frozen=True)
class Box:
    """An orthorhombic box of edge lengths ``lengths`` (d = 2 or 3 of them).

    ``periodic`` says, per axis, whether the box wraps (default: every axis); False is a
    wall. Positions may lie anywhere; periodic axes are wrapped into [0, L) where a
    search needs it. ``box[a]``, ``len(box)``, ``list(box)`` and ``np.array(box)`` are
    the lengths, and a box equals the list of its lengths.
    """

    lengths: tuple
    periodic: tuple = field(default=None)

    def __post_init__(self):
        if isinstance(self.lengths, Box) and self.periodic is None:  # (a copy keeps the walls)
            object.__setattr__(self, "periodic", self.lengths.periodic)
        lengths = tuple(float(x) for x in self.lengths)
        if len(lengths) not in (2, 3) or not all(np.isfinite(x) and x > 0 for x in lengths):
            raise ValueError(f"Box: lengths must be 2 or 3 positive numbers, not {self.lengths}")
        periodic = (True,) * len(lengths) if self.periodic is None else tuple(bool(p) for p in self.periodic)
        if len(periodic) != len(lengths):
            raise ValueError("Box: periodic needs one flag per axis")
        object.__setattr__(self, "lengths", lengths)
        object.__setattr__(self, "periodic", periodic)

    @property
    def dimension(self):
        return len(self.lengths)

    @property
    def volume(self):
        """Area in 2D, volume in 3D."""
        return float(np.prod(self.lengths))

    @property
    def boundary(self):
        """Per axis "periodic" or "wall", as a config's [box] boundary names them."""
        return tuple("periodic" if p else "wall" for p in self.periodic)

    # The list of lengths that Gas.box and frame["box"] used to be.
    def __len__(self):
        return len(self.lengths)

    def __getitem__(self, index):
        return self.lengths[index]

    def __iter__(self):
        return iter(self.lengths)

    def __array__(self, dtype=None, copy=None):
        return np.array(self.lengths, dtype=dtype)

    def __eq__(self, other):
        if isinstance(other, Box):
            return self.lengths == other.lengths and self.periodic == other.periodic
        if isinstance(other, (list, tuple, np.ndarray)):
            return len(other) == len(self.lengths) and all(
                float(a) == b for a, b in zip(other, self.lengths))
        return NotImplemented

    def wrap(self, positions):
        """Positions with periodic axes wrapped into [0, L) (walled axes shifted by the
        least coordinate, so that the result is non-negative); a copy."""
        x = np.array(positions, dtype=float)
        for a, (L, p) in enumerate(zip(self.lengths, self.periodic)):
            x[..., a] = np.mod(x[..., a], L) if p else x[..., a] - x[..., a].min()
        # (np.mod of a value just below 0 can round to L itself)
        for a, (L, p) in enumerate(zip(self.lengths, self.periodic)):
            if p:
                x[..., a] = np.where(x[..., a] >= L, 0.0, x[..., a])
        return x

    def tree_size(self):
        """cKDTree's boxsize: L on periodic axes; on walled ones a size past any distance."""
        return np.array([L if p else 4.0 * L for L, p in zip(self.lengths, self.periodic)])

    def minimum_image(self, dr):
        """Displacements with the nearest periodic image on periodic axes."""
        dr = np.array(dr, dtype=float)
        for a, (L, p) in enumerate(zip(self.lengths, self.periodic)):
            if p:
                dr[..., a] -= L * np.round(dr[..., a] / L)
        return dr
