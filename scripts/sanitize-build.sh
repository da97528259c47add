#!/bin/sh
# Configures (once) and builds build-sanitize: clang at -O1 with AddressSanitizer and
# UndefinedBehaviorSanitizer everywhere, libFuzzer coverage in the libraries, the test
# suite and every fuzz target (no benchmarks, no examples). One build serves the
# sanitized test run (scripts/test-sanitize.sh) and fuzzing (scripts/fuzz-smoke.sh,
# scripts/fuzz.sh). Extra arguments go to cmake --build (e.g. --target fuzz_scene).
set -eu
cd "$(dirname "$0")/.."
if [ ! -f build-sanitize/build.ninja ]; then
  # -O1: quicker to compile than -O2, and sanitizer reports keep their frames;
  # line tables only (no full debug info) keep objects and links small.
  cmake -S . -B build-sanitize -G Ninja -DCMAKE_BUILD_TYPE=Sanitize \
    -DCMAKE_CXX_COMPILER=clang++ \
    -DCMAKE_CXX_FLAGS_SANITIZE="-O1 -gline-tables-only" \
    -DREFX_SANITIZE=ON -DREFX_FUZZ=ON -DREFX_BENCH=OFF -DREFX_EXAMPLES=OFF
fi
cmake --build build-sanitize "$@"
