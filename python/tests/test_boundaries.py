"""A walled box read back is walled (issue 49): the boundaries of a run or of a Gas's
recording survive every format pedesis writes and reads. GSD stores them as the chunk
log/pedesis/periodic (python3-gsd: frame.log["pedesis/periodic"]), extended XYZ as
the standard pbc key (ASE: atoms.pbc); pedesis' own readers (read_frames, [initial]
file) take them from either. Gas.box is a pedesis.Box with the per-axis flags, which
still reads as the list of lengths it was."""
import shutil

import ase.io
import gsd.hoomd
import numpy as np
import pedesis
import pedesis.analyze as pa
import pytest

READ = "r" if hasattr(gsd.hoomd, "Frame") else "rb"

# walls on x, periodic along y: species named as elements, so that ASE reads the XYZ as is
WALLED = """dimension = 2
seed = 7
[box]
lengths = [14.0, 12.0]
boundary = ["wall", "periodic"]
[[species]]
name = "Ar"
count = 30
radius = 0.5
[initial]
velocities = "equal_speed"
"""

RUN = """
[run]
time = 1.0
[output]
snapshot_interval = 0.5
progress = false
formats = ["gsd", "xyz"]
"""


def gsd_periodic(path):
    """log/pedesis/periodic of every frame, as python3-gsd reads it."""
    with gsd.hoomd.open(str(path), READ) as t:
        return [np.asarray(f.log["pedesis/periodic"]).tolist() for f in t]


def ase_pbc(path):
    return [a.pbc.tolist() for a in ase.io.read(str(path), index=":")]


@pytest.fixture
def walled_run(tmp_path, run_cli):
    (tmp_path / "walled.toml").write_text(WALLED + RUN)
    run_cli("run", "walled.toml", "--out", "out", cwd=tmp_path)
    return tmp_path / "out"


def test_walled_run_files_read_back_walled(walled_run, tmp_path):
    assert gsd_periodic(walled_run / "trajectory.gsd") == [[0, 1]] * 3
    assert ase_pbc(walled_run / "trajectory.xyz") == [[False, True, False]] * 3
    # read_frames of the file alone, with no config.toml beside it to say so
    shutil.copy(walled_run / "trajectory.gsd", tmp_path / "alone.gsd")
    traj = pa.read_frames(str(tmp_path / "alone.gsd"))
    assert traj.box.periodic == (False, True)
    assert traj.box == pedesis.Box([14.0, 12.0], [False, True])


@pytest.mark.parametrize("name", ["trajectory.gsd", "trajectory.xyz"])
def test_initial_file_of_a_walled_run_keeps_its_walls(walled_run, tmp_path, pedesis_bin, name):
    import subprocess

    def start(boundary):
        config = WALLED.replace('boundary = ["wall", "periodic"]', f"boundary = {boundary}")
        config = config.replace("count = 30\n", "").replace('velocities = "equal_speed"',
                                                            f'file = "out/{name}"')
        (tmp_path / "again.toml").write_text(config + RUN)
        return subprocess.run([pedesis_bin, "run", "again.toml", "--out", "again"],
                              capture_output=True, text=True, cwd=tmp_path)

    # a periodic [box] would let the particles of a walled run pass where its walls were
    r = start('"periodic"')
    assert r.returncode == 2, r.stderr
    assert f"out/{name}" in r.stderr and "boundary" in r.stderr and "wall" in r.stderr, r.stderr
    r = start('["wall", "periodic"]')
    assert r.returncode == 0, r.stderr
    assert gsd_periodic(tmp_path / "again" / "trajectory.gsd")[0] == [0, 1]


def test_gas_box_carries_its_walls_and_reads_as_the_old_list():
    gas = pedesis.Gas(WALLED)
    box = gas.box
    assert isinstance(box, pedesis.Box)
    assert box.periodic == (False, True) and box.boundary == ("wall", "periodic")
    # what scripts did with the list of lengths
    assert box == [14.0, 12.0] and box != [14.0, 13.0]
    assert len(box) == 2 and box[0] == 14.0 and box[-1] == 12.0 and list(box) == [14.0, 12.0]
    assert np.array_equal(np.array(box), [14.0, 12.0]) and np.prod(box) == 168.0
    assert gas.frame()["box"].periodic == (False, True)
    # pedesis.analyze takes it as its box, walls and all
    assert pa.Box(box).periodic == (False, True)


def test_walled_gas_recording_saved_reads_back_walled(tmp_path):
    gas = pedesis.Gas(WALLED)
    movie = gas.record(time=0.5)
    gas.run(time=1.0)
    assert all(f["box"].periodic == (False, True) for f in movie)
    movie.save(tmp_path / "gas.gsd")
    movie.save(tmp_path / "gas.xyz")
    assert gsd_periodic(tmp_path / "gas.gsd") == [[0, 1]] * 3
    assert ase_pbc(tmp_path / "gas.xyz") == [[False, True, False]] * 3
    assert pa.read_frames(str(tmp_path / "gas.gsd")).box.periodic == (False, True)


def test_simulation_frame_box_carries_the_walls(tmp_path):
    (tmp_path / "walled.toml").write_text(WALLED + RUN)
    sim = pedesis.Simulation.from_file(str(tmp_path / "walled.toml"), out=str(tmp_path / "o"),
                                       quiet=True)
    assert sim.frame()["box"].periodic == (False, True)


@pytest.mark.parametrize("given", ["../my/binary.toml", "{path}"])
def test_gas_given_a_path_points_at_from_file(tmp_path, given):
    config = tmp_path / "binary.toml"
    config.write_text(WALLED)
    text = given.format(path=config)
    with pytest.raises(pedesis.InputError) as e:
        pedesis.Gas(text)
    assert str(e.value) == (f"Gas(...) takes the config's text; to read a file use "
                            f"pedesis.Gas.from_file('{text}')")
    with pytest.raises(pedesis.InputError, match="Gas.from_file"):
        pedesis.Gas(config)  # a pathlib.Path
    assert pedesis.Gas.from_file(str(config)).box.periodic == (False, True)


def test_system_box_is_a_box_and_refuses_a_walled_start(walled_run, tmp_path):
    # the soft engine's System: its box is a pedesis.Box too, and a walled file is
    # refused as `pedesis run` refuses walls for the soft engines (it used to be read
    # as a periodic box, the walls lost)
    with pytest.raises(pedesis.InputError, match="wall on axis 0.*periodic boxes only"):
        pedesis.System(rcut=1.5).read_init(str(walled_run / "trajectory.gsd"))
    init = tmp_path / "init.json"
    pedesis.builder.random_init(0.2, 12, rcut=1.0, outfile=init, seed=3)
    s = pedesis.System(rcut=1.5)
    s.read_init(str(init))
    assert isinstance(s.box, pedesis.Box)
    assert s.box == [12.0, 12.0] and s.box.periodic == (True, True)
