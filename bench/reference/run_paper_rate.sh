#!/usr/bin/env bash
# The paper-size test at the paper's rate (issue 16, point 4): prepares 10,000 clumps (dense,
# 100 kPa) and shears them at 20 /s to 25 % on 2 threads (bench/reference/dense_100kPa_20s.toml),
# timed whole, then the SFF analysis and the plot. Figures: bench/RESULTS.md, "Paper size at the
# paper's rate".
set -euo pipefail
cd "$(dirname "$0")/../.."
./scripts/build.sh >/dev/null
out=${1:-out/reference_20s}
mkdir -p "$out"
/usr/bin/time -v ./build/sffcal dem --force -c bench/reference/dense_100kPa_20s.toml \
  -o "$out/dense_100kPa_20s.h5" 2>&1 | tee "$out/dense_100kPa_20s.log"
./build/sffcal sff "$out/dense_100kPa_20s.h5" -o "$out/sff"
/usr/bin/python3 bench/reference/plot_triaxial.py "$out/dense_100kPa_20s.h5" "$out/dense_100kPa_20s.png"
