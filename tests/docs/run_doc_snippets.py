"""Runs the ```python blocks of a Markdown document as a reader would: in order, in one
session, in a fresh directory outside the repository (so that no path may lean on the
source tree). Fails with the block's line in the document and the error.

    /usr/bin/python3 tests/docs/run_doc_snippets.py docs/python.md
    /usr/bin/python3 tests/docs/run_doc_snippets.py README.md \
        --setup 'pedesis run SRC/examples/course_1_relaxation.toml --out runs/demo'

--setup runs a shell command in that directory first (the run directories a document
takes as made, as `make demo` makes runs/demo); SRC in it is the source tree, and
`pedesis` is $PEDESIS_BIN.
"""
import contextlib
import io
import os
import pathlib
import re
import shlex
import subprocess
import sys
import tempfile
import traceback

BLOCK = re.compile(r"^```python\n(.*?)^```", re.S | re.M)


def blocks(text):
    for match in BLOCK.finditer(text):
        yield text.count("\n", 0, match.start()) + 2, match.group(1)


def prepare(commands):
    source = str(pathlib.Path(__file__).resolve().parents[2])
    binary = os.environ.get("PEDESIS_BIN", "pedesis")
    for command in commands:
        words = [w.replace("SRC", source) for w in shlex.split(command)]
        if words and words[0] == "pedesis":
            words[0] = binary
        done = subprocess.run(words, capture_output=True, text=True)
        if done.returncode != 0:
            print(f"setup {command!r} failed:\n{done.stderr}", file=sys.stderr)
            return False
    return True


def main(doc, setup=()):
    text = pathlib.Path(doc).read_text(encoding="utf-8")
    found = list(blocks(text))
    if not found:
        print(f"{doc}: no python blocks", file=sys.stderr)
        return 1
    namespace = {"__name__": "__main__"}
    with tempfile.TemporaryDirectory(prefix="pedesis_doc_") as scratch:
        os.chdir(scratch)
        if not prepare(setup):
            return 1
        for line, code in found:
            out = io.StringIO()
            try:
                with contextlib.redirect_stdout(out):
                    exec(compile(code, f"{doc}:{line}", "exec"), namespace)
            except Exception:
                print(f"{doc}, the block at line {line} failed:\n{code}", file=sys.stderr)
                traceback.print_exc()
                return 1
            print(f"{doc}:{line}: ran ({len(code.splitlines())} lines)")
    return 0


def command_line(description):
    """The documents and --setup commands, as this runner and run_doc_console.py take them."""
    import argparse
    parser = argparse.ArgumentParser(description=description)
    parser.add_argument("documents", nargs="+")
    parser.add_argument("--setup", action="append", default=[],
                        help="a command to run in the scratch directory first")
    return parser.parse_args()


if __name__ == "__main__":
    arguments = command_line("Run a document's Python blocks.")
    sys.exit(max(main(d, arguments.setup) for d in arguments.documents))
