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
# model as given, the joint calibrated, after). extract is told the 54 averages of the test, so
# the modes carry standard errors from the coherence, which identify and diagnose then use.
# Then summary.csv (per level and mode: frequency, damping, MPC, their standard errors, k2
# identified on that mode with its standard deviation), replicates.csv (the levels as
# replicates: the standard error beside the scatter and trend across levels), calibrated.csv (per level: k1, k2 calibrated on
# both modes, with standard errors) and the figures k2_vs_level.svg and k2_vs_mode.svg
# (examples/unesp_joint_figure.rs). Then levels.toml and `jointid amplitude`: per mode, the
# stiffness and damping against the response amplitude by three laws with the chosen one
# (amplitude_levels.csv, amplitude_laws.csv, amplitude_parameters.csv, amplitude_bands.csv,
# amplitude_mode1.svg, amplitude_mode2.svg), and with --joint k2 the same of the joint's own
# k2 and damping (joint_*.csv, joint_mode1.svg, joint_mode2.svg) with the frequencies before
# (one k2 for every level) and after (the chosen law) in joint_errors.csv.
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
echo "level_V,mode,frequency_hz,frequency_std,damping_ratio,damping_std,mpc,k2_identified,k2_std" > "$OUT/summary.tmp"
for level in 0p05 0p10 0p15 0p20 0p25 0p30; do
    echo "== $level V" >&2
    "$J" extract --quiet --frf "$DATA/frf_${level}V.uff" --geometry "$DATA/geometry.uff" \
        --band 10:110 --modes 2 --max-order 30 --averages 54 \
        --out "$OUT/modes_${level}V.csv" --chart "$OUT/chart_${level}V.svg"
    "$J" identify --model "$MODEL" --measured "$OUT/modes_${level}V.csv" \
        --n 4 --m 2 --weighting inverse --params k2 --out "$OUT/corrections_${level}V.csv"
    "$J" diagnose --model "$MODEL" --measured "$OUT/modes_${level}V.csv" \
        --json "$OUT/diagnose_${level}V.json" > "$OUT/diagnose_${level}V.txt"
    # One row per mode: the first sensor's row of the modes (frequency, damping, MPC and the
    # standard errors) and the identified k2 of the same mode with its standard deviation.
    awk -F, -v level="${level/p/.}" '
        FNR == 1 { file++; next }
        file == 1 && !seen[$1]++ { f[$1] = $2; z[$1] = $6; c[$1] = $7; fs[$1] = $8; zs[$1] = $9 }
        file == 2 && $2 == "k2" {
            print level "," $1 "," f[$1] "," fs[$1] "," z[$1] "," zs[$1] "," c[$1] "," $5 "," $12
        }
    ' "$OUT/modes_${level}V.csv" "$OUT/corrections_${level}V.csv" >> "$OUT/summary.tmp"
done
mv "$OUT/summary.tmp" "$OUT/summary.csv"
# The levels as replicates: per mode and quantity, the mean standard error of one level beside
# the scatter across the six levels (their standard deviation) and what a straight line in the
# level leaves (the residual standard deviation, 4 degrees of freedom): a scatter or a residual
# far above the standard error is a real change with level (amplitude dependence), not noise.
awk -F, '
    NR == 1 { next }
    {
        m = $2; n[m]++; x[m, n[m]] = $1
        v[m, "frequency_hz", n[m]] = $3; s[m, "frequency_hz"] += $4
        v[m, "damping_ratio", n[m]] = $5; s[m, "damping_ratio"] += $6
        v[m, "k2_identified", n[m]] = $8; s[m, "k2_identified"] += $9
    }
    END {
        print "mode,quantity,mean,mean_std,scatter_sd,scatter_over_std,slope_per_V,residual_sd,residual_over_std"
        split("frequency_hz damping_ratio k2_identified", q, " ")
        for (m = 1; m in n; m++) for (i = 1; i <= 3; i++) {
            k = n[m]; sx = sy = sxx = sxy = 0
            for (j = 1; j <= k; j++) { a = x[m, j]; b = v[m, q[i], j]; sx += a; sy += b; sxx += a * a; sxy += a * b }
            mx = sx / k; my = sy / k; slope = (sxy - k * mx * my) / (sxx - k * mx * mx)
            ss = rr = 0
            for (j = 1; j <= k; j++) { d = v[m, q[i], j] - my; ss += d * d; e = d - slope * (x[m, j] - mx); rr += e * e }
            sd = sqrt(ss / (k - 1)); rd = sqrt(rr / (k - 2)); st = s[m, q[i]] / k
            printf "%d,%s,%.8g,%.4g,%.4g,%.3g,%.6g,%.4g,%.3g\n", m, q[i], my, st, sd, sd / st, slope, rd, rd / st
        }
    }
' "$OUT/summary.csv" > "$OUT/replicates.csv"
"$ROOT/target/release/examples/unesp_joint_figure" "$OUT"
# Amplitude dependence across the six levels: levels.toml names each level's modes and FRFs
# (the data folder by a path relative to results/unesp-bert when it is the default one); the
# amplitude is the RMS response of each mode at the tip accelerometer (node 1) under the flat
# random drive of 0-110 Hz whose RMS is the level; `jointid amplitude` fits the constant,
# power and Iwan laws to each mode's stiffness and damping -> amplitude_*.csv, amplitude_mode*.svg.
DATA_REL=$(realpath --relative-to="$OUT" "$DATA")
{
    echo "# The six levels of UNESP-BERT for jointid amplitude (written by scripts/unesp-bert.sh)."
    echo 'model = "../../models/unesp-bert.toml"'
    echo "reference = 1"
    echo 'excitation_unit = "V"'
    echo "random_band_hz = 110.0"
    echo "reference_x = 0.5  # the tip accelerometer (node 1) in the modes files: --joint takes the lap's rotation"
    for level in 0p05 0p10 0p15 0p20 0p25 0p30; do
        printf '\n[[level]]\nexcitation = %s\nmodes = "modes_%sV.csv"\nfrf = "%s/frf_%sV.uff"\n' \
            "${level/p/.}" "$level" "$DATA_REL" "$level"
    done
} > "$OUT/levels.toml"
"$J" amplitude "$OUT/levels.toml" --out "$OUT" --joint k2
column -s, -t "$OUT/summary.csv"
column -s, -t "$OUT/calibrated.csv"
column -s, -t "$OUT/replicates.csv"
