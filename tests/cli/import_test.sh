#!/usr/bin/env bash
# `sffcal import` as a user calls it (docs/import.md): the committed YADE and LAMMPS (periodic and
# between walls) and LIGGGHTS runs (made by
# the real programs: scripts/regenerate_import_fixtures.sh) imported, analysed and calibrated, their
# imported contact stress against the source's own; an existing output kept unless --force; with
# `yade`, `lmp` and `liggghts` installed (CI installs them), a fresh run of each end to end, LAMMPS on two MPI
# ranks (--oversubscribe: a machine of one core runs them too), LIGGGHTS likewise. Usage: import_test.sh SFFCAL_BINARY PYTHON
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

# Between walls: the worst |sigma_walls - sigma_source| / |sigma_source| over the snapshots of RUN,
# sigma_walls from the imported walls (their contacts' normal forces over the face areas).
wall_stress_agreement() {
  "$python" - "$1" <<'PY'
import sys
import h5py
import numpy as np
with h5py.File(sys.argv[1], "r") as f:
    series = f["series"]
    rows = {int(s): k for k, s in enumerate(series["step"][()])}
    worst = 0.0
    for name, snapshot in f["snapshots"].items():
        walls = snapshot["walls"][()]
        lo, hi, force = np.zeros(3), np.zeros(3), np.zeros(3)
        for w in walls:
            (hi if w["upper"] else lo)[w["axis"]] = w["position"]
            force[w["axis"]] += 0.5 * w["normal_force"]
        size = hi - lo
        stress = force * size / np.prod(size)
        r = rows[int(snapshot.attrs["step"])]
        source = np.array([series["stress_" + c][r] for c in ("xx", "yy", "zz")])
        worst = max(worst, np.abs(stress - source).max() / np.linalg.norm(source))
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
# An import that stops on a damaged dump leaves nothing behind, and keeps what --force would replace.
mkdir damaged && cp "$(dirname "$fixture")"/* damaged/
head -c 300000 "$(dirname "$fixture")/contacts.dump" > damaged/contacts.dump
out=$("$sffcal" import damaged/import.toml -o new.h5 2>&1) && fail "a truncated dump was imported"
[[ $out == *"contacts dump"*"line"* && ! -e new.h5 ]] && echo "ok   a failed import leaves no file" \
  || fail "failed import: $out; $(ls)"
cp run.h5 kept.h5
"$sffcal" import damaged/import.toml -o run.h5 --force > /dev/null 2>&1
cmp -s run.h5 kept.h5 && [[ -z $(ls | grep replacing) ]] \
  && echo "ok   a failed import with --force keeps the file it would replace" || fail "failed --force"

# import_analyse_calibrate NAME DESCRIPTION [AGREEMENT]: import, sff and calibrate, the stress
# against the source's (AGREEMENT: stress_agreement, or wall_stress_agreement between walls).
import_analyse_calibrate() {
  local name=$1 description=$2 agreement=${3:-stress_agreement} worst
  "$sffcal" import "$description" -o "$name.h5" > "$name.log" 2>&1 \
    && "$sffcal" sff "$name.h5" --resamples 0 >> "$name.log" 2>&1 \
    || { cat "$name.log"; fail "$name: import and sff"; return; }
  worst=$("$agreement" "$name.h5")
  "$python" -c "import sys; sys.exit(0 if float('$worst') < 1e-6 else 1)" \
    && echo "ok   $name: the imported contacts give the source's stress ($worst, $agreement)" \
    || fail "$name: stress agreement $worst"
  "$sffcal" calibrate "$name.h5" -o "$name.fit" >> "$name.log" 2>&1 && [ -s "$name.fit/parameters.json" ] \
    && echo "ok   $name: the import calibrates" || { cat "$name.log"; fail "$name: calibrate"; }
}

import_analyse_calibrate yade_fixture "$fixture"
import_analyse_calibrate lammps_fixture "$source_dir/tests/data/import/lammps/import.toml"
import_analyse_calibrate liggghts_fixture "$source_dir/tests/data/import/liggghts/import.toml"
import_analyse_calibrate lammps_walls_fixture "$source_dir/tests/data/import/lammps_walls/import.toml" \
  wall_stress_agreement
import_analyse_calibrate yade_walls_fixture "$source_dir/tests/data/import/yade_walls/import.toml" \
  wall_stress_agreement

# Fresh runs, where the programs are installed (CI installs them).
if command -v yade > /dev/null; then
  PYTHONPATH="$source_dir/python" yade -n -j1 -x "$source_dir/examples/yade/triaxial.py" \
    --clumps 100 --final-strain 0.02 --frame-strain 0.01 --seed 3 --output yade_run > yade.log 2>&1 \
    && import_analyse_calibrate yade_fresh yade_run/import.toml || { tail -20 yade.log; fail "the YADE run"; }
  cat > bad_walls.py <<'PY'
from yade import utils
from yade.wrapper import Omega
from sffcal.yade_export import Exporter
O = Omega()
ids = O.bodies.append(utils.aabbWalls([(0, 0, 0), (1, 1, 1)], thickness=0.1))
ids.append(O.bodies.append(utils.sphere((0.5, 0.5, 0.5), 0.1)))
for walls in (ids[:5], ids[1:]):
    try:
        Exporter("bad_walls_out", physics={}, test={}, walls=walls)
    except ValueError as e:
        print("refused:", e)
PY
  out=$(PYTHONPATH="$source_dir/python" yade -n -j1 -x bad_walls.py 2>&1)
  [[ $out == *"walls must be six distinct body ids"* && $out == *"wall 6 is not a Box body"* \
     && ! -e bad_walls_out ]] && echo "ok   the YADE exporter refuses walls that are not six boxes" \
    || fail "the exporter's walls: $out"
  PYTHONPATH="$source_dir/python" yade -n -j1 -x "$source_dir/examples/yade/triaxial.py" --walls \
    --clumps 100 --final-strain 0.02 --frame-strain 0.01 --seed 3 --output yade_walls_run \
    > yade_walls.log 2>&1 \
    && import_analyse_calibrate yade_walls_fresh yade_walls_run/import.toml wall_stress_agreement \
    || { tail -20 yade_walls.log; fail "the YADE run between walls"; }
else
  echo "skip a fresh YADE run: yade is not installed"
fi
if command -v lmp > /dev/null && command -v mpirun > /dev/null; then
  MPIRUN_FLAGS=--oversubscribe "$source_dir/examples/lammps/run.sh" -np 2 lammps_run -var nclumps 100 -var final_strain 0.02 \
    -var seed 3 > lammps.log 2>&1 \
    && import_analyse_calibrate lammps_fresh_2_ranks lammps_run/import.toml \
    || { tail -20 lammps.log; fail "the LAMMPS run"; }
  # Between walls: a specimen of sffcal's sheared in LAMMPS with sffcal's lateral servo.
  sed -e 's/^seed = 1$/seed = 3/' -e 's/^bodies = 200$/bodies = 150/' \
    "$source_dir/examples/lammps/walls/specimen.toml" > prepare.toml
  "$sffcal" prepare -c prepare.toml -o specimen.h5 > prepare.log 2>&1 \
    && MPIRUN_FLAGS=--oversubscribe "$source_dir/examples/lammps/walls/run.sh" -np 2 specimen.h5 \
         lammps_walls_run -var nsteps 4000 > lammps_walls.log 2>&1 \
    && import_analyse_calibrate lammps_walls_fresh_2_ranks lammps_walls_run/import.toml \
         wall_stress_agreement \
    || { tail -20 prepare.log lammps_walls.log; fail "the LAMMPS run between walls"; }
else
  echo "skip a fresh LAMMPS run: lmp (Debian's lammps) is not installed"
fi
if command -v liggghts > /dev/null && command -v mpirun > /dev/null; then
  MPIRUN_FLAGS=--oversubscribe "$source_dir/examples/liggghts/run.sh" -np 2 liggghts_run \
    -var n 300 -var final_strain 0.02 -var seed 10009 > liggghts.log 2>&1 \
    && import_analyse_calibrate liggghts_fresh_2_ranks liggghts_run/import.toml \
    || { tail -20 liggghts.log; fail "the LIGGGHTS run"; }
else
  echo "skip a fresh LIGGGHTS run: liggghts is not installed"
fi
exit $((failures > 0))
