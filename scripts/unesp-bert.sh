#!/usr/bin/env bash
# Regenerates results/unesp-bert/ from the real FRFs of UNESP-BERT (bolted cantilever, six
# excitation levels), read from ../shared/data/unesp-bert/ (licence CC BY-NC-SA: the data are
# never copied into the project; the script skips, saying so, when the folder is absent).
#
# Per level: `jointid extract` (band 10-110 Hz, the excited band of the band-limited random
# test; two modes; model orders up to 30, which gives the same modes as the default 60 to five
# digits) -> modes_<level>V.csv and the stabilisation chart chart_<level>V.svg; `jointid
# identify` with models/unesp-bert.toml, k2 only (four sensors: with k1 too, the per-mode
# system is ill-conditioned and k1 runs to -7e8 N/m on mode 1), n = 4 (the four sensors),
# m = 2 -> corrections_<level>V.csv; `jointid diagnose` -> diagnose_<level>V.txt/.json (the
# model as given, the joint calibrated, after). Then summary.csv (per level and mode: frequency,
# damping, MPC, k2 identified on that mode), calibrated.csv (per level: k1, k2 calibrated on
# both modes, with standard errors) and the figures k2_vs_level.svg and k2_vs_mode.svg
# (examples/unesp_joint_figure.rs).
#
# usage: bash scripts/unesp-bert.sh
set -euo pipefail
ROOT=$(cd "$(dirname "$0")/.." && pwd)
DATA=${UNESP_BERT_DIR:-$ROOT/../shared/data/unesp-bert}
OUT=$ROOT/results/unesp-bert
MODEL=$ROOT/models/unesp-bert.toml
if [ ! -d "$DATA" ]; then
    echo "skipped: $DATA is absent (UNESP-BERT data not shared here)" >&2
    exit 0
fi
cd "$ROOT"
cargo build --release --quiet --bin jointid --example unesp_joint_figure
J=$ROOT/target/release/jointid
mkdir -p "$OUT"
echo "level_V,mode,frequency_hz,damping_ratio,mpc,k2_identified" > "$OUT/summary.tmp"
for level in 0p05 0p10 0p15 0p20 0p25 0p30; do
    echo "== $level V" >&2
    "$J" extract --quiet --frf "$DATA/frf_${level}V.uff" --geometry "$DATA/geometry.uff" \
        --band 10:110 --modes 2 --max-order 30 \
        --out "$OUT/modes_${level}V.csv" --chart "$OUT/chart_${level}V.svg"
    "$J" identify --model "$MODEL" --measured "$OUT/modes_${level}V.csv" \
        --n 4 --m 2 --weighting inverse --params k2 --out "$OUT/corrections_${level}V.csv"
    "$J" diagnose --model "$MODEL" --measured "$OUT/modes_${level}V.csv" \
        --json "$OUT/diagnose_${level}V.json" > "$OUT/diagnose_${level}V.txt"
    # One row per mode: the first sensor's row of the modes (frequency, damping, MPC) and the
    # identified k2 of the same mode.
    awk -F, -v level="${level/p/.}" '
        FNR == 1 { file++; next }
        file == 1 && !seen[$1]++ { f[$1] = $2; z[$1] = $6; c[$1] = $7 }
        file == 2 && $2 == "k2" { print level "," $1 "," f[$1] "," z[$1] "," c[$1] "," $5 }
    ' "$OUT/modes_${level}V.csv" "$OUT/corrections_${level}V.csv" >> "$OUT/summary.tmp"
done
mv "$OUT/summary.tmp" "$OUT/summary.csv"
"$ROOT/target/release/examples/unesp_joint_figure" "$OUT"
column -s, -t "$OUT/summary.csv"
column -s, -t "$OUT/calibrated.csv"
