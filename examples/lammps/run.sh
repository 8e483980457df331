#!/usr/bin/env bash
# Runs examples/lammps/triaxial.in in a new folder and puts import.toml beside its outputs, so
# that `sffcal import FOLDER/import.toml -o run.h5` reads the run (docs/import.md).
#
#   examples/lammps/run.sh [-np N] FOLDER [-var NAME VALUE ...]
#
#   -np N     run on N MPI ranks (mpirun; as root, --allow-run-as-root is added). Extra mpirun
#             flags: MPIRUN_FLAGS="--oversubscribe"; another LAMMPS binary: LMP=/path/to/lmp.
#   FOLDER    a new folder (an existing empty one is taken; a non-empty one is refused)
#   -var ...  the deck's parameters (see the head of triaxial.in): nclumps seed radius E ratio
#             rho mu mu_compact p0 rate final_strain frame_strain row_steps ...
# E, ratio, rho, mu, p0 and rate given here are written into FOLDER/import.toml; the strain
# rate there is the one the deck ran (rounded to whole steps a frame), read from its log.
set -euo pipefail

deck="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
usage() { echo "usage: $0 [-np N] FOLDER [-var NAME VALUE ...]" >&2; exit 2; }

np=""
if [[ $# -ge 2 && "$1" == "-np" ]]; then
  np="$2"
  [[ "$np" =~ ^[1-9][0-9]*$ ]] || { echo "run.sh: -np needs a positive integer, not '$np'" >&2; exit 2; }
  shift 2
fi
[[ $# -ge 1 ]] || usage
out="$1"
shift
[[ "$out" != -* ]] || usage

# The deck's defaults, overridden by -var NAME VALUE.
declare -A value=([E]=1.5e8 [ratio]=0.5 [rho]=2650.0 [mu]=0.5 [p0]=1e5 [rate]=0.5)
args=("$@")
while [[ $# -gt 0 ]]; do
  case "$1" in
    -var|-v)
      [[ $# -ge 3 ]] || { echo "run.sh: -var needs a name and a value" >&2; exit 2; }
      [[ "$2" != "deck" ]] || { echo "run.sh: 'deck' is set by run.sh" >&2; exit 2; }
      if [[ -v "value[$2]" ]]; then value[$2]="$3"; fi
      shift 3 ;;
    *) echo "run.sh: unknown argument '$1' (only -var NAME VALUE may follow the folder)" >&2; exit 2 ;;
  esac
done

if [[ -e "$out" ]]; then
  [[ -d "$out" ]] || { echo "run.sh: '$out' exists and is not a folder" >&2; exit 1; }
  [[ -z "$(ls -A "$out")" ]] || { echo "run.sh: '$out' is not empty; give a new folder" >&2; exit 1; }
fi
mkdir -p "$out"
cd "$out"

lmp="${LMP:-lmp}"
command=("$lmp" -in "$deck/triaxial.in" -log log.lammps -var deck "$deck" "${args[@]}")
if [[ -n "$np" ]]; then
  flags=()
  [[ "$(id -u)" != 0 ]] || flags+=(--allow-run-as-root)
  # shellcheck disable=SC2206
  flags+=(${MPIRUN_FLAGS:-})
  command=(mpirun "${flags[@]}" -np "$np" "${command[@]}")
fi
echo "run.sh: in $PWD: ${command[*]}"
start=$SECONDS
"${command[@]}" > screen.txt 2>&1 || { tail -20 screen.txt >&2; echo "run.sh: LAMMPS failed (screen.txt, log.lammps)" >&2; exit 1; }
grep '^triaxial.in:' log.lammps || true
grep -q '^triaxial.in: done' log.lammps || { echo "run.sh: the deck did not finish (log.lammps)" >&2; exit 1; }
[[ -s contacts.dump ]] || { echo "run.sh: the deck wrote no contacts.dump" >&2; exit 1; }

# import.toml with this run's values.
rate="$(sed -n 's/^triaxial.in: compressing at \([^ ]*\) \/s.*/\1/p' log.lammps | tail -1)"
[[ -n "$rate" ]] || rate="${value[rate]}"
sed -e "s|^youngs_modulus = [^ ]*|youngs_modulus = ${value[E]}|" \
    -e "s|^stiffness_ratio = [^ ]*|stiffness_ratio = ${value[ratio]}|" \
    -e "s|^friction = [^ ]*|friction = ${value[mu]}|" \
    -e "s|^grain_density = [^ ]*|grain_density = ${value[rho]}|" \
    -e "s|^confining_stress = [^ ]*|confining_stress = ${value[p0]}|" \
    -e "s|^strain_rate = [^ ]*|strain_rate = ${rate}|" \
    -e "s|sigma_3 1e5 Pa|sigma_3 ${value[p0]} Pa|g" \
    -e "s|strain-controlled at 0.5 /s|strain-controlled at ${rate} /s|" \
    "$deck/import.toml" > import.toml
echo "run.sh: done in $((SECONDS - start)) s; sffcal import $out/import.toml -o RUN.h5"
