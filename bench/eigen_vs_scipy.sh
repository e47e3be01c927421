#!/usr/bin/env bash
# Lowest 20 modes of a 1e5-DOF banded beam model (a clamped-free cantilever of 50 000
# elements), jointid's shift-invert Lanczos beside scipy's eigsh(sigma=0) on the same matrices,
# exported by examples/eigen_bench.rs. Usage: bash bench/eigen_vs_scipy.sh [ELEMENTS] [REPEAT]
set -euo pipefail
cd "$(dirname "$0")/.."
elements=${1:-50000}
repeat=${2:-5}
count=20
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
cargo build --release --example eigen_bench
ours=$(./target/release/examples/eigen_bench "$elements" "$count" "$repeat" "$dir")
echo "$ours" | grep -v '^frequencies_hz'
python=$(bash scripts/python-env.sh)
"$python" bench/eigen_vs_scipy.py "$dir" "$count" "$repeat" \
    $(echo "$ours" | grep '^frequencies_hz' | cut -d' ' -f2-)
