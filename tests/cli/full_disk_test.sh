#!/usr/bin/env bash
# A full disk (docs/run-file.md, "A full disk"), on a small tmpfs: `triaxial` stops with an error
# that names it (no crash), and the run file it leaves holds every row and snapshot of its last
# flush and resumes, once there is room, to the uninterrupted run bit for bit; `--force` over a
# good run keeps it; `vtk`, `sff -o` and `config -o` fail by name and leave no empty or cut-short
# file. Mounting needs root (or sudo without a password): elsewhere the test is skipped (77).
# Usage: full_disk_test.sh SFFCAL_BINARY PYTHON (with h5py)
set -u
sffcal=$1
python=$2
work=$(mktemp -d)
disk=$work/disk
mkdir "$disk"
as_root=()
[ "$(id -u)" -eq 0 ] || as_root=(sudo -n)
if ! "${as_root[@]}" mount -t tmpfs -o size=1m tmpfs "$disk" 2> /dev/null; then
  echo "skip: cannot mount a tmpfs here (needs root or sudo without a password)"
  rm -rf "$work"
  exit 77
fi
trap '"${as_root[@]}" umount "$disk"; rm -rf "$work"' EXIT
cd "$work"
failures=0
pass() { echo "ok   $1"; }
fail() { echo "FAIL $1"; failures=$((failures + 1)); }

# expect_named_failure DESCRIPTION NEEDLE COMMAND...: exits 1..123 (not a signal) naming NEEDLE.
expect_named_failure() {
  local what=$1 needle=$2
  shift 2
  local output status
  output=$(timeout 120 "$@" 2>&1)
  status=$?
  if [ $status -eq 0 ] || [ $status -ge 124 ]; then
    fail "$what: exit status $status: $(echo "$output" | tail -2)"
  elif [[ $output != *"$needle"* ]]; then
    fail "$what: message without '$needle': $(echo "$output" | tail -2)"
  else
    pass "$what"
  fi
}

# 60 clumps, a snapshot every 0.2 % of strain: about 1 MB of run file by 2.6 %.
"$sffcal" config -o base.toml > /dev/null || { echo "FAIL config"; exit 1; }
sed -e 's/^bodies = .*/bodies = 60/' -e 's/^max_axial_strain = .*/max_axial_strain = 0.05/' \
  -e 's/^snapshot_strain_interval = .*/snapshot_strain_interval = 0.002/' base.toml > small.toml
"$sffcal" prepare -c small.toml -o specimen.h5 > /dev/null || { echo "FAIL prepare"; exit 1; }
"$sffcal" triaxial -c small.toml -s specimen.h5 -o whole.h5 > /dev/null || { echo "FAIL run"; exit 1; }

expect_named_failure "a run on a full disk stops by name" "no room on the disk" \
  "$sffcal" triaxial -c small.toml -s specimen.h5 -o "$disk/run.h5"
if info=$("$sffcal" info "$disk/run.h5" 2>&1) && [[ $info =~ snapshots:\ ([0-9]+) ]] &&
    [ "${BASH_REMATCH[1]}" -ge 1 ]; then
  pass "the run file left opens, with ${BASH_REMATCH[1]} snapshots"
else
  fail "the run file left does not open: $info"
fi

"${as_root[@]}" mount -o remount,size=20m "$disk"
if "$sffcal" triaxial --resume -o "$disk/run.h5" > resume.log 2>&1; then
  pass "with room again, --resume completes"
else
  fail "--resume after the full disk: $(tail -2 resume.log)"
fi
if "$python" - "$disk/run.h5" whole.h5 <<'PY'; then
import sys
import h5py
import numpy as np
a, b = h5py.File(sys.argv[1], "r"), h5py.File(sys.argv[2], "r")
names = list(b["series"].keys())
assert sorted(a["series"].keys()) == sorted(names)
for name in names:
    assert np.array_equal(a["series"][name][:], b["series"][name][:]), name
assert len(a["snapshots"]) == len(b["snapshots"])
for k in b["snapshots"]:
    for d in ("particles", "contacts"):
        assert a["snapshots"][k][d][:].tobytes() == b["snapshots"][k][d][:].tobytes(), (k, d)
PY
  pass "the resumed run is the uninterrupted one, bit for bit"
else
  fail "the resumed run differs from the uninterrupted one"
fi

# Full again: nothing may replace the good run, or leave empty or cut-short files.
cp "$disk/run.h5" good.h5
room=$(df --output=avail -B1 "$disk" | tail -1)
fallocate -l $((room - 16384)) "$disk/filler"
expect_named_failure "--force over a good run on a full disk fails by name" "No space left" \
  "$sffcal" triaxial -c small.toml -s specimen.h5 -o "$disk/run.h5" --force
if cmp -s good.h5 "$disk/run.h5"; then pass "the good run is kept"; else fail "the good run changed"; fi
expect_named_failure "vtk on a full disk fails by name" "disk full" \
  "$sffcal" vtk whole.h5 -o "$disk/vtk"
expect_named_failure "sff -o on a full disk fails by name" "disk full" \
  "$sffcal" sff whole.h5 -o "$disk/sff"
expect_named_failure "config -o on a full disk fails by name" "disk full" \
  "$sffcal" config -o "$disk/config.toml"
left=$(find "$disk" \( -empty -type f -o -name '*.partial*' -o -name '*.replacing*' \) -print)
if [ -z "$left" ] && [ ! -e "$disk/config.toml" ]; then
  pass "no empty, partial or cut-short file is left"
else
  fail "left behind: $left"
fi
echo "$failures failure(s)"
[ "$failures" -eq 0 ]
