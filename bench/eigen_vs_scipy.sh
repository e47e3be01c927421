#!/usr/bin/env bash
# Lowest 20 modes of a 1e5-DOF banded beam model (a clamped-free cantilever of 50 000
# elements), jointid's shift-invert Lanczos beside scipy's eigsh(sigma=0) on the same matrices,
# exported by examples/eigen_bench.rs; scipy on 1 and on 2 BLAS threads (jointid's solver is
# sequential). Usage: bash bench/eigen_vs_scipy.sh [ELEMENTS] [REPEAT]
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
# jointid's solver runs on one thread: scipy on one BLAS/OpenMP thread is the like-for-like
# comparison; two threads (both cores here) for reference.
for threads in 1 2; do
    echo "scipy with $threads BLAS/OpenMP thread(s):"
    OMP_NUM_THREADS=$threads OPENBLAS_NUM_THREADS=$threads MKL_NUM_THREADS=$threads \
        "$python" bench/eigen_vs_scipy.py "$dir" "$count" "$repeat" \
        $(echo "$ours" | grep '^frequencies_hz' | cut -d' ' -f2-)
done
