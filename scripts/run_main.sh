#!/usr/bin/env bash
# Sets up, builds and runs the main job: the Snakemake workflow workflow/Snakefile through its
# command line scripts/pipeline.py, on the default scene (examples/main_scene.toml): small
# specimens prepared and sheared on their loading paths with two seeds each, analysed with SFF,
# averaged, the ACST model calibrated on them, the deal.II element checks, and a report in
# out/main/report/. Arguments go to scripts/pipeline.py: e.g. --matrix (the paper-size matrix),
# --from calibrate, --only report, --force, -n, `-- --profile workflow/profiles/slurm` (a Slurm
# cluster); docs/pipeline.md. Jobs whose inputs are unchanged are not run again.
set -euo pipefail
cd "$(dirname "$0")/.."
./scripts/install_deps.sh
./scripts/build.sh
source scripts/python_env.sh  # the scripts import the package sffcal as built (docs/python.md)
/usr/bin/python3 scripts/pipeline.py "$@"
