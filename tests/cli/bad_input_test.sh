#!/usr/bin/env bash
# Bad input as a careless or hostile user gives it to sffcal (issue 17): each is refused with a
# non-zero exit and a message that names the cause, never a crash, a hang or a wrapped number,
# and the files given are left as they were. Usage: bad_input_test.sh SFFCAL_BINARY [PYTHON].
# PYTHON (with h5py) edits a checkpoint; without it those cases are skipped and say so.
set -u
sffcal=$1
python=${2:-/usr/bin/python3}
examples=$(cd "$(dirname "$0")/../../examples" && pwd)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work"
failures=0
cases=0

# expect_failure DESCRIPTION NEEDLE COMMAND...: the command exits non-zero (not by a signal) within
# 60 s and says NEEDLE.
expect_failure() {
  local what=$1 needle=$2
  shift 2
  cases=$((cases + 1))
  local output status
  output=$(timeout 60 "$@" 2>&1)
  status=$?
  if [ $status -eq 0 ]; then
    echo "FAIL $what: exit status 0"; failures=$((failures + 1))
  elif [ $status -ge 124 ]; then
    echo "FAIL $what: killed or timed out (status $status): $output"; failures=$((failures + 1))
  elif [[ $output != *"$needle"* ]]; then
    echo "FAIL $what: message without '$needle': $output"; failures=$((failures + 1))
  else
    echo "ok   $what"
  fi
}

# A small scene: 60 clumps, a short test with frequent checkpoints.
"$sffcal" config -o base.toml > /dev/null || { echo "FAIL config"; exit 1; }
sed -e 's/^bodies = .*/bodies = 60/' -e 's/^max_axial_strain = .*/max_axial_strain = 0.02/' \
  -e 's/^checkpoint_strain_interval = .*/checkpoint_strain_interval = 0.005/' base.toml > small.toml

# Configs.
: > empty.toml
expect_failure "an empty config is refused, not run with every default" "sets no key" \
  "$sffcal" prepare -c empty.toml -o s.h5
sed 's/^bodies = .*/bodies = 4294967376/' small.toml > wrap.toml
expect_failure "bodies = 2^32 + 80 is refused, not wrapped to 80" "bodies must be in" \
  "$sffcal" prepare -c wrap.toml -o s.h5
sed 's/^threads = .*/threads = 4294967297/' small.toml > threads.toml
expect_failure "threads = 2^32 + 1 is refused, not wrapped to 1" "threads must be in" \
  "$sffcal" prepare -c threads.toml -o s.h5
sed 's/^bodies = .*/bodies = 1e9/' small.toml > float.toml
expect_failure "a float where an integer belongs" "bodies must be an integer" \
  "$sffcal" prepare -c float.toml -o s.h5
sed 's/^friction = .*/friction = nan/' small.toml > nan.toml
expect_failure "a NaN friction" "friction" "$sffcal" prepare -c nan.toml -o s.h5
printf '[grains\n' > syntax.toml
expect_failure "a TOML syntax error names the line" "TOML syntax error at line 1" \
  "$sffcal" prepare -c syntax.toml -o s.h5
test ! -e s.h5 && echo "ok   no specimen was written by the refused configs" ||
  { echo "FAIL s.h5 was written"; failures=$((failures + 1)); }

# Run files.
"$sffcal" prepare -c small.toml -o specimen.h5 > /dev/null || { echo "FAIL prepare"; exit 1; }
expect_failure "--resume on a specimen file names what it is" "is a specimen file" \
  "$sffcal" triaxial --resume -o specimen.h5
"$sffcal" triaxial -c small.toml -s specimen.h5 -o run.h5 > /dev/null || { echo "FAIL triaxial"; exit 1; }
echo "not HDF5" > text.h5
expect_failure "a text file given as a run file" "cannot open the file" "$sffcal" info text.h5

