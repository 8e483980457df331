#!/usr/bin/env bash
# The paper-size test at the paper's rate (issue 16, point 4): prepares 10,000 clumps (dense,
# 100 kPa) and shears them at 20 /s to 25 % on 2 threads (bench/reference/dense_100kPa_20s.toml),
# timed whole, then the SFF analysis and the plot. Figures: bench/RESULTS.md, "Paper size at the
# paper's rate".
#   bench/reference/run_paper_rate.sh [OUT] [SEED] [SCALING]
# (defaults: out/reference_20s, seed 1, the config's density scaling 16; SCALING 1 is the
# unscaled run, with the paper's grain masses)
set -euo pipefail
cd "$(dirname "$0")/../.."
./scripts/build.sh >/dev/null
source scripts/python_env.sh  # the package sffcal as built (docs/python.md)
out=${1:-out/reference_20s}
seed=${2:-1}
scaling=${3:-16.0}
mkdir -p "$out"
name=dense_100kPa_20s_seed${seed}_scaling$scaling
sed -e "s/^seed = 1 /seed = $seed /" -e "s/^density_scaling = 16.0 /density_scaling = $scaling /" \
  bench/reference/dense_100kPa_20s.toml > "$out/$name.toml"
grep -q "^seed = $seed " "$out/$name.toml"
grep -q "^density_scaling = $scaling " "$out/$name.toml"
/usr/bin/time -v ./build/sffcal dem --force -c "$out/$name.toml" -o "$out/$name.h5" 2>&1 |
  tee "$out/$name.log"
./build/sffcal sff "$out/$name.h5" -o "$out/sff"
/usr/bin/python3 -m sffcal.plot_triaxial "$out/$name.h5" "$out/$name.png"
