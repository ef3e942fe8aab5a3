#!/usr/bin/python3
"""Tilted tori, where holes appear and vanish between slices: each must come out as one valid genus-1 surface
whose volume between the first and last slice planes is within 2 % of the true torus's there.

    check_tilted_torus.py CLI CASES [--frames N]     (CASES: first:last, last excluded, or a comma list of them)

Case 0 is the issue's torus (tilt 10°, R 30 mm, tube 12 mm, 5 mm slices, 1 mm pixels); cases 1.. are drawn
from a seeded family (tilt 3–30°, R 20–35 mm, tube 8–14 mm, slices 3 mm to 0.6 × the tube radius apart,
pixels 0.8–1.5 mm). With --frames N the tube breathes (make_torus.py) and the whole cycle is reconstructed;
frames 0 and N/2 are measured. The mask is written by make_torus.py; the truth in the slab is the torus's
indicator integrated on a 0.2 mm grid. Prints one line per case; exits non-zero on the first failure.
"""
import argparse
import json
import math
import os
import random
import subprocess
import sys
import tempfile

import numpy as np

try:
    from vtkmodules.vtkCommonDataModel import vtkPlane, vtkPlaneCollection
    from vtkmodules.vtkFiltersCore import vtkMassProperties, vtkTriangleFilter
    from vtkmodules.vtkFiltersGeneral import vtkClipClosedSurface
    from vtkmodules.vtkIOXML import vtkXMLPolyDataReader
except ImportError as e:
    sys.exit(f"python3-vtk9 is missing ({e}): run scripts/setup.sh")

HERE = os.path.dirname(os.path.abspath(__file__))


def case(seed):
    """(tilt°, R, r, slice spacing, pixel) of one case."""
    if seed == 0:
        return 10.0, 30.0, 12.0, 5.0, 1.0
    rng = random.Random(seed)
    tilt, big, small = rng.uniform(3, 30), rng.uniform(20, 35), rng.uniform(8, 14)
    return tilt, big, small, rng.uniform(3, 0.6 * small), rng.uniform(0.8, 1.5)


def truth_in_slab(big, small, tilt, z0, z1, step=0.2):
    """Volume (mm³) of the tilted torus between the planes z = z0 and z = z1, on a grid of `step` mm."""
    t = math.radians(tilt)
    rot = np.array([[math.cos(t), 0, -math.sin(t)], [0, 1, 0], [math.sin(t), 0, math.cos(t)]])
    ext = big + small + 2
    g = np.arange(-ext, ext, step) + step / 2
    x, y = np.meshgrid(g, g, indexing="ij")
    nz = int(math.ceil((z1 - z0) / step))
    dz = (z1 - z0) / nz
    count = 0
    for z in z0 + (np.arange(nz) + 0.5) * dz:
        p = np.stack([x, y, np.full_like(x, z)], -1) @ rot
        q = np.hypot(p[..., 0], p[..., 1]) - big
        count += np.count_nonzero(q * q + p[..., 2] ** 2 <= small * small)
    return count * step * step * dz


def mesh_in_slab(vtp, z0, z1):
    """Volume (mm³) of the closed surface in `vtp` between the planes z = z0 and z = z1 (VTK's clip)."""
    reader = vtkXMLPolyDataReader()
    reader.SetFileName(vtp)
    planes = vtkPlaneCollection()
    for origin, normal in ((z0, 1), (z1, -1)):
        p = vtkPlane()
        p.SetOrigin(0, 0, origin)
        p.SetNormal(0, 0, normal)
        planes.AddItem(p)
    clip = vtkClipClosedSurface()
    clip.SetInputConnection(reader.GetOutputPort())
    clip.SetClippingPlanes(planes)
    tri = vtkTriangleFilter()
    tri.SetInputConnection(clip.GetOutputPort())
    mass = vtkMassProperties()
    mass.SetInputConnection(tri.GetOutputPort())
    mass.Update()
    return mass.GetVolume()


def run(cli, seed, frames, work):
    tilt, big, small, spacing, pixel = case(seed)
    d = os.path.join(work, f"case{seed}")
    os.makedirs(d)
    mask = os.path.join(d, "torus.nii.gz")
    subprocess.run([sys.executable, os.path.join(HERE, "make_torus.py"), mask, "--tilt", str(tilt), "--R", str(big),
                    "--r", str(small), "--spacing", str(spacing), "--pixel", str(pixel), "--frames", str(frames)],
                   check=True, capture_output=True)
    out = os.path.join(d, "out")
    args = [cli, "reconstruct", mask, "--threads", "2", "-o", out] + (["--frame", "0"] if frames == 1 else [])
    r = subprocess.run(args, capture_output=True, text=True)
    name = f"case {seed} (tilt {tilt:.1f}°, R {big:.1f}, r {small:.1f}, slices {spacing:.2f} mm, pixels {pixel:.2f} mm)"
    if r.returncode != 0:
        return f"{name}: reconstruct exited {r.returncode}: {r.stderr.strip()[-300:]}", None
    subprocess.run([cli, "evaluate", out, "--check"], check=True, capture_output=True)
    ev = json.load(open(os.path.join(out, "evaluation.json")))
    subprocess.run([cli, "extract", mask, "-o", os.path.join(d, "c.json")], check=True, capture_output=True)
    contours = json.load(open(os.path.join(d, "c.json")))
    errors = []
    for f in sorted({0, frames // 2}):
        topo = ev["frames"][f]["topology"]
        if topo["genus"] != 1 or topo["components"] != 1:
            return f"{name}: frame {f} has genus {topo['genus']} and {topo['components']} components", None
        zs = [c["points"][0][2] for c in contours["frames"][f]["contours"]]
        breathe = 0.5 * (1 - math.cos(2 * math.pi * f / frames)) if frames > 1 else 0.0
        truth = truth_in_slab(big, small * (1 - 0.2 * breathe), tilt, min(zs), max(zs))
        vol = mesh_in_slab(os.path.join(out, "frames", f"frame_{f:03d}.vtp"), min(zs), max(zs))
        errors.append(100 * (vol / truth - 1))
    line = f"{name}: genus 1, volume in the slab " + ", ".join(f"{e:+.2f} %" for e in errors)
    return line, max(abs(e) for e in errors)


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("cli")
    p.add_argument("cases", help="first:last (last excluded) or a comma list of them, e.g. 0:8,24:25")
    p.add_argument("--frames", type=int, default=1)
    p.add_argument("--max-volume-error", type=float, default=2.0, help="percent")
    a = p.parse_args()
    seeds = []
    for part in a.cases.split(","):
        first, last = (int(x) for x in part.split(":"))
        seeds += range(first, last)
    with tempfile.TemporaryDirectory() as work:
        for seed in seeds:
            line, err = run(a.cli, seed, a.frames, work)
            print(line, flush=True)
            if err is None or err > a.max_volume_error:
                sys.exit(f"FAILED: {line}")
    print("all tilted tori valid")


if __name__ == "__main__":
    main()
