"""`python3 -m pedesis.analyze transport RUN` (docs/analyze.md), on run directories
written here by hand in the format of docs/formats.md: the lines it prints, the PNG it
draws, and one line with exit 2 for each kind of bad or missing file."""
import json
import os
import struct
import subprocess
import sys

import pytest

CONFIG_3D = 'dimension = 3\ndynamics = "event"\n[box]\nlength = 10.0\n[[species]]\ncount = 500\n'

CURVES_3D = """quantity,lag,correlation,running_coefficient
diffusion,0,0,nan
diffusion,0.01,0.0003,0.09
diffusion,0.1,0.03,0.07
diffusion,1,0.33,0.056
diffusion,10,3.2,0.054
shear_viscosity,0.01,0.001,1.2
shear_viscosity,0.1,0.05,2.1
shear_viscosity,1,0.7,2.4
shear_viscosity,10,7.1,2.3
velocity_autocorrelation,0,3,0
velocity_autocorrelation,0.1,2.0,0.08
velocity_autocorrelation,1,0.01,0.055
"""

SUMMARY_3D = {"particles": 500, "transport": {
    "diffusion": {"value": 0.0541, "error": 0.0012},
    "diffusion_infinite": {"value": 0.058, "error": 0.0013},
    "shear_viscosity": {"value": 2.31, "error": 0.09},
    "bulk_viscosity": {"value": None, "error": None, "why": "no pressure tensor logged"},
    "thermal_conductivity": {"value": 9.0, "error": None},
    "fit_window": {"from": 0.5, "to": 2.0}, "blocks": 8, "interval": 0.01,
    "enskog": {"diffusion": 0.05385, "shear_viscosity": 2.355, "bulk_viscosity": 2.71,
               "thermal_conductivity": 9.359}}}


def make_run(folder, config=CONFIG_3D, curves=CURVES_3D, summary=SUMMARY_3D):
    folder.mkdir()
    (folder / "config.toml").write_text(config)
    if curves is not None:
        (folder / "transport.csv").write_text(curves)
    if summary is not None:
        (folder / "summary.json").write_text(
            summary if isinstance(summary, str) else json.dumps(summary))
    return folder


def analyze(run, *extra):
    return subprocess.run([sys.executable, "-m", "pedesis.analyze", "transport", str(run),
                           *extra], capture_output=True, text=True, env=dict(os.environ))


def png_size(path):
    """(width, height) from a PNG's signature and IHDR chunk; fails on anything else."""
    data = path.read_bytes()
    assert data[:8] == b"\x89PNG\r\n\x1a\n", "not a PNG signature"
    assert data[12:16] == b"IHDR"
    return struct.unpack(">II", data[16:24])


def test_prints_each_coefficient_beside_enskog_and_draws_them(tmp_path):
    run = make_run(tmp_path / "run")
    r = analyze(run)
    assert r.returncode == 0, r.stderr
    assert r.stdout.splitlines() == [
        "diffusion: 0.0541 +- 0.0012 (Enskog 0.05385, ratio 1.005)",
        "diffusion_infinite: 0.058 +- 0.0013 (Yeh-Hummer, the infinite system)",
        "shear_viscosity: 2.31 +- 0.09 (Enskog 2.355, ratio 0.981)",
        "bulk_viscosity: not measured (no pressure tensor logged)",
        "thermal_conductivity: 9 (no error: fewer than 2 blocks; Enskog 9.359, ratio 0.962)",
        "fit window: lag 0.5 to 2 (8 blocks, interval 0.01)",
        f"wrote {run / 'transport.png'}"]
    # three panels (diffusion, shear viscosity, thermal conductivity) in two columns at 150 dpi
    width, height = png_size(run / "transport.png")
    assert (width, height) == (1950, 1380)


def test_a_2d_run_with_one_coefficient_and_no_enskog_value(tmp_path):
    config = CONFIG_3D.replace("dimension = 3", "dimension = 2").replace("dynamics = \"event\"",
                                                                         "dynamics = \"langevin\"")
    curves = "quantity,lag,correlation,running_coefficient\ndiffusion,0.5,2.1,1.05\ndiffusion,5,20,0.98\n"
    summary = {"transport": {"diffusion": {"value": 0.99, "error": 0.02},
                             "shear_viscosity": {"value": None, "why": "soft runs: not yet"},
                             "fit_window": {"from": 1, "to": 4}}}
    run = make_run(tmp_path / "run", config, curves, summary)
    out = tmp_path / "d.png"
    r = analyze(run, "--out", str(out))
    assert r.returncode == 0, r.stderr
    assert r.stdout.splitlines() == ["diffusion: 0.99 +- 0.02",
                                     "shear_viscosity: not measured (soft runs: not yet)",
                                     "fit window: lag 1 to 4", f"wrote {out}"]
    assert png_size(out) == (975, 750)  # one panel
    assert not (run / "transport.png").exists()


GOOD_CURVES = "quantity,lag,correlation,running_coefficient\ndiffusion,0.5,2.1,1.05\n"


@pytest.mark.parametrize("curves, summary, message", [
    (None, SUMMARY_3D, "transport.csv: missing; the run measured no transport coefficients: "
                       "add a [transport] table to its config, and run again"),
    (GOOD_CURVES, None, "summary.json: missing (the run did not finish, or was killed)"),
    (GOOD_CURVES, "{\"transport\": ", "summary.json: not valid JSON"),
    (GOOD_CURVES, {"particles": 5}, "summary.json: no \"transport\" object; the run measured no "
                                    "transport coefficients"),
    ("quantity,lag,value\n", SUMMARY_3D, "transport.csv: the header must be "
                                         "quantity,lag,correlation,running_coefficient, not "
                                         "quantity,lag,value"),
    (GOOD_CURVES + "viscosity,1,2,3\n", SUMMARY_3D, "transport.csv: line 3: unknown quantity "
                                                    "'viscosity' (known: diffusion, "),
    (GOOD_CURVES + "diffusion,1,abc,3\n", SUMMARY_3D, "transport.csv: line 3: 'abc' is not a "
                                                      "number"),
    (GOOD_CURVES + "diffusion,1,2\n", SUMMARY_3D, "transport.csv: line 3 has 3 fields"),
    (GOOD_CURVES + "diffusion,0.5,2,3\n", SUMMARY_3D, "transport.csv: line 3: the lags of "
                                                      "diffusion are not in ascending order"),
    (GOOD_CURVES, {"transport": {"diffusion": {"value": "0.1"}}},
     "summary.json: transport.diffusion.value: '0.1' is not a number"),
    (GOOD_CURVES, {"transport": {"diffusion": 0.1}},
     "summary.json: transport.diffusion must be an object with \"value\""),
    (GOOD_CURVES, {"transport": {"fit_window": {"from": 3, "to": 1}}},
     "summary.json: transport.fit_window: from 3 to 1 is not a window"),
    ("quantity,lag,correlation,running_coefficient\n",
     {"transport": {"diffusion": {"value": None, "why": "too short"}}},
     "no transport coefficient to draw: transport.csv has no curve and summary.json no value "
     "(diffusion: too short)"),
])
def test_bad_or_missing_files_give_one_line_and_exit_2(tmp_path, curves, summary, message):
    run = make_run(tmp_path / "run", curves=curves, summary=summary)
    r = analyze(run)
    assert r.returncode == 2, r.stdout + r.stderr
    assert r.stdout == ""
    lines = r.stderr.splitlines()
    assert len(lines) == 1 and lines[0].startswith("pedesis: error: "), r.stderr
    assert message in lines[0], lines[0]
    assert not (run / "transport.png").exists()
