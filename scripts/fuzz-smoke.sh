#!/bin/sh
# Runs every fuzz target (fuzz/fuzz_NAME.cpp) for SECONDS (default 20) on its seed
# corpus fuzz/seeds/NAME, as many at once as there are cores, from the sanitized build
# (scripts/sanitize-build.sh). The mutations come from a fixed random seed (FUZZ_SEED,
# default 1), so the same build explores the same inputs in the same order (a faster
# machine just gets further); another build (other code, another checkout path) may take
# another path. A failing input is kept either way. Open-ended fuzzing: scripts/fuzz.sh. New inputs go to a scratch corpus that is thrown away;
# a crash, sanitizer report, leak or timeout fails the run and its input is kept in
# fuzz-corpus/NAME-artifacts/ (reproduce with build-sanitize/fuzz/fuzz_NAME FILE).
#   scripts/fuzz-smoke.sh [SECONDS]
# Long fuzzing of one target: scripts/fuzz.sh NAME [SECONDS].
set -eu
cd "$(dirname "$0")/.."
if [ "${1:-}" = "--one" ]; then  # one target: --one NAME SECONDS SCRATCH
  name=$2 seconds=$3 scratch=$4
  . ./scripts/sanitizer-env.sh
  mkdir -p "$scratch/$name" "fuzz-corpus/$name-artifacts"
  seeds=
  [ -d "fuzz/seeds/$name" ] && seeds=fuzz/seeds/$name
  # shellcheck disable=SC2086
  if "./build-sanitize/fuzz/fuzz_$name" -max_total_time="$seconds" -seed="${FUZZ_SEED:-1}" -max_len=65536 \
       -rss_limit_mb=2048 -timeout=10 -print_final_stats=1 \
       -artifact_prefix="fuzz-corpus/$name-artifacts/" "$scratch/$name" $seeds \
       >"$scratch/$name.log" 2>&1; then
    echo "fuzz_$name: $(sed -n 's/^stat::number_of_executed_units: *//p' "$scratch/$name.log") runs in ${seconds} s, ok"
  else
    tail -n 60 "$scratch/$name.log"
    echo "fuzz_$name: FAILED (input kept in fuzz-corpus/$name-artifacts/)"
    exit 1
  fi
  exit 0
fi
seconds=${1:-20}
names=$(for f in fuzz/fuzz_*.cpp; do n=${f#fuzz/fuzz_}; echo "${n%.cpp}"; done)
targets=$(for n in $names; do printf 'fuzz_%s ' "$n"; done)
# shellcheck disable=SC2086
./scripts/sanitize-build.sh --target $targets
scratch=$(mktemp -d)
trap 'rm -rf "$scratch"' EXIT
# shellcheck disable=SC2086
echo $names | tr ' ' '\n' |
  xargs -P "$(nproc)" -I NAME ./scripts/fuzz-smoke.sh --one NAME "$seconds" "$scratch"
