#!/bin/sh
# Writes everything refx produces for the built-in inputs into one folder, so two builds
# can be compared file by file (a refactoring or a new execution path must not change
# a pixel, a token or a message):
#   scripts/output-snapshot.sh OUT [REFX]
#   diff -r OLD NEW
# OUT gets: the gallery on every caps profile (PNG), every scene's frame (PNG, every
# render target) and its output, the tokens (hex) and listing of every shader assembly
# file in data/ and tests/, the validator's messages for each of them and for every
# effect, and the fxc output of every HLSL file in data/hlsl.
set -eu
cd "$(dirname "$0")/.."
OUT=${1:?usage: output-snapshot.sh OUT [REFX]}
REFX=${2:-./build/refx}
[ -x "$REFX" ] || { echo "output-snapshot: $REFX is not an executable (build first)" >&2; exit 2; }
mkdir -p "$OUT/gallery" "$OUT/scenes" "$OUT/shaders" "$OUT/effects" "$OUT/hlsl"
progress() { [ -t 2 ] && printf '\r%-70s' "$1" >&2 || true; }

for caps in data/caps/*.caps; do
  profile=$(basename "$caps" .caps)
  progress "gallery $profile"
  "$REFX" gallery --caps "$profile" --size 64x64 --out "$OUT/gallery/$profile" 2>&1 |
    sed "s|$OUT/||" > "$OUT/gallery/$profile.log" || true
  # render times differ from run to run
  sed -i 's|<i>render:</i> [0-9.]* ms||g' "$OUT/gallery/$profile/index.html"
done

for scene in tests/scenes/*.scene tests/scenes_hardware/*.scene tests/scenes_must_fail/*.scene; do
  [ -f "$scene" ] || continue
  dir=$(basename "$(dirname "$scene")"); name=$(basename "$scene" .scene)
  progress "scene $dir/$name"
  mkdir -p "$OUT/scenes/$dir"
  # Precision comes from the scene's own header; extra render targets are written too.
  "$REFX" replay "$scene" --check -o "$OUT/scenes/$dir/$name.png" > "$OUT/scenes/$dir/$name.log" 2>&1 || echo "exit=$?" >> "$OUT/scenes/$dir/$name.log"
  for target in 1 2 3; do
    "$REFX" replay "$scene" --target "$target" -o "$OUT/scenes/$dir/$name.rt$target.png" > /dev/null 2>&1 ||
      rm -f "$OUT/scenes/$dir/$name.rt$target.png"
  done
done

find data tests -type f \( -name '*.psh' -o -name '*.vsh' -o -name '*.asm' \) | sort | while read -r src; do
  key=$(echo "$src" | tr '/' '_')
  progress "shader $src"
  { "$REFX" asm "$src" -o - --no-validate 2>&1 | od -An -tx4 -v; echo "exit=$?"; } > "$OUT/shaders/$key.tokens" || true
  { "$REFX" asm "$src" -o /dev/null --listing 2>&1; echo "exit=$?"; } > "$OUT/shaders/$key.listing" || true
  { "$REFX" validate "$src" 2>&1; echo "exit=$?"; } > "$OUT/shaders/$key.validate" || true
done

find data tests -type f -name '*.fx' | sort | while read -r fx; do
  key=$(echo "$fx" | tr '/' '_')
  progress "effect $fx"
  { "$REFX" validate "$fx" 2>&1; echo "exit=$?"; } > "$OUT/effects/$key.validate" || true
done

# Each HLSL sample names its compile commands in a "// Compile:" line.
for src in data/hlsl/*.hlsl; do
  key=$(basename "$src" .hlsl)
  progress "hlsl $src"
  grep -h '^// Compile:' "$src" | sed 's/^\/\/ Compile: //' | tr ';' '\n' | while read -r _refx _fxc args; do
    # shellcheck disable=SC2086
    set -- $args
    profile=$2; entry=$4
    listing="$OUT/hlsl/$key.$profile.$entry"
    { "$REFX" fxc /T "$profile" /E "$entry" /Fc "$listing.listing" /Fo "$listing.bin" "$src" 2>&1; echo "exit=$?"; } > "$listing.log" || true
  done
done
progress ""
[ -t 2 ] && printf '\r' >&2 || true
echo "wrote $(find "$OUT" -type f | wc -l) files to $OUT"
