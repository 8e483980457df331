#!/usr/bin/env bash
# Installs every build and run dependency of sffcal from the Debian 12 archive.
# Idempotent: packages already present are skipped by apt. No other downloads.
set -euo pipefail

packages=(
  build-essential cmake ninja-build pkg-config
  libeigen3-dev libceres-dev libdeal.ii-dev
  libhdf5-dev hdf5-tools
  libgtest-dev libgmock-dev libbenchmark-dev
  libcli11-dev libtomlplusplus-dev nlohmann-json3-dev
  openmpi-bin  # mpiexec, for the distributed-mesh test
  dpkg-dev gfortran libspooles-dev libarpack2-dev liblapack-dev  # CalculiX with the UMAT (build_calculix.sh)
  python3 python3-h5py python3-markdown python3-matplotlib python3-numpy
  snakemake  # the main job's workflow (workflow/Snakefile; scripts/pipeline.py, docs/pipeline.md)
  python3-dev pybind11-dev python3-pybind11 python3-pytest  # the compiled module sffcal._core and its tests (docs/python.md)
  python3-pip python3-setuptools  # the pure-Python part installed from python/pyproject.toml (test_install.sh)
  clang libclang-rt-14-dev libomp-dev llvm  # the fuzz targets: libFuzzer, OpenMP, llvm-symbolizer (scripts/fuzz.sh)
)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done

if [ ${#missing[@]} -eq 0 ]; then
  echo "install_deps: all ${#packages[@]} packages present"
  exit 0
fi

sudo_cmd=()
[ "$(id -u)" -eq 0 ] || sudo_cmd=(sudo)
echo "install_deps: installing ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
"${sudo_cmd[@]}" apt-get update -qq
"${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}"
