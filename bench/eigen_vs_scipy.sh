#!/usr/bin/env bash
# jointid's sparse eigensolver beside scipy's eigsh on the same matrices, at equal threads:
# the lowest 20 modes of a clamped-free steel cantilever of 5 000 and 50 000 elements
# (N = 1e4 and 1e5, banded) and the lowest 12 elastic modes of the free-free 3D lap of
# bench/lap-solid.toml (N = 23,958, six rigid-body modes). K and M are exported as Matrix
# Market by examples/eigen_bench.rs; every timed run is its own process (jointid's
# `eigen_bench solve`, scipy's bench/eigen_vs_scipy.py in three variants: eigsh's SuperLU,
# SuperLU with minimum degree, LAPACK's banded Cholesky), runs interleaved, REPEAT of each
# at 1 and at 2 threads (RAYON_NUM_THREADS; OMP/OPENBLAS/MKL_NUM_THREADS). Prints the table of
# bench/eigen_table.py: medians of the solve times (the reading of the files excluded), their
# ratio, peak resident memory (/usr/bin/time, the whole process) and the largest relative
# residual ||K y - lambda M y|| / ||K y|| over the modes (jointid's with its rounding floor,
# eps || |K| |y| || / ||K y||: see src/modal/residual.rs).
# Usage: bash bench/eigen_vs_scipy.sh [REPEAT] [CASES]   (CASES: any of chain1e4 chain1e5 solid
# solid212k; the default leaves out solid212k, the lap of 212,562 DOFs of
# bench/lap-solid-212k.toml: about 3 minutes a repeat, 2.4 GB)
set -euo pipefail
cd "$(dirname "$0")/.."
repeat=${1:-5}
cases=${2:-"chain1e4 chain1e5 solid"}
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
cargo build --release --locked --example eigen_bench --bin jointid >&2
bench=./target/release/examples/eigen_bench
python=$(bash scripts/python-env.sh)
for case in $cases; do
    mkdir -p "$dir/$case"
    case $case in
        chain1e4) $bench export chain 5000 "$dir/$case" >&2 ;;
        chain1e5) $bench export chain 50000 "$dir/$case" >&2 ;;
        solid)
            ./target/release/jointid solid bench/lap-solid.toml --out "$dir/solid-model" >&2
            $bench export model "$dir/solid-model/model.toml" "$dir/$case" >&2 ;;
        solid212k)
            ./target/release/jointid solid bench/lap-solid-212k.toml --out "$dir/solid212k-model" >&2
            $bench export model "$dir/solid212k-model/model.toml" "$dir/$case" >&2 ;;
        *) echo "unknown case $case" >&2; exit 2 ;;
    esac
done
log="$dir/runs.txt"
run() { # case threads solver command...
    local case=$1 threads=$2 solver=$3
    shift 3
    local out
    out=$(RAYON_NUM_THREADS=$threads OMP_NUM_THREADS=$threads OPENBLAS_NUM_THREADS=$threads \
        MKL_NUM_THREADS=$threads /usr/bin/time -f "rss_kb %M" "$@" 2>&1) || {
        echo "$case $threads $solver failed: $out" >&2
        return
    }
    echo "$out" | awk -v c="$case" -v t="$threads" -v s="$solver" '
        /^time_s/ {time = $2} /^rss_kb/ {rss = $2} /^skipped/ {skip = 1}
        /^mode/ {for (i = 1; i < NF; i++) {
                     if ($i == "relative_residual" && $(i + 1) > worst) worst = $(i + 1)
                     if ($i == "floor" && $(i + 1) > floor) floor = $(i + 1)}
                 if ($2 == 1) f1 = $4}
        END {if (!skip) printf "%s %s %s %s %s %s %s %s\n", c, t, s, time, rss, worst + 0, f1, floor + 0}' >> "$log"
}
for r in $(seq "$repeat"); do
    for case in $cases; do
        count=20
        variants="superlu mmd banded"
        [ "$case" = solid ] && count=12
        # eigsh's own SuperLU took 147 s and 7.2 GB on a model of this size: left out there.
        [ "$case" = solid212k ] && count=12 && variants="mmd banded"
        for threads in 1 2; do
            echo "run $r/$repeat: $case, $threads thread(s)" >&2
            run "$case" "$threads" jointid $bench solve "$dir/$case" $count
            for variant in $variants; do
                run "$case" "$threads" "scipy-$variant" "$python" bench/eigen_vs_scipy.py \
                    "$dir/$case" $count $variant
            done
        done
    done
done
echo "load average at the end: $(cut -d' ' -f1-3 /proc/loadavg)"
"$python" bench/eigen_table.py "$log"
