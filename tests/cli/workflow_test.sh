#!/usr/bin/env bash
# The main job's workflow (workflow/Snakefile) through its command line scripts/pipeline.py
# (docs/pipeline.md) on a tiny scene (tests/data/workflow/scene.toml): a run interrupted by SIGINT
# completes when run again; a run file equal, bit for bit, to that of the same config through
# `sffcal prepare` and `sffcal triaxial` by hand; a second run with nothing changed runs no job; a
# changed option of the fit reruns the fit and what follows it only; --only, --from and --force
# select the jobs they say; bad options are refused by name and a failed job shows its log; the
# paper-size matrix scene plans every specimen of the matrix; through the Slurm profile on a
# one-node Slurm started by the test (scripts/local_slurm.sh: as root, with Debian's slurm-wlm and
# munge), every output equal to the local run's.
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
pipeline() {
  /usr/bin/python3 "$source_dir/scripts/pipeline.py" --scene "$work/scene.toml" --sffcal "$sffcal" "$@"
}
# planned OUT [OPTIONS]: the rules of the jobs a dry run with OPTIONS lists, sorted, one per job
planned() {
  local out=$1; shift
  pipeline -o "$out" -n "$@" 2>&1 | sed -n 's/^ *[0-9]*:[0-9]* \(local\)\{0,1\}rule \([a-z_]*\):$/\2/p' \
    | sort | tr '\n' ' '
}

# Interrupted as Ctrl-C does (SIGINT to the process group) once the triaxial jobs run, then run
# again: the second run completes (its outputs are compared with the Slurm run's below).
set -m  # a background job of its own process group, SIGINT not ignored
pipeline -o "$work/local" > "$work/interrupted.log" 2>&1 &
leader=$!
for _ in $(seq 1200); do
  grep -q "rule triaxial:" "$work/local/pipeline.log" 2> /dev/null && break
  sleep 0.05
done
kill -INT -- "-$leader" 2> /dev/null
wait "$leader"
code=$?
set +m
if [[ $code == 130 ]] && grep -q "interrupted; the jobs that were running rerun next time" "$work/interrupted.log"; then
  echo "ok   an interrupted run stops and says so"
else
  tail -5 "$work/interrupted.log"; fail "the interrupted run exited with $code"
fi
pipeline -o "$work/local" > "$work/local.log" 2>&1 && echo "ok   the run after the interrupt completes" \
  || { tail -30 "$work/local.log"; fail "pipeline.py after the interrupt"; }

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

# One run of the workflow against the same config by hand: every dataset that `sffcal triaxial`
# writes is the same (the workflow's file holds the SFF tables besides).
stem=iso_dense_100kPa_s1
mkdir -p "$work/direct"
if "$sffcal" prepare -c "$work/local/configs/$stem.toml" -o "$work/direct/specimen.h5" > "$work/direct.log" 2>&1 \
   && "$sffcal" triaxial -c "$work/local/configs/$stem.toml" -s "$work/direct/specimen.h5" \
        -o "$work/direct/$stem.h5" >> "$work/direct.log" 2>&1; then
  /usr/bin/python3 - "$work/direct/$stem.h5" "$work/local/runs/$stem.h5" <<'PY' \
    && echo "ok   the workflow's run equals sffcal prepare + triaxial by hand" || fail "the workflow's run differs"
import sys

import h5py

differ, count = [], 0


def compare(a, b, where):
    global count
    for key in a:
        if isinstance(a[key], h5py.Group):
            compare(a[key], b[key], f"{where}/{key}")
        else:
            count += 1
            if a[key][()].tobytes() != b[key][()].tobytes():
                differ.append(f"{where}/{key}")


with h5py.File(sys.argv[1], "r") as a, h5py.File(sys.argv[2], "r") as b:
    compare(a, b, "")
print(f"{count} datasets compared; differing: {differ or 'none'}")
sys.exit(1 if differ or count < 10 else 0)
PY
else
  tail "$work/direct.log"; fail "sffcal prepare + triaxial by hand"
fi
[ -s "$work/local/report/report.md" ] && grep -q "Snakemake's benchmark records" "$work/local/report/report.md" \
  && echo "ok   the report's stage times come from the benchmark records" || fail "the report"
grep -q "rule triaxial:" "$work/local/pipeline.log" && echo "ok   the console's lines are in pipeline.log" \
  || fail "pipeline.log"
grep -qE "^ *[0-9]+:[0-9]+ checks: [0-9]+ of [0-9]+ passed" "$work/local.log" \
  && echo "ok   the console ends with the report's count of checks" || fail "no count of checks on the console"

out=$(pipeline -o "$work/local" 2>&1)
[[ $out == *"Nothing to be done"* ]] && echo "ok   a second run with nothing changed runs no job" \
  || fail "second run: $out"

# A changed option of the fit: the fit, the check and the report rerun, nothing before them.
sed -i 's/"--points", "10"/"--points", "12"/' "$work/scene.toml"
jobs=$(planned "$work/local")
[[ $jobs == "calibrate fe_check report " ]] \
  && echo "ok   a changed fit option reruns calibrate, fe_check and report only" \
  || fail "after a changed option the dry run lists: $jobs"
