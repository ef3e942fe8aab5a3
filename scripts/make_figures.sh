#!/usr/bin/env bash
# Regenerates docs/images/bivme-4d.png: the 4D LV endocardium of biv-me patient1 drawn headless by
# `contour4d render` (EGL; Mesa's llvmpipe without a GPU), four frames side by side.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
cmake -S . -B build-demo -G Ninja -DCMAKE_BUILD_TYPE=Release -DC4D_BUILD_TESTS=OFF -DC4D_BUILD_BENCH=OFF >/dev/null
cmake --build build-demo
c4d=build-demo/apps/contour4d/contour4d
tmp=$(mktemp -d)
"$c4d" reconstruct ../shared/data/bivme-patient1/guidepoints -o "$tmp/lv" >/dev/null
"$c4d" render "$tmp/lv" -o "$tmp/png" --size 360x360 >/dev/null
/usr/bin/python3 - "$tmp" <<'PY'
import json, sys
from PIL import Image, ImageDraw
tmp = sys.argv[1]
vols = [f["volume_mm3"] / 1000 for f in json.load(open(f"{tmp}/lv/report.json"))["frames"]]
frames, w = [0, 4, 9, 16], 360
out = Image.new("RGB", (w * len(frames), w + 30), "white")
d = ImageDraw.Draw(out)
for i, f in enumerate(frames):
    out.paste(Image.open(f"{tmp}/png/frame_{f:03d}.png").convert("RGB"), (i * w, 0))
    d.text((i * w + 10, w + 8), f"frame {f}: {vols[f]:.0f} ml", fill="black")
out.save("docs/images/bivme-4d.png")
PY
rm -rf "$tmp"
echo "wrote docs/images/bivme-4d.png"
