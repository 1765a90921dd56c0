"""pedesis.Simulation runs any engine through the CLI's own loop: the same config gives
the same run directory byte for byte, a run cut into pieces equals the run in one go,
triggers fire exactly on their grid (also after a restart), and script writers and
callbacks see the state of those instants."""
import re

import gsd.hoomd
import numpy as np
import pedesis
import pytest

EVENT = """dimension = 2
seed = 3
[box]
lengths = [12.0, 10.0]
boundary = ["wall", "periodic"]
[[species]]
name = "small"
count = 30
radius = 0.5
[[species]]
name = "big"
count = 6
radius = 0.8
mass = 2.5
[event]
restitution = 0.9
tc = 1e-6
[run]
time = 3.0
[output]
log_interval = 0.5
snapshot_interval = 1.0
progress = false
"""

STEPPED = EVENT.replace("[event]\nrestitution = 0.9\ntc = 1e-6\n",
                        "[stepped]\ndt = 0.01\n").replace("seed = 3", "seed = 3\ndynamics = \"stepped\"")

SOFT = """dimension = 2
dynamics = "langevin"
seed = 5
[box]
length = 14.0
[[species]]
name = "A"
count = 60
radius = 0.5
[initial]
positions = "square"
[[force]]
name = "wca"
epsilon = 1.0
[[force]]
name = "self_propulsion"
alpha = 0.5
[[integrator]]
name = "langevin"
T = 0.8
gamma = 1.0
[run]
steps = 600
dt = 0.005
[output]
log_every = 50
snapshot_every = 200
checkpoint_every = 300
progress = false
"""

CONFIGS = {"event": EVENT, "stepped": STEPPED, "soft": SOFT}


def write(tmp_path, name, text):
    path = tmp_path / f"{name}.toml"
    path.write_text(text)
    return path


@pytest.mark.parametrize("engine", sorted(CONFIGS))
def test_simulation_equals_the_cli_byte_for_byte(tmp_path, run_cli, engine):
    cfg = write(tmp_path, engine, CONFIGS[engine])
    run_cli("run", cfg, "--out", tmp_path / "cli")
    sim = pedesis.Simulation.from_file(cfg, out=tmp_path / "py")
    assert sim.run() == ("steps" if engine == "soft" else "time")
    for f in ("log.csv", "checkpoint.bin", "trajectory.gsd"):
        assert (tmp_path / "cli" / f).read_bytes() == (tmp_path / "py" / f).read_bytes(), f
    header = (tmp_path / "py" / "log.csv").read_text().splitlines()[0].split(",")
    last = (tmp_path / "py" / "log.csv").read_text().splitlines()[-1].split(",")
    assert list(sim.log) == header
    assert [float(x) for x in last] == pytest.approx(list(sim.log.values()), rel=1e-9)


@pytest.mark.parametrize("engine", sorted(CONFIGS))
def test_a_run_in_pieces_equals_the_run_in_one_go(tmp_path, engine):
    cfg = write(tmp_path, engine, CONFIGS[engine])
    pedesis.Simulation.from_file(cfg, out=tmp_path / "whole").run()
    sim = pedesis.Simulation.from_file(cfg, out=tmp_path / "pieces")
    if engine == "event":
        # stops between the log times, at times no trigger asks for
        for _ in range(4):
            assert sim.run(time=0.3) is None
    else:
        for _ in range(3):
            assert sim.run(steps=77) is None
        assert sim.step == 231
    sim.run()
    for f in ("log.csv", "checkpoint.bin"):
        assert (tmp_path / "whole" / f).read_bytes() == (tmp_path / "pieces" / f).read_bytes(), f


