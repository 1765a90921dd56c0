"""Runs you can see in a notebook: the viewer page and movies, inline.

    run = pedesis.open_run("runs/abp")   # a run directory, as `pedesis run` leaves it
    run                                  # a notebook cell ending with it draws the particles
    pedesis.show("runs/abp")             # the same, explicitly
    pedesis.movie("runs/abp")            # an MP4 made by `pedesis render`, inline

The inline view is the page of `pedesis view --export` (docs/view.md): one HTML file
with the page and the frames inside, shown in an iframe, so that it works offline, in a
saved notebook and in nbconvert's HTML. Frames are thinned (every k-th, and the last)
until the page is under `max_bytes` (5 MB by default), so a notebook stays small.
A `Simulation` ending a cell shows its run directory the same way.
"""
import base64
import csv
import html
import math
import os
import pathlib
import re
import subprocess
import tempfile

__all__ = ["RunDirectory", "open_run", "show", "movie", "InlineHTML"]

DEFAULT_MAX_BYTES = 5_000_000


class InlineHTML:
    """HTML that a notebook shows inline (`_repr_html_`); `html` is its text, `bytes` its
    size, and save(path) writes it to a file."""

    def __init__(self, text, note=""):
        self.html = text
        self.note = note

    @property
    def bytes(self):
        return len(self.html.encode())

    def _repr_html_(self):
        return self.html

    def save(self, path):
        pathlib.Path(path).write_text(self.html, encoding="utf-8")

    def __repr__(self):
        return f"<pedesis inline view, {self.bytes / 1e6:.2f} MB{self.note}>"


def _binary():
    try:
        from ._binary import binary  # the installed package's, or the build tree's
        return binary()
    except ImportError:
        import shutil
        for name in ("PEDESIS_BINARY", "PEDESIS_BIN"):
            if os.environ.get(name):
                return os.environ[name]
        found = shutil.which("pedesis")
        if not found:
            raise FileNotFoundError("the pedesis command is not on PATH (set PEDESIS_BINARY)")
        return found


def _run_directory(obj):
    if isinstance(obj, RunDirectory):
        return obj.path
    out = getattr(obj, "out_dir", None)  # a Simulation
    if out is not None:
        return pathlib.Path(out)
    return pathlib.Path(obj)


def _pedesis(*args):
    r = subprocess.run([_binary(), *map(str, args)], capture_output=True, text=True)
    if r.returncode != 0:
        raise RuntimeError(f"pedesis {' '.join(map(str, args))}: "
                           f"{(r.stderr or r.stdout).strip()}")
    return r


def _export(run_dir, every, target):
    _pedesis("view", run_dir, "--export", target, "--every", every)
    return pathlib.Path(target).read_text(encoding="utf-8")


def _frames_held(page):
    found = re.search(r'"frames":\s*(\d+)', page)
    return int(found.group(1)) if found else 0


def _inline_frame(page, name, height):
    # srcdoc keeps the page's own Content-Security-Policy and scripts apart from the
    # notebook's; the sandbox lets it run its script and nothing else (no navigation, no
    # access to the notebook)
    return (f'<iframe title="pedesis view of {html.escape(name)}" '
            f'sandbox="allow-scripts allow-downloads" style="width:100%;height:{int(height)}px;'
            f'border:1px solid #ccc" srcdoc="{html.escape(page, quote=True)}"></iframe>')


