#!/bin/sh
# Usage: scripts/fuzz.sh NAME [SECONDS]
# Builds the libFuzzer target fuzz_NAME in the sanitized build (clang, ASan + UBSan,
# scripts/sanitize-build.sh) and runs it for SECONDS (default 600) on the corpus
# fuzz-corpus/NAME, seeded from fuzz/seeds/NAME.
set -eu
cd "$(dirname "$0")/.."
name=${1:?usage: scripts/fuzz.sh NAME [SECONDS]}
seconds=${2:-600}
./scripts/sanitize-build.sh --target "fuzz_$name"
. ./scripts/sanitizer-env.sh
corpus=fuzz-corpus/$name
mkdir -p "$corpus" "$corpus-artifacts"
seeds=
[ -d "fuzz/seeds/$name" ] && seeds=fuzz/seeds/$name
# Inputs up to 64 KiB; an input using more than 2 GiB or 10 s counts as a failure.
# shellcheck disable=SC2086
exec "./build-sanitize/fuzz/fuzz_$name" -max_total_time="$seconds" -print_final_stats=1 \
  -max_len=65536 -rss_limit_mb=2048 -timeout=10 -artifact_prefix="$corpus-artifacts/" \
  "$corpus" $seeds
