#!/usr/bin/env bash
# The main job as a Snakemake workflow (workflow/Snakefile, docs/pipeline.md) against
# scripts/pipeline.py on a tiny scene (tests/data/workflow/scene.toml): the same run files, bit for
# bit (series, snapshots, the SFF tables), the mean tests, the fitted parameters and the element
# check; a second run with nothing changed runs no job; a changed option of the fit reruns the fit
# and what follows it only; through the Slurm profile on a one-node Slurm started by the test
# (scripts/local_slurm.sh: as root, with Debian's slurm-wlm and munge), the same outputs again.
# Skipped (77) where snakemake is not installed (CI installs it, and slurm-wlm and munge).
# Usage: workflow_test.sh SFFCAL_BINARY PYTHONPATH
set -u
sffcal=$1
export PYTHONPATH=$2
source_dir=$(cd "$(dirname "$0")/../.." && pwd)
command -v snakemake > /dev/null || { echo "skip: snakemake is not installed"; exit 77; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
failures=0
fail() { echo "FAIL $1"; failures=$((failures + 1)); }
cp "$source_dir/tests/data/workflow/scene.toml" "$work/scene.toml"
snake() {
  snakemake -s "$source_dir/workflow/Snakefile" --directory "$work/snake" --cores 2 \
    --config scene="$work/scene.toml" sffcal="$sffcal" "$@"
}

/usr/bin/python3 "$source_dir/scripts/pipeline.py" --scene "$work/scene.toml" -o "$work/pipeline" \
  --sffcal "$sffcal" > "$work/pipeline.log" 2>&1 || { tail -20 "$work/pipeline.log"; fail "pipeline.py"; }
mkdir -p "$work/snake"
snake > "$work/snake.log" 2>&1 || { tail -30 "$work/snake.log"; fail "snakemake"; }

# same_outputs A B: every dataset of every run file and mean test, the parameters and the check's
# table of output folder A equal those of B.
same_outputs() {
  /usr/bin/python3 - "$1" "$2" <<'PY'
import glob
import json
import os
import sys

import h5py

a_root, b_root = sys.argv[1:]
differ = []


def compare(a, b, where):
    for key in a:
        if isinstance(a[key], h5py.Group):
            compare(a[key], b[key], f"{where}/{key}")
        elif a[key][()].tobytes() != b[key][()].tobytes():
            differ.append(f"{where}/{key}")


files = sorted(glob.glob(os.path.join(a_root, "runs", "*.h5")) + glob.glob(os.path.join(a_root, "mean", "*.h5")))
assert len(files) == 6, files
for path in files:
    other = path.replace(a_root, b_root, 1)
    with h5py.File(path, "r") as a, h5py.File(other, "r") as b:
        compare(a, b, os.path.relpath(path, a_root))
parameters = [json.load(open(os.path.join(r, "calibrate", "parameters.json")))["parameters"]
              for r in (a_root, b_root)]
if parameters[0] != parameters[1]:
    differ.append("calibrate/parameters.json")
if open(os.path.join(a_root, "fe_check", "summary.csv")).read() != \
        open(os.path.join(b_root, "fe_check", "summary.csv")).read():
    differ.append("fe_check/summary.csv")
print(f"{len(files)} run files and mean tests compared; differing: {differ or 'none'}")
sys.exit(1 if differ else 0)
PY
}
same_outputs "$work/pipeline" "$work/snake" && echo "ok   the workflow's outputs equal pipeline.py's" \
  || fail "the workflow's outputs differ from pipeline.py's"
[ -s "$work/snake/report/report.md" ] && grep -q "Snakemake's benchmark records" "$work/snake/report/report.md" \
  && echo "ok   the report's stage times come from the benchmark records" || fail "the report"

out=$(snake 2>&1)
[[ $out == *"Nothing to be done"* ]] && echo "ok   a second run with nothing changed runs no job" \
  || fail "second run: $out"

# A changed option of the fit: the fit, the check and the report rerun, nothing before them.
sed -i 's/"--points", "10"/"--points", "12"/' "$work/scene.toml"
out=$(snake -n 2>&1)
jobs=$(echo "$out" | sed -n 's/^rule \([a-z_]*\):$/\1/p' | sort | tr '\n' ' ')
[[ $jobs == "calibrate fe_check report " ]] \
  && echo "ok   a changed fit option reruns calibrate, fe_check and report only" \
  || fail "after a changed option the dry run lists: $jobs"
sed -i 's/"--points", "12"/"--points", "10"/' "$work/scene.toml"

# Through the Slurm profile on a one-node Slurm started here (as root, where slurm-wlm and munge
# are installed): the same outputs as the local run.
cluster="$work/cluster"
chmod go+x "$work"  # MUNGE's socket lies in it
if "$source_dir/scripts/local_slurm.sh" start "$cluster" > "$work/cluster.log" 2>&1; then
  mkdir -p "$work/slurm"
  SLURM_CONF="$cluster/slurm.conf" snakemake -s "$source_dir/workflow/Snakefile" \
    --profile "$source_dir/workflow/profiles/slurm" --directory "$work/slurm" \
    --config scene="$work/scene.toml" sffcal="$sffcal" > "$work/slurm.log" 2>&1 \
    || { tail -30 "$work/slurm.log"; fail "snakemake on Slurm"; }
  jobs=$(grep -c "Submitted job .* with external jobid" "$work/slurm.log")
  same_outputs "$work/snake" "$work/slurm" \
    && echo "ok   through Slurm ($jobs sbatch jobs) the outputs equal the local run's" \
    || fail "the Slurm run's outputs differ from the local run's"
  "$source_dir/scripts/local_slurm.sh" stop "$cluster" || fail "stopping the local Slurm"
else
  code=$?
  cat "$work/cluster.log"
  [[ $code == 77 ]] && echo "skip the Slurm run: no local Slurm here" || fail "starting a local Slurm"
fi
exit $((failures > 0))