sed -i 's/"--points", "12"/"--points", "10"/' "$work/scene.toml"

# The options that choose stages.
expect() {  # expect "JOBS" OPTIONS...: the jobs a dry run with OPTIONS lists
  local want=$1; shift
  jobs=$(planned "$work/local" "$@")
  [[ $jobs == "$want" ]] && echo "ok   $* plans: ${want:-nothing}" || fail "$* plans '$jobs', not '$want'"
}
expect "" --only report
expect "report " --only report --force
expect "calibrate fe_check report " --from calibrate --force
expect "all_triaxial triaxial triaxial triaxial triaxial " --only triaxial --force
expect "all_mean mean mean sff " --only sff,mean --force
report_time=$(stat -c %Y "$work/local/report/report.md")
fit_time=$(stat -c %Y "$work/local/calibrate/parameters.json")
sleep 1
pipeline -o "$work/local" --only report --force > "$work/only.log" 2>&1 \
  && [ "$(stat -c %Y "$work/local/report/report.md")" -gt "$report_time" ] \
  && [ "$(stat -c %Y "$work/local/calibrate/parameters.json")" = "$fit_time" ] \
  && echo "ok   --only report --force rewrites the report and nothing else" || fail "--only report --force"
refused() {  # refused "MESSAGE" OPTIONS...: pipeline.py exits non-zero, naming the problem
  local want=$1; shift
  if out=$(pipeline -o "$work/local" "$@" 2>&1); then
    fail "$* was accepted"
  else
    [[ $out == *"$want"* ]] && echo "ok   $* refused: $want" || fail "$* refused with: $out"
  fi
}
refused "unknown stage 'bogus'" --only bogus
refused "unknown stage 'fit'" --from fit
refused "give --only or --from, not both" --only sff --from sff
refused "not found: build it" --sffcal "$work/no_such_sffcal"
if out=$(pipeline -o "$work/empty" --only calibrate 2>&1); then
  fail "--only calibrate without the tests was accepted"
else
  [[ $out == *"Missing input files for rule calibrate"* ]] \
    && echo "ok   --only calibrate without the tests names the missing inputs" || fail "--only calibrate: $out"
fi

# A job that fails (an unknown model for the fit): exit code 1, the end of its log shown.
cp -a "$work/local" "$work/failing"
sed 's/"--points", "10"/"--points", "10", "--model", "no_such_model"/' "$work/scene.toml" > "$work/failing.toml"
out=$(/usr/bin/python3 "$source_dir/scripts/pipeline.py" --scene "$work/failing.toml" --sffcal "$sffcal" \
        -o "$work/failing" 2>&1)
code=$?
[[ $code == 1 && $out == *"the end of $work/failing/logs/calibrate_fit.log:"* \
   && $out == *"unknown model 'no_such_model'"* ]] \
  && echo "ok   a failed job: exit code 1, the end of its log shown" || fail "a failed job ($code): $out"

# The paper-size matrix scene: a prepare and a triaxial job for every specimen of the matrix.
specimens=$(/usr/bin/python3 -c "from sffcal import matrix; print(len(list(matrix.matrix())))")
plan=$(/usr/bin/python3 "$source_dir/scripts/pipeline.py" --matrix -o "$work/matrix" -n 2>&1)
prepare=$(echo "$plan" | grep -cE "^ *[0-9]+:[0-9]+ rule prepare(_deposit)?:$")
triaxial=$(echo "$plan" | grep -cE "^ *[0-9]+:[0-9]+ rule triaxial:$")
[[ $prepare == "$specimens" && $triaxial == "$specimens" ]] \
  && echo "ok   the matrix scene plans $specimens prepare and triaxial jobs" \
  || fail "the matrix scene plans $prepare prepare and $triaxial triaxial jobs, not $specimens"

# Through the Slurm profile on a one-node Slurm started here (as root, where slurm-wlm and munge
# are installed): the same outputs as the local run.
cluster="$work/cluster"
chmod go+x "$work"  # MUNGE's socket lies in it
if "$source_dir/scripts/local_slurm.sh" start "$cluster" > "$work/cluster.log" 2>&1; then
  SLURM_CONF="$cluster/slurm.conf" pipeline -o "$work/slurm" -- --profile "$source_dir/workflow/profiles/slurm" \
    > "$work/slurm.log" 2>&1 || { tail -30 "$work/slurm.log"; fail "the workflow on Slurm"; }
  jobs=$(grep -c "Submitted job .* with external jobid" "$work/slurm.log")
  same_outputs "$work/local" "$work/slurm" \
    && echo "ok   through Slurm ($jobs sbatch jobs) the outputs equal the local run's" \
    || fail "the Slurm run's outputs differ from the local run's"
  "$source_dir/scripts/local_slurm.sh" stop "$cluster" || fail "stopping the local Slurm"
else
  code=$?
  cat "$work/cluster.log"
  [[ $code == 77 ]] && echo "skip the Slurm run: no local Slurm here" || fail "starting a local Slurm"
fi
exit $((failures > 0))
