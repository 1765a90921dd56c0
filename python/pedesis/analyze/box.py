"""The simulation box: pedesis.Box (pedesis/box.py), the one box type of the package, so
that a Gas's box, a frame's and a Trajectory's are the same thing."""
from ..box import Box

__all__ = ["Box"]
