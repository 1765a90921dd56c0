"""The hard-particle engines driven from Python: stop conditions, conservation, and the
measured pressure and speed distribution against kinetic theory."""
import numpy as np
import pedesis
import pytest


def walled_gas(dynamics, n=400, L=100.0, seed=11, extra=""):
    return pedesis.Gas(f"""
dimension = 2
dynamics = "{dynamics}"
seed = {seed}
[box]
length = {L}
boundary = "wall"
[[species]]
name = "disk"
count = {n}
radius = 0.5
mass = 1.0
[initial]
velocities = "equal_speed"
speed = 1.0
{extra}
""")


def henderson_z(eta):
    """Henderson's equation of state of hard disks, Z = (1 + eta^2 / 8) / (1 - eta)^2."""
    return (1 + eta**2 / 8) / (1 - eta) ** 2


def test_event_gas_conserves_energy_and_stops_where_asked():
    g = walled_gas("event")
    assert g.dynamics == "event" and g.dim == 2 and len(g) == 400
    k0 = g.kinetic_energy()
    assert k0 == pytest.approx(200.0, rel=1e-12)  # equal speeds 1, mass 1
    assert g.run(collisions_per_particle=2.0) == "collisions_per_particle"
    assert 800 <= g.collisions < 800 + 10  # stops at the first collision past the target
    assert g.run(time=g.time + 5.0) == "time"
    # elastic collisions and walls: energy to rounding over ~1000 collisions
    assert g.kinetic_energy() == pytest.approx(k0, rel=1e-10)
    r = g.positions
    assert r.shape == (400, 2) and np.all(np.abs(r) <= 50.0 - 0.5 + 1e-9)
    assert np.allclose(g.speeds, np.hypot(*g.velocities.T), rtol=1e-15, atol=0)
    assert np.all(g.masses == 1.0) and np.all(g.radii == 0.5) and np.all(g.types == 0)


def test_event_gas_relaxes_to_rayleigh_and_obeys_the_equation_of_state():
    n, L = 2000, 200.0
    g = walled_gas("event", n=n, L=L)
    g.run(collisions_per_particle=10.0)  # ~10 collisions: relaxed from equal speeds
    g.pressure()  # start the pressure average here
    g.run(time=g.time + 200.0)
    P = g.pressure()
    T = 2 * g.kinetic_energy() / (2 * n)
    eta = n * np.pi * 0.25 / L**2
    # ~2e5 wall hits give the pressure to ~0.3%; walls shift it by O(sigma / L) = 0.5%
    assert P * L**2 / (n * T) == pytest.approx(henderson_z(eta), rel=0.02)
    # the tensor over the next interval: symmetric; each diagonal component is one axis's
    # wall momentum, ~1200 hits over 200 time units (scatter ~3 %); the off-diagonal is
    # the kinetic sum m u_x u_y / V and collisions (~2 % of P, 1 / sqrt(N)); 4-5 sigma bounds
    g.run(time=g.time + 200.0)
    t = g.pressure(tensor=True)
    assert t.shape == (2, 2) and t[0, 1] == t[1, 0]
    assert abs(t[0, 1]) < 0.1 * P
    assert t[0, 0] == pytest.approx(P, rel=0.12) and t[1, 1] == pytest.approx(P, rel=0.12)

    # Kolmogorov-Smirnov distance of the N speeds from the Rayleigh distribution at the
    # measured T: below 1.63 / sqrt(N), the 1% critical value, for independent samples.
    v = np.sort(g.speeds)
    cdf = 1 - np.exp(-v**2 / (2 * T))
    i = np.arange(1, n + 1)
    ks = max(np.max(i / n - cdf), np.max(cdf - (i - 1) / n))
    assert ks < 1.63 / np.sqrt(n)


