#!/usr/bin/python3
"""Classical baseline (Miara et al.'s "original method"): marching cubes per frame on a label mask.

Runs skimage.measure.marching_cubes on the mask of one label of every frame of a 3D or 4D label
image (NIfTI), with the voxel spacing, and reports mesh size, time and, when a sidecar JSON gives
the true ellipsoid per frame (extract_bench --c4d-write=FILE writes FILE.json), the staircase: the
radial distance of each vertex to the true surface, the same measure extract_bench reports for the
extracted contours (lv_err_*). Coordinates are voxel-index × spacing (mm), which equals world
coordinates for the identity direction and zero origin that extract_bench writes.

    /usr/bin/python3 bench/marching_cubes_baseline.py cine.nii.gz --label 3
Needs python3-skimage and python3-nibabel (Debian packages).
"""
import argparse
import json
import os
import sys
import time

import numpy as np

try:
    import nibabel as nib
    from skimage.measure import marching_cubes
except ImportError as e:  # pragma: no cover
    sys.exit(f"needs python3-skimage and python3-nibabel: {e}")


def radial_error(verts, center, axes):
    q = verts - np.asarray(center)
    r = np.sqrt(((q / np.asarray(axes)) ** 2).sum(axis=1))
    return np.linalg.norm(q, axis=1) * (r - 1) / np.maximum(r, 1e-12)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("image", help="3D or 4D label image (.nii / .nii.gz)")
    ap.add_argument("--label", type=int, default=None, help="label value (default: from the sidecar, else 1)")
    ap.add_argument("--json", help="write the figures here as JSON")
    args = ap.parse_args()

    img = nib.load(args.image)
    data = np.asanyarray(img.dataobj)
    spacing = tuple(float(s) for s in img.header.get_zooms()[:3])
    if data.ndim == 3:
        data = data[..., np.newaxis]
    truth = None
    side = args.image + ".json"
    if os.path.exists(side):
        with open(side) as f:
            truth = json.load(f)
    label = args.label if args.label is not None else (truth or {}).get("label", 1)

    frames = []
    total = 0.0
    for t in range(data.shape[3]):
        mask = (data[..., t] == label).astype(np.float32)
        # Pad so the surface closes at the volume border, as contour extraction does.
        mask = np.pad(mask, 1)
        t0 = time.perf_counter()
        verts, faces, _, _ = marching_cubes(mask, level=0.5, spacing=spacing)
        dt = time.perf_counter() - t0
        total += dt
        verts = verts - np.asarray(spacing)  # undo the padding
        row = {"frame": t, "vertices": int(len(verts)), "triangles": int(len(faces)), "seconds": dt}
        if truth:
            e = np.abs(radial_error(verts, truth["frames"][t]["center"], truth["frames"][t]["axes"]))
            row["err_max_mm"] = float(e.max())
            row["err_mean_mm"] = float(e.mean())
        frames.append(row)

    n = len(frames)
    summary = {
        "method": "marching cubes (skimage), per frame",
        "label": label,
        "frames": n,
        "frames_per_s": n / total if total > 0 else float("inf"),
        "vertices_per_frame": sum(f["vertices"] for f in frames) / n,
        "triangles_per_frame": sum(f["triangles"] for f in frames) / n,
        "bytes_per_frame_float32": sum(12 * f["vertices"] + 12 * f["triangles"] for f in frames) / n,
    }
    if truth:
        summary["err_max_mm"] = max(f["err_max_mm"] for f in frames)
        summary["err_mean_mm"] = sum(f["err_mean_mm"] for f in frames) / n
    print(json.dumps(summary, indent=2))
    if args.json:
        with open(args.json, "w") as f:
            json.dump({"summary": summary, "frames": frames}, f, indent=2)


if __name__ == "__main__":
    main()