# A run file edited by hand: short arrays, indices out of range, NaN.
if "$python" -c 'import h5py, numpy' 2> /dev/null; then
  tamper() {  # tamper FILE CASE
    "$python" - "$1" "$2" << 'EOF'
import sys
import h5py
import numpy as np
with h5py.File(sys.argv[1], "r+") as f:
    g = f["checkpoint"]
    case = sys.argv[2]
    if case == "short_mass":
        m = g["mass"][:-3]
        del g["mass"]
        g["mass"] = m
    elif case == "pair_index":
        p = g["pair_j"][:]
        p[0] = 10**6
        g["pair_j"][...] = p
    elif case == "wall_index":
        w = g["wall_index"][:]
        w[0] = 99
        g["wall_index"][...] = w
    elif case == "nan_position":
        x = g["position"][:]
        x[2, 0] = np.nan
        g["position"][...] = x
    elif case == "first_sphere":
        s = g["first_sphere"][:]
        s[1] = 10**6
        g["first_sphere"][...] = s
    elif case == "nan_extra":
        g["extras"].attrs["height0"] = np.nan
    elif case == "zero_height":
        g["extras"].attrs["height0"] = 0.0
    elif case == "negative_width":
        g["extras"].attrs["width0_x"] = -1e-3
    elif case == "series_ahead":
        g.attrs["series_length"] = np.int64(10**9)
    elif case == "snapshots_ahead":
        g.attrs["num_snapshots"] = np.int64(-1)
    elif case == "series_behind":  # rows would be dropped: the state is past them
        g.attrs["series_length"] = np.int64(g.attrs["series_length"] - 3)
    elif case == "snapshots_behind":
        g.attrs["num_snapshots"] = np.int64(0)
    elif case == "nan_axial_stress":
        g["extras"].attrs["axial_stress"] = np.nan
    elif case == "nan_servo":
        s = g["wall_servo_integral"][:]
        s[0] = np.nan
        g["wall_servo_integral"][...] = s
    elif case == "spinning":  # finite, and it ran on
        L = g["angular_momentum"][:]
        L[0] = 1e300
        g["angular_momentum"][...] = L
    elif case == "two_values":  # read into one value, it overflowed the stack
        f.attrs["schema_version"] = np.array([2, 2], dtype=np.int64)
    elif case == "nan_p":
        p = f["series/p"][:]
        p[1] = np.nan
        f["series/p"][...] = p
    elif case == "one_row":
        for name in f["series"]:
            f["series"][name].resize((1,))
    elif case == "falling_strain":
        a = f["series/axial_strain"][:]
        a[2] = a[1] - 1e-3
        f["series/axial_strain"][...] = a
    elif case == "snapshot_body":
        c = f["snapshots/000000/contacts"][:]
        c["body_a"][0] = 10**9
        f["snapshots/000000/contacts"][...] = c
    elif case == "newer_schema":
        f.attrs["schema_version"] = np.int64(3)
    elif case == "no_physics":
        del f["physics"]
EOF
  }
  for c in short_mass:"mass has 57 entries" pair_index:"pair 0" wall_index:"wall candidate 0" \
           nan_position:"not finite" first_sphere:"outside the" \
           nan_extra:"'height0' is not finite" zero_height:"'height0' = 0" \
           negative_width:"'width0_x' = -0.001" series_ahead:"series_length 1000000000" \
           snapshots_ahead:"num_snapshots -1" series_behind:"its next row is due at" \
           snapshots_behind:"it keeps no snapshot" nan_axial_stress:"'axial_stress' is not finite" \
           nan_servo:"servo state of wall 0 is not finite" spinning:"more than its radius" \
           two_values:"holds 2 values where one is expected"; do
    name=${c%%:*}
    cp run.h5 "$name.h5"
    tamper "$name.h5" "$name"
    expect_failure "a checkpoint with a bad ${name//_/ } is refused by name" "${c#*:}" \
      "$sffcal" triaxial --resume -o "$name.h5"
  done
  for c in nan_p:"not finite" falling_strain:"does not rise at row 2" \
           one_row:"fe-check compares at least two"; do
    name=${c%%:*}
    cp run.h5 "$name.h5"
    tamper "$name.h5" "$name"
    expect_failure "fe-check --dem with a run whose series has ${name//_/ } is refused" "${c#*:}" \
      "$sffcal" fe-check --parameters "$examples/acst_toyoura.json" --dem "$name.h5" --no-mesh -o "fe_$name"
  done
  expect_failure "a triaxial run given as a specimen (-s) is refused" "not a specimen" \
    "$sffcal" triaxial -c small.toml -s run.h5 -o from_run.h5
  cp run.h5 snapshot_body.h5
  tamper snapshot_body.h5 snapshot_body
  expect_failure "vtk of a snapshot whose contact names a missing body" "refers to body 1000000000" \
    "$sffcal" vtk snapshot_body.h5 -o vtk
  # The run file's schema (issue 15): a newer one is refused naming both versions, and a schema-2
  # file without its /physics names the group rather than guessing the constants.
  cp run.h5 newer_schema.h5
  tamper newer_schema.h5 newer_schema
  expect_failure "a run file of a newer schema is refused" "schema version 3, this version reads 1 to 2" \
    "$sffcal" info newer_schema.h5
  cp run.h5 no_physics.h5
  tamper no_physics.h5 no_physics
  expect_failure "a schema-2 run file without /physics names it" "cannot open group physics" \
    "$sffcal" sff no_physics.h5