def test_time_triggers_of_the_event_engine_are_exact(tmp_path):
    cfg = write(tmp_path, "event", EVENT)
    sim = pedesis.Simulation.from_file(cfg, out=tmp_path / "out")
    times = []
    sim.callbacks.append(pedesis.Callback(lambda: times.append(sim.time),
                                          pedesis.Periodic(time=0.25)))
    sim.writers.append(pedesis.XYZWriter(str(tmp_path / "extra.xyz"), pedesis.Periodic(time=0.75)))
    sim.run()
    # every multiple of 0.25 before the stop at t = 3, exactly (the engine stops there)
    assert times == [0.25 * k for k in range(1, 12)]
    written = [float(t) for t in re.findall(r"Time=(\S+)", (tmp_path / "extra.xyz").read_text())]
    # the start, each multiple before the stop, and the stop, as the run's own frames
    assert written == [0.0, 0.75, 1.5, 2.25, 3.0]


def gsd_clock(path):
    """(step, log/time) of each frame of a GSD file."""
    with gsd.hoomd.open(str(path), "rb") as traj:
        return [(int(f.configuration.step), float(f.log["time"][0])) for f in traj]


@pytest.mark.parametrize("engine, trigger", [("soft", pedesis.Periodic(steps=200)),
                                             ("event", pedesis.Periodic(time=1.0))])
def test_a_writer_on_the_runs_own_grid_writes_the_runs_own_frames(tmp_path, engine, trigger):
    # the run's own frames end with the stop (here a multiple of the interval); a writer
    # fired only before it: GSDWriter(..., Periodic(steps=500)) over 4000 steps wrote
    # t = 0 ... 17.5, the run's trajectory t = 0 ... 20
    cfg = write(tmp_path, engine, CONFIGS[engine])
    sim = pedesis.Simulation.from_file(cfg, out=tmp_path / "run")
    sim.writers.append(pedesis.GSDWriter(str(tmp_path / "run" / "extra.gsd"), trigger))
    sim.run()
    own = gsd_clock(tmp_path / "run" / "trajectory.gsd")
    assert len(own) == 4
    assert gsd_clock(tmp_path / "run" / "extra.gsd") == own


def test_a_writer_ends_with_the_state_where_a_script_closes_the_run(tmp_path):
    cfg = write(tmp_path, "soft", SOFT)
    sim = pedesis.Simulation.from_file(cfg, out=tmp_path / "run")
    sim.writers.append(pedesis.GSDWriter(str(tmp_path / "run" / "extra.gsd"),
                                         pedesis.Periodic(steps=100)))
    sim.run(steps=250)
    sim.close()
    steps = [s for s, _ in gsd_clock(tmp_path / "run" / "extra.gsd")]
    assert steps == [0, 100, 200, 250]
    assert steps[-1] == gsd_clock(tmp_path / "run" / "trajectory.gsd")[-1][0]
    sim = pedesis.Simulation.from_file(cfg, out=tmp_path / "again")
    sim.writers.append(pedesis.GSDWriter(str(tmp_path / "again" / "extra.gsd"),
                                         pedesis.Periodic(steps=100)))
    sim.run(steps=200)  # closed where the trigger fired: that frame once
    sim.close()
    assert [s for s, _ in gsd_clock(tmp_path / "again" / "extra.gsd")] == [0, 100, 200]


def test_step_triggers_keep_their_grid_across_a_restart(tmp_path):
    cfg = write(tmp_path, "soft", SOFT)
    half = write(tmp_path, "half", SOFT.replace("steps = 600", "steps = 300"))
    pedesis.Simulation.from_file(half, out=tmp_path / "half").run()
    sim = pedesis.Simulation.from_file(cfg, out=tmp_path / "cont",
                                       restart=tmp_path / "half" / "checkpoint.bin")
    steps = []
    sim.callbacks.append(pedesis.Callback(lambda: steps.append(sim.step), pedesis.Periodic(steps=70)))
    sim.writers.append(pedesis.GSDWriter(str(tmp_path / "extra.gsd"), pedesis.Periodic(steps=140)))
    sim.run()
    assert steps == [350, 420, 490, 560]  # multiples of 70 after step 300, before the stop
    traj = gsd.hoomd.open(str(tmp_path / "extra.gsd"), "rb")
    assert [int(f.configuration.step) for f in traj] == [300, 420, 560, 600]
    # the continued run equals the uninterrupted one (the checkpoints differ only in the
    # frame count: the half run wrote its last frame at step 300)
    whole = pedesis.Simulation.from_file(cfg, out=tmp_path / "whole")
    whole.run()
    last = lambda d: (tmp_path / d / "log.csv").read_text().splitlines()[-1]
    assert last("whole") == last("cont")
    np.testing.assert_array_equal(whole.frame()["position"], sim.frame()["position"])
    np.testing.assert_array_equal(whole.frame()["velocity"], sim.frame()["velocity"])
    # the callback saw the state of its step: the frame of the extra trajectory at 420
    # holds what frame() returned then
    sim2 = pedesis.Simulation.from_file(cfg, out=tmp_path / "again")
    sim2.run(steps=420)
    np.testing.assert_allclose(traj[1].particles.position[:, :2], sim2.frame()["position"],
                               atol=1e-5)


