#!/usr/bin/env bash
# Sets up a fresh Debian 12 machine, builds, and runs every test suite through CTest.
set -euo pipefail
cd "$(dirname "$0")/.."
./scripts/install_deps.sh
./scripts/build.sh
# CalculiX built from Debian's source with the UMAT, for the CalculiX tests (docs/fe.md).
./scripts/build_calculix.sh build
# CTest runs nproc tests at once, each with OpenMP on every core: idle OpenMP threads must sleep,
# not spin, or the oversubscribed cores spend their time spinning.
export OMP_WAIT_POLICY=PASSIVE
ctest --test-dir build --output-on-failure --parallel "$(nproc)" --timeout 600
# The fuzz targets of the input readers under ASan and UBSan, 30 s each from their committed
# corpus (fuzz/README.md; clang's libFuzzer, its own build folder build-fuzz), with a fixed seed
# so that a CI run explores the same inputs each time (longer, random runs: by hand).
FUZZ_SEED=1 ./scripts/fuzz.sh 30 build-fuzz
# The installed package, as an FE program outside this tree links it (examples/external_fe).
./scripts/test_install.sh
