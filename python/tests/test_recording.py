"""Gas.record and Evolver.record: frames kept as the run goes, on their trigger's grid,
without changing the trajectory; saved as files that python3-gsd and ASE read back; and
drawn inline as a notebook draws them."""
import ase.io
import gsd.hoomd
import numpy as np
import pedesis
import pytest


def gas(dynamics, extra=""):
    return pedesis.Gas(f"""
dimension = 2
dynamics = "{dynamics}"
seed = 5
[box]
length = 30.0
[[species]]
name = "Ar"
count = 60
radius = 0.5
[[species]]
name = "He"
count = 40
radius = 0.3
mass = 0.5
[initial]
velocities = "equal_speed"
speed = 1.0
{extra}
""")


def test_event_gas_frames_fall_on_the_time_grid_and_leave_the_trajectory_alone():
    recorded, plain = gas("event"), gas("event")
    movie = recorded.record(time=0.5)
    assert len(movie) == 1 and movie.times[0] == 0.0  # the state when recording began
    recorded.run(time=10.0)
    plain.run(time=10.0)
    # stopping at each grid time must not perturb the collisions that follow
    assert np.array_equal(recorded.positions, plain.positions)
    assert np.array_equal(recorded.velocities, plain.velocities)
    assert recorded.collisions == plain.collisions
    expected = np.arange(0.0, 10.0 + 1e-9, 0.5)
    assert movie.times == pytest.approx(expected, abs=1e-12)
    assert movie.positions.shape == (len(expected), 100, 2)
    # a frame is the state at its time: a gas run to t = 4.5 has the 10th frame's positions
    at = gas("event")
    at.run(time=4.5)
    assert np.allclose(movie[9]["position"], at.positions, atol=1e-9, rtol=0)
    # a later run goes on along the same grid, with no frame twice
    recorded.run(time=11.0)
    assert movie.times[-3:] == pytest.approx([10.0, 10.5, 11.0], abs=1e-12)


def test_stepped_gas_frames_every_n_steps_equal_a_run_to_that_step():
    recorded = gas("stepped", "[stepped]\ndt = 0.01")
    movie = recorded.record(steps=5)
    assert recorded.run(steps=23) == "steps"
    assert list(movie.steps) == [0, 5, 10, 15, 20]
    at = gas("stepped", "[stepped]\ndt = 0.01")
    at.run(steps=15)
    assert np.array_equal(movie[3]["position"], at.positions)
    assert np.array_equal(movie[3]["velocity"], at.velocities)


def test_event_gas_has_no_steps_to_record_on():
    with pytest.raises(pedesis.InputError, match="no steps"):
        gas("event").record(steps=10)
    with pytest.raises(pedesis.InputError, match="steps or time"):
        gas("event").record()
    with pytest.raises(pedesis.InputError, match="positive"):
        gas("event").record(time=-1.0)


def test_saved_gsd_and_xyz_are_read_back_by_gsd_and_ase(tmp_path):
    g = gas("event")
    movie = g.record(time=1.0, file=tmp_path / "live.gsd")
    g.run(time=3.0)
    # written whole when run() returns
    with gsd.hoomd.open(str(tmp_path / "live.gsd"), "rb") as t:
        assert len(t) == 4
        last = t[3]
        assert list(last.particles.types) == ["Ar", "He"]
        assert np.array_equal(last.particles.typeid, movie[3]["type"])
        assert np.array_equal(last.particles.position[:, :2],
                              movie[3]["position"].astype(np.float32))
        assert np.allclose(last.particles.diameter, 2 * movie[3]["radius"])
        assert last.configuration.box[:2] == pytest.approx([30.0, 30.0])
    movie.save(tmp_path / "copy.xyz")  # (species named as elements, for ASE's sake)
    frames = ase.io.read(str(tmp_path / "copy.xyz"), index=":")
    assert len(frames) == 4
    assert np.allclose(frames[2].get_positions()[:, :2], movie[2]["position"], atol=1e-6)
    with pytest.raises(pedesis.InputError, match=".gsd or .xyz"):
        movie.save(tmp_path / "movie.mp4")
    with pytest.raises(FileNotFoundError):
        g.record(time=1.0, file=tmp_path / "missing" / "x.gsd")


def test_stop_ends_a_recording():
    g = gas("event")
    movie = g.record(time=1.0)
    g.run(time=2.0)
    movie.stop()
    g.run(time=5.0)
    assert len(movie) == 3


@pytest.fixture
def evolver(tmp_path):
    def make():
        init = tmp_path / "init.json"
        pedesis.builder.random_init(0.3, 20, rcut=1.0, outfile=init, seed=7)
        s = pedesis.System(rcut=2.0, pad=0.5, seed=1)
        s.read_init(str(init))
        e = pedesis.Evolver(s, sort_every=7)
        e.add_force(pedesis.HarmonicForce(s, 10.0, 2.0))
        e.add_force(pedesis.SelfPropulsion(s, 1.0))
        e.add_integrator(pedesis.BrownianIntegrator(s, T=0.1, gamma=1.0))
        e.add_integrator(pedesis.BrownianRotIntegrator(s, T=0.1, gamma=1.0))
        return e
    return make


def test_evolver_records_at_multiples_and_keeps_the_callbacks_and_trajectory(evolver):
    recorded, plain = evolver(), evolver()
    movie = recorded.record(steps=10)
    called = []
    recorded.run(100, 0.01, every=25, callback=called.append)
    plain.run(100, 0.01)
    assert called == [25, 50, 75, 100]
    assert list(movie.steps) == list(range(0, 101, 10))
    assert np.array_equal(movie[-1]["position"], plain.system.positions)
    assert np.array_equal(movie[-1]["director"], plain.system.directors)
    # one step at a time: the frames fall on the same multiples
    for _ in range(20):
        recorded.evolve(0.01)
    assert list(movie.steps[-2:]) == [110, 120]
    assert movie.directors.shape == (len(movie), len(recorded.system), 2)


def test_inline_view_holds_the_frames():
    g = gas("event")
    movie = g.record(time=1.0)
    g.run(time=6.0)
    view = pedesis.show(movie)
    assert "srcdoc=" in view.html and view.bytes < 5_000_000
    assert '&quot;frames&quot;: 7' in view.html or '&quot;frames&quot;:7' in view.html
    assert g._repr_html_().startswith("<iframe")
    s_html = pedesis.Gas(
        "dimension = 2\n[box]\nlength = 10.0\n[[species]]\nname = 'a'\ncount = 5\n")
    assert s_html._repr_html_().startswith("<iframe")  # no recording: the state now


def test_a_file_is_written_when_frames_come_and_only_then(evolver, tmp_path):
    e = evolver()
    path = tmp_path / "abp.gsd"
    e.record(steps=10, file=path)
    e.evolve(0.01)  # step 1: the first frame (step 0) is written now
    with gsd.hoomd.open(str(path), "rb") as t:
        assert len(t) == 1
    path.unlink()
    for _ in range(8):  # steps 2 to 9: no new frame, so no write
        e.evolve(0.01)
    assert not path.exists()
    e.evolve(0.01)  # step 10: a frame, and the file again, whole
    with gsd.hoomd.open(str(path), "rb") as t:
        assert [int(f.configuration.step) for f in t] == [0, 10]
