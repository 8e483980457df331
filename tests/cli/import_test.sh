#!/usr/bin/env bash
# `sffcal import` as a user calls it (docs/import.md): the committed YADE run (made by the real
# program: scripts/regenerate_import_fixtures.sh) imported, analysed and calibrated; an existing
# output kept unless --force; with `yade` installed, a fresh YADE run end to end, its imported
# contact stress against YADE's own. Usage: import_test.sh SFFCAL_BINARY PYTHON
set -u
sffcal=$1
python=$2
source_dir=$(cd "$(dirname "$0")/../.." && pwd)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work"
failures=0
fail() { echo "FAIL $1"; failures=$((failures + 1)); }

# The worst |sigma_contacts - sigma_source| / |sigma_source| over the snapshots of RUN.
stress_agreement() {
  "$python" - "$1" <<'PY'
import sys
import h5py
import numpy as np
with h5py.File(sys.argv[1], "r") as f:
    series, table = f["series"], f["analysis/sff"]
    rows = {int(s): k for k, s in enumerate(series["step"][()])}
    worst = 0.0
    for k, step in enumerate(table["step"][()]):
        r = rows[int(step)]
        def tensor(group, index):
            v = {c: group["stress_" + c][index] for c in ("xx", "yy", "zz", "yz", "xz", "xy")}
            return np.array([[v["xx"], v["xy"], v["xz"]], [v["xy"], v["yy"], v["yz"]],
                             [v["xz"], v["yz"], v["zz"]]])
        source = tensor(series, r)
        worst = max(worst, np.linalg.norm(tensor(table, k) - source) / np.linalg.norm(source))
print(f"{worst:.3e}")
PY
}

fixture=$source_dir/tests/data/import/yade/import.toml
out=$("$sffcal" import "$fixture" -o run.h5 2>&1) || fail "import of the YADE fixture: $out"
[[ $out == *"wrote run.h5: 3 snapshots"* ]] && echo "ok   the YADE fixture imports" || fail "import: $out"
out=$("$sffcal" info run.h5 2>&1)
[[ $out == *"import: yade 2023.02a"* && $out == *"drained_compression"* ]] \
  && echo "ok   info names the source" || fail "info: $out"
cp run.h5 kept.h5
out=$("$sffcal" import "$fixture" -o run.h5 2>&1) && fail "an existing output was overwritten"
[[ $out == *"run.h5"*"exists"* ]] && cmp -s run.h5 kept.h5 && echo "ok   an existing output is kept" \
  || fail "existing output: $out"
"$sffcal" import "$fixture" -o run.h5 --force > /dev/null 2>&1 && echo "ok   --force replaces it" \
  || fail "--force"
"$sffcal" sff run.h5 --resamples 0 > sff.log 2>&1 || { cat sff.log; fail "sff of the import"; }
worst=$(stress_agreement run.h5)
"$python" -c "import sys; sys.exit(0 if float('$worst') < 1e-6 else 1)" \
  && echo "ok   the imported contacts give YADE's stress ($worst)" || fail "stress agreement $worst"
"$sffcal" calibrate run.h5 -o fit > fit.log 2>&1 && [ -s fit/parameters.json ] \
  && echo "ok   the import calibrates" || { cat fit.log; fail "calibrate the import"; }

# A fresh YADE run, where YADE is installed (CI installs it).
if command -v yade > /dev/null; then
  PYTHONPATH="$source_dir/python" yade -n -j1 -x "$source_dir/examples/yade/triaxial.py" \
    --clumps 100 --final-strain 0.02 --frame-strain 0.01 --seed 3 --output fresh > yade.log 2>&1 \
    || { tail -20 yade.log; fail "the YADE run"; }
  "$sffcal" import fresh/import.toml -o fresh.h5 > /dev/null 2>&1 \
    && "$sffcal" sff fresh.h5 --resamples 0 > /dev/null 2>&1 || fail "import and sff of a fresh YADE run"
  worst=$(stress_agreement fresh.h5)
  "$python" -c "import sys; sys.exit(0 if float('$worst') < 1e-6 else 1)" \
    && echo "ok   a fresh YADE run: its imported contacts give YADE's stress ($worst)" \
    || fail "fresh stress agreement $worst"
else
  echo "skip a fresh YADE run: yade is not installed"
fi
exit $((failures > 0))
