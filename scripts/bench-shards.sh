#!/usr/bin/env bash
# Wall time of a study run whole and as N local shards run side by side (all N processes at
# once, cores / N threads each, then `jointid merge`), interleaved in one run so that every
# configuration sees the same machine load; medians of REPEAT rounds. Every merged CSV is
# compared byte for byte with the whole run's.
#
#   scripts/bench-shards.sh [STUDY] [TRIALS] [REPEAT] [SHARDS...]
#   default: studies/paper-case-1.toml 100000 3 1 2 4 8
#
# Needs the release build (cargo build --release).
set -euo pipefail
cd "$(dirname "$0")/.."
STUDY=${1:-studies/paper-case-1.toml}
TRIALS=${2:-100000}
REPEAT=${3:-3}
shift $(( $# < 3 ? $# : 3 ))
SHARDS=("${@:-1 2 4 8}")
read -r -a SHARDS <<<"${SHARDS[*]}"
J=$PWD/target/release/jointid
CORES=$(nproc)
WORK=$(mktemp -d /tmp/jointid-bench-shards.XXXXXX)
trap 'rm -rf "$WORK"' EXIT
sed -e "s|^model = \"\\.\\./|model = \"$PWD/|" -e "s|^trials = .*|trials = $TRIALS|" \
    -e "s|^csv = .*|csv = \"$WORK/whole.csv\"|" "$STUDY" >"$WORK/s.toml"

now() { date +%s.%N; }
declare -A T
run_whole() { # threads
    local t0; t0=$(now)
    "$J" study "$WORK/s.toml" --threads "$1" --quiet --out "$WORK/whole-$1.csv" >/dev/null
    echo "$(now) - $t0" | bc
}
run_shards() { # N
    local n=$1 t0 pids=() threads=$(( CORES / $1 > 0 ? CORES / $1 : 1 ))
    t0=$(now)
    for k in $(seq "$n"); do
        "$J" study "$WORK/s.toml" --shard "$k/$n" --threads "$threads" --quiet \
            --out "$WORK/shard-$k-of-$n.csv" >/dev/null &
        pids+=($!)
    done
    for p in "${pids[@]}"; do wait "$p"; done
    "$J" merge "$WORK"/shard-*-of-"$n".csv --out "$WORK/merged-$n.csv" >/dev/null
    echo "$(now) - $t0" | bc
}
sed -e "s|^trials = .*|trials = 1|" "$WORK/s.toml" >"$WORK/startup.toml"
run_startup() {
    local t0; t0=$(now)
    "$J" study "$WORK/startup.toml" --threads 1 --quiet --out "$WORK/startup.csv" >/dev/null
    echo "$(now) - $t0" | bc
}
for r in $(seq "$REPEAT"); do
    T[startup]+="$(run_startup) "
    T[whole1]+="$(run_whole 1) "
    T[whole]+="$(run_whole "$CORES") "
    for n in "${SHARDS[@]}"; do
        T[s$n]+="$(run_shards "$n") "
        cmp -s "$WORK/whole-$CORES.csv" "$WORK/merged-$n.csv" || { echo "merged $n differs" >&2; exit 1; }
    done
done
median() { tr ' ' '\n' | grep . | sort -g | awk '{a[NR]=$1} END {print a[int((NR+1)/2)]}'; }
echo "study $(basename "$STUDY"), $TRIALS trials per cell, $CORES cores, median of $REPEAT rounds"
printf '%-50s %s\n' "configuration" "wall time (s)"
printf '%-50s %.2f\n' "start-up alone (1 trial per cell, 1 thread)" "$(echo "${T[startup]}" | median)"
printf '%-50s %.2f\n' "whole study, 1 thread" "$(echo "${T[whole1]}" | median)"
printf '%-50s %.2f\n' "whole study, $CORES threads" "$(echo "${T[whole]}" | median)"
for n in "${SHARDS[@]}"; do
    th=$(( CORES / n > 0 ? CORES / n : 1 ))
    printf '%-50s %.2f\n' "$n shard(s) at once, $th thread(s) each + merge" "$(echo "${T[s$n]}" | median)"
done
