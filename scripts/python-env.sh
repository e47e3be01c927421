#!/usr/bin/env bash
# The Python peers of the benchmark scripts (numpy, scipy, pyuff, sdypy-EMA) and what builds and
# tests the Python package (maturin, pytest), installed from
# PyPI into .venv beside the project, once. Prints the interpreter to use.
#   usage: PY=$(bash scripts/python-env.sh)
set -euo pipefail
cd "$(dirname "$0")/.."
venv=.venv
if [ ! -x "$venv/bin/python" ] || ! "$venv/bin/python" -c "import numpy, scipy, pyuff, sdypy.EMA, pytest, maturin" 2>/dev/null; then
  python3 -m venv "$venv" >&2
  "$venv/bin/python" -m pip install --quiet --disable-pip-version-check \
    -r scripts/python-requirements.txt >&2
fi
echo "$PWD/$venv/bin/python"
