#!/usr/bin/env bash
# Sets up, builds and runs the main job. At this stage of the project (the DEM), the main job
# prepares a small dense specimen of two-sphere clumps, runs a drained triaxial compression on it,
# writes the run file, exports its snapshots for ParaView, analyses them with the SFF equations and
# plots the curves, all under out/main.
# Pass another config as the first argument (e.g. bench/reference/dense_100kPa.toml).
set -euo pipefail
cd "$(dirname "$0")/.."
config=${1:-examples/quick_triaxial.toml}
./scripts/install_deps.sh
./scripts/build.sh
mkdir -p out/main
./build/sffcal dem -c "$config" -o out/main/triaxial.h5
./build/sffcal vtk out/main/triaxial.h5 -o out/main/vtk
./build/sffcal sff out/main/triaxial.h5 -o out/main
/usr/bin/python3 bench/reference/plot_triaxial.py out/main/triaxial.h5 out/main/triaxial.png
/usr/bin/python3 scripts/plot_sff.py out/main/triaxial.h5 -o out/main
echo "main job done: out/main/triaxial.h5 (HDF5, see docs/run-file.md), out/main/triaxial.png,"
echo "  out/main/triaxial.h5.{series,sff,sff_checks,sff_rose}.csv (tables, docs/sff.md),"
echo "  out/main/triaxial_eta.png, triaxial_rose.png, anisotropy.png (SFF plots),"
echo "  out/main/vtk/spheres.pvd (ParaView)"
