"""Where the pedesis command-line program is, and the `pedesis` command of an installed
package.

`binary()` is what the Python side runs when it needs the CLI (pedesis.show draws with
`pedesis render`/`view`). `main()` is the `pedesis` console script that `pip install`
puts into the environment's bin/: it runs the binary bundled in the package
(pedesis/bin/pedesis, docs/python.md#installing) with the environment's interpreter
and package for the commands that run Python (`analyze`, `validate`).
"""
import os
import shutil
import sys
from pathlib import Path

_PACKAGE = Path(__file__).resolve().parent


def _executable(path) -> bool:
    return os.path.isfile(path) and os.access(path, os.X_OK)


def binary() -> str:
    """The path of the pedesis binary: the one bundled in the installed package
    (pedesis/bin/pedesis), else $PEDESIS_BINARY (or $PEDESIS_BIN, which CTest sets), else
    the build tree's (build/pedesis, next to build/python/pedesis), else `pedesis` on
    PATH. Raises FileNotFoundError, saying where it looked, when there is none."""
    bundled = _PACKAGE / "bin" / "pedesis"
    if _executable(bundled):
        return str(bundled)
    for variable in ("PEDESIS_BINARY", "PEDESIS_BIN"):
        value = os.environ.get(variable)
        if value:
            if not _executable(value):
                raise FileNotFoundError(f"{variable}={value} is not an executable file")
            return value
    build_tree = _PACKAGE.parent.parent / "pedesis"
    if _executable(build_tree):
        return str(build_tree)
    found = shutil.which("pedesis")
    if found:
        return found
    raise FileNotFoundError(
        f"no pedesis binary: not bundled in {_PACKAGE} (a package installed with pip has it), "
        f"no $PEDESIS_BINARY, no build tree's {build_tree}, none on PATH")


def main():
    """The `pedesis` console script: replaces this process with the binary. The commands
    that run `python -m pedesis.analyze` or `.validate` get this interpreter and the
    folder of this package (PEDESIS_PYTHON, PEDESIS_PYTHONPATH, unless already set): the
    paths built into the binary are those of the build, not of the install."""
    path = binary()
    if os.path.realpath(path) == os.path.realpath(sys.argv[0]):
        sys.exit(f"pedesis: {path} is this script itself, not the binary: reinstall the "
                 f"package or set PEDESIS_BINARY")
    env = dict(os.environ)
    env.setdefault("PEDESIS_PYTHON", sys.executable)
    env.setdefault("PEDESIS_PYTHONPATH", str(_PACKAGE.parent))
    os.execve(path, ["pedesis", *sys.argv[1:]], env)  # argv[0] as a shell gives it


if __name__ == "__main__":
    main()
