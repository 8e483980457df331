#!/usr/bin/env bash
# Reproduces the throughput table of bench/RESULTS.md (builds first if needed) and appends its
# rates to bench/throughput_history.csv (commit, date, bodies, kind, threads, rates per core), so
# that a slowdown between commits shows as a drop in that file's rows.
# Run it on an otherwise idle machine: the figures are wall-clock rates.
# Environment: BODIES (2000,10000), STEPS (2000), HISTORY (bench/throughput_history.csv; empty: none),
# BUILD (build: built first with scripts/build.sh; another folder is used as it is).
set -euo pipefail
cd "$(dirname "$0")/.."
build=${BUILD:-build}
if [ "$build" = build ]; then ./scripts/build.sh >/dev/null; fi
commit=$(git rev-parse --short HEAD)$(git diff --quiet HEAD -- dem bench || echo "+changes")
history=${HISTORY-bench/throughput_history.csv}
echo "commit $commit, $(nproc) cores, $(lscpu | sed -n 's/^Model name: *//p')"
table=$("$build"/bench/dem_throughput --bodies "${BODIES:-2000,10000}" --steps "${STEPS:-2000}" --threads 1,2)
echo "$table"
if [ -n "$history" ]; then
  [ -f "$history" ] || echo "commit,date,bodies,kind,threads,body_steps_per_s_per_core,sphere_steps_per_s_per_core,contact_steps_per_s_per_core" > "$history"
  # table columns: bodies, kind, threads, contacts, candidates, steps, wall s, body-, sphere-, contact-steps/s/core, ...
  echo "$table" | awk -F'|' -v c="$commit" -v d="$(date -u +%Y-%m-%d)" \
    'NR > 2 { gsub(/ /, ""); print c "," d "," $2 "," $3 "," $4 "," $9 "," $10 "," $11 }' >> "$history"
  echo "appended to $history"
fi
