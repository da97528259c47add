#!/bin/sh
# Configures (once) and builds refx into ./build. Extra arguments go to cmake --build.
set -eu
cd "$(dirname "$0")/.."
[ -f build/build.ninja ] || cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release
cmake --build build "$@"
