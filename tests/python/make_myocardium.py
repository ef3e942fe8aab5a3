#!/usr/bin/python3
"""Myocardium-shell label masks: a family of left-ventricular walls for the all-frames tests.

An ellipsoidal shell (label 2, the acdc preset's "myo") around a cavity (label 3, "lv") that closes
towards the apex, cut by parallel short-axis slices, contracting through the frames. Every shape
parameter can be drawn from a seed, so the tests build a family of cases instead of one phantom:

    make_myocardium.py OUT.nii.gz [--seed S] [--frames N] [--wall MM] [--contraction C] [--tilt DEG]
                       [--slices K] [--spacing MM] [--pixel MM]

Units are millimetres; the NIfTI affine is RAS as NIfTI stores it (contour4d reads it as LPS through
ITK). Prints a JSON line with the parameters and, per frame, the voxel counts of each label × the
voxel volume (ml), the truth a reconstruction's volume is checked against.
"""
import argparse
import json
import math
import sys

import numpy as np
import nibabel as nib


def shell_frame(shape, pixel, spacing, rot, center_z, a_out, c_out, wall, base_z):
    """Labels of one frame: 2 inside the outer ellipsoid and outside the inner one, 3 in the cavity.

    The ellipsoids are truncated at base_z (the base plane, open like a real ventricle's base). The
    inner one (the cavity) is the outer shrunk by the wall thickness, so the wall closes at the apex."""
    nx, ny, nz = shape
    i = (np.arange(nx) - (nx - 1) / 2.0) * pixel
    j = (np.arange(ny) - (ny - 1) / 2.0) * pixel
    k = (np.arange(nz) - (nz - 1) / 2.0) * spacing
    X, Y, Z = np.meshgrid(i, j, k, indexing="ij")
    P = np.stack([X, Y, Z - center_z], axis=-1) @ rot  # voxel centres in the body frame (rot: rows = body axes)
    x, y, z = P[..., 0], P[..., 1], P[..., 2]
    out = (x / a_out) ** 2 + (y / a_out) ** 2 + (z / c_out) ** 2 <= 1.0
    a_in, c_in = a_out - wall, c_out - wall
    inn = (x / a_in) ** 2 + (y / a_in) ** 2 + (z / c_in) ** 2 <= 1.0
    keep = Z <= base_z  # the base plane is a plane of the image (between two slices)
    lab = np.zeros(shape, np.uint8)
    lab[out & keep] = 2
    lab[inn & keep] = 3
    return lab


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("out")
    p.add_argument("--seed", type=int, default=None, help="draw the parameters not given from this seed")
    p.add_argument("--frames", type=int)
    p.add_argument("--wall", type=float, help="wall thickness (mm)")
    p.add_argument("--contraction", type=float, help="volume contraction at end systole (0.12 = 12 %%)")
    p.add_argument("--tilt", type=float, help="tilt of the long axis against the slice normal (deg)")
    p.add_argument("--slices", type=int)
    p.add_argument("--spacing", type=float, help="slice spacing (mm)")
    p.add_argument("--pixel", type=float, help="in-plane pixel (mm)")
    a = p.parse_args()
    rng = np.random.default_rng(a.seed if a.seed is not None else 0)
    draw = lambda v, lo, hi: v if v is not None else float(rng.uniform(lo, hi))
    frames = a.frames if a.frames is not None else int(rng.integers(4, 21))
    wall = draw(a.wall, 5.0, 10.0)
    contraction = draw(a.contraction, 0.05, 0.35)
    tilt = draw(a.tilt, 0.0, 15.0)
    slices = a.slices if a.slices is not None else 12
    spacing = draw(a.spacing, 8.0, 8.0) if a.spacing is None else a.spacing
    pixel = a.pixel if a.pixel is not None else 1.25
    phase = float(rng.uniform(0, 2 * math.pi))
    # Outer semi-axes at end diastole (mm): the ellipsoid's centre lies just below the base plane (a
    # truncated half-ellipsoid, open at the base) and its apex about one slice above the lowest slice, so
    # the cavity (the outer shrunk by the wall) closes on the slices above the apex.
    half = 0.5 * (slices - 1) * spacing
    base = half - 0.5 * spacing  # between the top two slices
    a0 = float(rng.uniform(24.0, 30.0))
    c0 = (base + half - spacing) / 1.1 + float(rng.uniform(-0.5, 0.5)) * spacing
    if a.seed is None:
        phase = 0.0
        a0, c0 = 27.0, (base + half - spacing) / 1.1
    center_z = base - 0.1 * c0
    t = math.radians(tilt)
    rot = np.array([[math.cos(t), 0, -math.sin(t)], [0, 1, 0], [math.sin(t), 0, math.cos(t)]]) @ np.array(
        [[math.cos(phase), -math.sin(phase), 0], [math.sin(phase), math.cos(phase), 0], [0, 0, 1]])
    extent = 2 * a0 + 16
    n_in = int(math.ceil(extent / pixel)) | 1
    shape = (n_in, n_in, slices)
    vox_ml = pixel * pixel * spacing / 1000.0
    labs, truth = [], []
    for f in range(frames):
        # a smooth cycle: contraction peaks at the middle frame (volume scale 1 − contraction)
        s = 0.5 * (1 - math.cos(2 * math.pi * f / frames)) if frames > 1 else 0.0
        scale = (1.0 - contraction * s) ** (1.0 / 3.0)
        lab = shell_frame(shape, pixel, spacing, rot, center_z, a0 * scale, c0 * scale, wall, base)
        labs.append(lab)
        truth.append({"frame": f, "myo_ml": float((lab == 2).sum() * vox_ml), "lv_ml": float((lab == 3).sum() * vox_ml)})
    data = np.stack(labs, axis=-1) if frames > 1 else labs[0]
    aff = np.diag([pixel, pixel, spacing, 1.0])
    aff[:3, 3] = [-(n_in - 1) / 2 * pixel, -(n_in - 1) / 2 * pixel, -(slices - 1) / 2 * spacing]
    img = nib.Nifti1Image(data, aff)
    img.header.set_xyzt_units("mm", "msec")
    nib.save(img, a.out)
    print(json.dumps({"out": a.out, "seed": a.seed, "frames": frames, "wall_mm": wall, "contraction": contraction,
                      "tilt_deg": tilt, "slices": slices, "spacing_mm": spacing, "pixel_mm": pixel,
                      "truth": truth}))


if __name__ == "__main__":
    sys.exit(main())
