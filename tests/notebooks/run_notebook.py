"""Executes an example notebook as a user's Jupyter would (Debian's nbclient and
ipykernel), headless, in a scratch directory, then writes its HTML (nbconvert) for the
browser check (inline_view_check.mjs). Fails on any cell's error, on an inline view over
its size limit, or on a notebook slower than a minute.

    run_notebook.py NOTEBOOK SCRATCH_DIR OUT.html
"""
import pathlib
import shutil
import sys
import time

import nbformat
from nbclient import NotebookClient
from nbconvert import HTMLExporter

INLINE_LIMIT = 5_000_000  # bytes of one inline view (pedesis.show's default)
TIME_LIMIT = 60.0         # seconds for the whole notebook

notebook, scratch, html_out = map(pathlib.Path, sys.argv[1:4])
shutil.rmtree(scratch, ignore_errors=True)
scratch.mkdir(parents=True)
nb = nbformat.read(notebook, as_version=4)
start = time.monotonic()
NotebookClient(nb, timeout=120, kernel_name="python3",
               resources={"metadata": {"path": str(scratch)}}).execute()
seconds = time.monotonic() - start
nbformat.write(nb, scratch / notebook.name)

failures = []
views = 0
for k, cell in enumerate(nb.cells):
    for out in cell.get("outputs", []):
        if out.get("output_type") == "error":
            failures.append(f"cell {k}: {out.get('ename')}: {out.get('evalue')}")
        page = out.get("data", {}).get("text/html", "")
        if "<iframe" in page or "<video" in page:
            views += 1
            size = len(page.encode())
            print(f"{notebook.name}: cell {k}: inline {'view' if '<iframe' in page else 'movie'} "
                  f"of {size / 1e6:.2f} MB")
            if size > INLINE_LIMIT:
                failures.append(f"cell {k}: an inline output of {size} bytes (limit {INLINE_LIMIT})")
if views == 0:
    failures.append("no cell shows a run inline")
print(f"{notebook.name}: executed in {seconds:.1f} s")
if seconds > TIME_LIMIT:
    failures.append(f"the notebook took {seconds:.0f} s (limit {TIME_LIMIT:.0f})")

body, _ = HTMLExporter().from_notebook_node(nb)
html_out.write_text(body, encoding="utf-8")
print(f"{notebook.name}: HTML of {len(body.encode()) / 1e6:.2f} MB at {html_out}")
for f in failures:
    print("FAILED:", f)
sys.exit(1 if failures else 0)
