#!/bin/sh
# Usage: scripts/fuzz.sh NAME [SECONDS]
# Builds the libFuzzer target fuzz_NAME with clang (ASan + UBSan) in build-fuzz and runs
# it for SECONDS (default 600) on the corpus fuzz-corpus/NAME, seeded from fuzz/seeds/NAME.
set -eu
cd "$(dirname "$0")/.."
name=${1:?usage: scripts/fuzz.sh NAME [SECONDS]}
seconds=${2:-600}
if [ ! -f build-fuzz/build.ninja ]; then
  cmake -S . -B build-fuzz -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DREFX_FUZZ=ON \
    -DREFX_TESTS=OFF -DREFX_BENCH=OFF -DCMAKE_CXX_COMPILER=clang++
fi
cmake --build build-fuzz --target "fuzz_$name" -j2
corpus=fuzz-corpus/$name
mkdir -p "$corpus" "$corpus-artifacts"
seeds=
[ -d "fuzz/seeds/$name" ] && seeds=fuzz/seeds/$name
# Inputs up to 64 KiB; an input using more than 2 GiB or 10 s counts as a failure.
# shellcheck disable=SC2086
exec "./build-fuzz/fuzz/fuzz_$name" -max_total_time="$seconds" -print_final_stats=1 \
  -max_len=65536 -rss_limit_mb=2048 -timeout=10 -artifact_prefix="$corpus-artifacts/" \
  "$corpus" $seeds
