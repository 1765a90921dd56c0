"""Every error path raises the Python exception a user expects, with the C++ message:
ValueError (pedesis.InputError) for bad parameters and malformed files,
FileNotFoundError for missing files, RuntimeError (pedesis.RunError) for a run that
cannot go on, KeyboardInterrupt for Ctrl-C; never a crash."""
import os
import signal
import threading

import numpy as np
import pedesis
import pytest


def test_exception_classes():
    assert issubclass(pedesis.InputError, ValueError)
    assert issubclass(pedesis.RunError, RuntimeError)


def test_missing_files(tmp_path, system):
    with pytest.raises(FileNotFoundError, match="no such file"):
        pedesis.System().read_init(str(tmp_path / "absent.json"))
    with pytest.raises(FileNotFoundError):
        pedesis.Gas.from_file(str(tmp_path / "absent.toml"))
    with pytest.raises(FileNotFoundError, match="no such directory"):
        pedesis.Dump(system).dump_vtp(str(tmp_path / "no" / "dir" / "a.vtp"))
    with pytest.raises(FileNotFoundError):
        pedesis.builder.random_init(0.3, 10, outfile=tmp_path / "no" / "init.json")


def test_malformed_initial_file_names_the_file_and_place(tmp_path):
    bad = tmp_path / "bad.json"
    bad.write_text('{"system": {"box": {"Lx": 10, "Ly": 10}, "particles": [')
    with pytest.raises(ValueError, match="bad.json"):
        pedesis.System().read_init(str(bad))
    nan = tmp_path / "nan.json"
    nan.write_text('{"system": {"box": {"Lx": 10, "Ly": 10}, "particles": '
                   '[{"id": 0, "type": 0, "r": [0.0, "x"]}]}}')
    with pytest.raises(pedesis.InputError, match="particle 0"):
        pedesis.System().read_init(str(nan))


@pytest.mark.parametrize("make, words", [
    (lambda s: pedesis.HarmonicForce(s, -1.0), "k: must be >= 0"),
    (lambda s: pedesis.HarmonicForce(s, float("nan")), "k: must be a finite number"),
    (lambda s: pedesis.HarmonicForce(s, 1.0, b=2.0), "no parameter 'b'"),
    (lambda s: pedesis.HarmonicForce(s, 1.0, 2.0, 3.0), "at most 2 parameters"),
    (lambda s: pedesis.HarmonicForce(s), "needs k"),
    (lambda s: pedesis.HarmonicForce(s, "stiff"), "must be a number"),
    (lambda s: pedesis.BrownianIntegrator(s, T=0.0, gamma=0.0), "gamma: must be positive"),
    (lambda s: pedesis.SelfPropulsion(s, {"B": 1.0}), "species 'A'"),
    (lambda s: pedesis.PolarAlign(s, {"A": 1.0}, 2.0), "one number for all species"),
    (lambda s: pedesis.HarmonicForce("not a system", 1.0), "first argument"),
])
def test_bad_parameters_are_value_errors_naming_the_parameter(system, make, words):
    with pytest.raises(ValueError, match=words):
        make(system)


def test_bad_system_and_evolver_use(tmp_path, system):
    with pytest.raises(ValueError, match="pad"):
        pedesis.System(pad=-1.0)
    with pytest.raises(ValueError, match="dim"):
        pedesis.System(dim=4)
    with pytest.raises(ValueError, match="read_init"):
        pedesis.System().positions
    with pytest.raises(ValueError, match="has particles already"):
        system.read_init(str(tmp_path / "init.json"))
    e = pedesis.Evolver(system)
    with pytest.raises(ValueError, match="torque; use Evolver.add_torque"):
        e.add_force(pedesis.PolarAlign(system, 1.0, 2.0))
    with pytest.raises(ValueError, match="dt"):
        e.evolve(-0.1)
    with pytest.raises(ValueError, match="every"):
        e.run(10, 0.01, callback=print)
    with pytest.raises(ValueError, match="random_init: phi"):
        pedesis.builder.random_init(-1, 10, outfile=tmp_path / "x.json")
    with pytest.raises(ValueError, match="too dense|impossible"):
        pedesis.builder.random_init(2.0, 10, rcut=1.0, outfile=tmp_path / "x.json")
    assert not (tmp_path / "x.json").exists()


def test_a_box_too_small_for_the_cutoff(system):
    e = pedesis.Evolver(system)
    e.add_force(pedesis.HarmonicForce(system, 1.0, 11.0))
    e.add_integrator(pedesis.BrownianIntegrator(system, T=0.0, gamma=1.0))
    with pytest.raises(ValueError, match="box too small"):
        e.evolve(0.01)


def test_a_blow_up_is_a_run_error_naming_the_particle(system):
    e = pedesis.Evolver(system)
    e.add_force(pedesis.HarmonicForce(system, 1e6, 2.0))
    e.add_integrator(pedesis.BrownianIntegrator(system, T=0.0, gamma=1.0))
    with pytest.raises(pedesis.RunError, match="particle"):
        e.run(100, 0.1)
    assert np.array_equal(system.tags, np.arange(len(system)))  # still in tag order


