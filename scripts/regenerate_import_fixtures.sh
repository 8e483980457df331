#!/usr/bin/env bash
# Regenerates the fixtures of `sffcal import` (docs/import.md) with the real programs.
# yade: tests/data/import/yade/, a small drained triaxial compression of 150 two-sphere clumps in
#   YADE (Debian's `yade`; examples/yade/triaxial.py, 4 % axial strain, a snapshot every 2 %),
#   written from inside YADE by sffcal.yade_export (python/sffcal, pure Python: PYTHONPATH=python,
#   no build needed): import.toml, atoms.dump, contacts.dump, series.txt: 0.55 MB, 10-20 s on one
#   core. Also the seed of the import fuzz target, fuzz/corpus/import_seed (40 clumps, two frames),
#   and its corpus entries fuzz/corpus/import/seed_* (each file behind the byte that chooses it:
#   fuzz/import_fuzzer.cc).
# yade_walls: tests/data/import/yade_walls/, the same test between six walls
#   (TriaxialStressController; examples/yade/triaxial.py --walls, 150 clumps, 2 % axial strain, a
#   snapshot every 1 %): 0.5 MB, 10 s.
# lammps: tests/data/import/lammps/, 100 clumps in a periodic cell in LAMMPS (Debian's `lammps`;
#   examples/lammps/run.sh on two MPI ranks, 2 % axial strain, a snapshot every 1 %): 0.45 MB, 15 s.
# lammps_walls: tests/data/import/lammps_walls/, 200 clumps between six walls: a specimen made by
#   `sffcal prepare` (build/sffcal, or $SFFCAL) sheared in LAMMPS by examples/lammps/walls/run.sh
#   on two MPI ranks (4000 steps, 2.8 % axial strain, a snapshot every 2000 steps): 0.4 MB, 5 s.
#   Also the import fuzz target's second seed, fuzz/corpus/import_walls_seed (40 clumps, two
#   frames), and its corpus entries fuzz/corpus/import/seed_walls_* (behind bytes 4-7).
# liggghts: tests/data/import/liggghts/, 300 spheres in LIGGGHTS (Debian's `liggghts`;
#   examples/liggghts/run.sh on two MPI ranks, 2 % axial strain, a snapshot every 1 %): 0.45 MB,
#   10 s.
# An existing fixture is never written over: --force removes it first.
# Usage: scripts/regenerate_import_fixtures.sh [--force] [yade|yade_walls|lammps|lammps_walls|liggghts ...]
#        (no name: all five)
set -euo pipefail
cd "$(dirname "$0")/.."
out=tests/data/import/yade
seed=fuzz/corpus/import_seed
lammps_out=tests/data/import/lammps
walls_out=tests/data/import/lammps_walls
yade_walls_out=tests/data/import/yade_walls
walls_seed=fuzz/corpus/import_walls_seed
liggghts_out=tests/data/import/liggghts
sffcal="${SFFCAL:-$PWD/build/sffcal}"
usage="usage: scripts/regenerate_import_fixtures.sh [--force] [yade|yade_walls|lammps|lammps_walls|liggghts ...]"

force=0
names=()
for arg in "$@"; do
  case "$arg" in
    --force) force=1 ;;
    yade|yade_walls|lammps|lammps_walls|liggghts) names+=("$arg") ;;
    *) echo "$usage" >&2; exit 2 ;;
  esac
