#!/bin/sh
# Builds the test suite with AddressSanitizer + UndefinedBehaviorSanitizer
# (scripts/sanitize-build.sh) and runs it, all of it (about 1 minute on two cores):
# any sanitizer report fails its test.
set -eu
cd "$(dirname "$0")/.."
./scripts/sanitize-build.sh
. ./scripts/sanitizer-env.sh
ctest --test-dir build-sanitize --output-on-failure -j"$(nproc)"
