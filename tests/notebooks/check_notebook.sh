#!/bin/sh
# One example notebook, as a user's Jupyter runs it and as a browser shows the result:
# executed headless (run_notebook.py: no error, each inline output under 5 MB, under a
# minute), then its HTML opened in chromium (inline_view_check.mjs: every inline view
# draws its particles).
#   check_notebook.sh PYTHON NODE WEB_VIEWER_DIR NOTEBOOK SCRATCH_DIR
set -e
python=$1 node=$2 web=$3 notebook=$4 scratch=$5
here=$(dirname "$0")
"$python" "$here/run_notebook.py" "$notebook" "$scratch" "$scratch.html"
"$node" "$here/inline_view_check.mjs" "$web" "$scratch.html" 2000
