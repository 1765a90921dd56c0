"""The build of the `pedesis` Python package (pyproject.toml; docs/python.md#installing).

setuptools is the backend because it is the one PEP 517 backend Debian 12 ships that can
drive a CMake project (python3-setuptools; scikit-build-core and scikit-build are not
in Debian 12, meson-python would need the build rewritten for Meson), so that
`pip install --no-build-isolation .` works offline from Debian's packages alone. The
build step is CMake's own build of the project (CMakeLists.txt): for the interpreter
that runs this file, the targets `_pedesis` (the extension) and `pedesis` (the CLI),
which go into the wheel as pedesis/_pedesis*.so and pedesis/bin/pedesis; the `pedesis`
console script (pedesis/_binary.py) runs the latter.

Where things go: CMake's tree is build-py/cmake-<SOABI>/ (kept, so that a second install
only rebuilds what changed), setuptools' is build-py/setuptools/; both git-ignored.

Environment variables:
  PEDESIS_CMAKE_BUILD_DIR  an already-built CMake tree (e.g. build/ of `make build`) to
                           package instead of building: its options must be the ones
                           this build would use (checked against its CMakeCache.txt),
                           its _pedesis module must be for this interpreter's ABI, and
                           it must be built from the same sources (not checked: build it
                           first). Nothing is built in it.
  PEDESIS_GRAPHICS         ON/OFF: `pedesis render` and `view` (Cairo, cpp-httplib);
                           default ON where pkg-config finds both.
  PEDESIS_CMAKE_ARGS       more arguments for CMake's configure step (-DNAME=VALUE ...).
  CMAKE_BUILD_PARALLEL_LEVEL  compile jobs (default: the number of CPUs).
"""
import os
import re
import shlex
import shutil
import subprocess
import sys
import sysconfig
from pathlib import Path

from setuptools import Extension, find_packages, setup
from setuptools.command.build_ext import build_ext
from setuptools.command.build_py import build_py

ROOT = Path(__file__).resolve().parent
WORK = ROOT / "build-py"
# pybind11 supports numpy 2 from 2.12 on; a module built with an older one needs numpy 1
PYBIND11_NUMPY2 = (2, 12)


def project_version():
    """The version of CMakeLists.txt's project(), the one `pedesis --version` prints."""
    text = (ROOT / "CMakeLists.txt").read_text()
    found = re.search(r"project\(\s*pedesis\s+VERSION\s+([0-9]+(?:\.[0-9]+)*)", text)
    if not found:
        sys.exit("setup.py: no project(pedesis VERSION ...) in CMakeLists.txt")
    return found.group(1)


def version_tuple(text):
    return tuple(int(n) for n in re.findall(r"\d+", text)[:3])


def pybind11_config_version(cmake_dir):
    path = Path(cmake_dir) / "pybind11ConfigVersion.cmake"
    if not path.is_file():
        return None
    found = re.search(r'set\(PACKAGE_VERSION "([^"]+)"\)', path.read_text())
    return found.group(1) if found else None


def pybind11_of_environment():
    """(version, CMake dir to pass or None): pip's pybind11 where this interpreter has it
    (the isolated build's, from PyPI), else the one CMake finds by itself (Debian's
    pybind11-dev)."""
    try:
        import pybind11
        return pybind11.__version__, pybind11.get_cmake_dir()
    except ImportError:
        pass
    for prefix in (sys.prefix, "/usr/local", "/usr"):
        for sub in ("lib/cmake/pybind11", "share/cmake/pybind11"):
            version = pybind11_config_version(Path(prefix) / sub)
            if version:
                return version, None
    return None, None


def on_off(value):
    value = str(value).strip().upper()
    if value in ("ON", "TRUE", "YES", "Y", "1"):
        return "ON"
    if value in ("OFF", "FALSE", "NO", "N", "0", "") or value.endswith("NOTFOUND"):
        return "OFF"
    return None