def test_frame_and_errors(tmp_path):
    sim = pedesis.Simulation.from_file(write(tmp_path, "event", EVENT), out=tmp_path / "out")
    f = sim.frame()
    assert f["position"].shape == (36, 2) and f["species"] == ["small", "big"]
    assert list(np.unique(f["type"])) == [0, 1]
    assert "director" not in f
    with pytest.raises(pedesis.InputError, match="no steps"):
        sim.run(steps=10)
    with pytest.raises(pedesis.InputError, match="steps or time"):
        sim.callbacks.append(pedesis.Callback(print, pedesis.Periodic(steps=1, time=1.0)))
    with pytest.raises(pedesis.InputError, match="not a GSDWriter"):
        sim.writers.append("trajectory.gsd")
    with pytest.raises(FileNotFoundError):
        pedesis.Simulation.from_file(tmp_path / "missing.toml")


def test_set_changes_the_run_and_the_record_replays_it_in_the_cli(tmp_path, run_cli):
    # a Langevin run (gamma = 1, m = 1) whose bath temperature is raised fourfold at step
    # 200 (t = 1): two relaxation times later the kinetic temperature of the 60 disks is
    # near 4 T0 (each row fluctuates by ~13 %, so 3-5 T0 over the last rows separates it
    # clearly from T0), and the CLI replaying steering.csv writes the same files byte
    # for byte (the change applies between the same two steps)
    cfg = write(tmp_path, "soft", CONFIGS["soft"])
    sim = pedesis.Simulation.from_file(cfg, out=tmp_path / "py")
    assert set(sim.steerable) == {"temperature", "alpha"}
    t0 = sim.steerable["temperature"]
    assert sim.run(steps=200) is None
    sim.set("temperature", 4 * t0)
    assert sim.steerable["temperature"] == 4 * t0
    with pytest.raises(ValueError, match="unknown parameter 'J'"):
        sim.set("J", 1.0)
    with pytest.raises(ValueError, match=r"temperature must lie in \[0, "):
        sim.set("temperature", -1.0)
    assert sim.run() == "steps"
    record = (tmp_path / "py" / "steering.csv").read_text().splitlines()
    assert record[0] == "step,time,parameter,value"
    assert record[1].startswith("200,") and record[1].endswith(",temperature," + repr(4 * t0))
    rows = (tmp_path / "py" / "log.csv").read_text().splitlines()
    header = rows[0].split(",")
    temperature = [float(r.split(",")[header.index("temperature")]) for r in rows[1:]]
    steps = [int(r.split(",")[0]) for r in rows[1:]]
    late = [t for s, t in zip(steps, temperature) if s >= 450]
    assert 3 * t0 < sum(late) / len(late) < 5 * t0
    run_cli("run", cfg, "--out", tmp_path / "cli", "--steering", tmp_path / "py" / "steering.csv")
    for f in ("log.csv", "checkpoint.bin", "trajectory.gsd", "steering.csv"):
        assert (tmp_path / "cli" / f).read_bytes() == (tmp_path / "py" / f).read_bytes(), f


