#!/usr/bin/env bash
# The paper-size reference run: prepares ~10,000 clumps (dense, 100 kPa), shears them to the
# critical state, and plots the curves into bench/reference/. About an hour on 2 cores.
set -euo pipefail
cd "$(dirname "$0")/../.."
./scripts/build.sh >/dev/null
source scripts/python_env.sh  # the package sffcal as built (docs/python.md)
mkdir -p out/reference
/usr/bin/time -v ./build/sffcal dem --force -c bench/reference/dense_100kPa.toml \
  -o out/reference/dense_100kPa.h5 2>&1 | tee out/reference/dense_100kPa.log
/usr/bin/python3 -m sffcal.plot_triaxial out/reference/dense_100kPa.h5 \
  bench/reference/dense_100kPa.png
