"""pedesis installed as a user installs it (issue 28; docs/python.md#installing): a fresh
venv that sees Debian's numpy, `pip install --no-build-isolation` of a clean copy of the
source tree, and then, from a folder outside the tree, `import pedesis` and a short run
from Python, the `pedesis` command from the venv's bin/ (its version, a short run, an
analysis that runs the venv's Python), the distribution's metadata, `python3 -m build`'s
wheel and sdist, a Jupyter kernel of the venv, and an uninstall that leaves nothing.

A full build of the wheel compiles the whole core (about 10 CPU-minutes here), too long
for `make test`: the wheel packages the outputs of the already built CMake tree of this
test run instead (PEDESIS_CMAKE_BUILD_DIR, setup.py), which setup.py accepts only when
its CMakeCache.txt has the options of the build it would run itself and its module is for
this interpreter's ABI. The install, the package and the command are the same as with a
full build; only where the two binary files come from differs.
"""
import json
import os
import re
import shutil
import subprocess
import sys
import sysconfig
import tarfile
import time
import zipfile
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parents[2]
SYSTEM_PYTHON = "/usr/bin/python3"  # Debian's: the venv sees its numpy, scipy, matplotlib

TINY = """dimension = 2
seed = 1
[box]
length = 20.0
boundary = "wall"
[[species]]
name = "A"
count = 50
radius = 0.5
[initial]
positions = "square"
velocities = "maxwell_boltzmann"
temperature = 1.0
[run]
time = 2.0
[output]
progress = false
"""


def built_tree():
    """The CMake tree that CTest runs from: the folder of PEDESIS_BIN (build/pedesis)."""
    if os.environ.get("PEDESIS_CMAKE_BUILD_DIR"):
        return Path(os.environ["PEDESIS_CMAKE_BUILD_DIR"])
    binary = os.environ.get("PEDESIS_BIN")
    return Path(binary).parent if binary else REPO / "build"


def user_environment():
    """The environment of a user's shell: nothing of CTest's pointing into the build."""
    env = {k: v for k, v in os.environ.items()
           if k not in ("PYTHONPATH", "PYTHONHOME", "VIRTUAL_ENV", "PEDESIS_BIN",
                        "PEDESIS_BINARY", "PEDESIS_PYTHON", "PEDESIS_PYTHONPATH",
                        "PEDESIS_CMAKE_BUILD_DIR")}
    env["PIP_DISABLE_PIP_VERSION_CHECK"] = "1"
    # nor a pedesis.pth of `make python` in the user's site-packages, which a venv with the
    # system's site-packages also reads (after its own: it would answer the last import)
    env["PYTHONNOUSERSITE"] = "1"
    return env


def copy_source_tree(target):
    """The working tree's files as git sees them (tracked, and new files not ignored):
    the current sources, none of the build trees, runs or node_modules."""
    listed = subprocess.run(["git", "-C", str(REPO), "ls-files", "-z", "--cached", "--others",
                             "--exclude-standard"], capture_output=True)
    if listed.returncode == 0:
        for name in listed.stdout.decode().split("\0"):
            source = REPO / name
            if name and source.is_file():  # (a tracked file deleted in the work tree: none)
                (target / name).parent.mkdir(parents=True, exist_ok=True)
                shutil.copy2(source, target / name)
    else:  # not a git checkout (an unpacked sdist): all but what builds make
        shutil.copytree(REPO, target, ignore=shutil.ignore_patterns(
            "build*", "runs", "node_modules", ".git", "__pycache__", "*.egg-info"))


def run(command, cwd, env=None, timeout=300, check=True):
    r = subprocess.run([str(c) for c in command], cwd=cwd, env=env or user_environment(),
                       capture_output=True, text=True, timeout=timeout)
    if check:
        assert r.returncode == 0, f"{command} failed ({r.returncode}):\n{r.stdout}\n{r.stderr}"
    return r


class Install:
    pass