else
  echo "skip the edited checkpoints: $python has no h5py"
fi

# The model and fe-check.
expect_failure "fe-check with a void ratio the model cannot carry" "--void-ratio -1 is not" \
  "$sffcal" fe-check --parameters "$examples/acst_toyoura.json" --void-ratio -1 --no-mesh -o fe
printf '{"model": "acst", "parameters": {"G0": {"value": 1e400}}}' > overflow.json
expect_failure "a parameter file with 1e400 names the file" "overflow.json" \
  "$sffcal" fe-check --parameters overflow.json --no-mesh -o fe
sed 's/"value": 125.0/"value": NaN/' "$examples/acst_toyoura.json" > nan.json
expect_failure "a parameter file with NaN names the file" "nan.json" \
  "$sffcal" fe-check --parameters nan.json --no-mesh -o fe
# Bounded work: a cone narrower than the integration resolves in bounded substeps (m = 1e-8 ran
# 69 s and failed its checks) is refused by value; an FE run past its wall-time budget stops by name.
sed '/"m": {/,/}/ s/"value": 0.01/"value": 1e-8/' "$examples/acst_toyoura.json" > narrow_cone.json
expect_failure "an ACST cone narrower than 1e-4 (minutes of substeps) is refused" \
  "'m' = 1e-08 is not physical: it must be >= 0.0001" \
  "$sffcal" fe-check --parameters narrow_cone.json --no-mesh -o fe
expect_failure "fe-check --time-limit below 0" "--time-limit must be >= 0" \
  "$sffcal" fe-check --parameters "$examples/acst_toyoura.json" --time-limit -1 --no-mesh -o fe
expect_failure "an FE run past fe-check's --time-limit stops naming the limit" \
  "wall-time limit of 1e-09 s" \
  "$sffcal" fe-check --parameters "$examples/acst_toyoura.json" --time-limit 1e-9 --no-mesh \
  --pressures 1e5 -o fe_time_limit
expect_failure "calibrate --range beyond a parameter's physical range" \
  "0.7 is not physical for 'nu'" "$sffcal" calibrate small.toml -o fit --range nu=0:0.7
expect_failure "calibrate --range with a name the fit does not know" "unknown parameter 'n_x'" \
  "$sffcal" calibrate small.toml -o fit --range n_x=0:1

# Second round (issue 51): inputs that are not finite, not files, or not what they claim.
expect_failure "a config that is a device (/dev/zero) is refused, not read until memory ends" \
  "not a regular file" "$sffcal" prepare -c /dev/zero -o refused.h5
for option in "--a-cs nan" "--dem-eta-tol nan" "--pressures 1e5,inf" "--max-strain 1e999"; do
  expect_failure "fe-check $option: a numeric option that is not finite" "not a finite number" \
    "$sffcal" fe-check --parameters "$examples/acst_toyoura.json" $option -o refused
done
printf '%s trailing' "$(cat "$examples/acst_toyoura.json")" > trailing.json
expect_failure "a parameter file with content after its JSON" "expected end of input" \
  "$sffcal" umat-cards --parameters trailing.json
sed 's/"parameters": {/"parameters": {"G0": {"value": 99, "unit": "1"},/' \
  "$examples/acst_toyoura.json" > duplicate.json
