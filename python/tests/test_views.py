"""The arrays of a System view the C++ memory: no copy, the same buffer on every access,
in tag order, and writes go both ways."""
import numpy as np
import pedesis
import pytest


@pytest.fixture
def system(tmp_path):
    init = tmp_path / "init.json"
    pedesis.builder.random_init(0.3, 20, rcut=1.0, outfile=init, seed=7)
    s = pedesis.System(rcut=2.0, pad=0.5, seed=1)
    s.read_init(str(init))
    e = pedesis.Evolver(s, sort_every=5)  # sorts often, so that tag order is exercised
    e.add_force(pedesis.HarmonicForce(s, 10.0, 2.0))
    e.add_force(pedesis.SelfPropulsion(s, 1.0))
    # no translational noise: tests below compare positions and forces after tiny steps
    e.add_integrator(pedesis.BrownianIntegrator(s, T=0.0, gamma=1.0))
    e.add_integrator(pedesis.BrownianRotIntegrator(s, T=0.1, gamma=1.0))
    return s, e


def address(a):
    return a.__array_interface__["data"][0]


NAMES = ["positions", "velocities", "directors", "forces", "torques", "images", "tags", "types"]


@pytest.mark.parametrize("name", NAMES)
def test_views_are_zero_copy_and_stable(system, name):
    s, e = system
    a = getattr(s, name)
    assert not a.flags.owndata  # a view of memory numpy does not own
    e.run(20, 0.01)
    b = getattr(s, name)
    assert address(a) == address(b)
    assert np.shares_memory(a, b)


def test_shapes_and_tag_order(system):
    s, e = system
    n = len(s)
    assert s.positions.shape == (n, 2) and s.torques.shape == (n,)
    for _ in range(3):
        e.run(7, 0.01)  # ends between sorts: storage is sorted, views must not be
        assert np.array_equal(s.tags, np.arange(n))


def test_cpp_changes_show_in_a_view_taken_before(system):
    s, e = system
    r = s.positions
    before = r.copy()
    e.evolve(0.01)
    assert not np.array_equal(r, before)
    assert np.array_equal(r, s.positions)


def test_python_writes_reach_the_simulation(system):
    s, e = system
    s.velocities[:] = 0.0  # overdamped: velocities are not touched by the integrator
    # a particle moved across the box: the neighbour list must notice by itself
    s.positions[0] = [9.5, 9.5]
    s.directors[0] = [0.0, 1.0]
    # a step so short that the positions after it are those the forces were computed at
    # (moves of ~1e-8 change the harmonic forces by ~1e-7)
    e.evolve(1e-9)
    assert np.allclose(s.positions[0], [9.5, 9.5], atol=1e-3)
    # the forces of step 1 were computed at the written position: particle 0 gets
    # alpha n0 = (0, 1) plus its harmonic force from its new neighbours only
    r = s.positions
    d = r - r[0]
    d -= 20 * np.round(d / 20)
    dist = np.hypot(d[:, 0], d[:, 1])
    near = (dist < 2.0) & (dist > 0)
    expected = np.array([0.0, 1.0]) - (10.0 * (2.0 - dist[near]) / dist[near])[:, None].T @ d[near]
    assert np.allclose(s.forces[0], expected.ravel(), rtol=1e-6, atol=1e-6)


def test_a_position_written_outside_the_box_is_wrapped_with_its_image(system):
    s, e = system
    x0 = s.positions[3].copy()
    s.positions[3, 0] = x0[0] + 20.0  # one box length to the right
    e.evolve(1e-9)
    assert abs(s.positions[3, 0] - x0[0]) < 1e-6
    assert s.images[3, 0] == 1


def test_writing_in_a_callback(system):
    s, e = system

    def freeze_first(step):
        s.positions[0] = [0.0, 0.0]

    e.run(30, 0.01, every=10, callback=freeze_first)
    assert s.step == 30
    # after the last callback one more step would move it; the callback ran at step 30
    assert np.allclose(s.positions[0], [0.0, 0.0])


def test_views_keep_the_system_alive(tmp_path):
    init = tmp_path / "init.json"
    pedesis.builder.random_init(0.3, 10, outfile=init)
    s = pedesis.System()
    s.read_init(str(init))
    r = s.positions
    expected = r.copy()
    del s
    assert np.array_equal(r, expected)


def test_paths_may_be_pathlib_objects(tmp_path):
    init = pedesis.builder.random_init(0.3, 10, outfile=tmp_path / "init.json")
    s = pedesis.System()
    s.read_init(init)
    pedesis.Dump(s).dump_vtp(tmp_path / "a.vtp")
    pedesis.Dump(s).dump_json(tmp_path / "a.json")
    t = pedesis.System()
    t.read_init(tmp_path / "a.json")
    assert np.array_equal(t.positions, s.positions)
    # read_init normalises directors, which may move the last bit
    assert np.allclose(t.directors, s.directors, rtol=0, atol=1e-15)
    assert (tmp_path / "a.vtp").read_text().startswith("<?xml")
