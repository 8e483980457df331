#!/usr/bin/env bash
# One CalculiX check (an examples/calculix/ script: single_element.py, rotated_element.py) in a
# fresh folder; exit 77 (skipped) where the ccx with sffcal's UMAT has not been built
# (scripts/build_calculix.sh builds it; CI does).
# Usage: run_case.sh SCRIPT CCX OUTPUT_FOLDER [the script's options...]
set -u
script=$1 ccx=$2 out=$3
shift 3
if [ ! -x "$ccx" ]; then
  echo "skipped: $ccx not built (scripts/build_calculix.sh)"
  exit 77
fi
rm -rf "$out"
exec /usr/bin/python3 "$(dirname "$0")/../../examples/calculix/$script" --ccx "$ccx" -o "$out" "$@"
