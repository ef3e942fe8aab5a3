#!/usr/bin/python3
"""Miara et al. Table I for contour4d: per-frame marching cubes meshes against model.c4d.

Subcommands (bench/storage_table.sh runs them in order):

  lv-mask OUT.nii.gz      a cardiac-like 4D label mask, 512 x 512 x 38 voxels x 20 frames
                          (0.625 x 0.625 x 2.5 mm): a beating thick-walled half-ellipsoidal left
                          ventricle, myocardium label 2 and cavity label 3 (ACDC numbering), with
                          ejection, base descent, wall thickening and twist of an elliptic section.
  contour-mask CONTOURS.json OUT.nii.gz
                          the same kind of mask from a phantom's contours: each slice's contours
                          filled (even-odd) on a 512 x 512 grid of 0.625 mm pixels in the slice
                          plane, one voxel layer per slice plane; label 1. Slice planes must be normal to a coordinate axis.
  mc MASK.nii.gz OUTDIR --label L
                          marching cubes (skimage, level 0.5, voxel spacing) of label L in every
                          frame, one binary little-endian PLY per frame (float32 x,y,z; uchar 3 +
                          int32 x 3 per face): the "original method" of Table I. Prints the bytes.
  compare FULL_DIR UNPACKED_DIR
                          the per-vertex error of the unpacked meshes against the full-resolution
                          ones (frames/frame_NNN.obj in both): vertices matched once on frame 0
                          (nearest neighbour; pack reorders ids), then the distance of every
                          matched vertex in every frame.
Needs python3-numpy, python3-nibabel, python3-skimage, python3-matplotlib (Debian).
"""
import argparse
import glob
import json
import math
import os
import sys

import numpy as np

try:
    import nibabel as nib
except ImportError as e:  # pragma: no cover
    sys.exit(f"needs python3-nibabel: {e}")

DIMS = (512, 512, 38)
SPACING = (0.625, 0.625, 2.5)
FRAMES = 20


def ejection(phase):
    # Cardiac volume curve: ejection to end-systole at 35 % of the cycle, then filling.
    if phase < 0.35:
        return 0.5 - 0.5 * math.cos(math.pi * phase / 0.35)
    return 0.5 + 0.5 * math.cos(math.pi * (phase - 0.35) / 0.65)


def lv_mask(out):
    nx, ny, nz = DIMS
    sx, sy, sz = SPACING
    x = (np.arange(nx, dtype=np.float32) - nx / 2 + 0.3) * sx  # mm from the long axis
    y = (np.arange(ny, dtype=np.float32) - ny / 2 - 0.2) * sy
    X, Y = np.meshgrid(x, y, indexing="ij")
    data = np.zeros((nx, ny, nz, FRAMES), dtype=np.uint8)
    truth = []
    for f in range(FRAMES):
        e = ejection(f / FRAMES)
        apex = 14.0 + 2.0 * e                 # cavity apex (mm along the slice axis)
        base = 84.0 - 8.0 * e                 # base plane descends towards the apex in systole
        a = 26.0 * (1.0 - 0.22 * e)           # cavity semi-axes in the section (mm)
        b = 22.0 * (1.0 - 0.22 * e)
        c = base - apex                       # cavity half-length (the base is the equator)
        w = 9.0 + 4.0 * e                     # wall thickens in systole
        twist = 0.3 * e                       # rad at the base, 0 at the apex
        for k in range(nz):
            z = k * sz
            if z > base:
                continue
            s = (base - z) / c                # 0 at the base, 1 at the cavity apex
            ang = twist * (1.0 - s) + 0.2
            U = X * math.cos(ang) + Y * math.sin(ang)
            V = -X * math.sin(ang) + Y * math.cos(ang)
            zz = (base - z)
            cav = (U / a) ** 2 + (V / b) ** 2 + (zz / c) ** 2 <= 1.0
            epi = (U / (a + w)) ** 2 + (V / (b + w)) ** 2 + (zz / (c + w)) ** 2 <= 1.0
            sl = data[:, :, k, f]
            sl[epi] = 2
            sl[cav] = 3
        truth.append({"frame": f, "apex_mm": apex, "base_mm": base, "a": a, "b": b, "wall": w})
    aff = np.diag([SPACING[0], SPACING[1], SPACING[2], 1.0])
    img = nib.Nifti1Image(data, aff)
    img.header.set_zooms(SPACING + (1.0,))
    img.header.set_xyzt_units("mm", "msec")
    nib.save(img, out)
    print(f"wrote {out}: {nx}x{ny}x{nz} voxels x {FRAMES} frames, spacing {SPACING} mm, labels myo=2 lv=3")


