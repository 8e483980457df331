#!/usr/bin/env bash
# The 1000-clump test of the time step (issue 50; bench/RESULTS.md "The stability limit"): a dense
# specimen (compaction friction 0.15, p'0 = 100 kPa, seed 1) compacted by one executable (PREPARER,
# e.g. an earlier version standing in for another code) is sheared drained at 20 /s to 25 % axial
# strain by REFERENCE at its own default step and by SFFCAL at each safety factor, one thread each,
# with a series row every 0.05 % and no stop at the critical state; the table
# (bench/reference/compare_paper_rate.py against REFERENCE's run: peak and critical q/p,
# volumetric strain, worst lateral stress error after 0.5 %, steps) goes to stdout and
# OUT/table.md, the overlaid curves to OUT/curves.png.
#
#   bench/time_step/run_1000.sh OUT SFFCAL REFERENCE [PREPARER=REFERENCE] ["0.7 0.85 1.0"]
set -euo pipefail
if [ $# -lt 3 ]; then
  sed -n '2,12p' "$0" >&2
  exit 2
fi
out=$1 sffcal=$2 reference=$3 preparer=${4:-$3} safeties=${5:-"0.7 0.85 1.0"}
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../.." && pwd)
config="/usr/bin/python3 $root/bench/servo/make_config.py"
shear="--max-strain 0.25 --set critical_min_strain=1.0"
mkdir -p "$out"
if [ ! -f "$out/dense_1000.h5" ]; then
  $config "$out/prepare.toml" 1000 dense 20 --sffcal "$preparer" $shear
  "$preparer" prepare -c "$out/prepare.toml" -o "$out/dense_1000.h5" > "$out/prepare.log"
fi
run() {  # executable name [safety]
  [ -f "$out/$2.h5" ] && return 0
  $config "$out/$2.toml" 1000 dense 20 ${3:-} --sffcal "$1" $shear
  "$1" triaxial -c "$out/$2.toml" -s "$out/dense_1000.h5" -o "$out/$2.h5" > "$out/$2.log"
}
run "$reference" reference
runs=()
for s in $safeties; do
  run "$sffcal" "safety_$s" "$s"
  runs+=("$out/safety_$s.h5")
done
PYTHONPATH="$root/build/python" /usr/bin/python3 "$root/bench/reference/compare_paper_rate.py" \
  "${runs[@]}" --reference "$out/reference.h5" --png "$out/curves.png" | tee "$out/table.md"
