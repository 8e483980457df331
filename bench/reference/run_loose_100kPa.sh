#!/usr/bin/env bash
# The fourth paper-size run of the calibration (issue 19): loose at 100 kPa, 10,000 clumps, on both
# cores, then its SFF analysis; about 15 min on 2 cores. With dense_100kPa, dense_300kPa and
# loose_200kPa (bench/reference/run.sh, run_calibration_set.sh) it lets a fit learn the loose side
# at paper size and hold back a pressure (docs/calibration.md, "Fit to paper-size runs").
set -euo pipefail
cd "$(dirname "$0")/../.."
./scripts/build.sh >/dev/null
mkdir -p out/reference
/usr/bin/time -f "%e s wall" ./build/sffcal dem -c bench/reference/loose_100kPa.toml \
  -o out/reference/loose_100kPa.h5 > out/reference/loose_100kPa.log 2>&1
./build/sffcal sff out/reference/loose_100kPa.h5 --resamples 50 >> out/reference/loose_100kPa.log 2>&1
echo "loose_100kPa done: out/reference/loose_100kPa.h5 (log beside it)"
