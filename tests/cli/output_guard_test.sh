#!/usr/bin/env bash
# The output checks of the sffcal front end (apps/sffcal/output_guard.h), as a user meets them:
# an existing output is refused without --force and left untouched, an output that is an input is
# refused, a missing or non-folder destination is refused before any work, a failed write is an
# error, and --force replaces a run only once the new one is complete.
# Usage: output_guard_test.sh SFFCAL_BINARY. Exit status 0 when every check passes.
set -u
sffcal=$1
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work"
failures=0

# expect_failure DESCRIPTION NEEDLE COMMAND...: the command exits non-zero and says NEEDLE.
expect_failure() {
  local what=$1 needle=$2
  shift 2
  local output
  if output=$("$@" 2>&1); then
    echo "FAIL $what: exit status 0"; failures=$((failures + 1))
  elif [[ $output != *"$needle"* ]]; then
    echo "FAIL $what: message without '$needle': $output"; failures=$((failures + 1))
  else
    echo "ok   $what"
  fi
}
expect_unchanged() {
  if cmp -s "$1" "$2"; then echo "ok   $3"; else echo "FAIL $3"; failures=$((failures + 1)); fi
}

"$sffcal" config -o my.toml > /dev/null || { echo "FAIL config -o my.toml"; exit 1; }
cp my.toml original.toml
echo "# edited by hand" >> my.toml
cp my.toml edited.toml

expect_failure "config -o onto an existing file is refused" "pass --force" \
  "$sffcal" config -o my.toml
expect_unchanged my.toml edited.toml "the existing file is left as it was"
"$sffcal" config -o my.toml --force > /dev/null && expect_unchanged my.toml original.toml \
  "config -o --force overwrites it"
# A device is never replaced, even with --force.
expect_failure "an output that is a device (/dev/full) is refused" "is not a regular file" \
  "$sffcal" config -o /dev/full --force
# A failed write, without root (full_disk_test.sh mounts a full disk): under a 1 kB file-size
# limit, with SIGXFSZ ignored, writing the config fails with EFBIG and nothing is left behind.
expect_failure "a failed write (a file-size limit) is an error naming the file" \
  "writing limited.toml failed" bash -c "ulimit -f 1; trap '' XFSZ; exec \"\$0\" config -o limited.toml" "$sffcal"
if [ ! -e limited.toml ] && [ -z "$(ls limited.toml.partial-* 2> /dev/null)" ]; then
  echo "ok   ... and leaves no file, whole or partial"
else
  echo "FAIL a failed write left a file"; failures=$((failures + 1))
fi

expect_failure "prepare with the output equal to the config is refused" "is also an input" \
  "$sffcal" prepare -c my.toml -o my.toml
expect_failure "... also when spelled differently, with --force" "is also an input" \
  "$sffcal" prepare -c my.toml -o ./my.toml --force
expect_unchanged my.toml original.toml "the config is left as it was"
cp my.toml specimen.h5
expect_failure "triaxial with the output equal to the specimen is refused" "is also an input" \
  "$sffcal" triaxial -c my.toml -s specimen.h5 -o "$work/specimen.h5" --force
expect_unchanged specimen.h5 original.toml "the specimen is left as it was"
expect_failure "prepare into a missing folder is refused before any work" "does not exist" \
  "$sffcal" prepare -c my.toml -o missing/specimen.h5
cp my.toml run.h5.specimen.h5
expect_failure "dem refuses an existing specimen file beside the run" "run.h5.specimen.h5' exists" \
  "$sffcal" dem -c my.toml -o run.h5
expect_failure "an output folder under a file cannot be created" "not a writable folder" \
  "$sffcal" vtk specimen.h5 -o my.toml/vtk
# A folder that takes no new file whoever runs the test: root writes into a mode-555 folder, so
# /proc (which accepts no new files, even from root) stands for a read-only mount.
expect_failure "prepare into a folder that takes no files (/proc) is refused before any work" \
  "not a writable folder" "$sffcal" prepare -c my.toml -o /proc/specimen.h5
expect_failure "calibrate into a folder that cannot be made under /proc is refused before the fit" \
  "cannot be created" "$sffcal" calibrate specimen.h5 -o /proc/sffcal-calibration
if [[ $(id -u) != 0 ]]; then
  mkdir locked && chmod 555 locked
  expect_failure "prepare into a mode-555 folder is refused before any work" \
    "not a writable folder" "$sffcal" prepare -c my.toml -o locked/specimen.h5
  chmod 755 locked
else
  echo "skip the mode-555 folder (root may write into it)"
fi
test ! -e run.h5 && echo "ok   nothing was written by the refused commands" ||
  { echo "FAIL run.h5 was written"; failures=$((failures + 1)); }

# --force never destroys a good run before the new one is whole: a replacing run is made beside
# it (X.replacing-PID-N) and moved over it only when complete.
sed -e 's/^bodies = .*/bodies = 40/' -e 's/^threads = .*/threads = 1/' \
  -e 's/^max_axial_strain = .*/max_axial_strain = 0.004/' original.toml > small.toml
sed -e 's/^max_overlap_ratio = .*/max_overlap_ratio = 0.0001/' small.toml > fails.toml
if "$sffcal" prepare -c small.toml -o small_specimen.h5 > /dev/null &&
   "$sffcal" triaxial -c small.toml -s small_specimen.h5 -o keep.h5 > /dev/null; then
  cp keep.h5 keep_before.h5
  cp keep.h5.series.csv keep_before.csv
  expect_failure "--force with a run that fails keeps the earlier run and says so" \
    "'keep.h5' is kept as it was" "$sffcal" triaxial -c fails.toml -s small_specimen.h5 -o keep.h5 --force
  expect_unchanged keep.h5 keep_before.h5 "... its run file unchanged"
  expect_unchanged keep.h5.series.csv keep_before.csv "... and its series CSV"
  # The failed run's own file stays beside it, named in its message; the completed one leaves none.
  left_before=$(ls keep.h5.replacing-* keep.h5.partial-* 2> /dev/null | wc -l)
  if "$sffcal" triaxial -c small.toml -s small_specimen.h5 -o keep.h5 --force > /dev/null &&
     [ "$(ls keep.h5.replacing-* keep.h5.partial-* 2> /dev/null | wc -l)" -eq "$left_before" ] &&
     [[ -s keep.h5 && -s keep.h5.series.csv ]]; then
    echo "ok   --force with a run that completes replaces it (nothing left beside it)"
  else
    echo "FAIL --force with a run that completes"; failures=$((failures + 1))
  fi
else
  echo "FAIL a small run for the --force checks"; failures=$((failures + 1))
fi

echo "$failures check(s) failed"
exit $((failures > 0))