def contour_mask(contours_json, out, n=512, pixel=0.625):
    from matplotlib.path import Path
    d = json.load(open(contours_json))
    frames = d["frames"]
    pts = np.concatenate([np.asarray(c["points"], float) for fr in frames for c in fr["contours"]])
    # The slice axis: the coordinate constant within each contour.
    c0 = np.asarray(frames[0]["contours"][0]["points"], float)
    axis = int(np.argmin(np.ptp(c0, axis=0)))
    inplane = [i for i in range(3) if i != axis]
    planes = sorted({round(float(np.asarray(c["points"], float)[0, axis]), 6) for fr in frames for c in fr["contours"]})
    lo = pts[:, inplane].min(axis=0)
    hi = pts[:, inplane].max(axis=0)
    pix = pixel if pixel > 0 else float((hi - lo).max()) * 1.1 / n
    if float((hi - lo).max()) > pix * (n - 2):
        sys.exit(f"the contours span {float((hi - lo).max()):.1f} mm: more than {n} pixels of {pix} mm")
    origin = (lo + hi) / 2 - pix * n / 2
    data = np.zeros((n, n, len(planes), len(frames)), dtype=np.uint8)
    index = {p: i for i, p in enumerate(planes)}
    for f, fr in enumerate(frames):
        for c in fr["contours"]:
            p = np.asarray(c["points"], float)
            k = index[round(float(p[0, axis]), 6)]
            q = p[:, inplane]
            a = np.clip(np.floor((q.min(axis=0) - origin) / pix).astype(int) - 1, 0, n)
            b = np.clip(np.ceil((q.max(axis=0) - origin) / pix).astype(int) + 1, 0, n)
            U, V = np.meshgrid(origin[0] + (np.arange(a[0], b[0]) + 0.5) * pix,
                               origin[1] + (np.arange(a[1], b[1]) + 0.5) * pix, indexing="ij")
            inside = Path(q).contains_points(np.column_stack([U.ravel(), V.ravel()])).reshape(U.shape)
            data[a[0]:b[0], a[1]:b[1], k, f] ^= inside.astype(np.uint8)  # even-odd: holes
    dz = planes[1] - planes[0] if len(planes) > 1 else 1.0
    print(f"wrote {out}: {n}x{n}x{len(planes)} voxels x {len(frames)} frames, pixel {pix:.4f} mm, "
          f"slice {dz:.3f} mm (axis {axis}), label 1")
    aff = np.diag([pix, pix, dz, 1.0])
    img = nib.Nifti1Image(data, aff)
    img.header.set_zooms((pix, pix, dz, 1.0))
    nib.save(img, out)


def write_ply(path, verts, faces):
    header = ("ply\nformat binary_little_endian 1.0\n"
              f"element vertex {len(verts)}\nproperty float x\nproperty float y\nproperty float z\n"
              f"element face {len(faces)}\nproperty list uchar int vertex_indices\nend_header\n").encode()
    v = np.ascontiguousarray(verts, dtype="<f4").tobytes()
    fa = np.zeros(len(faces), dtype=[("n", "u1"), ("i", "<i4", 3)])
    fa["n"] = 3
    fa["i"] = faces
    with open(path, "wb") as fh:
        fh.write(header)
        fh.write(v)
        fh.write(fa.tobytes())
    return len(header) + len(v) + fa.nbytes