def show(obj, max_bytes=DEFAULT_MAX_BYTES, height=560, every=None):
    """The viewer page of a run directory (a path, a RunDirectory or a Simulation), inline:
    particles, playback and the log's plot. Frames are thinned (every k-th, and the last)
    until the page is under `max_bytes`, or as `every` says. A Recording, a Gas or a System
    shows its frames (pedesis/recording.py)."""
    if type(obj).__name__ in ("Gas", "System"):  # a Gas's latest recording, or the state now
        from .recording import latest_recording
        obj = latest_recording(obj)
    if hasattr(obj, "frames") and hasattr(obj, "save"):  # a Recording
        return obj.show(max_bytes, height, every)
    run_dir = _run_directory(obj)
    if not run_dir.is_dir():
        raise FileNotFoundError(f"{run_dir}: no such run directory")
    def size(page):  # (as the notebook stores it: escaped into the iframe)
        return len(_inline_frame(page, run_dir.name, height).encode())

    with tempfile.TemporaryDirectory(prefix="pedesis_show_") as scratch:
        target = os.path.join(scratch, "view.html")
        page = _export(run_dir, every or 1, target)
        frames = _frames_held(page)
        if every is None and size(page) > max_bytes:
            # a page is the page itself plus a share per frame: measured with the first
            # and last frames only, the stride that fits follows
            least = _export(run_dir, 1_000_000, target)
            fixed = size(least)
            if fixed > max_bytes:
                raise ValueError(f"{run_dir}: the page with its first and last frames only "
                                 f"is {fixed / 1e6:.2f} MB, over max_bytes={max_bytes}")
            per_frame = (size(page) - fixed) / max(frames - 2, 1)
            fitting = 2 + int((max_bytes - fixed) / per_frame)
            every = max(2, math.ceil((frames - 1) / max(fitting - 1, 1)))
            page = _export(run_dir, every, target)
            for _ in range(16):  # (rounding: a stride or two more at most)
                if size(page) <= max_bytes:
                    break
                every += 1
                page = _export(run_dir, every, target)
        every = every or 1
    frame = _inline_frame(page, run_dir.name, height)
    note = "" if every == 1 else f", every {every}th frame: {_frames_held(page)} of {frames}"
    return InlineHTML(frame, note)


def movie(obj, color="species", fps=20, every=1, size=None):
    """An MP4 of a run directory's frames made by `pedesis render` (ffmpeg), inline as an
    HTML5 video."""
    run_dir = _run_directory(obj)
    with tempfile.TemporaryDirectory(prefix="pedesis_movie_") as scratch:
        target = os.path.join(scratch, "movie.mp4")
        args = ["render", run_dir, "--out", target, "--color", color, "--fps", fps,
                "--every", every]
        if size:
            args += ["--size", size]
        _pedesis(*args)
        data = base64.b64encode(pathlib.Path(target).read_bytes()).decode()
    return InlineHTML(f'<video controls loop autoplay muted style="max-width:100%" '
                      f'src="data:video/mp4;base64,{data}"></video>')


class RunDirectory:
    """A run directory as `pedesis run` (or a Simulation) leaves it: `log` is log.csv's
    columns as lists of floats, `summary` summary.json; in a notebook it shows itself
    (show()); movie() makes its MP4."""

    def __init__(self, path):
        self.path = pathlib.Path(path)
        if not self.path.is_dir():
            raise FileNotFoundError(f"{self.path}: no such run directory")

    @property
    def log(self):
        for name in ("log.csv", "log.csv.part"):
            f = self.path / name
            if f.exists():
                with open(f, newline="") as handle:
                    rows = list(csv.reader(handle))
                if not rows:
                    return {}
                columns = {c: [] for c in rows[0]}
                for row in rows[1:]:
                    if len(row) != len(rows[0]):
                        continue  # a row still being written
                    for c, v in zip(rows[0], row):
                        columns[c].append(float(v))
                return columns
        return {}

    @property
    def summary(self):
        import json
        f = self.path / "summary.json"
        return json.loads(f.read_text()) if f.exists() else {}

    def show(self, max_bytes=DEFAULT_MAX_BYTES, height=560):
        return show(self, max_bytes, height)

    def movie(self, **options):
        return movie(self, **options)

    def _repr_html_(self):
        return self.show()._repr_html_()

    def __repr__(self):
        return f"RunDirectory({str(self.path)!r})"


def open_run(path):
    """A run directory (see RunDirectory)."""
    return RunDirectory(path)