def test_stepped_gas_steps_and_conserves_energy():
    g = walled_gas("stepped", extra="[stepped]\ndt = 0.05\n")
    assert g.dynamics == "stepped"
    k0 = g.kinetic_energy()
    assert g.run(steps=400) == "steps"
    assert g.steps == 400 and g.time == pytest.approx(20.0, rel=1e-12)
    assert g.collisions > 0 and g.wall_collisions > 0
    # every collision the stepped engine resolves is elastic: energy to rounding
    assert g.kinetic_energy() == pytest.approx(k0, rel=1e-10)
    assert np.all(np.abs(g.positions) <= 50.0)
    assert g.run(time=25.0) == "time" and g.steps == 500


def test_event_and_stepped_agree_on_the_pressure():
    """The same gas on both engines: at dt of 0.05 mean free times the stepped engine
    misses a fraction x^2/24 < 1e-3 of collisions (docs/engines.md), so the pressures
    agree within their statistical errors (~1% each over this run)."""
    pressures = []
    for dyn in ("event", "stepped"):
        g = walled_gas(dyn, n=1000, L=100.0, extra="[stepped]\ndt = 0.05\n" if dyn == "stepped" else "")
        g.run(time=20.0)
        g.pressure()
        g.run(time=220.0)
        pressures.append(g.pressure())
    assert pressures[1] == pytest.approx(pressures[0], rel=0.04)


@pytest.mark.parametrize("boundary, conserved", [('"periodic"', 2), ('"wall"', 0),
                                                 ('["wall", "periodic"]', 1)])
def test_temperature_counts_the_degrees_of_freedom_the_dynamics_leaves(boundary, conserved):
    # docs/engines.md, "Temperature and degrees of freedom": f = d N - c, with c the
    # momentum components the dynamics conserves (one per periodic axis here)
    n = 30
    g = pedesis.Gas(f"""
dimension = 2
seed = 4
[box]
length = 20.0
boundary = {boundary}
[[species]]
name = "disk"
count = {n}
temperature = 2.0
""")
    assert g.degrees_of_freedom() == 2 * n - conserved
    # the Maxwell-Boltzmann start is scaled to the requested T under the same rule
    assert g.temperature() == pytest.approx(2.0, rel=1e-12)
    assert g.kinetic_energy() == pytest.approx(2.0 * (2 * n - conserved) / 2, rel=1e-12)
    g.run(time=3.0)
    assert g.temperature() == pytest.approx(2.0, rel=1e-10)  # elastic: K and T stay


def test_event_gas_growth_stops_at_the_packing_fraction():
    """Lubachevsky-Stillinger growth from Python: run() says "grown" when the packing
    fraction (disks of radius r: N pi r^2 / L^2) reaches its target, and goes on after."""
    g = walled_gas("event", n=400, L=40.0,
                   extra="[event]\ngrowth_rate = 0.2\ngrowth_packing_fraction = 0.5\n")
    assert g.run(time=1000.0) == "grown"
    r = g.radii
    assert np.allclose(r, r[0])
    assert 400 * np.pi * r[0] ** 2 / 40.0**2 == pytest.approx(0.5, rel=1e-9)
    assert g.run(time=g.time + 1.0) == "time"


@pytest.mark.parametrize("dynamics", ["event", "stepped"])
def test_a_gas_with_a_shear_rate_is_sheared(dynamics):
    # [box] shear_rate reaches the engine: one disk at (0, 4.5) in a 10 x 10 box at rate
    # 0.2 with peculiar velocity (0.3, 1) crosses the top face and lands, at t = 2, at
    # (-1.6, -3.5) with peculiar velocity (-0.1, 1) (worked out in
    # tests/unit/event_shear_test.cpp); without the shear it would be at (0.6, -3.5)
    stepped = '[stepped]\ndt = 0.01\n' if dynamics == "stepped" else ""
    g = pedesis.Gas(f"""
dimension = 2
dynamics = "{dynamics}"
[box]
length = 10.0
shear_rate = 0.2
[[species]]
name = "A"
count = 1
radius = 0.5
positions = "point"
position = [0.0, 4.5]
velocities = "given"
velocity = [0.3, 1.0]
{stepped}""")
    g.run(time=2.0)
    assert g.positions[0] == pytest.approx([-1.6, -3.5], abs=1e-9)
    assert g.velocities[0] == pytest.approx([-0.1, 1.0], abs=1e-9)
