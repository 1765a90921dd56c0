"""The tutorial API (System, Evolver, the terms) refuses what a config refuses, by the
same rule and with the same words (issue 49): each case below is a config that
`pedesis run` refuses (exit 2) and the script that builds the same evolver, which must
raise pedesis.InputError naming the same fault. Before, a script could add two position
integrators (both moved the particles: twice the step), a torque that turned nothing,
or step with no integrator at all (nothing moved, silently). Assignments to a term's
parameters raise instead of changing nothing."""
import subprocess

import numpy as np
import pedesis
import pytest


def config(init, dynamics, blocks):
    return (f'dimension = 2\ndynamics = "{dynamics}"\n[initial]\nfile = "{init}"\n'
            f'{blocks}\n[run]\nsteps = 10\ndt = 0.01\n')


BROWNIAN = '[[integrator]]\nname = "brownian"\nT = 0.0\ngamma = 1.0\n'
LANGEVIN = '[[integrator]]\nname = "langevin"\nT = 1.0\ngamma = 1.0\n'
NVE = '[[integrator]]\nname = "nve"\n'
ROTATION = '[[integrator]]\nname = "brownian_rotation"\nT = 0.1\ngamma = 1.0\n'
ALIGN = '[[torque]]\nname = "polar_align"\nJ = 1.0\na = 2.0\n'
TUMBLE = '[[integrator]]\nname = "run_and_tumble"\nrate = 1.0\n'


def brownian(s):
    return pedesis.BrownianIntegrator(s, T=0.0, gamma=1.0)


def langevin(s):
    return pedesis.LangevinIntegrator(s, T=1.0, gamma=1.0)


def nve(s):
    return pedesis.NVEIntegrator(s)


def rotation(s):
    return pedesis.BrownianRotIntegrator(s, T=0.1, gamma=1.0)


def align(s):
    return pedesis.PolarAlign(s, 1.0, 2.0)


def tumble(s):
    return pedesis.RunAndTumble(s, rate=1.0)


def steps(e):
    e.evolve(0.01)


# (name, dynamics, config blocks, what the config's message says, the script's steps,
#  what the script's message says)
REFUSALS = [
    ("two brownian", "brownian", BROWNIAN + BROWNIAN, "a second position integrator",
     [("i", brownian), ("i", brownian)], "a second position integrator"),
    ("brownian and langevin", "brownian", BROWNIAN + LANGEVIN, "a second position integrator",
     [("i", brownian), ("i", langevin)], "a second position integrator"),
    ("langevin and brownian", "langevin", LANGEVIN + BROWNIAN, "a second position integrator",
     [("i", langevin), ("i", brownian)], "a second position integrator"),
    ("nve and brownian", "nve", NVE + BROWNIAN, "a second position integrator",
     [("i", nve), ("i", brownian)], "a second position integrator"),
    ("two rotations", "brownian", BROWNIAN + ROTATION + ROTATION, "a second 'brownian_rotation'",
     [("i", brownian), ("i", rotation), ("i", rotation)], "a second BrownianRotIntegrator"),
    ("two run-and-tumbles", "brownian", BROWNIAN + TUMBLE + TUMBLE, "a second 'run_and_tumble'",
     [("i", brownian), ("i", tumble), ("i", tumble)], "a second RunAndTumble"),
    ("rotation only", "brownian", ROTATION, "needs an [[integrator]]",
     [("i", rotation), ("step", steps)], "nothing moves the particles"),
    ("no integrator", "brownian", "", "needs an [[integrator]]",
     [("step", steps)], "nothing moves the particles"),
    ("torque without rotation", "brownian", BROWNIAN + ALIGN,
     "a torque turns nothing without a 'brownian_rotation' integrator",
     [("i", brownian), ("t", align), ("step", steps)],
     "a torque turns nothing without a BrownianRotIntegrator"),
    ("torque with run-and-tumble only", "brownian", BROWNIAN + TUMBLE + ALIGN,
     "a torque turns nothing without a 'brownian_rotation' integrator",
     [("i", brownian), ("i", tumble), ("t", align), ("step", steps)],
     "a torque turns nothing without a BrownianRotIntegrator"),
    ("negative temperature", "brownian",
     '[[integrator]]\nname = "brownian"\nT = -1.0\ngamma = 1.0\n', "must be >= 0",
     [("i", lambda s: pedesis.BrownianIntegrator(s, T=-1.0, gamma=1.0))], "must be >= 0"),
    ("zero friction", "brownian",
     '[[integrator]]\nname = "brownian"\nT = 1.0\ngamma = 0.0\n', "must be positive",
     [("i", lambda s: pedesis.BrownianIntegrator(s, T=1.0, gamma=0.0))], "must be positive"),
    ("unknown parameter", "brownian",
     BROWNIAN + '[[force]]\nname = "harmonic"\nk = 1.0\nkappa = 2.0\n', "unknown key",
     [("f", lambda s: pedesis.HarmonicForce(s, 1.0, kappa=2.0))], "kappa"),
    ("a shared parameter per species", "brownian",
     BROWNIAN + ROTATION + '[[torque]]\nname = "polar_align"\nJ = { A = 1.0 }\na = 2.0\n',
     "is one number for all species",
     [("t", lambda s: pedesis.PolarAlign(s, {"A": 1.0}, 2.0))], "is one number for all species"),
    ("an unknown species", "brownian",
     '[[integrator]]\nname = "brownian"\nT = { Z = 1.0 }\ngamma = 1.0\n', "species",
     [("i", lambda s: pedesis.BrownianIntegrator(s, T={"Z": 1.0}, gamma=1.0))], "species"),
]


