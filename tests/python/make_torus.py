#!/usr/bin/python3
"""A torus label mask whose axis is tilted against the slice normal: holes appear and vanish between slices.

    make_torus.py OUT.nii.gz [--tilt DEG] [--R MM] [--r MM] [--spacing MM] [--pixel MM] [--frames N]

Label 1 inside the torus (major radius R, tube radius r; with frames > 1 the tube breathes from r to 0.8 r
and back). Units mm; the NIfTI affine is RAS as NIfTI stores it. Prints a JSON line with the true volume
of each frame (2 π² R r², ml) and the voxel-count volume.
"""
import argparse, json, math, sys
import numpy as np
import nibabel as nib


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("out")
    p.add_argument("--tilt", type=float, default=10.0)
    p.add_argument("--R", type=float, default=30.0)
    p.add_argument("--r", type=float, default=12.0)
    p.add_argument("--spacing", type=float, default=5.0)
    p.add_argument("--pixel", type=float, default=1.0)
    p.add_argument("--frames", type=int, default=1)
    a = p.parse_args()
    t = math.radians(a.tilt)
    rot = np.array([[math.cos(t), 0, -math.sin(t)], [0, 1, 0], [math.sin(t), 0, math.cos(t)]])
    ext = a.R + a.r + 6
    n_in = int(math.ceil(2 * ext / a.pixel)) | 1
    n_sl = int(math.ceil(2 * (a.r + a.R * math.sin(t) + 6) / a.spacing)) | 1
    i = (np.arange(n_in) - (n_in - 1) / 2.0) * a.pixel
    k = (np.arange(n_sl) - (n_sl - 1) / 2.0) * a.spacing
    X, Y, Z = np.meshgrid(i, i, k, indexing="ij")
    P = np.stack([X, Y, Z], axis=-1) @ rot
    x, y, z = P[..., 0], P[..., 1], P[..., 2]
    q = np.sqrt(x * x + y * y) - a.R
    labs, truth = [], []
    for f in range(a.frames):
        s = 0.5 * (1 - math.cos(2 * math.pi * f / a.frames)) if a.frames > 1 else 0.0
        r = a.r * (1 - 0.2 * s)
        lab = (q * q + z * z <= r * r).astype(np.uint8)
        labs.append(lab)
        truth.append({"frame": f, "true_ml": 2 * math.pi ** 2 * a.R * r * r / 1000.0,
                      "voxel_ml": float(lab.sum() * a.pixel * a.pixel * a.spacing / 1000.0)})
    data = np.stack(labs, axis=-1) if a.frames > 1 else labs[0]
    aff = np.diag([a.pixel, a.pixel, a.spacing, 1.0])
    aff[:3, 3] = [-(n_in - 1) / 2 * a.pixel, -(n_in - 1) / 2 * a.pixel, -(n_sl - 1) / 2 * a.spacing]
    img = nib.Nifti1Image(data, aff)
    img.header.set_xyzt_units("mm", "msec")
    nib.save(img, a.out)
    print(json.dumps({"out": a.out, "tilt_deg": a.tilt, "truth": truth}))


if __name__ == "__main__":
    sys.exit(main())
