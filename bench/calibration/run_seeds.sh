#!/usr/bin/env bash
# Runs specimens of the reference matrix (python/sffcal/matrix.py) for several packing seeds,
# JOBS processes at a time, each followed by its SFF analysis without resampling:
# OUT/seed<S>/<specimen>.{toml,h5,log}. A run that finished before (its .done marker) is kept;
# the script fails, naming them, if any run did not finish.
# Used by seed_spread.sh and matrix_means.sh.
# Usage: bench/calibration/run_seeds.sh OUT "SEEDS" "SPECIMENS" JOBS
set -euo pipefail
cd "$(dirname "$0")/../.."
source scripts/python_env.sh  # the package sffcal as built (docs/python.md)
out=$1
seeds=$2
specimens=$3
jobs=$4
for seed in $seeds; do
  mkdir -p "$out/seed$seed"
  for name in $specimens; do
    # --only matches substrings (dep_dense_a45 also writes dep_dense_a45_ext's config): only the
    # named specimens are run
    /usr/bin/python3 bench/matrix/make_configs.py "$out/seed$seed" --seed "$seed" --only "$name" >/dev/null
    [ -f "$out/seed$seed/$name.toml" ] || { echo "run_seeds.sh: no matrix specimen $name" >&2; exit 1; }
  done
done
start=$(date +%s)
configs=()
for seed in $seeds; do for name in $specimens; do configs+=("$out/seed$seed/$name.toml"); done; done
printf '%s\n' "${configs[@]}" | xargs -P "$jobs" -I{} bash -c \
  'f={}; r=${f%.toml}.h5; [ -f "$r.done" ] && echo "$r was made before" && exit 0; \
   build/sffcal dem --force -c "$f" -o "$r" > "${f%.toml}.log" 2>&1 && \
   build/sffcal sff "$r" --resamples 0 >> "${f%.toml}.log" 2>&1 && touch "$r.done" && echo "$r done" \
   || echo "$r FAILED (see ${f%.toml}.log)"'
echo "DEM: $(( $(date +%s) - start )) s with $jobs jobs"
failed=()
for f in "${configs[@]}"; do [ -f "${f%.toml}.h5.done" ] || failed+=("${f%.toml}.h5"); done
if [ ${#failed[@]} -gt 0 ]; then
  echo "run_seeds.sh: ${#failed[@]} run(s) did not finish: ${failed[*]}" >&2
  exit 1
fi
