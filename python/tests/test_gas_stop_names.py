"""Gas.run names its stop as `pedesis run` does (summary.json's stopped_by), and the
names of earlier versions keep working with a DeprecationWarning (issue 28, item 7)."""
import json
import warnings

import pedesis
import pytest

FROZEN = """
dimension = 2
seed = 4
[box]
length = 10.0
[[species]]
name = "A"
count = 4
velocities = "zero"
"""


def test_frozen_gas_stops_with_the_cli_name(tmp_path, run_cli):
    g = pedesis.Gas(FROZEN)
    why = g.run(time=5.0)
    assert isinstance(why, pedesis.StopName) and isinstance(why, str)
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # the new name warns of nothing
        assert why == "no more events"
        assert str(why) == "no more events" and why != "time"
    # the same config through the CLI: summary.json says the same word for word
    (tmp_path / "frozen.toml").write_text(
        FROZEN + "[run]\ncollisions_per_particle = 5\n[output]\nprogress = false\n")
    run_cli("run", "frozen.toml", "--out", "out", cwd=tmp_path)
    summary = json.loads((tmp_path / "out" / "summary.json").read_text())
    assert summary["stopped_by"] == str(why)


def test_old_names_compare_equal_with_a_deprecation_warning():
    why = pedesis.Gas(FROZEN).run(time=5.0)
    with pytest.warns(DeprecationWarning, match="'no_events' is deprecated"):
        assert why == "no_events"
    with pytest.warns(DeprecationWarning):
        assert "no_events" == why  # either side
    with pytest.warns(DeprecationWarning):
        assert not (why != "no_events")
    energy = pedesis.StopName("energy_fraction")
    with pytest.warns(DeprecationWarning, match="'energy_fraction' now"):
        assert energy == "energy"
    with pytest.warns(DeprecationWarning):
        assert why in ("time", "no_events")  # what a script may have written
    # an old name equals only the name it became
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        assert energy != "no_events" and why != "energy"
        assert pedesis.StopName("time") != "no_events"


def test_every_limit_is_named_as_the_cli_names_it():
    g = pedesis.Gas("""
dimension = 2
dynamics = "stepped"
seed = 2
[box]
length = 40.0
[[species]]
name = "A"
count = 100
radius = 0.5
[stepped]
dt = 0.01
""")
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        assert g.run(steps=3) == "steps"
        assert g.run(time=g.time + 0.05) == "time"
        assert g.run(collisions_per_particle=0.0) == "collisions_per_particle"
    # the names are hashable as the str they are
    assert {"steps": 1}[pedesis.StopName("steps")] == 1