@pytest.mark.parametrize("case", REFUSALS, ids=[c[0] for c in REFUSALS])
def test_the_config_and_the_script_refuse_alike(case, tmp_path, init, system, pedesis_bin):
    name, dynamics, blocks, config_says, script, script_says = case
    path = tmp_path / "refused.toml"
    path.write_text(config(init, dynamics, blocks))
    r = subprocess.run([pedesis_bin, "run", str(path), "--out", str(tmp_path / "run")],
                       capture_output=True, text=True)
    assert r.returncode == 2, (name, r.stdout, r.stderr)
    assert config_says in r.stderr, (name, r.stderr)

    e = pedesis.Evolver(system)
    add = {"i": e.add_integrator, "f": e.add_force, "t": e.add_torque}
    with pytest.raises(pedesis.InputError) as raised:
        for kind, make in script:
            if kind == "step":
                make(e)
            else:
                add[kind](make(system))
    assert script_says in str(raised.value), (name, str(raised.value))
    assert system.step == 0  # nothing moved


def test_one_position_integrator_moves_the_particles_one_step(system):
    # the reported case: a second BrownianIntegrator doubled every move
    e = pedesis.Evolver(system)
    e.add_force(pedesis.SelfPropulsion(system, 1.0))
    e.add_integrator(brownian(system))
    with pytest.raises(pedesis.InputError):
        e.add_integrator(brownian(system))
    box = np.array(system.box)
    before = system.positions + system.images * box
    e.evolve(0.01)
    moved = np.linalg.norm(system.positions + system.images * box - before, axis=1)
    assert np.allclose(moved, 0.01, rtol=1e-9)  # alpha dt / gamma, not twice that
    assert e.terms == ["self_propulsion", "brownian"]


def test_a_terms_parameters_read_back_and_refuse_assignment(system):
    bi = pedesis.BrownianIntegrator(system, T=0.0, gamma=1.0)
    assert bi.T == 0.0 and bi.gamma == 1.0
    assert bi.uniform_noise is None  # not given: the default
    with pytest.raises(AttributeError, match="fixed when it is made"):
        bi.T = 1.0
    assert bi.T == 0.0
    with pytest.raises(AttributeError, match="no parameter 'temperature'"):
        bi.temperature = 1.0
    with pytest.raises(AttributeError, match="no attribute 'kT'"):
        bi.kT
    # the reported case: T changed on the object after it was made moved nothing
    e = pedesis.Evolver(system)
    e.add_integrator(bi)
    before = system.positions.copy()
    e.evolve(0.01)
    assert np.array_equal(system.positions, before)  # T = 0, no force: still


def test_the_engine_objects_refuse_unknown_attributes(system):
    e = pedesis.Evolver(system)
    for obj, attribute in ((system, "dt"), (e, "dt"), (system, "box")):
        with pytest.raises(AttributeError):
            setattr(obj, attribute, 1.0)


def test_a_simulation_refuses_settings_it_would_ignore(tmp_path, repo):
    sim = pedesis.Simulation.from_file(repo / "examples" / "abp_tutorial.toml",
                                       out=tmp_path / "abp")
    with pytest.raises(AttributeError, match=r"sim.set\('alpha', 2.0\)"):
        sim.alpha = 2.0  # steerable: the message shows the call that takes effect
    with pytest.raises(AttributeError, match="no setting 'dt'"):
        sim.dt = 0.001
    with pytest.raises(AttributeError, match="no setting 'step'"):
        sim.step = 5
    sim.out_dir = tmp_path / "abp"  # what from_file sets stays settable
    assert sim.step == 0


def test_a_term_added_as_the_wrong_kind_says_which_kind_it_is(system):
    e = pedesis.Evolver(system)
    with pytest.raises(pedesis.InputError,
                       match="BrownianIntegrator is an integrator; use Evolver.add_integrator"):
        e.add_force(brownian(system))
    with pytest.raises(pedesis.InputError, match="PolarAlign is a torque; use Evolver.add_torque"):
        e.add_integrator(align(system))
