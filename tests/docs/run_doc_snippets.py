"""Runs the ```python blocks of a Markdown document as a reader would: in order, in one
session, in a fresh directory outside the repository (so that no path may lean on the
source tree). Fails with the block's line in the document and the error.

    /usr/bin/python3 tests/docs/run_doc_snippets.py docs/python.md
"""
import contextlib
import io
import os
import pathlib
import re
import sys
import tempfile
import traceback

BLOCK = re.compile(r"^```python\n(.*?)^```", re.S | re.M)


def blocks(text):
    for match in BLOCK.finditer(text):
        yield text.count("\n", 0, match.start()) + 2, match.group(1)


def main(doc):
    text = pathlib.Path(doc).read_text(encoding="utf-8")
    found = list(blocks(text))
    if not found:
        print(f"{doc}: no python blocks", file=sys.stderr)
        return 1
    namespace = {"__name__": "__main__"}
    with tempfile.TemporaryDirectory(prefix="pedesis_doc_") as scratch:
        os.chdir(scratch)
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


if __name__ == "__main__":
    sys.exit(max(main(d) for d in sys.argv[1:]) if len(sys.argv) > 1 else 2)
