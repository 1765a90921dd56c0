"""The simulation box: an orthorhombic box with periodic or walled axes."""
from dataclasses import dataclass, field

import numpy as np


@dataclass(frozen=True)
class Box:
    """An orthorhombic box of edge lengths ``lengths`` (d = 2 or 3 of them).

    ``periodic`` says, per axis, whether the box wraps (default: every axis). Positions
    may lie anywhere; periodic axes are wrapped into [0, L) where a search needs it.
    """

    lengths: tuple
    periodic: tuple = field(default=None)

    def __post_init__(self):
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
