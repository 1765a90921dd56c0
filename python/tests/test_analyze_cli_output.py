"""What `pedesis analyze` prints (docs/analyze.md): the frames structure averages, the
`wrote PATH` line last, a closed pipe ending quietly, and a log whose [log] quantities
left out a column the figure needs."""
import os
import re
import subprocess

import numpy as np
import pytest

KINDS = ("speed", "thermo", "msd", "order", "structure", "bond_order", "clusters")


def lattice_run(tmp_path, run_cli, steps, T=0.0, log=""):
    """A 20 x 20 triangular lattice of spacing 1 under brownian dynamics at temperature
    T, a GSD frame every step: steps + 1 frames at t = 0, 0.01, ..."""
    cfg = tmp_path / f"lattice_{steps}.toml"
    cfg.write_text(
        'dimension = 2\ndynamics = "brownian"\nseed = 1\n[box]\n'
        f'lengths = [20.0, {20 * np.sqrt(3) / 2!r}]\n'
        '[[species]]\nname = "A"\ncount = 400\nradius = 0.45\n[initial]\npositions = "hexagonal"\n'
        f'[[integrator]]\nname = "brownian"\nT = {T!r}\ngamma = 1.0\n'
        f'[run]\ndt = 0.01\nsteps = {steps}\n{log}[output]\nlog_every = 1\nsnapshot_every = 1\n'
        'formats = ["gsd"]\nprogress = false\n')
    out = tmp_path / f"run_{steps}"
    run_cli("run", cfg, "--out", out)
    return out


@pytest.mark.parametrize("steps, frames", [(12, 10), (10, 10), (9, 9), (1, 1)])
def test_structure_averages_the_last_10_frames_leaving_out_only_the_start(tmp_path, run_cli,
                                                                          steps, frames):
    # 13 frames gave "(9 frames)": the first of the last 10 was dropped as if it were the
    # run's start. Only t = 0 is left out, and only when there are others.
    run = lattice_run(tmp_path, run_cli, steps)
    out = run_cli("analyze", "structure", run).stdout
    assert re.search(rf"\({frames} frames\)\n", out), out

    from pedesis.analyze.plots.run_dir import Run, read_trajectory
    times = read_trajectory(Run(run), most=10, last=10, skip_start=True).times
    assert np.allclose(times, 0.01 * np.arange(steps + 1 - frames, steps + 1))


def test_a_run_of_one_frame_keeps_it(tmp_path, run_cli):
    import gsd.hoomd
    run = lattice_run(tmp_path, run_cli, 1)
    with gsd.hoomd.open(str(run / "trajectory.gsd"), "rb") as f:
        start = f[0]
    (run / "trajectory.gsd").unlink()
    with gsd.hoomd.open(str(run / "trajectory.gsd"), "wb") as f:
        f.append(start)
    from pedesis.analyze.plots.run_dir import Run, read_trajectory
    assert list(read_trajectory(Run(run), most=10, last=10, skip_start=True).times) == [0.0]


@pytest.fixture
def warm_run(tmp_path, run_cli):
    """A lattice at a low temperature, 12 steps: every figure draws it."""
    return lattice_run(tmp_path, run_cli, 12, T=0.001)


@pytest.mark.parametrize("kind", KINDS)
def test_every_figure_prints_wrote_path_last(warm_run, run_cli, kind, tmp_path):
    # structure, bond_order and clusters printed `wrote PATH` before their result lines
    out = tmp_path / f"{kind}.png"
    lines = run_cli("analyze", kind, warm_run, "--out", out).stdout.splitlines()
    assert lines[-1] == f"wrote {out}"
    assert sum(line.startswith("wrote ") for line in lines) == 1, lines
    assert out.stat().st_size > 10000


@pytest.mark.parametrize("kind", ["clusters", "speed"])
@pytest.mark.parametrize("unbuffered", [True, False])
def test_a_reader_that_leaves_ends_the_output_quietly(warm_run, pedesis_bin, tmp_path, kind,
                                                      unbuffered):
    # the reader closes the pipe before anything is written, so every line of the figure
    # meets a closed pipe: a BrokenPipeError traceback and "internal error", exit 1,
    # before; now the lines are dropped, the figure is still written, exit 0
    env = dict(os.environ)
    env.pop("PYTHONUNBUFFERED", None)
    if unbuffered:
        env["PYTHONUNBUFFERED"] = "1"
    out = tmp_path / "plot.png"
    p = subprocess.Popen([pedesis_bin, "analyze", kind, str(warm_run), "--out", str(out)],
                         stdout=subprocess.PIPE, stderr=subprocess.PIPE, env=env)
    p.stdout.close()
    err = p.stderr.read().decode()
    assert p.wait() == 0 and err == "", err
    assert out.stat().st_size > 10000


def test_piping_into_head_shows_the_first_line_and_exits_0(warm_run, pedesis_bin, tmp_path):
    out = tmp_path / "c.png"
    r = subprocess.run(["bash", "-c", f'set -o pipefail; "{pedesis_bin}" analyze clusters '
                        f'"{warm_run}" --out "{out}" | head -1'],
                       capture_output=True, text=True, env=dict(os.environ, PYTHONUNBUFFERED="1"))
    assert r.returncode == 0 and r.stderr == "", r.stderr
    assert r.stdout.startswith("clusters: contact distance") and r.stdout.count("\n") == 1


@pytest.mark.parametrize("kind, needs", [("msd", "the columns time and msd"),
                                         ("order", "the columns time and polar_order"),
                                         ("thermo", "the column time")])
def test_a_log_without_time_names_the_quantities_that_left_it_out(tmp_path, run_cli,
                                                                  pedesis_bin, kind, needs):
    # it said "no 'time' column in the header (is it a pedesis log?)" of a pedesis log
    run = lattice_run(tmp_path, run_cli, 3, T=0.1,
                      log='[log]\nquantities = ["msd", "polar_order", "pressure"]\n')
    r = subprocess.run([pedesis_bin, "analyze", kind, str(run)], capture_output=True, text=True)
    assert r.returncode == 2
    assert r.stderr == (f"pedesis: error: {run}/log.csv: no column 'time': the run's [log] "
                        f"quantities left out time, and {kind} needs {needs}; add \"time\" to "
                        "[log] quantities and run again\n")
