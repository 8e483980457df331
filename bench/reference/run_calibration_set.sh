#!/usr/bin/env bash
# The paper-size runs of the calibration (issue 5, docs/calibration.md "Fit to paper-size runs"):
# dense at 300 kPa and loose at 200 kPa, 10,000 clumps each, one thread each, side by side, then
# their SFF analysis. With dense_100kPa (bench/reference/run.sh) they make the fitted set and the
# held-back test. About 35 min on 2 cores.
set -euo pipefail
cd "$(dirname "$0")/../.."
./scripts/build.sh >/dev/null
mkdir -p out/reference
for name in dense_300kPa loose_200kPa; do
  ( /usr/bin/time -f "%e s wall" ./build/sffcal dem -c bench/reference/$name.toml -o out/reference/$name.h5 \
      > out/reference/$name.log 2>&1 \
    && ./build/sffcal sff out/reference/$name.h5 --resamples 50 >> out/reference/$name.log 2>&1 \
    && echo "$name done" ) &
done
wait