def graphics():
    setting = os.environ.get("PEDESIS_GRAPHICS")
    if setting:
        if on_off(setting) is None:
            sys.exit(f"setup.py: PEDESIS_GRAPHICS={setting}: say ON or OFF")
        return on_off(setting)
    pkg_config = shutil.which("pkg-config")
    found = pkg_config and subprocess.run(
        [pkg_config, "--exists", "cairo", "cpp-httplib"]).returncode == 0
    if not found:
        print("setup.py: pkg-config finds no cairo or cpp-httplib: building without "
              "`pedesis render` and `view` (apt-get install libcairo2-dev libcpp-httplib-dev "
              "libssl-dev, or make deps)", file=sys.stderr)
    return "ON" if found else "OFF"


def cmake_options():
    """The cache entries this build sets, and the rest of PEDESIS_CMAKE_ARGS."""
    options = {
        "CMAKE_BUILD_TYPE": "Release",
        "PEDESIS_TESTS": "OFF",
        "PEDESIS_PYTHON_MODULE": "ON",
        "PEDESIS_SANITIZE": "OFF",
        "PEDESIS_FUZZ": "OFF",
        "PEDESIS_CUDA": "OFF",
        "PEDESIS_MPI": "ON",
        "PEDESIS_GRAPHICS": graphics(),
        # the interpreter of the environment (CMakeLists.txt builds the module for
        # PEDESIS_PYTHON, Debian's /usr/bin/python3 unless told)
        "PEDESIS_PYTHON": sys.executable,
        "CMAKE_CXX_FLAGS": os.environ.get("CXXFLAGS", ""),
    }
    pybind11_dir = PYBIND11[1]
    if pybind11_dir:
        options["pybind11_DIR"] = pybind11_dir
    rest = []
    for arg in shlex.split(os.environ.get("PEDESIS_CMAKE_ARGS", "")):
        found = re.fullmatch(r"-D([A-Za-z0-9_]+)(?::[A-Z]+)?=(.*)", arg)
        if found:
            options[found.group(1)] = found.group(2)
        else:
            rest.append(arg)
    return options, rest


def read_cache(tree):
    values = {}
    for line in (tree / "CMakeCache.txt").read_text().splitlines():
        found = re.match(r"([A-Za-z0-9_.+-]+):[A-Z]+=(.*)$", line)
        if found:
            values[found.group(1)] = found.group(2)
    return values


def extension_name():
    return "_pedesis" + sysconfig.get_config_var("EXT_SUFFIX")


def prebuilt_tree():
    """PEDESIS_CMAKE_BUILD_DIR, checked: the outputs are what this build would make."""
    setting = os.environ.get("PEDESIS_CMAKE_BUILD_DIR")
    if not setting:
        return None
    tree = Path(setting).resolve()
    if not (tree / "CMakeCache.txt").is_file():
        sys.exit(f"setup.py: PEDESIS_CMAKE_BUILD_DIR={setting} is not a CMake build tree")
    cache = read_cache(tree)
    options, _ = cmake_options()
    differ = []
    for name, wanted in options.items():
        if name in ("PEDESIS_TESTS", "PEDESIS_PYTHON", "pybind11_DIR"):
            continue  # the tests are not packaged; the other two are compared below
        have = cache.get(name, "")
        switch = name.startswith("PEDESIS_") and on_off(wanted) is not None  # ON/OFF options
        same = on_off(wanted) == on_off(have) if switch else wanted == have
        if not same:
            differ.append(f"{name} is {have!r}, this build's is {wanted!r}")
    # the module's ABI: the same headers, the file named for this interpreter
    include = sysconfig.get_paths()["include"]
    if cache.get("_Python3_INCLUDE_DIR") != include:
        differ.append(f"its Python headers are {cache.get('_Python3_INCLUDE_DIR')!r}, this "
                      f"interpreter's are {include!r}")
    module = tree / "python" / "pedesis" / extension_name()
    if not module.is_file():
        differ.append(f"it has no {module} (built for another Python, or not built)")
    if not (tree / "pedesis").is_file():
        differ.append(f"it has no {tree / 'pedesis'} (not built)")
    theirs = pybind11_config_version(cache.get("pybind11_DIR", ""))
    if theirs != PYBIND11[0]:
        differ.append(f"it used pybind11 {theirs}, this environment has {PYBIND11[0]}")
    if differ:
        sys.exit(f"setup.py: PEDESIS_CMAKE_BUILD_DIR={setting} is not the build this would "
                 f"make: " + "; ".join(differ))
    return tree


