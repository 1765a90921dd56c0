"""The Python classes of issue 50's terms: words (a wall's potential and shape) and lists
(a trap's centre) pass through as in a config, bad ones raise InputError naming the
parameter, and an Evolver with a container, gravity and a trap moves the particles as
the forces say: an ideal particle in a stiff trap ends near the trap's centre shifted by
gravity, -w / k along y (the exact stationary mean of an overdamped particle)."""
import numpy as np
import pytest

import pedesis


def test_words_and_lists_are_taken(system):
    w = pedesis.Wall(system, potential="harmonic", k=20.0, shape="sphere", radius=9.0,
                     centre=[0.5, -0.5])
    assert w.potential == "harmonic" and w.shape == "sphere" and w.centre == [0.5, -0.5]
    t = pedesis.HarmonicTrap(system, k=[1.0, 2.0], centre=[0.0, 1.0])
    assert t.k == [1.0, 2.0]


@pytest.mark.parametrize("make, fragment", [
    (lambda s: pedesis.Wall(s, potential="soft"), "'soft' is not one of wca, lj93, harmonic"),
    (lambda s: pedesis.Wall(s, shape="box"), "'box' is not one of planes, sphere, cylinder"),
    (lambda s: pedesis.HarmonicTrap(s, k=1.0, centre=["a", 1.0]), "a list of numbers"),
    (lambda s: pedesis.Gravity(s, force="heavy"), "must be a number"),
    (lambda s: pedesis.ActiveOU(s, tau=-1.0, D_a=1.0), "tau"),
])
def test_bad_values_raise_input_error(system, make, fragment):
    with pytest.raises(pedesis.InputError) as e:
        make(system)
    assert fragment in str(e.value)


def test_a_planes_wall_in_a_periodic_box_says_so(system):
    e = pedesis.Evolver(system)
    e.add_force(pedesis.Wall(system, potential="harmonic", k=10.0))
    e.add_integrator(pedesis.BrownianIntegrator(system, T=0.0, gamma=1.0))
    with pytest.raises(pedesis.InputError) as err:
        e.evolve(0.01)
    assert "every axis of this box is periodic" in str(err.value)


def test_trap_and_gravity_hold_the_particles_where_theory_says(system):
    k, w = 2.0, 0.5
    e = pedesis.Evolver(system)
    e.add_force(pedesis.Wall(system, potential="harmonic", k=20.0, shape="sphere", radius=15.0))
    e.add_force(pedesis.HarmonicTrap(system, k=k, centre=[1.0, 1.0]))
    e.add_force(pedesis.Gravity(system, force=w))
    e.add_integrator(pedesis.BrownianIntegrator(system, T=0.0, gamma=1.0))
    e.run(2000, 0.01)  # 20 relaxation times 1 / k: noiseless, so every particle arrives
    mean = np.asarray(system.positions).mean(axis=0)
    assert mean == pytest.approx([1.0, 1.0 - w / k], abs=1e-6)
    assert "wall" in e.terms and "harmonic_trap" in e.terms and "gravity" in e.terms
