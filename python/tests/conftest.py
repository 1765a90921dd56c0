"""Shared set-up of the Python tests: CTest runs them with PYTHONPATH at the built
package and PEDESIS_BIN at the CLI, so that scripts and the CLI can be compared."""
import os
import pathlib
import subprocess

import pytest

REPO = pathlib.Path(__file__).resolve().parents[2]


@pytest.fixture
def repo():
    return REPO


@pytest.fixture
def pedesis_bin():
    path = os.environ.get("PEDESIS_BIN", str(REPO / "build" / "pedesis"))
    if not os.path.exists(path):
        pytest.fail(f"the pedesis CLI is not at {path}; build it or set PEDESIS_BIN")
    return path


@pytest.fixture
def run_cli(pedesis_bin):
    def run(*args, cwd=None):
        r = subprocess.run([pedesis_bin, *map(str, args)], capture_output=True, text=True,
                           cwd=cwd)
        assert r.returncode == 0, r.stderr
        return r
    return run
