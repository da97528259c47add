#!/bin/sh
# Installs dependencies, builds, and runs the whole test suite; then the suite again
# built with AddressSanitizer + UndefinedBehaviorSanitizer, and every fuzz target for
# 15 seconds on its seeds (scripts/test-sanitize.sh, scripts/fuzz-smoke.sh).
set -eu
cd "$(dirname "$0")/.."
./scripts/setup.sh
./scripts/build.sh
ctest --test-dir build --output-on-failure -j"$(nproc)"
./scripts/test-sanitize.sh
./scripts/fuzz-smoke.sh 15
