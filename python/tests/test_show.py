"""pedesis.show, open_run and movie: runs inline in a notebook (pedesis/show.py)."""
import base64
import html
import re

import pytest

import pedesis

CONFIG = """
dimension = 2
dynamics = "stepped"
seed = 3
[box]
length = 30.0
boundary = "wall"
[[species]]
name = "molecule"
count = 100
radius = 0.5
mass = 1.0
[initial]
positions = "random"
velocities = "normal"
sigma = 1.0
[stepped]
dt = 0.02
[run]
time = 20.0
[output]
log_interval = 1.0
snapshot_interval = 0.2
formats = ["gsd"]
progress = false
"""


@pytest.fixture
def run_dir(tmp_path, run_cli):
    (tmp_path / "gas.toml").write_text(CONFIG)
    run_cli("run", tmp_path / "gas.toml", "--out", tmp_path / "gas")
    return tmp_path / "gas"


def frames_in(view):
    """The frame count the embedded page holds (its data's info.frames)."""
    page = html.unescape(re.search(r'srcdoc="([^"]*)"', view.html).group(1))
    return int(re.search(r'"frames":\s*(\d+)', page).group(1))


def test_a_run_directory_shows_itself_with_every_frame(run_dir):
    run = pedesis.open_run(run_dir)
    view = run.show()
    assert view.html.startswith("<iframe") and 'sandbox="allow-scripts' in view.html
    assert frames_in(view) == 101
    assert run._repr_html_() == view.html
    assert run.log["time"][-1] == pytest.approx(20.0)
    assert run.summary  # summary.json, read


def test_frames_are_thinned_to_fit_the_size_limit(run_dir):
    whole = pedesis.show(run_dir)
    least = pedesis.show(run_dir, every=1_000_000)  # the first and last frames
    assert frames_in(least) == 2
    limit = least.bytes + (whole.bytes - least.bytes) // 4
    thin = pedesis.show(run_dir, max_bytes=limit)
    assert thin.bytes <= limit < whole.bytes
    assert 101 / 6 < frames_in(thin) <= 101 / 4 + 1
    assert "every" in repr(thin)
    with pytest.raises(ValueError, match="first and last frames only"):
        pedesis.show(run_dir, max_bytes=least.bytes - 1)


def test_a_simulation_shows_its_run_directory(tmp_path):
    (tmp_path / "gas.toml").write_text(CONFIG)
    sim = pedesis.Simulation.from_file(tmp_path / "gas.toml", out=tmp_path / "sim")
    sim.run()
    assert "<iframe" in sim._repr_html_()


def test_movie_is_an_inline_mp4(run_dir):
    video = pedesis.movie(run_dir, every=5, size="200x200")
    data = re.search(r'src="data:video/mp4;base64,([^"]+)"', video.html).group(1)
    assert base64.b64decode(data)[4:8] == b"ftyp"  # an MP4 container


def test_a_missing_directory_is_a_clear_error(tmp_path):
    with pytest.raises(FileNotFoundError, match="no such run directory"):
        pedesis.show(tmp_path / "nothing")
