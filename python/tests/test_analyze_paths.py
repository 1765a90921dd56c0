"""pedesis.analyze never returns the MSD of wrapped positions as physics: unwrapped() of
frames without image counts, and msd() of positions that jump across the box, raise with
the way out; read_frames of a missing path names what it takes."""
import gsd.hoomd
import numpy as np
import pedesis.analyze as pa
import pytest

EVENT = """dimension = 2
seed = 2
[box]
length = 8.0
[[species]]
name = "A"
count = 20
radius = 0.3
[run]
time = 4.0
[output]
snapshot_interval = 0.05
formats = ["gsd"]
progress = false
"""


def wrapped_walk(L=5.0, T=200, N=30, seed=1):
    """A random walk (T, N, 2) that crosses the edges of an L x L box, and its wrapped
    copy."""
    rng = np.random.default_rng(seed)
    x = rng.uniform(0, L, size=(1, N, 2)) + np.cumsum(rng.normal(scale=0.3, size=(T, N, 2)), axis=0)
    return x, np.mod(x, L)


def test_unwrapped_of_an_event_run_follows_the_paths_as_unwrap_does(tmp_path, run_cli):
    # the event engine counts box crossings (it wrote image counts of 0 once, and
    # positions + 0 * L passed for unwrapped, with an MSD levelling off near L^2/6)
    (tmp_path / "ev.toml").write_text(EVENT)
    run_cli("run", tmp_path / "ev.toml", "--out", tmp_path / "ev")
    traj = pa.read_frames(tmp_path / "ev")
    assert traj.images.any()
    with pytest.raises(ValueError, match="look like wrapped positions"):
        pa.msd(traj.positions)
    paths = pa.unwrap(traj.positions, traj.box)
    # continuous (speeds ~1, frames 0.05 apart), the stored positions modulo L, and far
    # past the box: the gas crossed its edges
    assert np.abs(np.diff(paths, axis=0)).max() < 1.0
    np.testing.assert_allclose(traj.box.minimum_image(paths - traj.positions), 0.0, atol=1e-4)
    assert np.ptp(paths) > 8.0
    assert pa.msd(paths, traj.box) == pytest.approx(pa.msd_direct(paths), rel=1e-9, abs=1e-9)
    # the engine's own counts give the same paths (float32 positions in the file)
    unwrapped = traj.unwrapped()
    np.testing.assert_allclose(unwrapped - unwrapped[0], paths - paths[0], atol=1e-4)
    # and the log's msd column is their mean squared displacement from the first frame
    log = np.genfromtxt(tmp_path / "ev" / "log.csv", delimiter=",", names=True)
    last = float(np.sum((unwrapped[-1] - unwrapped[0]) ** 2, axis=-1).mean())
    assert log["msd"][-1] == pytest.approx(last, rel=1e-5)


def test_unwrapped_of_frames_whose_images_miss_a_crossing_refuses(tmp_path):
    # a bare GSD file (no config.toml beside it): a particle jumps across the box between
    # two frames while its image count stays 0
    path = tmp_path / "frames.gsd"
    with gsd.hoomd.open(str(path), "wb") as f:
        for k, x in enumerate((4.9, 0.1)):
            frame = gsd.hoomd.Snapshot()
            frame.configuration.step = k
            frame.configuration.box = [5.0, 5.0, 0.0, 0, 0, 0]
            frame.configuration.dimensions = 2
            frame.particles.N = 2
            frame.particles.position = np.array([[x, 1.0, 0.0], [2.0, 2.0, 0.0]], np.float32)
            f.append(frame)
    traj = pa.read_frames(path)
    with pytest.raises(ValueError, match="particle 0 moves 4.8 along x between frames 0 and 1"):
        traj.unwrapped()
    assert traj.images_tracked is None  # (nothing says: the data did)


def test_msd_of_wrapped_positions_raises_and_of_their_unwrapping_is_right():
    paths, wrapped = wrapped_walk()
    box = pa.Box((5.0, 5.0))
    with pytest.raises(ValueError, match=r"msd: particle \d+ moves .* more than half the extent"):
        pa.msd(wrapped)
    with pytest.raises(ValueError, match="more than half the box length 5"):
        pa.msd(wrapped, box)
    with pytest.raises(ValueError, match="self_intermediate_scattering"):
        pa.self_intermediate_scattering(wrapped, q=1.0)
    expected = pa.msd_direct(paths)
    assert pa.msd(pa.unwrap(wrapped, box), box) == pytest.approx(expected, rel=1e-9, abs=1e-9)
    assert pa.msd(paths) == pytest.approx(expected, rel=1e-9, abs=1e-9)
    # walls: nothing wraps, nothing to check
    walled = pa.Box((5.0, 5.0), (False, False))
    assert pa.msd(wrapped, walled) == pytest.approx(pa.msd_direct(wrapped), rel=1e-9)


def test_read_frames_of_a_missing_path_names_what_it_takes(tmp_path):
    # gsd's own error was "OSError: [Errno 9] Bad file descriptor"
    with pytest.raises(FileNotFoundError, match="nope: no such run directory or file .*trajectory.gsd"):
        pa.read_frames(str(tmp_path / "nope"))
    (tmp_path / "notes.gsd").write_text("not a GSD file")
    with pytest.raises(ValueError, match="notes.gsd: cannot be read as GSD"):
        pa.read_frames(tmp_path / "notes.gsd")
