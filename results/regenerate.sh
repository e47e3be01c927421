#!/usr/bin/env bash
# Regenerates everything in results/: the three shipped studies (CSVs), their reports (SVG
# figures and index.html), and README's worked diagnosis (data, JSON report and plots).
set -euo pipefail
cd "$(dirname "$0")/.."

cargo build --release --locked
jointid=./target/release/jointid

"$jointid" study studies/paper-case-1.toml studies/paper-case-2.toml studies/ci-bias.toml --quiet > /dev/null
"$jointid" report results/paper-case-1.csv --out results/paper-case-1 --title "Paper case I"
"$jointid" report results/paper-case-2.csv --out results/paper-case-2 --title "Paper case II"
"$jointid" report results/ci-bias.csv --out results/ci-bias --title "CI bias gate"

mkdir -p results/worked-example
"$jointid" simulate --model models/paper-case-1.toml --effect joint_mass=0.05 --modes 6 \
    --frequency-noise 0.001 --shape-noise 0.02 --measure w --seed 1 --out results/worked-example/test.csv
"$jointid" diagnose --model models/paper-case-1.toml --measured results/worked-example/test.csv \
    --frequency-noise 0.001 --shape-noise 0.02 --json results/worked-example/report.json \
    --plots results/worked-example/plots > results/worked-example/report.txt
echo "results/ regenerated"
