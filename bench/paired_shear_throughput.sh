#!/usr/bin/env bash
# Paired timing of two shear_throughput binaries (issue 16, bench/RESULTS.md "Throughput in
# triaxial shear: tries not kept"): A and B shear the same specimen at the same time, one on each
# core, one thread each, swapping cores from pair to pair; each line gives both whole-process
# times and their ratio B/A. Drift of this shared machine (±20 % between runs in turn) hits both
# runs of a pair alike; two copies of one binary gave 0.986 and 1.003.
#
#   bench/paired_shear_throughput.sh A B SPECIMEN.h5 [PAIRS=4] [STRAIN=0.004] [OUT=out/bench/paired]
#
# A, B: shear_throughput binaries (e.g. build/bench/shear_throughput and a copy from another
# commit); SPECIMEN.h5 from `sffcal prepare`. Needs two cores and taskset (util-linux).
set -euo pipefail
if [ $# -lt 3 ]; then
  sed -n '2,12p' "$0" >&2
  exit 2
fi
a=$1 b=$2 specimen=$3 pairs=${4:-4} strain=${5:-0.004} out=${6:-out/bench/paired}
for tool in "$a" "$b"; do [ -x "$tool" ] || { echo "not executable: $tool" >&2; exit 2; }; done
[ -f "$specimen" ] || { echo "no specimen file: $specimen" >&2; exit 2; }
[ "$(nproc)" -ge 2 ] || { echo "needs two cores (has $(nproc))" >&2; exit 2; }
mkdir -p "$out"
run() {  # core binary folder timefile
  rm -rf "$3"
  OMP_NUM_THREADS=1 taskset -c "$1" /usr/bin/time -f "%e" -o "$4" "$2" "$specimen" --threads 1 \
    --strain "$strain" --rate 100 --out "$3" > /dev/null
}
echo "pair, A [s], B [s], B/A"
for k in $(seq 1 "$pairs"); do
  core_a=$(( (k + 1) % 2 )) core_b=$(( k % 2 ))
  run "$core_a" "$a" "$out/a" "$out/a.time" &
  pid_a=$!
  run "$core_b" "$b" "$out/b" "$out/b.time" &
  pid_b=$!
  wait "$pid_a" || { echo "A failed in pair $k" >&2; exit 1; }
  wait "$pid_b" || { echo "B failed in pair $k" >&2; exit 1; }
  ta=$(cat "$out/a.time") tb=$(cat "$out/b.time")
  echo "$k, $ta, $tb, $(/usr/bin/python3 -c "print(f'{$tb / $ta:.3f}')")"
done
