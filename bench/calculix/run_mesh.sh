#!/usr/bin/env bash
# The rough-platen mesh in CalculiX against deal.II (bench/RESULTS.md, "The rough-platen mesh in
# CalculiX with the whole tangent"): examples/calculix/rough_platen_mesh.py on
#   - the same element (C3D8 against Q1 with full integration), 3.5 % in 70 increments;
#   - C3D8I against Q1 with B-bar, 3 x 3 x 3 to 5 % in 50 and to 10 % in 100;
#   - the symmetric part of the tangent alone (as Debian's ccx), 3 x 3 x 3 to 5 % in 50;
#   - C3D20R, 3 x 3 x 3 to 5 % in 50, whole against symmetric;
#   - refined meshes, 6 and 10 cells a side, to 5 % in 50;
#   - the cost of the unsymmetric solve: 10 cells, 0.5 % in 5, whole against symmetric;
#   - NLGEOM through ABAQUS... and ABAQUSNL..., 10 % in 100, whole against symmetric.
# Prints each run's rows (ccx, then deal.II) and keeps the runs in OUT.
#
# Usage: bench/calculix/run_mesh.sh [BUILD (default build)] [OUT (default out/calculix_mesh)]
set -euo pipefail
cd "$(dirname "$0")/../.."
build=${1:-build}
out=${2:-out/calculix_mesh}
[ -x "$build/calculix/ccx_sffcal" ] || { echo "run_mesh: scripts/build_calculix.sh $build first" >&2; exit 1; }
[ -e "$out" ] && { echo "run_mesh: $out exists; give a new folder" >&2; exit 1; }
mkdir -p "$out"
export OMP_NUM_THREADS=1  # ccx and deal.II on one thread each

mesh() {  # NAME OPTIONS...: one run, its rows printed; a run that stops is shown, not fatal
  local name=$1
  shift
  echo "## $name: $*"
  /usr/bin/python3 examples/calculix/rough_platen_mesh.py --ccx "$build/calculix/ccx_sffcal" \
    --sffcal "$build/sffcal" --parameters examples/acst_toyoura.json -o "$out/$name" "$@" || true
}

mesh same_element --element C3D8 --strain 0.035 --steps 70 --fe-mesh "$build/bench/fe_mesh"
mesh c3d8i_5 --element C3D8I --fe-mesh "$build/bench/fe_mesh"
mesh c3d8i_10 --element C3D8I --strain 0.1 --steps 100 --fe-mesh "$build/bench/fe_mesh"
mesh c3d8i_5_symmetric --element C3D8I --symmetric-tangent
mesh c3d20r_5 --element C3D20R --fe-mesh "$build/bench/fe_mesh"
mesh c3d20r_5_symmetric --element C3D20R --symmetric-tangent
mesh c3d8i_5_6cells --element C3D8I --cells 6 --fe-mesh "$build/bench/fe_mesh"
mesh c3d8i_5_10cells --element C3D8I --cells 10 --fe-mesh "$build/bench/fe_mesh"
mesh cost_whole --element C3D8I --cells 10 --strain 0.005 --steps 5
mesh cost_symmetric --element C3D8I --cells 10 --strain 0.005 --steps 5 --symmetric-tangent
# Under NLGEOM (no deal.II: small strain), C3D8I to 10 % in 100 through ccx's two interfaces.
mesh nlgeom_whole --element C3D8I --strain 0.1 --steps 100 --nlgeom
mesh nlgeom_symmetric --element C3D8I --strain 0.1 --steps 100 --nlgeom --symmetric-tangent
mesh abaqusnl_whole --element C3D8I --strain 0.1 --steps 100 --nlgeom --abaqusnl
mesh abaqusnl_symmetric --element C3D8I --strain 0.1 --steps 100 --nlgeom --abaqusnl --symmetric-tangent
