#!/usr/bin/env bash
# The diagnose benchmark on the large independent battery, drawn with three seeds (2, 3, 4:
# 3 x 220 cases of one design): build the release binary, generate each draw into
# target/battery/large-s<seed> (git-ignored; regenerated when missing or older than the
# generator's sources; about 4-5 min each), run `jointid diagnose` on every case (2 at a time)
# and print the confusion matrices per noise situation, pooled, with each draw's score per
# situation (also in target/battery/large-results.md and .csv).
#   usage: bash bench/battery/run.sh [--regenerate]
set -euo pipefail
cd "$(dirname "$0")/../.."
PY=$(bash scripts/python-env.sh)
cargo build --release --locked
mkdir -p target/battery
folders=()
for seed in 2 3 4; do
  out=target/battery/large-s$seed
  if [ "${1:-}" = "--regenerate" ] || [ ! -f "$out/manifest.json" ] \
     || [ -n "$(find bench/battery -name '*.py' -newer "$out/manifest.json")" ]; then
    start=$(date +%s)
    "$PY" bench/battery/generate.py large --seed "$seed" --out "$out" --jobs 2 \
      > "target/battery/large-s$seed-generate.log"
    echo "generated $out in $(( $(date +%s) - start )) s" >&2
  fi
  folders+=("$out")
done
"$PY" bench/battery/run.py "${folders[@]}" --jobs 2 \
  --markdown target/battery/large-results.md --csv target/battery/large-results.csv