done
[ ${#names[@]} -gt 0 ] || names=(yade yade_walls lammps lammps_walls liggghts)
wanted() { [[ " ${names[*]} " == *" $1 "* ]]; }
declare -A program=([yade]=yade [yade_walls]=yade [lammps]=lmp [lammps_walls]=lmp [liggghts]=liggghts)
declare -A folders=([yade]="$out $seed" [yade_walls]="$yade_walls_out" [lammps]="$lammps_out" [lammps_walls]="$walls_out $walls_seed"
                    [liggghts]="$liggghts_out")
for name in "${names[@]}"; do
  if ! command -v "${program[$name]}" > /dev/null; then
    echo "regenerate_import_fixtures.sh: ${program[$name]} is not installed (Debian: apt-get" \
      "install yade lammps liggghts)" >&2
    exit 1
  fi
  for folder in ${folders[$name]}; do
    if [ -e "$folder" ]; then
      if [ "$force" = 1 ]; then
        rm -rf -- "$folder"
      else
        echo "regenerate_import_fixtures.sh: $folder exists: --force to regenerate it" >&2
        exit 1
      fi
    fi
  done
done
if wanted lammps_walls && [ ! -x "$sffcal" ]; then
  echo "regenerate_import_fixtures.sh: $sffcal is not built (it makes the walled fixture's" \
    "specimen)" >&2
  exit 1
fi
mkdir -p "$(dirname "$out")"
scratch=$(mktemp -d)
trap 'rm -rf "$scratch"' EXIT

if wanted yade; then
  # -j1: one thread, so that the run does not depend on the host's cores.
  PYTHONPATH="$PWD/python${PYTHONPATH:+:$PYTHONPATH}" yade -n -j1 -x examples/yade/triaxial.py \
    --clumps 150 --final-strain 0.04 --frame-strain 0.02 --seed 1 --output "$out"
  du -sh "$out"
  PYTHONPATH="$PWD/python${PYTHONPATH:+:$PYTHONPATH}" yade -n -j1 -x examples/yade/triaxial.py \
    --clumps 40 --final-strain 0.01 --frame-strain 0.01 --seed 1 --row-interval 1000 --output "$seed"
  rm -f fuzz/corpus/import/seed_{import,atoms,contacts,series}_*
  byte=0
  for name in import.toml atoms.dump contacts.dump series.txt; do
    { printf "\\$(printf '%03o' "$byte")"; cat "$seed/$name"; } > "fuzz/corpus/import/seed_${name/./_}"
    byte=$((byte + 1))
  done
  du -sh "$seed"
fi

if wanted yade_walls; then
  PYTHONPATH="$PWD/python${PYTHONPATH:+:$PYTHONPATH}" yade -n -j1 -x examples/yade/triaxial.py \
    --walls --clumps 150 --final-strain 0.02 --frame-strain 0.01 --seed 1 --output "$yade_walls_out"
  du -sh "$yade_walls_out"
fi

if wanted lammps; then
  examples/lammps/run.sh -np 2 "$scratch/run" -var nclumps 100 -var final_strain 0.02 \
    -var frame_strain 0.01 -var seed 1
  mkdir -p "$lammps_out"
  cp "$scratch"/run/{import.toml,atoms.dump,contacts.dump,series.txt} "$lammps_out"/
  du -sh "$lammps_out"
fi

if wanted lammps_walls; then
  # examples/lammps/walls/specimen.toml: 200 clumps of the scene of bench/lammps.
  cp examples/lammps/walls/specimen.toml "$scratch/prepare.toml"
  "$sffcal" prepare -c "$scratch/prepare.toml" -o "$scratch/specimen.h5" > /dev/null
  examples/lammps/walls/run.sh -np 2 "$scratch/specimen.h5" "$scratch/walls" -var nsteps 4000
  mkdir -p "$walls_out"
  cp "$scratch"/walls/{import.toml,atoms.dump,contacts.dump,series.txt} "$walls_out"/
  du -sh "$walls_out"
  sed -i 's/^bodies = 200$/bodies = 40/' "$scratch/prepare.toml"
  "$sffcal" prepare -c "$scratch/prepare.toml" -o "$scratch/small.h5" > /dev/null
  examples/lammps/walls/run.sh "$scratch/small.h5" "$scratch/walls_seed" -var nsteps 1000 \
    -var sample_every 250 -var dump_every 1000
  mkdir -p "$walls_seed"
  cp "$scratch"/walls_seed/{import.toml,atoms.dump,contacts.dump,series.txt} "$walls_seed"/
  rm -f fuzz/corpus/import/seed_walls_*
  byte=4
  for name in import.toml atoms.dump contacts.dump series.txt; do
    { printf "\\$(printf '%03o' "$byte")"; cat "$walls_seed/$name"; } \
      > "fuzz/corpus/import/seed_walls_${name/./_}"
    byte=$((byte + 1))
  done
  du -sh "$walls_seed"
fi

if wanted liggghts; then
  examples/liggghts/run.sh -np 2 "$scratch/liggghts" -var n 300 -var final_strain 0.02 \
    -var seed 10007
  mkdir -p "$liggghts_out"
  cp "$scratch"/liggghts/{import.toml,atoms.dump,contacts.dump,series.txt} "$liggghts_out"/
  du -sh "$liggghts_out"
fi
