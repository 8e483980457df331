#!/usr/bin/env bash
# `sffcal info` on the run file as a user opens it (issue 15): a fresh run (schema 2) shows its
# physics and its summary from their attributes; a committed schema-1 reference file (reduced, no
# snapshots) still opens, its physics read from its stored config. Usage: info_test.sh SFFCAL_BINARY.
set -u
sffcal=$1
source_dir=$(cd "$(dirname "$0")/../.." && pwd)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work"
failures=0

# expect_lines DESCRIPTION OUTPUT NEEDLE...: OUTPUT holds every NEEDLE.
expect_lines() {
  local what=$1 output=$2
  shift 2
  for needle in "$@"; do
    if [[ $output != *"$needle"* ]]; then
      echo "FAIL $what: no '$needle' in:"; echo "$output"; failures=$((failures + 1)); return
    fi
  done
  echo "ok   $what"
}

"$sffcal" config -o base.toml > /dev/null || { echo "FAIL config"; exit 1; }
# No [contact] friction key: the run shears at the DEM default, tan 30 deg, and says so.
sed -e 's/^bodies = .*/bodies = 60/' -e 's/^max_axial_strain = .*/max_axial_strain = 0.02/' \
  -e '/^friction = /d' base.toml > small.toml
"$sffcal" dem -c small.toml -o run.h5 > /dev/null || { echo "FAIL dem"; exit 1; }
expect_lines "a new run shows schema 2, its physics and its summary" "$("$sffcal" info run.h5 2>&1)" \
  "triaxial run" "schema 2" "friction 0.57735 (walls 0)" "E 1.5e+08 Pa" \
  "summary: maximum axial strain reached at axial strain 0.02"
expect_lines "a specimen file shows its physics and no summary" "$("$sffcal" info run.h5.specimen.h5 2>&1)" \
  "specimen run" "schema 2" "preparation:"
reference=$source_dir/tests/data/reference/matrix/iso_dense_100kPa.h5
expect_lines "a reduced schema-1 reference file still opens" "$("$sffcal" info "$reference" 2>&1)" \
  "schema 1" "friction 0.57735 (walls 0)" "(from the stored config)" "snapshots: 0" "summary: "

[ $failures -eq 0 ] && echo "all info checks passed" || echo "$failures info checks failed"
exit $((failures > 0))
