#!/usr/bin/env bash
# Sets up, builds and runs the main job: scripts/pipeline.py on the default scene
# (examples/main_scene.toml): four small specimens prepared and sheared in drained triaxial
# compression, analysed with SFF, three of them used to calibrate the ACST model, the deal.II
# element checks against the driver and all four DEM tests, and a report in out/main/report/.
# Arguments go to scripts/pipeline.py: e.g. --matrix (the paper-size matrix), --from calibrate,
# --only report, --force (docs/pipeline.md). Stages whose inputs are unchanged are skipped.
set -euo pipefail
cd "$(dirname "$0")/.."
./scripts/install_deps.sh
./scripts/build.sh
source scripts/python_env.sh  # the scripts import the package sffcal as built (docs/python.md)
/usr/bin/python3 scripts/pipeline.py "$@"
