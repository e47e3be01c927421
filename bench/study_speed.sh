#!/usr/bin/env bash
# Whole-process speed of `jointid study` on the paper cell (bench/paper-cell.toml: case I,
# n 10, m 5, NF 5, inverse, uniform 4%, modes 1-4) beside the numpy peer
# (../shared/bench/numpy_baseline.py, single-threaded BLAS), runs interleaved so that both see
# the same machine load; medians of REPEAT runs.
#
# usage: bash bench/study_speed.sh [REPEAT [TRIALS [THREADS [BINARY...]]]]
#   defaults: 5 runs, 1e6 trials, 2 threads, ./target/release/jointid (built if missing).
#   Several binaries (e.g. a build of main beside this one) are timed in the same rounds.
# jointid's time is the wall time of the whole process: reading the study, solving the model,
# planning, the trials, the statistics and writing the CSV. numpy's is also the whole process
# (imports included), and its own timer of the trial loop alone is shown beside it.
set -euo pipefail
cd "$(dirname "$0")/.."
repeat=${1:-5}
trials=${2:-1000000}
threads=${3:-2}
shift $(($# < 3 ? $# : 3))
binaries=("$@")
if [ ${#binaries[@]} -eq 0 ]; then
    [ -x target/release/jointid ] || cargo build --release --locked
    binaries=(./target/release/jointid)
fi
python=$(bash scripts/python-env.sh)
numpy=../shared/bench/numpy_baseline.py
work=$(mktemp -d)
trap 'rm -rf "$work" bench/.speed-cell.toml' EXIT
sed "s/^trials = .*/trials = $trials/" bench/paper-cell.toml > bench/.speed-cell.toml
modes=4
now() { date +%s.%N; }

for ((r = 0; r < repeat; r++)); do
    for ((b = 0; b < ${#binaries[@]}; b++)); do
        t0=$(now)
        /usr/bin/time -f "%U %S" -o "$work/cpu" "${binaries[$b]}" study bench/.speed-cell.toml \
            --quiet --threads "$threads" --out "$work/out.$b.csv" > /dev/null
        t1=$(now)
        echo "$t0 $t1 $(cat "$work/cpu")" >> "$work/jointid.$b"
        if [ "$r" -eq 0 ] && [ "$b" -gt 0 ]; then
            cmp -s "$work/out.0.csv" "$work/out.$b.csv" \
                && echo "${binaries[$b]}: CSV identical to ${binaries[0]}" \
                || echo "${binaries[$b]}: CSV DIFFERS from ${binaries[0]}"
        fi
    done
    if [ -f "$numpy" ]; then
        t0=$(now)
        rate=$(OMP_NUM_THREADS=1 OPENBLAS_NUM_THREADS=1 "$python" "$numpy" "$trials" \
            | sed -n 's/^\([0-9.e+]*\) trial-modes\/s.*/\1/p')
        t1=$(now)
        echo "$t0 $t1 $rate" >> "$work/numpy"
    fi
done

"$python" - "$work" "$trials" "$modes" "$threads" "$repeat" "${binaries[@]}" <<'PY'
import os, statistics, sys
work, trials, modes, threads, repeat = sys.argv[1], int(sys.argv[2]), int(sys.argv[3]), sys.argv[4], sys.argv[5]
binaries = sys.argv[6:]
tm = trials * modes
def rows(name):
    return [list(map(float, l.split())) for l in open(os.path.join(work, name))]
print(f"paper cell, {trials} trials x {modes} modes, {threads} thread(s), median of {repeat} interleaved runs")
print(f"load average at the end: {open('/proc/loadavg').read().split()[0]}")
np_rate = None
if os.path.exists(os.path.join(work, "numpy")):
    r = rows("numpy")
    np_wall = statistics.median(t1 - t0 for t0, t1, _ in r)
    np_rate = tm / np_wall
    np_inner = statistics.median(x for _, _, x in r)
print(f"| program | wall s | CPU s (user + sys) | trial-modes/s, whole process | x numpy |")
print(f"|---|---|---|---|---|")
for b, path in enumerate(binaries):
    r = rows(f"jointid.{b}")
    wall = statistics.median(t1 - t0 for t0, t1, _, _ in r)
    cpu = statistics.median(u + s for _, _, u, s in r)
    ratio = f"{tm / wall / np_rate:.1f}" if np_rate else "-"
    print(f"| jointid study ({path}) | {wall:.3f} | {cpu:.3f} | {tm / wall:.3g} | {ratio} |")
if np_rate:
    print(f"| numpy_baseline.py (1 thread) | {np_wall:.3f} | - | {np_rate:.3g} (its trial loop alone: {np_inner:.3g}) | 1 |")
PY
