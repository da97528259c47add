#!/bin/sh
# Installs dependencies, builds, and runs the whole test suite.
set -eu
cd "$(dirname "$0")/.."
./scripts/setup.sh
./scripts/build.sh
ctest --test-dir build --output-on-failure -j"$(nproc)"
