"""Continuous paths from wrapped positions, and the checks that keep an MSD of wrapped
positions (which levels off near the box size) from passing for physics."""
import numpy as np

from .box import Box

_AXES = "xyz"


def unwrap(positions, box):
    """Continuous paths (T, N, d) from wrapped positions: each particle follows, from one
    frame to the next, its nearest periodic image. Right while no particle moves half a
    box length between consecutive frames (nothing in the positions can tell otherwise);
    for frames without image counts, such as the event and stepped engines write."""
    box = box if isinstance(box, Box) else Box(box)
    x = np.asarray(positions, dtype=float)
    steps = box.minimum_image(np.diff(x, axis=0))
    return np.concatenate([x[:1], x[:1] + np.cumsum(steps, axis=0)])


def check_images(positions, images, box, tracked, source):
    """Raises ValueError where positions + images * L would not be continuous paths:
    frames whose engine does not track box crossings (tracked False), or a particle that
    moves more than half a box length between two frames with its image count
    unchanged."""
    if not any(box.periodic):
        return  # walls only: the stored positions are the paths
    if tracked is False:
        raise ValueError(
            f"{source}: these frames carry no image counts (the event and stepped engines do "
            "not track box crossings; their frames store 0), so unwrapped() would return "
            "wrapped positions, whose MSD levels off near the box size; "
            "pa.unwrap(traj.positions, traj.box) follows each particle to its nearest image "
            "from frame to frame instead (right while no particle moves half a box length "
            "between frames: write frames often enough)")
    jump = _first_jump(np.asarray(positions), box.lengths, box.periodic,
                       np.diff(np.asarray(images), axis=0) == 0)
    if jump is not None:
        raise ValueError(
            f"{source}: {_words(jump)}, more than half the box length "
            f"{box.lengths[jump[2]]:g}, with its image count unchanged: the image counts do not follow "
            "the box crossings, or the frames are too far apart to follow the paths; write "
            "frames more often, or, if no particle moves half a box length between frames, "
            "use pa.unwrap(traj.positions, traj.box)")


def check_unwrapped(positions, box, who):
    """Raises ValueError where ``positions`` (T, N, d) look wrapped: a particle moves more
    than half a box length between consecutive frames along a periodic axis. Without a
    box the length of an axis is taken as the extent of the positions along it (wrapped
    positions fill [0, L)); a box with walls (periodic False) skips its axes."""
    x = np.asarray(positions)
    if x.ndim != 3 or x.shape[0] < 2 or x.size == 0:
        return
    if box is None:
        lengths = np.ptp(x.reshape(-1, x.shape[2]), axis=0)
        periodic = lengths > 0
        what = "the extent of the positions"
    else:
        box = box if isinstance(box, Box) else Box(box)
        lengths, periodic, what = np.array(box.lengths), np.array(box.periodic), "the box length"
    jump = _first_jump(x, lengths, periodic, None)
    if jump is not None:
        raise ValueError(
            f"{who}: {_words(jump)}, more than half {what} {lengths[jump[2]]:.4g}: these look like wrapped positions, whose "
            "MSD levels off near the box size. Pass continuous paths: traj.unwrapped() for "
            "frames with image counts, positions + images * L, or pa.unwrap(positions, box) "
            "(each particle to its nearest image between frames). If these are paths that "
            "really move that far between frames, the frames are too far apart to trust; "
            "a box with periodic=False axes skips this check")


def _first_jump(x, lengths, periodic, unchanged):
    """The first move of more than half the length along a periodic axis between
    consecutive frames (where ``unchanged``, (T-1, N, d) bools, allows): (frame k,
    particle, axis, distance) for frames k and k + 1; or None. A block of particles at a time: the differences of a whole long trajectory
    would take gigabytes."""
    half = 0.5 * np.asarray(lengths, dtype=float)
    axes = np.asarray(periodic, dtype=bool)
    T, N = x.shape[0], x.shape[1]
    block = max(1, 1_000_000 // max(T, 1))
    for first in range(0, N, block):
        part = slice(first, first + block)
        dx = np.abs(np.diff(np.asarray(x[:, part], dtype=float), axis=0))
        bad = (dx > half) & axes
        if unchanged is not None:
            bad &= unchanged[:, part]
        if bad.any():
            k, i, a = np.argwhere(bad)[0]
            return int(k), int(first + i), int(a), float(dx[k, i, a])
    return None


def _words(jump):
    k, i, a, distance = jump
    return f"particle {i} moves {distance:.4g} along {_AXES[a]} between frames {k} and {k + 1}"