def test_nan_written_into_an_array(system):
    e = pedesis.Evolver(system)
    e.add_integrator(pedesis.BrownianIntegrator(system, T=0.0, gamma=1.0))
    system.positions[5, 1] = np.nan
    with pytest.raises(pedesis.RunError, match="particle 5"):
        e.evolve(0.01)


def test_an_exception_in_a_callback_propagates(system):
    e = pedesis.Evolver(system)
    e.add_integrator(pedesis.BrownianIntegrator(system, T=0.1, gamma=1.0))

    def fail(step):
        raise ZeroDivisionError(f"at {step}")

    with pytest.raises(ZeroDivisionError, match="at 20"):
        e.run(100, 0.01, every=20, callback=fail)
    assert system.step == 20


def test_ctrl_c_stops_a_long_run_at_a_step(system):
    e = pedesis.Evolver(system)
    e.add_force(pedesis.HarmonicForce(system, 10.0, 2.0))
    e.add_integrator(pedesis.BrownianIntegrator(system, T=0.1, gamma=1.0))
    timer = threading.Timer(0.3, lambda: os.kill(os.getpid(), signal.SIGINT))
    timer.start()
    try:
        with pytest.raises(KeyboardInterrupt):
            e.run(10**9, 1e-4)  # hours if not interrupted
    finally:
        timer.cancel()
    assert 0 < system.step < 10**9
    assert np.array_equal(system.tags, np.arange(len(system)))
    before = system.step
    e.run(5, 1e-4)  # the system is usable afterwards
    assert system.step == before + 5


def interrupted_after(seconds, call):
    """Sends SIGINT to this process after `seconds` while `call` runs; it must raise
    KeyboardInterrupt within a second of the signal."""
    import time
    sent = []
    timer = threading.Timer(seconds, lambda: (sent.append(time.monotonic()),
                                              os.kill(os.getpid(), signal.SIGINT)))
    timer.start()
    try:
        with pytest.raises(KeyboardInterrupt):
            call()
        assert time.monotonic() - sent[0] < 1.0
    finally:
        timer.cancel()


def test_ctrl_c_stops_an_event_gas_between_events():
    # a time limit hours away: only the signal ends this run
    gas = pedesis.Gas('dimension = 2\nseed = 4\n[box]\nlength = 30.0\n[[species]]\n'
                      'name = "a"\ncount = 200\nradius = 0.5\n')
    interrupted_after(0.3, lambda: gas.run(time=1e12))
    assert gas.time > 0 and gas.collisions > 0
    t = gas.time
    assert gas.run(time=t + 0.5) == "time"  # usable afterwards
    assert gas.time == pytest.approx(t + 0.5)


def test_ctrl_c_stops_a_simulation_between_triggers(tmp_path):
    # one log row at the start and none due for 10^9 steps: the stop comes from the engine
    cfg = tmp_path / "long.toml"
    cfg.write_text('dimension = 2\ndynamics = "brownian"\nseed = 1\n[box]\nlength = 20.0\n'
                   '[[species]]\nname = "A"\ncount = 40\nradius = 1.0\n[initial]\n'
                   'positions = "random"\n[[force]]\nname = "harmonic"\nk = 10.0\n'
                   '[[integrator]]\nname = "brownian"\nT = 0.1\ngamma = 1.0\n'
                   '[run]\nsteps = 1000000000\ndt = 0.001\n[output]\nprogress = false\n'
                   'log_every = 1000000000\nformats = ["gsd"]\n')
    sim = pedesis.Simulation.from_file(cfg, out=tmp_path / "out")
    interrupted_after(0.5, sim.run)
    step = sim.step
    assert 0 < step < 10**9
    assert sim.run(steps=10) is None  # goes on from there
    assert sim.step == step + 10
    sim.close()
    import json
    summary = json.loads((tmp_path / "out" / "summary.json").read_text())
    assert summary["stopped_by"] == "script"
    assert summary["final"]["step"] == step + 10
    assert not list((tmp_path / "out").glob("*.part"))


def test_gas_config_errors_name_the_line(tmp_path):
    with pytest.raises(ValueError, match=r"<Gas config>:\d+:\d+"):
        pedesis.Gas("dimension = 2\n[box\n")
    with pytest.raises(ValueError, match="dynamics"):
        pedesis.Gas('dynamics = "brownian"\n[box]\nlength = 10.0\n'
                    '[[species]]\nname = "a"\ncount = 3\n')
    gas = ('dimension = 2\ndynamics = "stepped"\n[box]\nlength = 50.0\nboundary = "wall"\n'
           '[[species]]\nname = "a"\ncount = 50\nradius = 0.5\n[initial]\nvelocities = '
           '"equal_speed"\nspeed = 10.0\n[stepped]\ndt = 1.0\n')
    with pytest.raises(ValueError, match="use dt = .* or less"):
        pedesis.Gas(gas)
    g = pedesis.Gas(gas.replace("dt = 1.0", "dt = 0.01"))
    with pytest.raises(ValueError, match="give time"):
        g.run()
    with pytest.raises(ValueError, match="collisions_per_particle"):
        g.run(collisions_per_particle=float("nan"))
