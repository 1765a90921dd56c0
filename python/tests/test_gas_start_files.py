"""Starts read from GSD (HOOMD-blue's layout, written by the gsd package) and extended XYZ
files by the Python module: System.read_init, a Gas's and a Simulation's [initial] file
(issue 28, item 6). Each gives the state of the file, in HOOMD-blue's conventions:
the box centred at the origin, radius = diameter / 2, the director the x axis turned
by the orientation quaternion."""
import numpy as np
import pytest

import gsd.hoomd
import pedesis

FRAME = getattr(gsd.hoomd, "Frame", None) or gsd.hoomd.Snapshot  # (gsd < 2.8: Snapshot)
WRITE = "w" if hasattr(gsd.hoomd, "Frame") else "wb"


def hoomd_gsd(path, frames=2, n=36, L=18.0, seed=3):
    """A 2D HOOMD-style trajectory: types "big" and "small", diameters 1.4 and 0.6, masses
    2 and 1, velocities and orientations (turns about z); frame k moves every particle."""
    rng = np.random.default_rng(seed)
    out = []
    with gsd.hoomd.open(str(path), WRITE) as t:
        for k in range(frames):
            f = FRAME()
            f.configuration.box = [L, L, 0, 0, 0, 0]
            f.configuration.dimensions = 2
            f.particles.N = n
            f.particles.types = ["big", "small"]
            f.particles.typeid = np.array([i % 2 for i in range(n)], dtype=np.uint32)
            grid = np.array([[-L / 2 + 1.5 + 2.5 * (i % 6), -L / 2 + 1.5 + 2.5 * (i // 6), 0.0]
                             for i in range(n)])
            grid[:, :2] += rng.uniform(-0.2, 0.2, (n, 2)) + 0.1 * k
            f.particles.position = grid.astype(np.float32)
            f.particles.diameter = np.where(f.particles.typeid == 0, 1.4, 0.6).astype(np.float32)
            f.particles.mass = np.where(f.particles.typeid == 0, 2.0, 1.0).astype(np.float32)
            v = rng.normal(size=(n, 3))
            v[:, 2] = 0
            f.particles.velocity = v.astype(np.float32)
            th = rng.uniform(-np.pi, np.pi, n)
            f.particles.orientation = np.stack(
                [np.cos(th / 2), 0 * th, 0 * th, np.sin(th / 2)], axis=1).astype(np.float32)
            t.append(f)
            out.append((grid[:, :2].astype(np.float32).astype(float),
                        v[:, :2].astype(np.float32).astype(float), th))
    return out


def test_system_reads_a_hoomd_frame(tmp_path):
    frames = hoomd_gsd(tmp_path / "start.gsd")
    for frame, (r, v, th) in [(None, frames[1]), (0, frames[0]), (-1, frames[1])]:
        s = pedesis.System(rcut=2.0, pad=0.3)
        if frame is None:
            s.read_init(str(tmp_path / "start.gsd"))  # the last frame
        else:
            s.read_init(str(tmp_path / "start.gsd"), frame=frame)
        assert s.dim == 2 and s.N == 36  # the dimension from configuration/dimensions
        assert np.allclose(s.box, [18.0, 18.0])
        assert [sp["name"] for sp in s.species] == ["big", "small"]
        assert [sp["radius"] for sp in s.species] == pytest.approx([0.7, 0.3], rel=1e-7)
        assert [sp["mass"] for sp in s.species] == [2.0, 1.0]
        assert np.array_equal(s.positions, r)
        assert np.array_equal(s.velocities, v)
        assert np.array_equal(s.types, [i % 2 for i in range(36)])
        assert np.allclose(s.directors, np.stack([np.cos(th), np.sin(th)], axis=1), atol=1e-6)


def test_simulation_and_gas_start_from_the_file(tmp_path):
    r, v, _ = hoomd_gsd(tmp_path / "start.gsd")[1]
    (tmp_path / "soft.toml").write_text("""
dimension = 2
dynamics = "nve"
[initial]
file = "start.gsd"
[[force]]
name = "wca"
epsilon = 1.0
[[integrator]]
name = "nve"
[run]
steps = 10
dt = 0.0001
[output]
progress = false
formats = []
""")
    sim = pedesis.Simulation.from_file(str(tmp_path / "soft.toml"), out=str(tmp_path / "run"))
    f = sim.frame()
    assert np.array_equal(f["position"], r) and np.array_equal(f["velocity"], v)
    assert np.allclose(f["radius"], np.where(np.arange(36) % 2 == 0, 0.7, 0.3), rtol=1e-7)
    sim.close()
    gas = pedesis.Gas(f"""
dimension = 2
[box]
length = 18.0
[[species]]
name = "small"
radius = 0.3
[[species]]
name = "big"
radius = 0.7
mass = 2.0
[initial]
file = "{tmp_path / 'start.gsd'}"
frame = 1
""")
    assert np.array_equal(gas.positions, r) and np.array_equal(gas.velocities, v)
    # matched by name: "big" is the config's second species
    assert np.array_equal(gas.types, [1 - i % 2 for i in range(36)])
    assert np.allclose(gas.radii, np.where(np.arange(36) % 2 == 0, 0.7, 0.3))


def test_a_frame_that_is_not_there_is_named(tmp_path):
    hoomd_gsd(tmp_path / "start.gsd")
    s = pedesis.System()
    with pytest.raises(pedesis.InputError, match=r"frame = 5, but the file has 2 frame\(s\)"):
        s.read_init(str(tmp_path / "start.gsd"), frame=5)
    (tmp_path / "start.json").write_text(
        '{"system": {"box": {"Lx": 5, "Ly": 5}, "particles": [{"id": 0, "r": [0, 0]}]}}')
    with pytest.raises(pedesis.InputError, match="is for GSD and XYZ files"):
        pedesis.System().read_init(str(tmp_path / "start.json"), frame=0)


def test_system_reads_an_extended_xyz_frame(tmp_path):
    # OVITO/ASE style: no Origin (the cell's corner at 0), 3D
    (tmp_path / "start.xyz").write_text(
        '3\nLattice="6 0 0 0 8 0 0 0 10" Properties=species:S:1:pos:R:3:velo:R:3 pbc="T T T"\n'
        "O 1 1 1 0.5 0 0\nH 2 2 2 0 0.5 0\nO 3 3 3 0 0 0.5\n")
    s = pedesis.System(rcut=1.0, pad=0.2)
    s.read_init(str(tmp_path / "start.xyz"))
    assert s.dim == 3
    assert [sp["name"] for sp in s.species] == ["O", "H"]
    assert np.array_equal(s.positions, [[-2, -3, -4], [-1, -2, -3], [0, -1, -2]])
    assert np.array_equal(s.velocities, 0.5 * np.eye(3))
    assert np.array_equal(s.types, [0, 1, 0])