def mc(mask_path, outdir, label):
    from skimage.measure import marching_cubes
    img = nib.load(mask_path)
    data = np.asanyarray(img.dataobj)
    spacing = tuple(float(s) for s in img.header.get_zooms()[:3])
    if data.ndim == 3:
        data = data[..., None]
    os.makedirs(outdir, exist_ok=True)
    total = 0
    tris = 0
    verts_total = 0
    for t in range(data.shape[3]):
        m = (data[..., t] == label)
        idx = np.argwhere(m)
        lo = np.maximum(idx.min(axis=0) - 1, 0)
        hi = idx.max(axis=0) + 2
        crop = np.pad(m[lo[0]:hi[0], lo[1]:hi[1], lo[2]:hi[2]].astype(np.float32), 1)
        v, fc, _, _ = marching_cubes(crop, 0.5, spacing=spacing)
        v += (lo - 1) * np.asarray(spacing)
        total += write_ply(os.path.join(outdir, f"frame_{t:03d}.ply"), v, fc)
        tris += len(fc)
        verts_total += len(v)
    nf = data.shape[3]
    print(json.dumps({"frames": nf, "bytes": total, "triangles_per_frame": tris / nf,
                      "vertices_per_frame": verts_total / nf, "spacing": spacing}))


def read_obj(path):
    v = []
    with open(path) as fh:
        for line in fh:
            if line.startswith("v "):
                v.append([float(s) for s in line.split()[1:4]])
    return np.asarray(v)


def compare(full_dir, unpacked_dir):
    a = sorted(glob.glob(os.path.join(full_dir, "frames", "frame_*.obj")))
    b = sorted(glob.glob(os.path.join(unpacked_dir, "frames", "frame_*.obj")))
    if not a or len(a) != len(b):
        sys.exit(f"frame counts differ or no OBJ frames: {len(a)} vs {len(b)}")
    A0, B0 = read_obj(a[0]), read_obj(b[0])
    if len(A0) != len(B0):
        sys.exit(f"vertex counts differ: {len(A0)} vs {len(B0)}")
    match = np.empty(len(B0), dtype=np.int64)
    for s in range(0, len(B0), 512):  # brute-force nearest neighbour, chunked
        d = ((B0[s:s + 512, None, :] - A0[None, :, :]) ** 2).sum(axis=2)
        match[s:s + 512] = d.argmin(axis=1)
    bijective = len(np.unique(match)) == len(match)
    worst = 0.0
    sq = 0.0
    n = 0
    for fa, fb in zip(a, b):
        e = np.linalg.norm(read_obj(fb) - read_obj(fa)[match], axis=1)
        worst = max(worst, float(e.max()))
        sq += float((e ** 2).sum())
        n += len(e)
    print(json.dumps({"frames": len(a), "vertices": len(A0), "bijective_match": bool(bijective),
                      "max_mm": worst, "rms_mm": math.sqrt(sq / n)}))


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = ap.add_subparsers(dest="cmd", required=True)
    p = sub.add_parser("lv-mask")
    p.add_argument("out")
    p = sub.add_parser("contour-mask")
    p.add_argument("contours")
    p.add_argument("out")
    p.add_argument("--size", type=int, default=512)
    p.add_argument("--pixel", type=float, default=0.625, help="pixel size (mm); 0: fit the contours")
    p = sub.add_parser("mc")
    p.add_argument("mask")
    p.add_argument("outdir")
    p.add_argument("--label", type=int, default=1)
    p = sub.add_parser("compare")
    p.add_argument("full")
    p.add_argument("unpacked")
    a = ap.parse_args()
    if a.cmd == "lv-mask":
        lv_mask(a.out)
    elif a.cmd == "contour-mask":
        contour_mask(a.contours, a.out, a.size, a.pixel)
    elif a.cmd == "mc":
        mc(a.mask, a.outdir, a.label)
    else:
        compare(a.full, a.unpacked)


if __name__ == "__main__":
    main()
