#!/usr/bin/env bash
# Builds the Python package (python/, pyo3 + maturin, release) and installs it into the
# project's venv (.venv, made by scripts/python-env.sh with numpy, scipy, pyuff, maturin and
# pytest from PyPI). Prints the interpreter to use.
#   usage: PY=$(bash scripts/python-package.sh)
set -euo pipefail
cd "$(dirname "$0")/.."
PY=$(bash scripts/python-env.sh)
PATH="$(dirname "$PY"):$PATH" "$PY" -m pip install --quiet --disable-pip-version-check --no-build-isolation --no-deps \
    --force-reinstall ./python >&2
echo "$PY"
