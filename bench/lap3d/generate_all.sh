#!/usr/bin/env bash
# Regenerates the 3D half-lap fixtures of tests/fixtures/lap3d/ (see its README.md) with
# bench/lap3d/generate.py: ten cases, fixed seeds, 0.1% frequency and 1% shape noise, three
# noise-free ones (exact-*: the model-form error alone), two of a stubbier specimen (stubby-*)
# and two of a softer interface (soft-*).
# About 25 s per case on two cores.   usage: bash bench/lap3d/generate_all.sh
set -euo pipefail
cd "$(dirname "$0")/../.."
PY=$(bash scripts/python-env.sh)
out=tests/fixtures/lap3d
gen() { local case=$1; shift; "$PY" bench/lap3d/generate.py "$out/$case" "$@"; }
gen uniform-3    --interface uniform --sensors 3 --seed 1
gen uniform-9    --interface uniform --sensors 9 --seed 2
gen bolts-3      --interface bolts   --sensors 3 --seed 3
gen bolts-9      --interface bolts   --sensors 9 --seed 4
gen glued-3      --interface glued   --sensors 3 --seed 5
gen glued-9      --interface glued   --sensors 9 --seed 6
gen tipmass-3    --interface uniform --tip-mass 0.02 --sensors 3 --seed 7
gen tipmass-9    --interface uniform --tip-mass 0.02 --sensors 9 --seed 8
gen monolithic-3 --monolithic --sensors 3 --seed 9
gen monolithic-9 --monolithic --sensors 9 --seed 10
gen exact-uniform-9 --interface uniform --sensors 9 --frequency-noise 0 --shape-noise 0
gen exact-bolts-9   --interface bolts   --sensors 9 --frequency-noise 0 --shape-noise 0
gen exact-glued-9   --interface glued   --sensors 9 --frequency-noise 0 --shape-noise 0
stubby="--length 0.7112 --overlap 0.29528,0.41593 --width 25.4e-3 --height 19.05e-3 --young 1.93e11 --density 8000"
gen stubby-bolts-3 --interface bolts --sensors 0,0.2,0.7112 --seed 11 $stubby
gen stubby-bolts-9 --interface bolts --sensors 0,0.0889,0.1778,0.2667,0.3556,0.4445,0.5334,0.6223,0.7112 --seed 13 $stubby
soft="--length 0.5 --height 15e-3 --overlap 0.22,0.30 --kn 6.56e10 --kt 1.0e10"
gen soft-bolts-9   --interface bolts   --sensors 9 --seed 107 $soft
gen soft-uniform-6 --interface uniform --sensors 0,0.1,0.2,0.3,0.4,0.5 --seed 108 $soft
gen soft-uniform-9 --interface uniform --sensors 9 --seed 112 $soft
