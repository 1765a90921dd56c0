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


@pytest.fixture
def init(tmp_path):
    """A 2D start of the soft engine: phi = 0.3 in a box of 20, centres 1 apart."""
    import pedesis
    path = tmp_path / "init.json"
    pedesis.builder.random_init(0.3, 20, rcut=1.0, outfile=path, seed=1)
    return path


@pytest.fixture
def system(init):
    """A System read from `init`, list cutoff 2, skin 0.5."""
    import pedesis
    s = pedesis.System(rcut=2.0, pad=0.5)
    s.read_init(str(init))
    return s
