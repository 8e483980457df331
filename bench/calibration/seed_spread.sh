#!/usr/bin/env bash
# Refits of the matrix calibration on specimens of other packing seeds (issue 19, point 3): runs
# the six fitted isotropic 500-clump specimens of docs/calibration.md ("Fit to the test matrix")
# and the three held back, for each seed, then `sffcal calibrate` on each seed's runs as the
# stored fit was made. bench/calibration/seed_spread.py then compares the covariance standard
# errors with the spread of the refits and measures the DEM's own noise between seeds.
# Usage: bench/calibration/seed_spread.sh [OUT=out/seed_spread] [SEEDS="1 2 3 4"] [JOBS=nproc]
set -euo pipefail
cd "$(dirname "$0")/../.."
out=${1:-out/seed_spread}
seeds=${2:-1 2 3 4}
jobs=${3:-$(nproc)}
./scripts/build.sh >/dev/null
fitted="iso_dense_100kPa iso_medium_100kPa iso_loose_100kPa iso_dense_300kPa iso_medium_300kPa iso_loose_300kPa"
held="iso_dense_200kPa iso_medium_200kPa iso_loose_200kPa"
mkdir -p "$out"
for seed in $seeds; do
  mkdir -p "$out/seed$seed"
  for name in $fitted $held; do
    /usr/bin/python3 bench/matrix/make_configs.py "$out/seed$seed" --seed "$seed" --only "$name" >/dev/null
  done
done
start=$(date +%s)
ls "$out"/seed*/*.toml | xargs -P "$jobs" -I{} bash -c \
  'f={}; r=${f%.toml}.h5; [ -f "$r" ] && echo "$r exists" && exit 0; \
   build/sffcal dem -c "$f" -o "$r" > "${f%.toml}.log" 2>&1 && \
   build/sffcal sff "$r" --resamples 0 >> "${f%.toml}.log" 2>&1 && echo "$r done" || echo "$r FAILED"'
echo "DEM: $(( $(date +%s) - start )) s with $jobs jobs"
for seed in $seeds; do
  d="$out/seed$seed"
  [ -f "$d/fit/parameters.json" ] && continue
  runs=(); for n in $fitted; do runs+=("$d/$n.h5"); done
  hold=(); for n in $held; do hold+=("$d/$n.h5"); done
  s=$(date +%s)
  build/sffcal calibrate "${runs[@]}" --hold-out "${hold[@]}" --threads "$jobs" -o "$d/fit" > "$d/fit.log" 2>&1
  echo "seed $seed fitted in $(( $(date +%s) - s )) s"
done
