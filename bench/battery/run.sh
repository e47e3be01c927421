#!/usr/bin/env bash
# The diagnose benchmark on the large independent battery: build the release binary, generate
# the battery into target/battery/large (git-ignored; regenerated when missing or older than the
# generator's sources), run `jointid diagnose` on every case (2 at a time) and print the
# confusion matrices per noise situation (also in target/battery/large-results.md and .csv).
#   usage: bash bench/battery/run.sh [--regenerate]
set -euo pipefail
cd "$(dirname "$0")/../.."
PY=$(bash scripts/python-env.sh)
cargo build --release --locked
out=target/battery/large
mkdir -p target/battery
if [ "${1:-}" = "--regenerate" ] || [ ! -f "$out/manifest.json" ] \
   || [ -n "$(find bench/battery -name '*.py' -newer "$out/manifest.json")" ]; then
  start=$(date +%s)
  "$PY" bench/battery/generate.py large --out "$out" --jobs 2 > target/battery/large-generate.log
  echo "generated $out in $(( $(date +%s) - start )) s" >&2
fi
"$PY" bench/battery/run.py "$out" --jobs 2 \
  --markdown target/battery/large-results.md --csv target/battery/large-results.csv
