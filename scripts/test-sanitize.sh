#!/bin/sh
# Builds the test suite with AddressSanitizer + UndefinedBehaviorSanitizer
# (scripts/sanitize-build.sh) and runs it; any sanitizer report fails its test.
# Tests labelled sanitize-slow (tests/CMakeLists.txt says which and why) are left out.
set -eu
cd "$(dirname "$0")/.."
./scripts/sanitize-build.sh
. ./scripts/sanitizer-env.sh
ctest --test-dir build-sanitize --output-on-failure -j"$(nproc)" -LE sanitize-slow
