#!/usr/bin/env bash
# Sets up, builds and runs the main job. At this stage of the project (DEM core), the main job
# prepares a small specimen of two-sphere clumps by isotropic compaction to 100 kPa and prints
# its state; later stages extend it to the full pipeline (triaxial, SFF, calibration, FE).
set -euo pipefail
cd "$(dirname "$0")/.."
./scripts/install_deps.sh
./scripts/build.sh
./build/sffcal compact "$@"
