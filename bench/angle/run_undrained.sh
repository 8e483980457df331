#!/usr/bin/env bash
# Deposits in an undrained cell: the matrix's dense and loose deposits at α = 90° (bedding normal
# along y; python/sffcal/matrix.py), 500 clumps, seed 1, sheared undrained to 10 % (the dense one
# reaches the overlap limit near 14 %, p' near 10 p0) with equal lateral strains and with
# σx = σy (triaxial.undrained_lateral, docs/dem.md), then a row each: |σx − σy| / p (largest and
# mean) and the worst lateral-stress error past 0.5 % while p > 0.05 p0, p / p0 and q / p at the
# end. Runs that finished before are kept.
# Usage: bench/angle/run_undrained.sh [OUT=out/angle_undrained] [JOBS=nproc]
set -euo pipefail
cd "$(dirname "$0")/../.."
out=${1:-out/angle_undrained}
jobs=${2:-$(nproc)}
./scripts/build.sh >/dev/null
source scripts/python_env.sh  # the package sffcal as built (docs/python.md)
mkdir -p "$out"
configs=()
for name in dep_dense_a90 dep_loose_a90; do
  /usr/bin/python3 bench/matrix/make_configs.py "$out" --seed 1 --only "$name" >/dev/null
  for lateral in equal_strains equal_stresses; do
    config=$out/${name}_$lateral.toml
    # The matrix's drained config, sheared undrained to 10 % with this lateral control.
    sed -e 's/^path = "drained_compression".*/path = "undrained_compression"\nundrained_lateral = "'"$lateral"'"/' \
        -e 's/^max_axial_strain = .*/max_axial_strain = 0.1/' "$out/$name.toml" > "$config"
    configs+=("$config")
  done
done
start=$(date +%s)
printf '%s\n' "${configs[@]}" | xargs -P "$jobs" -I{} bash -c \
  'f={}; r=${f%.toml}.h5; [ -f "$r.done" ] && exit 0; \
   build/sffcal dem --force -c "$f" -o "$r" > "${f%.toml}.log" 2>&1 && touch "$r.done" \
   || echo "$r FAILED (see ${f%.toml}.log)"'
echo "runs: $(( $(date +%s) - start )) s with $jobs jobs"
/usr/bin/python3 - "$out" <<'PY'
import glob, os, sys
import h5py
import numpy as np
# Past 0.5 % of axial strain and while p > 0.05 p0 (a loose deposit liquefies: p -> 0, where
# ratios to p or to the lateral stress mean nothing).
print("| specimen | lateral | rows | max |σx − σy|/p | its mean | worst lateral error | p/p0 at 10 % (min) | q/p at 10 % |")
print("|---|---|---|---|---|---|---|---|")
for path in sorted(glob.glob(os.path.join(sys.argv[1], "*_equal_str*s.h5"))):  # not *.specimen.h5
    with h5py.File(path, "r") as f:
        s = f["series"]
        ea, sx, sy, p, q, err = (np.asarray(s[k]) for k in (
            "axial_strain", "wall_stress_xx", "wall_stress_yy", "p", "q", "lateral_stress_error"))
    rows = (ea > 0.005) & (p > 0.05 * p[0])
    parting = np.abs(sx - sy)[rows] / p[rows]
    specimen, lateral = os.path.basename(path)[:-3].split("_equal_")
    end_eta = f"{q[-1] / p[-1]:.3f}" if p[-1] > 0.05 * p[0] else "–"
    worst = f"{err[rows].max():.3f}" if lateral == "stresses" else "–"  # kinematic walls: none
    print(f"| {specimen} | equal {lateral} | {rows.sum()} of {len(ea)} | {parting.max():.3f} | "
          f"{parting.mean():.3f} | {worst} | {p[-1] / p[0]:.2f} ({p.min() / p[0]:.2f}) | "
          f"{end_eta} |")
PY
