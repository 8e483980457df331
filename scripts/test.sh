#!/usr/bin/env bash
# Sets up a fresh Debian 12 machine, builds, and runs every test suite through CTest.
set -euo pipefail
cd "$(dirname "$0")/.."
./scripts/install_deps.sh
./scripts/build.sh
ctest --test-dir build --output-on-failure --parallel "$(nproc)" --timeout 600
