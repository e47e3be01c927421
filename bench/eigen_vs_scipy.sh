#!/usr/bin/env bash
# jointid beside scipy on the same matrices, at equal threads, as whole processes and as the
# eigensolution alone: the lowest 20 modes of a clamped-free steel cantilever of 5 000 and
# 50 000 elements (N = 1e4 and 1e5, banded) and the lowest 12 elastic modes of the free-free
# 3D laps of bench/lap-solid.toml (N = 23,958) and bench/lap-solid-212k.toml (N = 212,562),
# and of a lap made by another code (hex43k: bench/lap3d/export.py, fe3d.py's 20-node
# hexahedra tied at three bolt patches, open faces between them, N = 43,074), six rigid-body
# modes each.
#
# Every timed run is its own process, runs interleaved, REPEAT of each at every thread count
# of THREADS (RAYON_NUM_THREADS; OMP/OPENBLAS/MKL_NUM_THREADS, and scipy's Matrix Market
# reader's threads):
# - whole process, jointid: `jointid simulate --model MODEL/model.toml --modes COUNT --out
#   X.csv`: reads the external model (K.mtx, M.mtx, every dK/dp, dofs.csv), checks it
#   (symmetry, sizes, M positive definite, the rigid-body count), solves, writes every DOF of
#   every mode (one CSV line per mode and DOF);
# - whole process, scipy (bench/eigen_vs_scipy.py with MODEL and OUT): reads the same files
#   (scipy.io.mmread), assembles K(p) and M(p), eigsh in shift-invert mode at jointid's shift
#   with one of three operators (eigsh's SuperLU, SuperLU under minimum degree, LAPACK's
#   banded Cholesky), writes the modes (np.savetxt, a line per DOF); its solve time is the
#   eigen-only split;
# - eigen only, jointid: `eigen_bench solve` (examples/eigen_bench.rs) on K(p), M(p) exported
#   beforehand, the solve timed inside the process, with the residuals.
# A chain has no whole-process run of jointid: exported as an external model (with a 1e-300
# N/m tip spring as its parameter, which leaves K bitwise unchanged) it is refused by the
# rigid-body check, whose tolerance (1e-14 max K_jj / M_jj, 487 Hz on the 1e4 cantilever)
# lies above its first modes (src/model/matrices/build.rs); scipy's whole process reads that
# exported model all the same.
# Prints the table of bench/eigen_table.py: medians, their ratio, peak resident memory
# (/usr/bin/time), the largest relative residual ||K y - lambda M y|| / ||K y|| (jointid's
# with its rounding floor, src/modal/residual.rs), and the largest relative difference of
# jointid's frequencies (from its CSV) from scipy's.
# Usage: bash bench/eigen_vs_scipy.sh [REPEAT] [CASES]   (CASES: any of chain1e4 chain1e5
# solid solid212k hex43k; the default leaves out solid212k, about 2 minutes a repeat and 3 GB,
# and hex43k)
# Environment: THREADS (default "1 2"), VARIANTS (scipy's, default "superlu mmd banded";
# solid212k leaves out superlu: 147 s and 7.2 GB on a model of this size), LOG (a file to
# keep the run log in).
set -euo pipefail
cd "$(dirname "$0")/.."
repeat=${1:-5}
cases=${2:-"chain1e4 chain1e5 solid"}
threads_list=${THREADS:-"1 2"}
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
cargo build --release --locked --example eigen_bench --bin jointid >&2
target=${CARGO_TARGET_DIR:-target}
bench=$target/release/examples/eigen_bench
jointid=$target/release/jointid
python=$(bash scripts/python-env.sh)
declare -A model
for case in $cases; do
    mkdir -p "$dir/$case"
    case $case in
        chain1e4) $bench export chain 5000 "$dir/$case" >&2 ;;
        chain1e5) $bench export chain 50000 "$dir/$case" >&2 ;;
        solid) $jointid solid bench/lap-solid.toml --out "$dir/$case/model" >&2 ;;
        solid212k) $jointid solid bench/lap-solid-212k.toml --out "$dir/$case/model" >&2 ;;
        hex43k) "$python" bench/lap3d/export.py "$dir/$case/model" --interface bolts \
            --dx 10e-3 >&2 ;;
        *) echo "unknown case $case" >&2; exit 2 ;;
    esac
    model[$case]="$dir/$case/model"
    case $case in
        solid* | hex*) $bench export model "${model[$case]}/model.toml" "$dir/$case" >&2 ;;
    esac
done
log="$dir/runs.txt"
# One line a run: case threads solver kind wall_s solve_s rss_kb residual floor frequencies
run() { # case threads solver kind csv command...
    local case=$1 threads=$2 solver=$3 kind=$4 csv=$5
    shift 5
    local out
    out=$(RAYON_NUM_THREADS=$threads OMP_NUM_THREADS=$threads OPENBLAS_NUM_THREADS=$threads \
        MKL_NUM_THREADS=$threads /usr/bin/time -f "rss_kb %M wall_s %e" "$@" 2>&1) || {
        echo "$case $threads $solver failed: $out" >&2
        return
    }
    local hz=""
    if [ "$csv" != - ]; then # jointid's CSV: the frequency of each mode, at its first line
        hz=$(awk -F, 'NR > 1 && !seen[$1]++ {printf "%s%s", sep, $2; sep = ","}' "$csv")
        rm -f "$csv"
    fi
    echo "$out" | awk -v c="$case" -v t="$threads" -v s="$solver" -v k="$kind" -v hz="$hz" '
        /^time_s/ {time = $2} /^rss_kb/ {rss = $2; wall = $4} /^skipped/ {skip = 1}
        /^mode/ {for (i = 1; i < NF; i++) {
                     if ($i == "relative_residual" && $(i + 1) > worst) worst = $(i + 1)
                     if ($i == "floor" && $(i + 1) > floor) floor = $(i + 1)}
                 if (hz == "" || from_log) {hz = hz sep $4; sep = ","; from_log = 1}}
        END {if (!skip) printf "%s %s %s %s %s %s %s %s %s %s\n", c, t, s, k, wall, \
                 (time == "" ? "-" : time), rss, worst + 0, floor + 0, (hz == "" ? "-" : hz)}' >> "$log"
}
for r in $(seq "$repeat"); do
    for case in $cases; do
        count=20
        variants=${VARIANTS:-"superlu mmd banded"}
        case $case in
            solid | hex43k) count=12 ;;
            solid212k) count=12; variants=${VARIANTS:-"mmd banded"} ;;
        esac
        for threads in $threads_list; do
            echo "run $r/$repeat: $case, $threads thread(s) ($(cut -d' ' -f1-3 /proc/loadavg))" >&2
            case $case in
                solid* | hex*) run "$case" "$threads" jointid whole "$dir/out.csv" $jointid simulate \
                    --model "${model[$case]}/model.toml" --modes $count --out "$dir/out.csv" ;;
            esac
            run "$case" "$threads" jointid eigen - $bench solve "$dir/$case" $count
            for variant in $variants; do
                run "$case" "$threads" "scipy-$variant" whole - "$python" bench/eigen_vs_scipy.py \
                    "$dir/$case" $count $variant "${model[$case]}" "$dir/out-scipy.csv"
                rm -f "$dir/out-scipy.csv"
            done
        done
    done
done
echo "load average at the end: $(cut -d' ' -f1-3 /proc/loadavg)"
if [ -n "${LOG:-}" ]; then cp "$log" "$LOG"; fi # keep the run log where LOG says
"$python" bench/eigen_table.py "$log"