def test_set_restitution_of_an_event_run_at_a_time_off_the_grid_replays(tmp_path, run_cli):
    # the event engine has no steps: a change from Python at t = 1.3 (between two log
    # rows) is recorded with its time, and the CLI replaying the record stops the run at
    # that exact time, so the log and checkpoint are the same byte for byte; the elastic
    # gas (restitution 1 here) keeps its kinetic energy exactly up to the change (energy
    # fraction 1 to the log's 10 digits) and loses some on the rows after it
    cfg = write(tmp_path, "event", CONFIGS["event"].replace("restitution = 0.9", "restitution = 1.0"))
    sim = pedesis.Simulation.from_file(cfg, out=tmp_path / "py")
    assert set(sim.steerable) == {"restitution", "wall_restitution"}  # a walled box
    assert sim.run(time=1.3) is None
    sim.set("restitution", 0.5)
    with pytest.raises(ValueError, match=r"restitution must lie in \[0, 1\]"):
        sim.set("restitution", 1.5)
    assert sim.run() == "time"
    record = (tmp_path / "py" / "steering.csv").read_text().splitlines()
    assert len(record) == 2 and record[1].split(",")[1:] == ["1.3", "restitution", "0.5"]
    rows = (tmp_path / "py" / "log.csv").read_text().splitlines()
    header = rows[0].split(",")
    times = [float(r.split(",")[0]) for r in rows[1:]]
    energy = [float(r.split(",")[header.index("energy_fraction")]) for r in rows[1:]]
    assert all(e == 1.0 for t, e in zip(times, energy) if t < 1.3)
    assert all(e < 1.0 for t, e in zip(times, energy) if t > 1.3)
    run_cli("run", cfg, "--out", tmp_path / "cli", "--steering", tmp_path / "py" / "steering.csv")
    for f in ("log.csv", "checkpoint.bin", "steering.csv"):
        assert (tmp_path / "cli" / f).read_bytes() == (tmp_path / "py" / f).read_bytes(), f


@pytest.mark.parametrize("kwargs, message", [
    ({}, "give steps or time, one of them"),
    ({"steps": 1, "time": 1.0}, "give steps or time, one of them"),
    ({"steps": -5}, "steps must be positive, not -5"),
    ({"steps": 0}, "steps must be positive, not 0"),
    ({"steps": 2.5}, r"steps must be a whole number of time steps \(an int\), not 2.5"),
    ({"steps": True}, r"steps must be a whole number"),
    ({"time": 0.0}, "time must be a positive finite number, not 0.0"),
    ({"time": float("inf")}, "time must be a positive finite number, not inf"),
    ({"time": "1"}, "time must be a number of time units, not '1'"),
])
def test_a_periodic_trigger_is_refused_when_made(kwargs, message):
    # (Periodic() and Periodic(steps=1, time=1.0) were made and refused only when
    # appended; steps=-5 or 2.5 reached pybind11 as "incompatible function arguments")
    with pytest.raises(pedesis.InputError, match=f"^Periodic: {message}"):
        pedesis.Periodic(**kwargs)


def test_periodic_takes_numpy_and_int_values():
    assert pedesis.Periodic(steps=np.int64(3)).steps == 3
    assert type(pedesis.Periodic(steps=np.int64(3)).steps) is int
    assert pedesis.Periodic(time=2).time == 2.0


@pytest.mark.parametrize("kwargs, message", [
    ({"steps": -1}, "steps must be >= 0, not -1"),
    ({"steps": 2.5}, r"steps must be a whole number of time steps \(an int\), not 2.5"),
    ({"time": -1.0}, "time must be a finite number >= 0, not -1.0"),
    ({"time": float("nan")}, "time must be a finite number >= 0, not nan"),
    ({"steps": 10, "time": 1.0}, "give steps or time, not both"),
])
def test_simulation_run_refuses_bad_arguments_by_name(tmp_path, kwargs, message):
    sim = pedesis.Simulation.from_file(write(tmp_path, "soft", SOFT), out=tmp_path / "out")
    with pytest.raises(pedesis.InputError, match=f"^Simulation.run: {message}"):
        sim.run(**kwargs)
    assert sim.step == 0  # nothing ran
