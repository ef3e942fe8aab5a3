#!/usr/bin/env bash
# Installs what is missing (apt), builds contour4d, and runs the main job on bundled real data:
# the LV endocardium of biv-me patient1 (25 frames of cine MRI contours) -> a 4D mesh.
# Idempotent: re-running rebuilds only what changed and replaces the outputs.
set -euo pipefail
cd "$(dirname "$0")/.."
root=$(pwd)
data="$root/../shared/data"
out="$root/out/demo"

bash scripts/setup.sh
if [ ! -d "$data/bivme-patient1" ]; then
  echo "demo.sh: the bundled data folder $data/bivme-patient1 is missing (it lives in ../shared/data beside the checkout)." >&2
  exit 1
fi

echo "== building (build-demo/) =="
cmake -S "$root" -B "$root/build-demo" -G Ninja -DCMAKE_BUILD_TYPE=Release -DC4D_BUILD_TESTS=OFF -DC4D_BUILD_BENCH=OFF >/dev/null
cmake --build "$root/build-demo" -j "$(nproc 2>/dev/null || echo 2)"
c4d="$root/build-demo/apps/contour4d/contour4d"
mkdir -p "$out"

echo
echo "== 1. read the real contours: biv-me patient1, LV endocardium, all frames =="
"$c4d" extract "$data/bivme-patient1/guidepoints" -o "$out/bivme-lv-endo.json"

echo
echo "== 2. reconstruct the 4D mesh =="
set +e
"$c4d" reconstruct "$data/bivme-patient1/guidepoints" -o "$out/bivme-lv"
rc=$?
set -e
if [ $rc -ne 0 ]; then
  echo "(reconstruct exited with code $rc; see the message above)"
fi

echo
echo "== 3. an analytic phantom with known truth: the idealized left heart of Lim et al. =="
"$c4d" phantom left-heart -o "$out/left-heart"
"$c4d" reconstruct "$out/left-heart/contours.json" -o "$out/left-heart/mesh"
echo "-- the 4D mesh against the phantom's true surface (distances in mm over every frame):"
"$c4d" evaluate "$out/left-heart/mesh" --contours "$out/left-heart/contours.json" --truth "$out/left-heart/truth"

echo
echo "Results are in $out:"
echo "  $out/bivme-lv-endo.json         contours read from the GPFiles (mm, LPS patient space)"
[ -f "$out/bivme-lv/mesh.pvd" ] && echo "  $out/bivme-lv/mesh.pvd          the 4D mesh: one .vtp per frame (add --format vtp,obj for .obj), report.json"
echo "  $out/left-heart/                contours.json, the true surface (truth/mesh.pvd) and our 4D mesh (mesh/mesh.pvd)"
echo "Look at them: open a mesh.pvd in ParaView (File > Open, then press Play); reconstruct --format vtp,obj also writes frames/*.obj for MeshLab/Blender."