@pytest.fixture(scope="module")
def installed(tmp_path_factory):
    tree = built_tree()
    if not (tree / "CMakeCache.txt").is_file():
        pytest.fail(f"no built CMake tree at {tree} (set PEDESIS_CMAKE_BUILD_DIR)")
    base = tmp_path_factory.mktemp("install")
    i = Install()
    i.src, i.venv, i.home = base / "src", base / "venv", base / "elsewhere"
    i.home.mkdir()
    copy_source_tree(i.src)
    i.tree = tree
    run([SYSTEM_PYTHON, "-m", "venv", "--system-site-packages", i.venv], cwd=i.home)
    i.python, i.command = i.venv / "bin" / "python", i.venv / "bin" / "pedesis"
    i.site = Path(run([i.python, "-c", "import sysconfig; print(sysconfig.get_paths()['platlib'])"],
                      cwd=i.home).stdout.strip())
    env = user_environment()
    env["PEDESIS_CMAKE_BUILD_DIR"] = str(tree)
    start = time.monotonic()
    r = run([i.python, "-m", "pip", "install", "--no-index", "--no-build-isolation", i.src],
            cwd=i.home, env=env, check=False)
    if r.returncode != 0 and "is not the build this would make" in r.stdout + r.stderr:
        pytest.skip("the built tree is not the build pip would make: "
                    + re.findall(r"setup.py: (PEDESIS_CMAKE_BUILD_DIR.*)", r.stdout + r.stderr)[0])
    assert r.returncode == 0, f"pip install failed:\n{r.stdout}\n{r.stderr}"
    print(f"pip install: {time.monotonic() - start:.1f} s")
    (i.home / "tiny.toml").write_text(TINY)
    return i


def test_import_and_a_short_run_from_python(installed):
    i = installed
    script = """
import json, pedesis
from pedesis._binary import binary
sim = pedesis.Simulation.from_file("tiny.toml", out="runs/from_python")
stop = sim.run()
print(json.dumps({"file": pedesis.__file__, "binary": binary(), "stop": stop,
                  "time": sim.time, "n": len(sim.frame()["position"])}))
"""
    out = json.loads(run([i.python, "-c", script], cwd=i.home).stdout.splitlines()[-1])
    assert Path(out["file"]).parent == i.site / "pedesis"   # the venv's, not the build's
    assert out["binary"] == str(i.site / "pedesis" / "bin" / "pedesis")
    assert out["n"] == 50 and out["time"] == pytest.approx(2.0)
    assert (i.home / "runs" / "from_python" / "summary.json").is_file()


def test_the_command_in_the_venvs_bin(installed):
    i = installed
    version = run([i.command, "--version"], cwd=i.home).stdout
    assert re.fullmatch(r"pedesis \S+ \(commit .*\)\nCPU kernels: \S+ \(.*\)\n", version), version
    run([i.command, "run", "tiny.toml", "--out", "runs/from_cli"], cwd=i.home)
    summary = json.loads((i.home / "runs" / "from_cli" / "summary.json").read_text())
    assert summary["stopped_by"] == "time"
    # `analyze` runs python -m pedesis.analyze: the venv's interpreter and package (the
    # console script tells the binary, whose built-in paths are the build's)
    r = run([i.command, "analyze", "speed", "runs/from_cli"], cwd=i.home)
    assert (i.home / "runs" / "from_cli" / "speed_distribution.png").is_file(), r.stdout


def test_versions_agree(installed):
    i = installed
    cli = run([i.command, "--version"], cwd=i.home).stdout.split()[1]
    script = ("import importlib.metadata as m, pedesis; "
              "print(pedesis.__version__, m.version('pedesis'), *m.requires('pedesis'))")
    module, distribution, *requires = run([i.python, "-c", script], cwd=i.home).stdout.split()
    assert module == distribution == cli
    cmake = re.search(r"project\(pedesis VERSION (\S+)", (REPO / "CMakeLists.txt").read_text())
    assert cli == cmake.group(1)
    assert requires[0].startswith("numpy")


