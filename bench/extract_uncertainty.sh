#!/usr/bin/env bash
# The calibration table of extract's standard errors (README, "Standard errors of the modes"):
# 40 independent H1 realisations in each of four situations (tests/extract_uncertainty.rs),
# mean reported standard error over the empirical standard deviation, and the coverage of the
# 95% interval. Release build; about 10 s on 2 cores.
set -euo pipefail
cd "$(dirname "$0")/.."
cargo test --release --locked --test suite extract_uncertainty::calibration_table -- --ignored --nocapture 2>/dev/null | grep '^|'