def cmake_build():
    cmake = shutil.which("cmake")
    if not cmake:
        sys.exit("setup.py: no cmake on PATH: install CMake 3.22 or later and pedesis' C++ "
                 "dependencies (on Debian: make deps, or scripts/install-deps.sh)")
    options, rest = cmake_options()
    tree = WORK / f"cmake-{sysconfig.get_config_var('SOABI') or 'python'}"
    configure = [cmake, "-S", str(ROOT), "-B", str(tree), *rest,
                 *(f"-D{name}={value}" for name, value in options.items())]
    jobs = os.environ.get("CMAKE_BUILD_PARALLEL_LEVEL") or str(os.cpu_count() or 1)
    build = [cmake, "--build", str(tree), "--target", "_pedesis", "pedesis", "--parallel", jobs]
    for command in (configure, build):
        print("setup.py:", shlex.join(command), file=sys.stderr, flush=True)
        subprocess.run(command, check=True)
    return tree


class BuildPy(build_py):
    """The package's Python files, and pedesis/_version.py (the CMake build writes the same
    file into build/python/pedesis)."""

    def run(self):
        # a file deleted from the sources must not stay in the wheel
        shutil.rmtree(Path(self.build_lib) / "pedesis", ignore_errors=True)
        super().run()
        target = Path(self.build_lib) / "pedesis" / "_version.py"
        target.write_text(f'__version__ = "{VERSION}"\n')


class BuildCMake(build_ext):
    """The extension and the CLI from CMake, copied into the package: _pedesis*.so and
    bin/pedesis."""

    def build_extension(self, ext):
        if self.inplace:
            sys.exit("setup.py: editable installs are not supported: use `make python` for a "
                     "package that follows the build tree (docs/python.md)")
        tree = prebuilt_tree() or cmake_build()
        module = Path(self.get_ext_fullpath(ext.name))
        module.parent.mkdir(parents=True, exist_ok=True)
        shutil.copy2(tree / "python" / "pedesis" / extension_name(), module)
        program = module.parent / "bin" / "pedesis"
        program.parent.mkdir(exist_ok=True)
        shutil.copy2(tree / "pedesis", program)


VERSION = project_version()
PYBIND11 = pybind11_of_environment()  # what a build here uses: (version, CMake dir or None)
# the pybind11 of the module that goes into the wheel: the prebuilt tree's, or that one
BUILT_WITH = PYBIND11[0]
if os.environ.get("PEDESIS_CMAKE_BUILD_DIR"):
    _cache = Path(os.environ["PEDESIS_CMAKE_BUILD_DIR"]) / "CMakeCache.txt"
    if _cache.is_file():
        BUILT_WITH = pybind11_config_version(read_cache(_cache.parent).get("pybind11_DIR", ""))
NUMPY = "numpy"
if BUILT_WITH and version_tuple(BUILT_WITH) < PYBIND11_NUMPY2:
    NUMPY = "numpy<2"  # docs/python.md#installing: numpy 2 needs pybind11 2.12 or later

WORK.mkdir(exist_ok=True)
setup(
    version=VERSION,
    install_requires=[NUMPY],
    package_dir={"": "python"},
    packages=find_packages("python", include=["pedesis", "pedesis.*"]),
    ext_modules=[Extension("pedesis._pedesis", sources=[])],
    cmdclass={"build_py": BuildPy, "build_ext": BuildCMake},
    options={
        "build": {"build_base": str(WORK / "setuptools")},
        "egg_info": {"egg_base": str(WORK)},
    },
    zip_safe=False,
)
