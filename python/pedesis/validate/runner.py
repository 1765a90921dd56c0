"""Runs a validation case's simulations through the pedesis CLI, the binary the user runs,
and reads what they wrote."""
import os
import shutil
import subprocess
import threading
from pathlib import Path

from ..analyze.plots.run_dir import InputError, read_log
from .checks import CaseError


def find_binary():
    """The pedesis CLI: $PEDESIS_BIN (set by `pedesis validate`), else `pedesis` on PATH."""
    path = os.environ.get("PEDESIS_BIN") or shutil.which("pedesis")
    if not path or not os.access(path, os.X_OK):
        raise CaseError("no pedesis binary: run `pedesis validate`, or set PEDESIS_BIN")
    return path


class Context:
    """Where a case writes (``workdir/<case>/<run>``), how long it may run (``quick``), and
    how it starts a simulation."""

    def __init__(self, binary, workdir, quick):
        self.binary = binary
        self.workdir = Path(workdir)
        self.quick = quick
        self._running = set()
        self._lock = threading.Lock()
        self._stopped = False

    def pick(self, quick, full):
        """The quick mode's value or the full suite's."""
        return quick if self.quick else full

    def run(self, case, name, config):
        """Writes ``config`` (TOML text) to workdir/case/name.toml, runs it on one thread
        into workdir/case/name/, and returns that run directory."""
        folder = self.workdir / case
        folder.mkdir(parents=True, exist_ok=True)
        config_file = folder / f"{name}.toml"
        config_file.write_text(config)
        out = folder / name
        env = dict(os.environ, OMP_NUM_THREADS="1")
        with self._lock:
            if self._stopped:
                raise CaseError("stopped")
            run = subprocess.Popen([self.binary, "run", str(config_file), "--out", str(out),
                                    "--threads", "1"], stdout=subprocess.PIPE,
                                   stderr=subprocess.PIPE, text=True, env=env)
            self._running.add(run)
        try:
            _, stderr = run.communicate()
        finally:
            with self._lock:
                self._running.discard(run)
        if run.returncode != 0:
            last = (stderr.strip().splitlines() or ["(no message)"])[-1]
            raise CaseError(f"pedesis run {config_file} failed with exit {run.returncode}: {last}")
        return out

    def stop(self):
        """Ends the runs under way (SIGTERM: each writes its interrupted end) and starts no
        more; for a suite that was interrupted."""
        with self._lock:
            self._stopped = True
            for run in self._running:
                run.terminate()

    @staticmethod
    def log(run_dir):
        """log.csv of a run as {column: array}."""
        try:
            return read_log(Path(run_dir) / "log.csv")
        except InputError as e:
            raise CaseError(str(e)) from None
