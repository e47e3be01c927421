#!/usr/bin/env bash
# `jointid diagnose` on solid half-laps the fixtures were not tuned on: other specimens,
# materials, overlaps, sensor layouts and seeds, made by bench/lap3d/generate.py (independent
# of jointid, see tests/fixtures/lap3d/README.md), each diagnosed with the 1D model a user
# writes (model.toml: Euler-Bernoulli beams and [joint.lap]) and with Timoshenko beams
# (timoshenko.toml), at the noise they were made with (0.1% / 1%). Prints a markdown table:
# the verdict, the causes named, the frequency RMS error of the calibrated point joint
# (before) and of the named model (after), the modes left out and the wall time.
#   usage: bash bench/lap3d/variants.sh [DIR]   (DIR: target/lap3d-variants by default; the
#   cases are generated there once, about 30 s each, and reused)
set -euo pipefail
cd "$(dirname "$0")/../.."
dir=${1:-target/lap3d-variants}
mkdir -p "$dir"
PY=$(bash scripts/python-env.sh)
cargo build --release --locked --bin jointid >&2
j=${CARGO_TARGET_DIR:-./target}/release/jointid
alu="--young 7.0e10 --density 2700 --poisson 0.33 --length 0.8 --width 30e-3 --height 10e-3 --overlap 0.30,0.42"
alu9="0,0.09,0.2,0.28,0.36,0.45,0.55,0.68,0.8"
steel="--length 0.5 --height 15e-3 --overlap 0.22,0.30"
gen() {
    local case=$1
    shift
    [ -f "$dir/$case/measured.csv" ] || "$PY" bench/lap3d/generate.py "$dir/$case" "$@" >&2
}
gen alu-bolts-9   --interface bolts   --sensors "$alu9" --seed 101 $alu
gen alu-uniform-5 --interface uniform --sensors 0,0.15,0.36,0.6,0.8 --seed 102 $alu
gen alu-glued-9   --interface glued   --sensors "$alu9" --seed 104 $alu
gen alu-tip-9     --interface uniform --tip-mass 0.015 --sensors "$alu9" --seed 105 $alu
gen alu-mono-3    --monolithic --sensors 0,0.3,0.8 --seed 106 $alu
gen st-bolts-3    --interface bolts   --sensors 0,0.17,0.5 --seed 103 $steel
gen st-glued-3    --interface glued   --sensors 0,0.17,0.5 --seed 110 $steel
gen st-tip-3      --interface uniform --tip-mass 0.02 --sensors 0,0.17,0.5 --seed 109 $steel
soft="$steel --kn 6.56e10 --kt 1.0e10"
gen soft-bolts-3   --interface bolts   --sensors 0,0.17,0.5 --seed 111 $soft
gen vsoft-bolts-9  --interface bolts   --sensors 9 --seed 113 $steel --kn 1.64e10 --kt 2.5e9
cases="$dir/alu-bolts-9 $dir/alu-uniform-5 $dir/alu-glued-9 $dir/alu-tip-9 $dir/alu-mono-3
$dir/st-bolts-3 $dir/st-glued-3 $dir/st-tip-3
tests/fixtures/lap3d/soft-bolts-9 tests/fixtures/lap3d/soft-uniform-6 tests/fixtures/lap3d/soft-uniform-9
$dir/soft-bolts-3 $dir/vsoft-bolts-9"
echo "| case | model | verdict | causes | before (%) | after (%) | left out | s |"
echo "|---|---|---|---|---|---|---|---|"
for c in $cases; do
    for m in model timoshenko; do
        out="$dir/$(basename "$c")-$m.json"
        start=$(date +%s.%N)
        "$j" diagnose --model "$c/$m.toml" --measured "$c/measured.csv" --frequency-noise 0.001 \
            --shape-noise 0.01 --quiet --json "$out" >/dev/null
        end=$(date +%s.%N)
        "$PY" - "$out" "$(basename "$c")" "$m" "$start" "$end" <<'EOF'
import json
import sys

out, case, model, start, end = sys.argv[1:]
r = json.load(open(out))
causes = " + ".join(r.get("causes") or []) or "-"
left = ", ".join(str(m["mode"]) for m in r.get("left_out", [])) or "-"
print(f"| {case} | {model} | {r['verdict']} | {causes} | {r['before']['frequency_rms_pct']:.2f} "
      f"| {r['after']['frequency_rms_pct']:.2f} | {left} | {float(end) - float(start):.1f} |")
EOF
    done
done
