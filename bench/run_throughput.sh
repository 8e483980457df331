#!/usr/bin/env bash
# Reproduces the throughput table of bench/RESULTS.md (builds first if needed).
# Run it on an otherwise idle machine: the figures are wall-clock rates.
set -euo pipefail
cd "$(dirname "$0")/.."
./scripts/build.sh >/dev/null
echo "commit $(git rev-parse --short HEAD), $(nproc) cores, $(lscpu | sed -n 's/^Model name: *//p')"
./build/bench/dem_throughput --bodies "${BODIES:-2000,10000}" --steps "${STEPS:-2000}" --threads 1,2
