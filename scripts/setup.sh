#!/bin/sh
# Installs every Debian package refx needs to build, test, benchmark and fuzz.
# Safe to run again: apt-get skips what is already installed.
set -eu
PACKAGES="g++ cmake ninja-build ccache pkg-config libpng-dev zlib1g-dev libfmt-dev \
libcli11-dev libgtest-dev libgmock-dev libbenchmark-dev clang libclang-rt-14-dev python3 \
libmojoshader-dev libasmjit-dev"
missing=""
for p in $PACKAGES; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing="$missing $p"
done
if [ -n "$missing" ]; then
  SUDO=""
  [ "$(id -u)" -eq 0 ] || SUDO="sudo"
  export DEBIAN_FRONTEND=noninteractive
  $SUDO apt-get update -q
  $SUDO apt-get install -y -q --no-install-recommends $missing
fi
