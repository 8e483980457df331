#!/usr/bin/env bash
# Runs the reference test matrix (issue 7) as independent processes, JOBS at a time on this
# machine (xargs -P), then the SFF analysis of each run. Usage:
#   bench/matrix/run_matrix.sh [OUT=out/matrix] [JOBS=nproc] [BODIES=500] [ONLY=substring]
# On many machines run one specimen per MPI rank instead (OpenMPI comes with deal.II):
#   mpirun --allow-run-as-root -np 19 bash -c 'c=(out/matrix/configs/*.toml); \
#     f=${c[$OMPI_COMM_WORLD_RANK]}; n=$(basename $f .toml); \
#     build/sffcal dem -c $f -o out/matrix/$n.h5 > out/matrix/$n.log 2>&1'
# or a cluster job array with the same body indexed by $SLURM_ARRAY_TASK_ID.
set -euo pipefail
cd "$(dirname "$0")/../.."
out=${1:-out/matrix}
jobs=${2:-$(nproc)}
bodies=${3:-500}
only=${4:-}
./scripts/build.sh >/dev/null
source scripts/python_env.sh  # the package sffcal as built (docs/python.md)
mkdir -p "$out/configs"
/usr/bin/python3 bench/matrix/make_configs.py "$out/configs" --bodies "$bodies" --only "$only" >/dev/null
start=$(date +%s)
ls "$out"/configs/*"$only"*.toml | xargs -P "$jobs" -I{} bash -c \
  'n=$(basename {} .toml); /usr/bin/time -f "%e s" build/sffcal dem --force -c {} -o '"$out"'/$n.h5 > '"$out"'/$n.log 2>&1 \
   && build/sffcal sff '"$out"'/$n.h5 --resamples 50 >> '"$out"'/$n.log 2>&1 && echo "$n done" || echo "$n FAILED (see '"$out"'/$n.log)"'
echo "matrix: $(( $(date +%s) - start )) s with $jobs jobs"
