#!/usr/bin/env bash
# Regenerates the fixtures of `sffcal import` (docs/import.md) with the real programs.
# tests/data/import/lammps/: 100 clumps in LAMMPS (Debian's `lammps`; examples/lammps/run.sh on
# two MPI ranks, 2 % axial strain, a snapshot every 1 %): 0.45 MB, 15 s.
# tests/data/import/liggghts/: 300 spheres in LIGGGHTS (Debian's `liggghts`; examples/liggghts/run.sh
# on two MPI ranks, 2 % axial strain, a snapshot every 1 %): 0.45 MB, 10 s.
# tests/data/import/yade/, the YADE fixture, with
# the real program: a small drained triaxial compression of 150 two-sphere clumps in YADE (Debian's
# `yade`; examples/yade/triaxial.py, 4 % axial strain, a snapshot every 2 %), written from inside
# YADE by sffcal.yade_export (python/sffcal, pure Python: PYTHONPATH=python, no build needed):
# import.toml, atoms.dump, contacts.dump, series.txt: 0.55 MB, 10-20 s on one core. Also the seed
# of the import fuzz target, fuzz/corpus/import_seed (40 clumps, two frames), and its corpus entries
# fuzz/corpus/import/seed_* (each file behind the byte that chooses it: fuzz/import_fuzzer.cc).
# An existing fixture is never written over: --force removes it first.
# Usage: scripts/regenerate_import_fixtures.sh [--force]
set -euo pipefail
cd "$(dirname "$0")/.."
out=tests/data/import/yade
seed=fuzz/corpus/import_seed
lammps_out=tests/data/import/lammps
liggghts_out=tests/data/import/liggghts

force=0
case "${1:-}" in
  "") ;;
  --force) force=1 ;;
  *) echo "usage: scripts/regenerate_import_fixtures.sh [--force]" >&2; exit 2 ;;
esac
for program in yade lmp liggghts; do
  if ! command -v "$program" > /dev/null; then
    echo "regenerate_import_fixtures.sh: $program is not installed (Debian: apt-get install" \
      "yade lammps liggghts)" >&2
    exit 1
  fi
done
for folder in "$out" "$seed" "$lammps_out" "$liggghts_out"; do
  if [ -e "$folder" ]; then
    if [ "$force" = 1 ]; then
      rm -rf -- "$folder"
    else
      echo "regenerate_import_fixtures.sh: $folder exists: --force to regenerate it" >&2
      exit 1
    fi
  fi
done
mkdir -p "$(dirname "$out")"

# -j1: one thread, so that the run does not depend on the host's cores.
PYTHONPATH="$PWD/python${PYTHONPATH:+:$PYTHONPATH}" yade -n -j1 -x examples/yade/triaxial.py \
  --clumps 150 --final-strain 0.04 --frame-strain 0.02 --seed 1 --output "$out"
du -sh "$out"
PYTHONPATH="$PWD/python${PYTHONPATH:+:$PYTHONPATH}" yade -n -j1 -x examples/yade/triaxial.py \
  --clumps 40 --final-strain 0.01 --frame-strain 0.01 --seed 1 --row-interval 1000 --output "$seed"
rm -f fuzz/corpus/import/seed_*
byte=0
for name in import.toml atoms.dump contacts.dump series.txt; do
  { printf "\\$(printf '%03o' "$byte")"; cat "$seed/$name"; } > "fuzz/corpus/import/seed_${name/./_}"
  byte=$((byte + 1))
done
du -sh "$seed"

scratch=$(mktemp -d)
trap 'rm -rf "$scratch"' EXIT
examples/lammps/run.sh -np 2 "$scratch/run" -var nclumps 100 -var final_strain 0.02 \
  -var frame_strain 0.01 -var seed 1
mkdir -p "$lammps_out"
cp "$scratch"/run/{import.toml,atoms.dump,contacts.dump,series.txt} "$lammps_out"/
du -sh "$lammps_out"
examples/liggghts/run.sh -np 2 "$scratch/liggghts" -var n 300 -var final_strain 0.02 -var seed 10007
mkdir -p "$liggghts_out"
cp "$scratch"/liggghts/{import.toml,atoms.dump,contacts.dump,series.txt} "$liggghts_out"/
du -sh "$liggghts_out"
