#!/usr/bin/env bash
# A drained triaxial compression in LAMMPS between six walls, written for `sffcal import`
# (docs/import.md, "A box between walls"): an sffcal specimen (the file of `sffcal prepare`) is
# exported (export.py), sheared by shear.in with sffcal's lateral wall servo (servo.py) and its
# dumps, series and import.toml are left in a new folder:
#
#   sffcal prepare -c examples/lammps/walls/specimen.toml -o SPECIMEN.h5   (or a specimen of one's own)
#   examples/lammps/walls/run.sh [-np N] SPECIMEN.h5 FOLDER [-var NAME VALUE ...]
#   sffcal import FOLDER/import.toml -o run.h5
#
#   -np N     run on N MPI ranks (mpirun; as root, --allow-run-as-root is added). Extra mpirun
#             flags: MPIRUN_FLAGS="--oversubscribe"; another LAMMPS binary: LMP=/path/to/lmp.
#   FOLDER    a new folder (an existing empty one is taken; a non-empty one is refused)
#   -var ...  shear.in's parameters: nsteps (default 20000), dt [s] (7e-8, sffcal's step for the
#             50 um grains of bench/lammps), rate [1/s] (100), sample_every (a series row every
#             N steps, 100), dump_every (a snapshot every M steps, a multiple of N: 2000), p0 [Pa]
#             (sigma_3, 1e5), dtc [s] (the specimen's critical step, which scales the servo's
#             integral time: 1e-7) ...
# E, k_t/k_n, mu, the wall friction and the grain density are the specimen's (its /physics), which
# the LAMMPS run is given and import.toml states; the wall friction must be 0 (shear.in's walls
# are frictionless).
set -euo pipefail

deck="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
usage() { echo "usage: $0 [-np N] SPECIMEN.h5 FOLDER [-var NAME VALUE ...]" >&2; exit 2; }

