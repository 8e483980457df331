#!/usr/bin/env bash
# The deposits across the loading angle: the matrix's dense and loose deposits at α = 0, 30, 45,
# 60 and 90° (python/sffcal/matrix.py), 500 clumps, seeds 1-3 each (run_seeds.sh: sffcal dem and
# sffcal sff), the mean of each specimen's seeds (python3 -m sffcal.mean_of_seeds:
# OUT/mean/<specimen>.h5 and its noise), then the table of the angle's effects (angle_table.py).
# Runs that finished before are kept.
# Usage: bench/angle/run_angles.sh [OUT=out/angle] [JOBS=nproc]
set -euo pipefail
cd "$(dirname "$0")/../.."
out=${1:-out/angle}
jobs=${2:-$(nproc)}
seeds="1 2 3"
specimens=""
for density in dense loose; do
  for angle in 00 30 45 60 90; do specimens+="dep_${density}_a$angle "; done
done
./scripts/build.sh >/dev/null
source scripts/python_env.sh  # the package sffcal as built (docs/python.md)
start=$(date +%s)
bench/calibration/run_seeds.sh "$out" "$seeds" "$specimens" "$jobs"
echo "runs: $(( $(date +%s) - start )) s with $jobs jobs"
mkdir -p "$out/mean"
for name in $specimens; do
  [ -f "$out/mean/$name.h5" ] && continue
  runs=(); for seed in $seeds; do runs+=("$out/seed$seed/$name.h5"); done
  /usr/bin/python3 -m sffcal.mean_of_seeds "${runs[@]}" -o "$out/mean/$name.h5"
done
/usr/bin/python3 bench/angle/angle_table.py "$out"
