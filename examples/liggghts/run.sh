#!/usr/bin/env bash
# Runs examples/liggghts/triaxial.in in a new output folder and writes import.toml beside its
# outputs, ready for `sffcal import FOLDER/import.toml -o RUN.h5`.
#
#   examples/liggghts/run.sh [-np N] OUTPUT_FOLDER [-var NAME VALUE ...]
#
#   -np N     run on N MPI ranks (mpirun -np N liggghts ...); serial without it
#   -var ...  passed to LIGGGHTS (the deck's parameters: n, seed, mu, p0, rate, final_strain, ...);
#             those that the description states (E, ratio, rho, mu, p0, rate) are written into
#             its [physics] and [test]
#
# Outputs: atoms.dump, contacts.dump, series.txt (see triaxial.in), import.toml; screen.txt,
# log.liggghts, command.txt. (LIGGGHTS writes the dumps' box bounds to 6 digits; the importer
# takes the cell's lengths from the series rows, which the deck writes to 20.)
#
# The folder must be new or empty (LIGGGHTS writes log.liggghts into the current folder, so the
# run is made there). Environment: LIGGGHTS (default liggghts), MPIRUN_FLAGS (extra mpirun flags,
# e.g. --oversubscribe).
set -euo pipefail

here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
usage() { echo "usage: $0 [-np N] OUTPUT_FOLDER [-var NAME VALUE ...]" >&2; exit 2; }

np=0
if [[ $# -ge 2 && "$1" == "-np" ]]; then
  np="$2"; shift 2
  [[ "$np" =~ ^[1-9][0-9]*$ ]] || { echo "$0: -np needs a positive integer" >&2; exit 2; }
fi
[[ $# -ge 1 ]] || usage
out="$1"; shift

# the -var arguments: checked, and the described ones kept
declare -A var=([E]=1.5e8 [ratio]=0.5 [rho]=2650.0 [mu]=0.5 [p0]=1e5 [rate]=50.0)
args=("$@")
while [[ $# -gt 0 ]]; do
  [[ "$1" == "-var" && $# -ge 3 ]] || { echo "$0: expected -var NAME VALUE, found '$1'" >&2; usage; }
  var[$2]="$3"; shift 3
done

if [[ -e "$out" ]]; then
  [[ -d "$out" ]] || { echo "$0: $out exists and is not a folder" >&2; exit 1; }
  [[ -z "$(ls -A "$out")" ]] || { echo "$0: $out is not empty; give a new folder" >&2; exit 1; }
fi
mkdir -p "$out"
out="$(cd "$out" && pwd)"

liggghts="${LIGGGHTS:-liggghts}"
cmd=("$liggghts" -in "$here/triaxial.in" "${args[@]}")
if [[ "$np" -gt 0 ]]; then
  # shellcheck disable=SC2206
  mpi=(mpirun ${MPIRUN_FLAGS:-} -np "$np")
  [[ "$(id -u)" -ne 0 ]] || mpi+=(--allow-run-as-root)   # Open MPI refuses root otherwise
  cmd=("${mpi[@]}" "${cmd[@]}")
fi

cd "$out"
echo "${cmd[*]}" > command.txt
start=$(date +%s)
"${cmd[@]}" > screen.txt 2>&1 || { tail -20 screen.txt >&2; echo "$0: LIGGGHTS failed (see $out/screen.txt)" >&2; exit 1; }
end=$(date +%s)
grep -q "^ERROR" screen.txt && { grep "^ERROR" screen.txt >&2; exit 1; }
for f in atoms.dump contacts.dump series.txt; do
  [[ -s "$f" ]] || { echo "$0: LIGGGHTS wrote no $f (see $out/screen.txt)" >&2; exit 1; }
done

# import.toml: the repository's description with the run's physics and loading
sed -e "s|^youngs_modulus = [^ ]*|youngs_modulus = ${var[E]}|" \
    -e "s|^stiffness_ratio = [^ ]*|stiffness_ratio = ${var[ratio]}|" \
    -e "s|^friction = [^ ]*|friction = ${var[mu]}|" \
    -e "s|^grain_density = [^ ]*|grain_density = ${var[rho]}|" \
    -e "s|^confining_stress = [^ ]*|confining_stress = ${var[p0]}|" \
    -e "s|^strain_rate = [^ ]*|strain_rate = ${var[rate]}|" \
    -e "s|sigma_3 1e5 Pa|sigma_3 ${var[p0]} Pa|g" \
    -e "s|strain-controlled at 50 /s|strain-controlled at ${var[rate]} /s|" \
    "$here/import.toml" > import.toml
echo "$0: done in $((end - start)) s; outputs and import.toml in $out"
grep -E "^(LIGGGHTS deck|compression|done):" screen.txt || true
