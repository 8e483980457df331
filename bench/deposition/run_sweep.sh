#!/usr/bin/env bash
# Deposited specimens at loading angles 0-90 deg (issue 3): prepares one specimen per angle with
# `sffcal prepare` (independent processes, JOBS at once) and prints the fabric table of
# fabric_table.py. Usage: bench/deposition/run_sweep.sh [out_folder]  (env: SFFCAL, BODIES, JOBS,
# ANGLES, FRICTION, SEED)
set -euo pipefail
cd "$(dirname "$0")/../.."
out=${1:-out/deposition}
sffcal=${SFFCAL:-build/sffcal}
bodies=${BODIES:-1000}
jobs=${JOBS:-2}
angles=${ANGLES:-"0 30 45 60 90"}
mkdir -p "$out"
"$sffcal" config -o "$out/base.toml" > /dev/null
for a in $angles; do
  sed -e "s/^bodies = .*/bodies = $bodies/" -e 's/^threads = .*/threads = 1/' \
      -e "s/^seed = .*/seed = ${SEED:-1}/" -e 's/^method = .*/method = "deposition"/' \
      -e "s/^loading_angle_deg = .*/loading_angle_deg = $a.0/" \
      -e "s/^compaction_friction = .*/compaction_friction = ${FRICTION:-0.15}/" \
      "$out/base.toml" > "$out/a$a.toml"
done
printf "%s\n" $angles | xargs -P "$jobs" -I{} sh -c \
  "'$sffcal' prepare -c '$out/a{}.toml' -o '$out/a{}.h5' > '$out/a{}.log' 2>&1 || echo 'angle {} failed: see $out/a{}.log'"
/usr/bin/python3 bench/deposition/fabric_table.py "$out"/a*.h5