np=""
if [[ $# -ge 2 && "$1" == "-np" ]]; then
  np="$2"
  [[ "$np" =~ ^[1-9][0-9]*$ ]] || { echo "run.sh: -np needs a positive integer, not '$np'" >&2; exit 2; }
  shift 2
fi
[[ $# -ge 2 ]] || usage
specimen="$(realpath -e -- "$1")" || { echo "run.sh: no specimen file '$1'" >&2; exit 1; }
out="$2"
shift 2
[[ "$out" != -* ]] || usage

declare -A value=([nsteps]=20000 [rate]=100.0 [sample_every]=100 [dump_every]=2000 [p0]=1e5)
args=()
while [[ $# -gt 0 ]]; do
  case "$1" in
    -var|-v)
      [[ $# -ge 3 ]] || { echo "run.sh: -var needs a name and a value" >&2; exit 2; }
      case "$2" in
        deck|spec|lateral_walls|E|ratio|mu)
          echo "run.sh: '$2' is set by run.sh (E, ratio and mu are the specimen's)" >&2; exit 2 ;;
      esac
      if [[ -v "value[$2]" ]]; then value[$2]="$3"; else args+=(-var "$2" "$3"); fi
      shift 3 ;;
    *) echo "run.sh: unknown argument '$1' (only -var NAME VALUE may follow the folder)" >&2; exit 2 ;;
  esac
done
if (( value[dump_every] % value[sample_every] != 0 )); then
  echo "run.sh: dump_every (${value[dump_every]}) must be a multiple of sample_every" \
    "(${value[sample_every]}): every snapshot needs its series row" >&2
  exit 2
fi

# The specimen's physics, as import.toml states it.
read -r E ratio mu wall_mu rho scaling < <(/usr/bin/python3 - "$specimen" <<'EOF'
import sys
import h5py
with h5py.File(sys.argv[1], "r") as f:
    p = f["physics"].attrs
    print(*(repr(float(p[k])) for k in ("youngs_modulus", "stiffness_ratio", "friction",
                                       "wall_friction", "grain_density", "density_scaling")))
EOF
)
if [[ "$wall_mu" != "0.0" ]]; then
  echo "run.sh: the specimen's wall friction is $wall_mu; shear.in's walls are frictionless" >&2
  exit 1
fi

if [[ -e "$out" ]]; then
  [[ -d "$out" ]] || { echo "run.sh: '$out' exists and is not a folder" >&2; exit 1; }
  [[ -z "$(ls -A "$out")" ]] || { echo "run.sh: '$out' is not empty; give a new folder" >&2; exit 1; }
fi
mkdir -p "$out"
cd "$out"
/usr/bin/python3 "$deck/export.py" "$specimen" export

lmp=("${LMP:-lmp}")
if [[ -n "$np" ]]; then
  root=()
  [[ "$(id -u)" != 0 ]] || root=(--allow-run-as-root)
  # shellcheck disable=SC2206  # MPIRUN_FLAGS holds several flags
  lmp=(mpirun "${root[@]}" ${MPIRUN_FLAGS:-} -np "$np" "${lmp[@]}")
fi
vars=()
for name in "${!value[@]}"; do vars+=(-var "$name" "${value[$name]}"); done
"${lmp[@]}" -in "$deck/shear.in" -log log.lammps -screen none -var deck "$deck" \
  -var spec "$PWD/export" -var lateral_walls servo -var E "$E" -var ratio "$ratio" -var mu "$mu" \
  "${vars[@]}" "${args[@]}"
version="$(sed -n '1s/^LAMMPS (\(.*\))$/\1/p' log.lammps)"

cat > import.toml <<EOF
# sffcal import's description of examples/lammps/walls/run.sh's outputs (docs/import.md).
[source]
program = "lammps"
version = "${version:-unknown}"
[files]
atoms = "atoms.dump"
contacts = "contacts.dump"
series = "series.txt"
[physics]                        # the specimen's ($(basename "$specimen"))
youngs_modulus = $E              # k_n = E r between two equal spheres, 2 E r with a wall
stiffness_ratio = $ratio         # k_t / k_n (tangential linear_history)
friction = $mu
wall_friction = 0.0              # the walls are frictionless
grain_density = $rho
density_scaling = $scaling
[test]
kind = "triaxial"
path = "drained_compression"
boundary = "walls"
confining_stress = ${value[p0]}
strain_rate = ${value[rate]}     # engineering, of the axial strain [1/s]
axis_control = ["stress-controlled: sigma_3 ${value[p0]} Pa (sffcal's servo law, servo.py)",
                "stress-controlled: sigma_3 ${value[p0]} Pa (sffcal's servo law, servo.py)",
                "strain-controlled at ${value[rate]} /s (the platens' regions move)"]
[series]
stress_sign = "compression_positive"
stress_definition = "the walls' stress: the mean force of an axis' two walls over the face area (fix wall/gran/region contacts, summed)"
[contacts]
force_on = "atom1"               # compute pair/local gives the force on its first atom (patom1)
[columns.series]
xlo = "wall_xlo"                 # the lower walls' positions [m]
ylo = "wall_ylo"
zlo = "wall_zlo"
lx = "Lx"                        # the gaps between opposite walls [m]
ly = "Ly"
lz = "Lz"
[columns.contacts]               # the dump local's names (compute property/local, pair/local)
atom1 = "c_ids[1]"
atom2 = "c_ids[2]"
fx = "c_force[1]"                # pair/local fx fy fz: the normal part of the force on atom 1
fy = "c_force[2]"
fz = "c_force[3]"
ftx = "c_force[4]"               # pair/local p1 p2 p3: its tangential part
fty = "c_force[5]"
ftz = "c_force[6]"
[columns.atoms]                  # each wall's force on the sphere: fix wall/gran/region contacts
EOF
for wall in xlo xhi ylo yhi zlo zhi; do
  for k in 2 3 4; do
    echo "${wall}_f$(echo xyz | cut -c$((k - 1))) = \"f_w${wall}[$k]\"" >> import.toml
  done
done
echo "run.sh: $PWD: $(grep -c '^ITEM: TIMESTEP' atoms.dump) snapshots, $(($(wc -l < series.txt) - 1)) series rows; sffcal import $PWD/import.toml -o run.h5"
