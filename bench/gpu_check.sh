#!/usr/bin/env bash
# Playback on a GPU in one short run (docs/compact.md, "Rendering"): builds the command line if it is
# missing, prints the renderer, then ms per frame of the classical path (each frame's mesh uploaded) and
# the compact path (frame 0 and every frame's displacement uploaded once, blended in the vertex shader) at
# about 100 k and 1 M displayed triangles, the speed-up, frames per second, and writes PNGs of both paths.
# The scene: the ellipsoid phantom's analytic truth, 20 frames, one triangle list for all frames.
# Targets: compact >= 6x classical at >= 100 k triangles; >= 1,000 frames/s at 1 M.
# Usage: bench/gpu_check.sh [BUILD_DIR=build] [WORK_DIR=/tmp/c4d-gpu-check] [DRAWS=200]
# Without a GPU it runs on Mesa's llvmpipe and says so in the renderer line.
set -euo pipefail
ROOT="$(cd "$(dirname "$0")/.." && pwd)"
BUILD="${1:-$ROOT/build}"
WORK="${2:-/tmp/c4d-gpu-check}"
DRAWS="${3:-200}"
C4D="$BUILD/apps/contour4d/contour4d"
if [ ! -x "$C4D" ]; then
  bash "$ROOT/scripts/setup.sh"
  cmake -S "$ROOT" -B "$BUILD" -G Ninja -DCMAKE_BUILD_TYPE=Release -DC4D_BUILD_TESTS=OFF -DC4D_BUILD_BENCH=OFF
  cmake --build "$BUILD" --target contour4d-cli
fi
mkdir -p "$WORK"

# One scene: NAME TRUTH_EDGE_MM (0.5 mm: about 94 k triangles; 0.15 mm: about 1.05 M).
scene() {
  local name=$1 edge=$2 dir="$WORK/$1"
  [ -d "$dir/truth" ] || "$C4D" phantom ellipsoid --frames 20 --truth-edge "$edge" -o "$dir" > /dev/null
  "$C4D" render "$dir/truth" --bench "$DRAWS" --size 800x600 | tee "$WORK/$name.txt"
  local c k
  c=$(sed -n 's/.*classical: \([0-9.]*\) ms.*/\1/p' "$WORK/$name.txt")
  k=$(sed -n 's/.*compact: *\([0-9.]*\) ms.*/\1/p' "$WORK/$name.txt")
  echo "  $name: compact $(echo "$c / $k" | bc -l | xargs printf %.1f)x classical, $(echo "1000 / $k" | bc -l | xargs printf %.0f) frames/s compact"
  "$C4D" render "$dir/truth" -o "$WORK/png_$name" --frames 4 --size 800x600 > /dev/null
  "$C4D" render "$dir/truth" -o "$WORK/png_${name}_classical" --frames 4 --size 800x600 --classical > /dev/null
}

scene 100k 0.5
scene 1M 0.15
echo "PNGs in $WORK/png_* (compact) and $WORK/png_*_classical"