def test_python_m_build_makes_a_wheel_and_an_sdist(installed):
    i = installed
    if run([SYSTEM_PYTHON, "-c", "import build"], cwd=i.home, check=False).returncode != 0:
        pytest.fail("python3 -m build needs Debian's python3-build (make deps)")
    env = user_environment()
    env["PEDESIS_CMAKE_BUILD_DIR"] = str(i.tree)
    dist = i.home / "dist"
    run([SYSTEM_PYTHON, "-m", "build", "--no-isolation", "--wheel", "--sdist", "--outdir", dist,
         i.src], cwd=i.home, env=env)
    tag = f"cp{sys.version_info[0]}{sys.version_info[1]}"
    wheel, = dist.glob(f"pedesis-*-{tag}-{tag}-linux_*.whl")
    print(f"wheel: {wheel.name}, {wheel.stat().st_size / 1e6:.1f} MB")
    with zipfile.ZipFile(wheel) as z:
        names = {info.filename: info for info in z.infolist()}
        program = names["pedesis/bin/pedesis"]
        assert (program.external_attr >> 16) & 0o111, "the bundled binary is not executable"
        assert "pedesis/_pedesis" + sysconfig.get_config_var("EXT_SUFFIX") in names
        assert "pedesis/_version.py" in names and "pedesis/analyze/__init__.py" in names
        entry_points, = (n for n in names if n.endswith(".dist-info/entry_points.txt"))
        assert "pedesis = pedesis._binary:main" in z.read(entry_points).decode()
    sdist, = dist.glob("pedesis-*.tar.gz")
    with tarfile.open(sdist) as t:
        names = {n.split("/", 1)[1] for n in t.getnames() if "/" in n}
    for needed in ("CMakeLists.txt", "setup.py", "pyproject.toml", "cmake/git_version.cmake",
                   "src/pedesis/CMakeLists.txt", "apps/pedesis/main.cpp", "python/CMakeLists.txt",
                   "python/src/module.cpp", "python/pedesis/__init__.py",
                   "web/viewer/package-lock.json"):
        assert needed in names, f"the sdist lacks {needed}"
    assert not [n for n in names if "node_modules" in n or n.startswith("build")]
    # what a build from the sdist needs, CMake finds in it (configured, not built: the
    # build is the one of the tree above)
    with tarfile.open(sdist) as t:
        t.extractall(i.home / "unpacked")
    unpacked, = (i.home / "unpacked").iterdir()
    run(["cmake", "-S", unpacked, "-B", i.home / "sdist_build", "-DPEDESIS_TESTS=OFF",
         f"-DPEDESIS_PYTHON={i.python}"], cwd=i.home)


def test_a_jupyter_kernel_of_the_venv_imports_pedesis(installed):
    i = installed
    for module in ("ipykernel", "jupyter_client"):
        if run([i.python, "-c", f"import {module}"], cwd=i.home, check=False).returncode:
            pytest.fail(f"no {module}: install Debian's python3-ipykernel (make deps)")
    env = user_environment()
    env["JUPYTER_RUNTIME_DIR"] = str(i.home / "jupyter_runtime")  # not the user's home
    run([i.python, "-m", "ipykernel", "install", "--sys-prefix", "--name", "pedesis-venv",
         "--display-name", "Python (pedesis)"], cwd=i.home, env=env)
    spec = json.loads((i.venv / "share/jupyter/kernels/pedesis-venv/kernel.json").read_text())
    assert spec["argv"][0] == str(i.python)
    # the kernel started from its spec by a Jupyter outside the venv (Debian's, as a
    # JupyterHub's would be), told where the venv's kernels are, and asked what it imports
    env["JUPYTER_PATH"] = str(i.venv / "share" / "jupyter")
    script = """
import json, sys
from jupyter_client.manager import start_new_kernel
km, kc = start_new_kernel(kernel_name="pedesis-venv", startup_timeout=60)
out = []
try:
    reply = kc.execute_interactive(
        "import sys, pedesis; print(sys.prefix, pedesis.__file__, pedesis.__version__)",
        timeout=60, output_hook=lambda m: out.append(m["content"].get("text", "")))
    print(json.dumps({"status": reply["content"]["status"], "out": "".join(out)}))
finally:
    kc.stop_channels()
    km.shutdown_kernel(now=True)
"""
    result = json.loads(run([SYSTEM_PYTHON, "-c", script], cwd=i.home, env=env,
                            timeout=120).stdout.splitlines()[-1])
    assert result["status"] == "ok", result
    prefix, module, version = result["out"].split()
    assert Path(prefix) == i.venv and Path(module).parent == i.site / "pedesis", result


def test_uninstall_leaves_nothing(installed):  # (the last: the others need the install)
    i = installed
    run([i.python, "-m", "pip", "uninstall", "-y", "pedesis"], cwd=i.home)
    left = [p.name for p in i.site.iterdir() if p.name.lower().startswith("pedesis")]
    assert not left, f"left in {i.site}: {left}"
    assert not (i.venv / "bin" / "pedesis").exists()
    r = run([i.python, "-c", "import pedesis"], cwd=i.home, check=False)
    assert r.returncode != 0 and "No module named 'pedesis'" in r.stderr
