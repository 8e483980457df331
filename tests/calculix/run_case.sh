#!/usr/bin/env bash
# One CalculiX check (examples/calculix/single_element.py) in a fresh folder; exit 77 (skipped)
# where the ccx with sffcal's UMAT has not been built (scripts/build_calculix.sh builds it; CI does).
# Usage: run_case.sh CCX OUTPUT_FOLDER [single_element.py options...]
set -u
ccx=$1 out=$2
shift 2
if [ ! -x "$ccx" ]; then
  echo "skipped: $ccx not built (scripts/build_calculix.sh)"
  exit 77
fi
rm -rf "$out"
exec /usr/bin/python3 "$(dirname "$0")/../../examples/calculix/single_element.py" --ccx "$ccx" -o "$out" "$@"
