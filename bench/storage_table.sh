#!/usr/bin/env bash
# Miara et al. Table I for contour4d: bytes of model.c4d against per-frame marching cubes meshes
# (binary PLY) of the same organ, with the unpacked error and the glTF size, on
#  (a) the idealized left-heart cycle (phantom left-heart-cycle, 38 slice planes 2.97 mm apart; the
#      MC baseline runs on its contours filled on 512 x 512 pixels of 0.625 mm),
#  (b) a synthetic cardiac-like label mask, 512 x 512 x 38 voxels x 20 frames (0.625 x 0.625 x 2.5
#      mm), cavity label 3, reconstructed from the mask itself; and
#  (c) the left-heart cycle rasterised at 0.5 mm isotropic voxels, against the model of its own contours.
# Usage: bench/storage_table.sh [BUILD_DIR=build] [WORK_DIR=/tmp/c4d-storage]
# Needs python3-numpy, python3-nibabel, python3-skimage, python3-matplotlib. Takes a few minutes.
set -euo pipefail
ROOT="$(cd "$(dirname "$0")/.." && pwd)"
BUILD="${1:-$ROOT/build}"
WORK="${2:-/tmp/c4d-storage}"
C4D="$BUILD/apps/contour4d/contour4d"
PY=/usr/bin/python3
TOOL="$ROOT/bench/storage_table.py"
[ -x "$C4D" ] || { echo "storage_table: no $C4D (build the contour4d-cli target first)" >&2; exit 1; }
mkdir -p "$WORK"
cd "$WORK"

field() { sed -n "s/.*\"$2\": \([0-9.e+-]*\).*/\1/p" "$1" | head -1; }

# One case: NAME MASK LABEL RECONSTRUCT-INPUT [reconstruct options...]
run_case() {
  local name=$1 mask=$2 label=$3 input=$4
  shift 4
  echo "== $name"
  rm -rf "mc_$name" "rec_$name" "unpacked_$name"
  "$PY" "$TOOL" mc "$mask" "mc_$name" --label "$label" > "mc_$name.json"
  "$C4D" reconstruct "$input" "$@" --format vtp,obj -o "rec_$name" > "rec_$name.log"
  "$C4D" pack "rec_$name" -o "rec_$name/model.c4d" > "pack_vertex_$name.log"
  # The same vertex bound (0.05 mm) without the bound on the normals: the grid the tolerance alone allows.
  "$C4D" pack "rec_$name" --normal-p99 90 --step 0.0577 -o "rec_$name/model_coarse.c4d" --no-gltf > "pack_coarse_$name.log"
  "$C4D" unpack "rec_$name/model.c4d" --format vtp,obj -o "unpacked_$name" > /dev/null
  "$PY" "$TOOL" compare "rec_$name" "unpacked_$name" > "compare_$name.json"
  local mc_bytes tris c4d_v c4d_s glb fine
  mc_bytes=$(field "mc_$name.json" bytes)
  tris=$(field "mc_$name.json" triangles_per_frame)
  c4d_v=$(stat -c %s "rec_$name/model.c4d")
  c4d_s=$(stat -c %s "rec_$name/model_coarse.c4d")
  glb=$(stat -c %s "rec_$name/model.glb")
  fine=$(grep -o 'mesh: [0-9]* vertices, [0-9]* triangles' "rec_$name.log" | head -1)
  echo "  per-frame MC meshes (binary PLY): $mc_bytes B, $(printf %.0f "$tris") triangles/frame"
  echo "  our 4D mesh: $fine"
  echo "  model.c4d (default)          : $c4d_v B  ratio $(echo "$mc_bytes / $c4d_v" | bc -l | xargs printf %.1f)x"
  echo "    $(grep 'error vs input' "pack_vertex_$name.log" | sed 's/^ *//')"
  echo "    unpacked vs full resolution (independent check): $(cat "compare_$name.json")"
  echo "  model.c4d, no normal bound  : $c4d_s B  ratio $(echo "$mc_bytes / $c4d_s" | bc -l | xargs printf %.1f)x"
  echo "    $(grep 'error vs input' "pack_coarse_$name.log" | sed 's/^ *//')"
  echo "  model.glb: $glb B  ratio $(echo "$mc_bytes / $glb" | bc -l | xargs printf %.1f)x"
}

echo "== generating inputs in $WORK"
"$C4D" phantom left-heart-cycle --spacing 2.9729 --offset 32.5 -o lh > /dev/null
"$PY" "$TOOL" contour-mask lh/contours.json lh_mask.nii.gz
"$PY" "$TOOL" lv-mask lv_mask.nii.gz

run_case left-heart lh_mask.nii.gz 1 lh/contours.json
run_case lv-mask lv_mask.nii.gz 3 lv_mask.nii.gz --labels acdc --label lv

# (c) The issue's baseline: the left-heart cycle rasterised at 0.5 mm isotropic voxels (the analytic
# phantom, voxel centres inside), marching cubes per frame, against the model of the reconstruction from
# the phantom's own contours (5 mm apart).
echo "== left-heart, marching cubes at 0.5 mm voxels"
"$C4D" phantom left-heart-cycle -o lh05 --mask lh05_mask.nii.gz --mask-spacing 0.5,0.5,0.5 > /dev/null
"$PY" "$TOOL" mc lh05_mask.nii.gz mc_lh05 --label 1 > mc_lh05.json
"$C4D" phantom left-heart-cycle -o lh5 > /dev/null
rm -rf rec_lh5
"$C4D" reconstruct lh5/contours.json -o rec_lh5 > rec_lh5.log
"$C4D" pack rec_lh5 --no-gltf > pack_lh5.log
"$C4D" pack rec_lh5 --normal-p99 90 --step 0.0577 -o rec_lh5/model_coarse.c4d --no-gltf > pack_lh5_coarse.log
mc05=$(field mc_lh05.json bytes)
echo "  per-frame MC meshes (binary PLY): $mc05 B, $(printf %.0f "$(field mc_lh05.json triangles_per_frame)") triangles/frame"
for f in model model_coarse; do
  b=$(stat -c %s "rec_lh5/$f.c4d")
  echo "  $f.c4d: $b B  ratio $(echo "$mc05 / $b" | bc -l | xargs printf %.1f)x"
done
