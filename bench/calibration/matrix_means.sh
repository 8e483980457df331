#!/usr/bin/env bash
# The 500-clump matrix against the mean curve of three seeds of each specimen (issue 19, point 4):
# every kind of test (isotropic dense, medium and loose; deposits at three loading angles; drained
# extension; undrained compression), each specimen run for seeds 1-3 (run_seeds.sh), averaged
# (python3 -m sffcal.mean_of_seeds: OUT/mean/<specimen>.h5 and its noise), then fitted with one of
# each kind held back: a density (medium), a pressure (200 kPa), a loading angle (45 deg), an
# extension (200 kPa, and the 45 deg deposit's) and an undrained test (200 kPa). ACST with the
# defaults (OUT/fit_acst), and the contact-network model (OUT/fit_network) unless MODELS says
# otherwise. Then each seed's runs are fitted alone with each model, the same split
# (OUT/seed<S>/fit for ACST, OUT/seed<S>/fit_network), for the standard errors against the spread
# of refits.
# `bench/calibration/matrix_means.py OUT/mean OUT/fit_acst OUT/fit_network` tabulates the errors
# against the targets and the noise, `bench/calibration/seed_spread.py OUT [--fit fit_network]`
# the refits' spread against the standard errors.
# Usage: bench/calibration/matrix_means.sh [OUT=out/matrix_means] [JOBS=nproc] [MODELS="acst network"]
set -euo pipefail
cd "$(dirname "$0")/../.."
out=${1:-out/matrix_means}
jobs=${2:-$(nproc)}
models=${3:-acst network}
seeds="1 2 3"
fitted="iso_dense_100kPa iso_loose_100kPa iso_loose_300kPa dep_dense_a00 dep_dense_a90 ext_dense_100kPa ext_loose_100kPa und_dense_100kPa"
held="iso_medium_200kPa iso_dense_200kPa iso_loose_200kPa dep_dense_a45 ext_dense_200kPa und_dense_200kPa dep_dense_a45_ext"
./scripts/build.sh >/dev/null
source scripts/python_env.sh  # the package sffcal as built (docs/python.md)
bench/calibration/run_seeds.sh "$out" "$seeds" "$fitted $held" "$jobs"
mkdir -p "$out/mean"
for name in $fitted $held; do
  [ -f "$out/mean/$name.h5" ] && continue
  runs=(); for seed in $seeds; do runs+=("$out/seed$seed/$name.h5"); done
  /usr/bin/python3 -m sffcal.mean_of_seeds "${runs[@]}" -o "$out/mean/$name.h5"
done
fit_runs=(); for n in $fitted; do fit_runs+=("$out/mean/$n.h5"); done
held_runs=(); for n in $held; do held_runs+=("$out/mean/$n.h5"); done
for model in $models; do
  [ -f "$out/fit_$model/parameters.json" ] && continue
  extra=(); [ "$model" = network ] && extra=(--starts 4)
  s=$(date +%s)
  build/sffcal calibrate --model "$model" "${fit_runs[@]}" --hold-out "${held_runs[@]}" \
      "${extra[@]}" --threads "$jobs" -o "$out/fit_$model" > "$out/fit_$model.log" 2>&1
  echo "$model fitted in $(( $(date +%s) - s )) s"
done
for model in $models; do
  fit=fit; extra=()
  [ "$model" = network ] && { fit=fit_network; extra=(--starts 4); }
  for seed in $seeds; do
    d="$out/seed$seed"
    [ -f "$d/$fit/parameters.json" ] && continue
    fit_runs=(); for n in $fitted; do fit_runs+=("$d/$n.h5"); done
    held_runs=(); for n in $held; do held_runs+=("$d/$n.h5"); done
    s=$(date +%s)
    build/sffcal calibrate --model "$model" "${fit_runs[@]}" --hold-out "${held_runs[@]}" \
        "${extra[@]}" --threads "$jobs" -o "$d/$fit" > "$d/$fit.log" 2>&1
    echo "seed $seed fitted with $model in $(( $(date +%s) - s )) s"
  done
done