expect_failure "a parameter file with a key twice (the last silently won)" "appears twice" \
  "$sffcal" umat-cards --parameters duplicate.json
sed 's/"parameters": {/"parameters": {"nF": {"value": 5, "unit": "1"},/' \
  "$examples/acst_toyoura.json" > misspelt.json  # n_F is optional: read as 0 before
expect_failure "a misspelt optional parameter, named with the nearest one" "nearest: 'n_F'" \
  "$sffcal" umat-cards --parameters misspelt.json

# A packing row with a finite but huge position: refused, naming the span (it crashed the grid).
printf '# box: 0 0 0 1e21 6e-4 6e-4\nx,y,z,axis_x,axis_y,axis_z,diameter\n' > far.csv  # the body lies inside its box
printf '1.2e-4,1.2e-4,1.2e-4,0,0.6,0.8,5e-05\n3e-4,3e-4,3e-4,0,0.6,0.8,5e-05\n1e20,3e-4,1.2e-4,0,0.6,0.8,5e-05\n' >> far.csv
sed -e 's/^method = "compaction"/method = "csv"/' -e "s|^csv = \"\"|csv = \"$work/far.csv\"|" \
  small.toml > far.toml
expect_failure "a packing body at x = 1e20 m is refused, naming where" "far outside" \
  "$sffcal" prepare -c far.toml -o far.h5

sed -e 's/^strain_rate = .*/strain_rate = 1e9/' small.toml > fast.toml
expect_failure "strain_rate = 1e9 is refused, not run past its limit to a negative void ratio" \
  "lower strain_rate" "$sffcal" triaxial -c fast.toml -s specimen.h5 -o fast.h5

# Outputs that are not regular files, and the files a run writes beside its run file.
mkfifo fifo.h5
expect_failure "--force never replaces a FIFO (it replaced /dev/null before)" "not a regular file" \
  "$sffcal" prepare -c small.toml -o fifo.h5 --force
[ -p fifo.h5 ] && echo "ok   the FIFO is still a FIFO" || { echo "FAIL the FIFO was replaced"; failures=$((failures + 1)); }
cp small.toml run2.h5.series.csv
expect_failure "a file named like the run's series CSV is not overwritten without --force" \
  "run2.h5.series.csv' exists" "$sffcal" triaxial -c small.toml -s specimen.h5 -o run2.h5
cmp -s small.toml run2.h5.series.csv && echo "ok   it is left as it was" || { echo "FAIL it changed"; failures=$((failures + 1)); }
# A run file is made under a name no file holds: a user's own files named like it are never
# touched (mine.h5.partial was deleted before, as the fixed name of the file being made).
echo "mine" > mine.h5.partial
echo "mine" > "mine.h5.partial-$$-0"
if "$sffcal" prepare -c small.toml -o mine.h5 --force > /dev/null 2>&1 && [ -s mine.h5 ] &&
   grep -q mine mine.h5.partial && grep -q mine "mine.h5.partial-$$-0"; then
  echo "ok   a user's own X.partial and X.partial-N are left as they were"
else
  echo "FAIL a user's X.partial file was touched"; failures=$((failures + 1))
fi
cp small.toml run3.h5.series.csv
expect_failure "a config named like the run's series CSV is refused as an output, even with --force" \
  "also an input" "$sffcal" triaxial -c run3.h5.series.csv -s specimen.h5 -o run3.h5 --force

mkdir -p fe && cp "$examples/acst_toyoura.json" fe/summary.csv
expect_failure "fe-check whose parameter file lies in its output folder (summary.csv was overwritten)" \
  "lies in the output folder" "$sffcal" fe-check --parameters fe/summary.csv -o fe --no-mesh
cmp -s "$examples/acst_toyoura.json" fe/summary.csv && echo "ok   it is left as it was" || { echo "FAIL it changed"; failures=$((failures + 1)); }

sed -e 's/^density = .*/density = 265000.0/' small.toml > heavy.toml
expect_failure "a config whose grain density differs from the specimen's (recorded, not applied)" \
  "differs from the specimen's" "$sffcal" triaxial -c heavy.toml -s specimen.h5 -o heavy.h5

echo "$cases bad inputs, $failures check(s) failed"
exit $((failures > 0))
