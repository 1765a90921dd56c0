"""Simulation.transport and Simulation.summary: [transport]'s coefficients from Python, the
same as the run directory's summary.json (written by the same run), None before the end."""
import json

import pytest

import pedesis

CONFIG = """dimension = 2
dynamics = "event"
seed = 5
[box]
lengths = [30.0, 30.0]
[[species]]
name = "a"
count = 200
radius = 0.5
[run]
time = 200.0
[output]
log_interval = 50.0
formats = []
[transport]
block_time = 50.0
"""


def test_transport_of_a_run_from_python(tmp_path):
    config = tmp_path / "gas.toml"
    config.write_text(CONFIG)
    sim = pedesis.Simulation.from_file(config, out=tmp_path / "gas")
    assert sim.transport is None and sim.summary is None  # not ended yet
    sim.run(time=100.0)
    assert sim.transport is None
    assert sim.run() == "time"
    t = sim.transport
    with open(tmp_path / "gas" / "summary.json") as f:
        assert t == json.load(f)["transport"]
    assert t["blocks"] == 4
    for key in ("diffusion", "shear_viscosity", "bulk_viscosity", "thermal_conductivity"):
        assert t[key]["value"] > 0 and t[key]["error"] > 0, key
    # 2D hard disks at n = 0.222 (phi = 0.175): D within 25 % of Enskog's (Enskog's
    # D_E = 0.94 here; molecular dynamics runs some 10 % above it)
    assert t["diffusion"]["value"] == pytest.approx(t["enskog"]["diffusion"], rel=0.25)
    assert "diffusion_infinite" not in t  # 2D


def test_no_transport_without_the_table(tmp_path):
    config = tmp_path / "gas.toml"
    config.write_text(CONFIG.replace("[transport]\nblock_time = 50.0\n", ""))
    sim = pedesis.Simulation.from_file(config, out=tmp_path / "gas")
    sim.run()
    assert sim.transport is None
    assert sim.summary["stopped_by"] == "time"
