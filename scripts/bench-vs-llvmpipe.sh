#!/bin/sh
# Runs refx's and Mesa llvmpipe's versions of the same workloads alternately in one
# run and prints Mpixels/s and the ratio refx/llvmpipe per workload.
#   scripts/bench-vs-llvmpipe.sh [ROUNDS] [SECONDS_PER_RUN]
#   PAIRS="racorx9:specular" scripts/bench-vs-llvmpipe.sh   # a subset of the workloads
# llvmpipe's benchmark source is the anchor in ../shared/anchors/llvmpipe_bench (or
# $LLVMPIPE_BENCH_DIR); it is compiled into build/llvmpipe_bench.
set -eu
cd "$(dirname "$0")/.."
ROUNDS=${1:-3}
SECS=${2:-2}
ANCHOR=${LLVMPIPE_BENCH_DIR:-../shared/anchors/llvmpipe_bench}
[ -f "$ANCHOR/llvmpipe_bench.cpp" ] || { echo "llvmpipe anchor not found in $ANCHOR" >&2; exit 2; }
for p in libegl-dev libgl-dev libopengl-dev libegl-mesa0 libgl1-mesa-dri; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || MISSING="${MISSING:-} $p"
done
if [ -n "${MISSING:-}" ]; then
  SUDO=""; [ "$(id -u)" -eq 0 ] || SUDO=sudo
  $SUDO apt-get install -y -q --no-install-recommends $MISSING
fi
./scripts/build.sh --target refx >/dev/null
mkdir -p build
[ build/llvmpipe_bench -nt "$ANCHOR/llvmpipe_bench.cpp" ] ||
  g++ -O2 -std=c++17 -o build/llvmpipe_bench "$ANCHOR/llvmpipe_bench.cpp" -lEGL -lOpenGL
RES=1024x768
W=${RES%x*}; H=${RES#*x}
RAW=$(mktemp)
trap 'rm -f "$RAW"' EXIT
# workload pairs: refx workload name : llvmpipe workload name
# (RacorX6's ps.1.1 diffuse bump = llvmpipe's W2 `diffuse`, RacorX9's ps.1.1
# diffuse + specular = W3 `specular`)
PAIRS=${PAIRS:-"texture:texture racorx6:diffuse racorx9:specular"}
for round in $(seq 1 "$ROUNDS"); do
  for pair in $PAIRS; do
    rw=${pair%%:*}; lw=${pair#*:}
    for geom in quad sphere; do
      for thr in 1 2; do
        [ -t 2 ] && printf '\rround %s/%s %s %s %s threads   ' "$round" "$ROUNDS" "$rw" "$geom" "$thr" >&2
        ./build/refx bench --workload "$rw" --geom "$geom" --threads "$thr" --size "$RES" --min-time "$SECS" |
          awk -v w="$rw" -v g="$geom" -v t="$thr" 'NR>1 {print "refx", w, g, t, $6}' >> "$RAW"
        LP_NUM_THREADS=$thr ./build/llvmpipe_bench --workload "$lw" --geom "$geom" --width "$W" --height "$H" \
            --min-time "$SECS" --sync frame |
          sed -n 's/.*mpix_s=\([0-9.]*\).*/\1/p' | awk -v w="$rw" -v g="$geom" -v t="$thr" '{print "llvmpipe", w, g, t, $1}' >> "$RAW"
      done
    done
  done
done
[ -t 2 ] && printf '\r%60s\r' '' >&2
python3 - "$RAW" <<'PY'
import sys, statistics
from collections import defaultdict
runs = defaultdict(list)
for line in open(sys.argv[1]):
    who, w, g, t, v = line.split()
    runs[(who, w, g, t)].append(float(v))
keys = sorted({k[1:] for k in runs})
names = {"texture": "texture", "racorx6": "diffuse", "racorx9": "specular"}
print(f"{'workload':<10} {'llvmpipe':<9} {'geom':<7} {'threads':>7} {'refx Mpix/s':>12} {'llvmpipe Mpix/s':>16} {'refx/llvmpipe':>14}")
for w, g, t in keys:
    r = statistics.median(runs.get(("refx", w, g, t), [0]))
    l = statistics.median(runs.get(("llvmpipe", w, g, t), [0]))
    ratio = r / l if l else float("nan")
    print(f"{w:<10} {names.get(w, w):<9} {g:<7} {t:>7} {r:>12.1f} {l:>16.1f} {ratio:>14.2f}")
PY
