#!/usr/bin/env bash
# Playback on a GPU in one short run (docs/compact.md, "Rendering"): builds what is missing, then on the
# synthetic beating ellipsoid (20 frames) at 327,680 and 1,310,720 displayed triangles prints the renderer,
# ms per frame and frames per second of `contour4d render`'s classical path (each frame's mesh uploaded)
# and compact path (model.c4d decoded; frame 0 and every frame's displacement uploaded once, blended in
# the vertex shader), and writes PNGs of both paths of a reconstructed phantom.
# Targets: compact >= 6x classical at >= 100 k triangles; >= 1,000 frames/s at 1 M.
# Usage: bench/gpu_check.sh [BUILD_DIR=build] [WORK_DIR=/tmp/c4d-gpu-check] [DRAWS=200]
# Without a GPU it runs on Mesa's llvmpipe and says so in the renderer line.
set -euo pipefail
ROOT="$(cd "$(dirname "$0")/.." && pwd)"
BUILD="${1:-$ROOT/build}"
WORK="${2:-/tmp/c4d-gpu-check}"
DRAWS="${3:-200}"
C4D="$BUILD/apps/contour4d/contour4d"
BENCH="$BUILD/bench/playback_bench"
if [ ! -x "$C4D" ] || [ ! -x "$BENCH" ]; then
  bash "$ROOT/scripts/setup.sh"
  cmake -S "$ROOT" -B "$BUILD" -G Ninja -DCMAKE_BUILD_TYPE=Release -DC4D_BUILD_TESTS=OFF -DC4D_BUILD_BENCH=ON
  cmake --build "$BUILD" --target contour4d-cli playback_bench
fi
mkdir -p "$WORK"
for subdiv in 7 8; do
  "$BENCH" "$subdiv" 20 "$DRAWS" 2000 6 vertex | tee "$WORK/paths_$subdiv.txt"
done
"$C4D" phantom left-heart-cycle -o "$WORK/lh" > /dev/null
"$C4D" reconstruct "$WORK/lh/contours.json" -o "$WORK/lh_out" > /dev/null
"$C4D" render "$WORK/lh_out" -o "$WORK/png_compact" --size 800x600 > /dev/null
"$C4D" render "$WORK/lh_out" -o "$WORK/png_classical" --size 800x600 --classical > /dev/null
echo "PNGs of the 20-frame left-heart cycle: $WORK/png_compact (default path) and $WORK/png_classical"
