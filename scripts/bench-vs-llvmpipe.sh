#!/bin/sh
# Runs refx's and Mesa llvmpipe's versions of the same workloads alternately in one
# run and prints, per workload, geometry, resolution and thread count: the median
# Mpixels/s of each, the ratio refx/llvmpipe, refx's cycles per pixel next to the
# workload's FLOP-bound cycles per pixel (see `refx bench`), and the lowest and highest
# of the rounds' own ratios (a wide range: the machine was busy with something else).
# Workloads without an llvmpipe version (RacorX10/11's multi-pass frames) print "-" for
# llvmpipe.
#   scripts/bench-vs-llvmpipe.sh [ROUNDS] [SECONDS_PER_RUN]
#   PAIRS="racorx9:specular" scripts/bench-vs-llvmpipe.sh   # a subset of the workloads
#   RES=1920x1080 THREADS=1 scripts/bench-vs-llvmpipe.sh     # one resolution, one thread count
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
RES=${RES:-"1024x768 1920x1080"}
THREADS=${THREADS:-"1 2"}
RAW=$(mktemp)
trap 'rm -f "$RAW"' EXIT
# workload pairs: refx workload name : llvmpipe workload name ("-": refx only)
# (RacorX6's ps.1.1 diffuse bump = llvmpipe's W2 `diffuse`, RacorX9's ps.1.1
# diffuse + specular = W3 `specular`, data/hlsl/point_light.hlsl = W4 `phong`)
PAIRS=${PAIRS:-"texture:texture racorx6:diffuse racorx9:specular phong:phong racorx10:- racorx11:-"}
for round in $(seq 1 "$ROUNDS"); do
  for pair in $PAIRS; do
    rw=${pair%%:*}; lw=${pair#*:}
    for geom in quad sphere; do
      for res in $RES; do
        W=${res%x*}; H=${res#*x}
        for thr in $THREADS; do
          [ -t 2 ] && printf '\rround %s/%s %s %s %s %s threads   ' "$round" "$ROUNDS" "$rw" "$geom" "$res" "$thr" >&2
          ./build/refx bench --workload "$rw" --geom "$geom" --threads "$thr" --size "$res" --min-time "$SECS" |
            awk -v w="$rw" -v g="$geom" -v r="$res" -v t="$thr" \
              '$1 == w {print "refx", w, g, r, t, $6, $8, $9}' >> "$RAW"
          [ "$lw" = "-" ] && continue
          LP_NUM_THREADS=$thr ./build/llvmpipe_bench --workload "$lw" --geom "$geom" --width "$W" --height "$H" \
              --min-time "$SECS" --sync frame |
            sed -n 's/.*mpix_s=\([0-9.]*\).*/\1/p' |
            awk -v w="$rw" -v g="$geom" -v r="$res" -v t="$thr" '{print "llvmpipe", w, g, r, t, $1, 0, 0}' >> "$RAW"
        done
      done
    done
  done
done
[ -t 2 ] && printf '\r%60s\r' '' >&2
# The machine the ratios belong to (they differ between CPU generations: AVX2 or
# AVX-512, one or two 256-bit halves per 512-bit operation), and refx's own notes on it.
awk -F': *' -v ncpu="$(nproc)" '/^model name/ {m = $2} /^cpu family/ {f = $2} /^model\t/ {n = $2}
             END {printf "# cpu: %s (family %s, model %s), %s logical cpus\n", m, f, n, ncpu}' \
  /proc/cpuinfo 2>/dev/null || true
./build/refx bench --workload texture --geom quad --threads 1 --size 64x64 --frames 1 | grep '^#' || true
python3 - "$RAW" "$PAIRS" <<'PY'
import sys, statistics
from collections import defaultdict
runs = defaultdict(list)
for line in open(sys.argv[1]):
    who, w, g, r, t, mpix, cyc, flop = line.split()
    runs[(who, w, g, r, t)].append((float(mpix), float(cyc), float(flop)))
order = [p.split(":")[0] for p in sys.argv[2].split()]
names = dict(p.split(":") for p in sys.argv[2].split())
def res_key(r):
    w, h = r.split("x")
    return int(w) * int(h)
keys = sorted({k[1:] for k in runs if k[0] == "refx"},
              key=lambda k: (order.index(k[0]) if k[0] in order else len(order), k[1] != "quad", res_key(k[2]), int(k[3])))
print(f"{'workload':<10} {'llvmpipe':<9} {'geom':<7} {'res':<10} {'threads':>7} {'refx Mpix/s':>12} "
      f"{'llvmpipe Mpix/s':>16} {'refx/llvmpipe':>14} {'refx cyc/px':>12} {'flop-cyc/px':>12} {'rounds min-max':>15}")
def med(who, k, i):
    v = [x[i] for x in runs.get((who,) + k, [])]
    return statistics.median(v) if v else None
for k in keys:
    w, g, r, t = k
    rm, rc, rf = med("refx", k, 0), med("refx", k, 1), med("refx", k, 2)
    lm = med("llvmpipe", k, 0)
    lcol = f"{lm:>16.1f}" if lm else f"{'-':>16}"
    ratio = f"{rm / lm:>14.2f}" if lm else f"{'-':>14}"
    # Each round's refx/llvmpipe (the two ran one after the other): how much the
    # machine moved between rounds.
    pairs = [a[0] / b[0] for a, b in zip(runs.get(("refx",) + k, []), runs.get(("llvmpipe",) + k, [])) if b[0]]
    spread = f"{min(pairs):.2f}-{max(pairs):.2f}" if pairs else "-"
    print(f"{w:<10} {names.get(w, w):<9} {g:<7} {r:<10} {t:>7} {rm:>12.1f} {lcol} {ratio} {rc:>12.1f} {rf:>12.2f}"
          f" {spread:>15}")
PY
