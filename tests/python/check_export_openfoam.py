#!/usr/bin/python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Runs Debian's OpenFOAM (v1912) on an OpenFOAM export of `contour4d export` and checks the result.

usage: check_export_openfoam.py OUTDIR EXPORTDIR [TOL_MM]

On a copy of EXPORTDIR/openfoam written every step: checkMesh passes on the cavity; moveDynamicMesh moves the
mesh through the whole exported time span (displacementLaplacian, the wall and every opened end driven by
constant/boundaryData), its own per-step mesh check counting the cells of zero or negative volume; the moved
points of every surface vertex match, at every time, the export's own wall (boundaryData points + displacement)
and, on the vertices of no opened end, this script's own periodic Catmull-Rom of OUTDIR's frames within
TOL_MM (default 1e-6 mm); with the export's cavity/steps (--cavity-steps), contour4d's own moving cavity written as
OpenFOAM time directories passes checkMesh at every time. Exit 77 (skipped) with a message when OpenFOAM is not
installed; exit 0 when moveDynamicMesh inverted no cell either, exit 3 when all of the rest holds but OpenFOAM's
own displacementLaplacian inverted cells somewhere (the counts are printed).
"""
import os
import re
import shutil
import subprocess
import sys
import tempfile
import glob

import vtk
from vtk.util.numpy_support import vtk_to_numpy

import numpy as np

from export_common import catmull_rom, export_report, read_frames, wall_only_vertices

FOAM_DIR = "/usr/share/openfoam"


def foam(cmd, case, log):
    env = dict(os.environ, WM_PROJECT_DIR=FOAM_DIR, PWD=case)
    with open(log, "w") as f:
        rc = subprocess.call(cmd + ["-case", case], stdout=f, stderr=subprocess.STDOUT, env=env, cwd=case)
    text = open(log).read()
    if rc != 0:
        sys.exit(f"{' '.join(cmd)} failed ({rc}):\n{text[-3000:]}")
    return text


def read_vectors(path):
    """An OpenFOAM ASCII vectorField (points, pointDisplacement): N ( (x y z) ... )."""
    text = open(path).read()
    body = text
    if "FoamFile" in text:
        body = text[text.index("FoamFile"):]
        body = body[body.index("}") + 1:]
    body = "\n".join(line for line in body.splitlines() if not line.lstrip().startswith("//"))
    m = re.search(r"(\d+)\s*\(", body)
    n = int(m.group(1))
    nums = re.findall(r"\(([^()]*)\)", body[m.end() - 1:])
    v = np.array([[float(x) for x in s.split()] for s in nums[:n]])
    assert v.shape == (n, 3), path
    return v


def time_dirs(case):
    out = []
    for name in os.listdir(case):
        try:
            out.append((float(name), name))
        except ValueError:
            pass
    return sorted(out)


def check_own_motion(exportdir, work, unit_mm, rep):
    """contour4d's moving cavity (cavity/steps/*.vtu, --cavity-steps) as OpenFOAM time directories: checkMesh at
    every time must find no cell of zero or negative volume."""
    steps = sorted(glob.glob(os.path.join(exportdir, "cavity", "steps", "cavity_*.vtu")))
    if not steps:
        print("openfoam: no cavity/steps in the export (--cavity-steps): contour4d's own motion not checked here")
        return
    case = os.path.join(work, "own")
    shutil.copytree(os.path.join(exportdir, "openfoam"), case)
    header = open(os.path.join(case, "constant", "polyMesh", "points")).read()
    header = header[:header.index("}") + 1] + "\n\n"
    for k, path in enumerate(steps[1:], start=1):
        r = vtk.vtkXMLUnstructuredGridReader()
        r.SetFileName(path)
        r.Update()
        p = vtk_to_numpy(r.GetOutput().GetPoints().GetData()) / unit_mm
        d = os.path.join(case, "%.12g" % rep["steps"][k]["t_s"], "polyMesh")
        os.makedirs(d)
        with open(os.path.join(d, "points"), "w") as f:
            f.write(header + "%d\n(\n" % len(p) + "".join("(%.17g %.17g %.17g)\n" % tuple(v) for v in p) + ")\n")
    log = foam(["checkMesh", "-time", "0:1e9"], case, os.path.join(work, "checkMesh-own.log"))
    ok = log.count("Mesh OK.")
    negative = len(re.findall(r"negative", log, re.I))
    assert ok == len(steps) and negative == 0, (
        f"contour4d's moving cavity in checkMesh: {ok} of {len(steps)} times OK, {negative} negative:\n" + log[-3000:])
    print(f"openfoam: contour4d's own moving cavity as {len(steps)} time directories: checkMesh OK at every time, "
          "no negative volume")


def main():
    outdir, exportdir = sys.argv[1], sys.argv[2]
    tol = float(sys.argv[3]) if len(sys.argv) > 3 else 1e-6
    if not (shutil.which("moveDynamicMesh") and shutil.which("checkMesh") and os.path.isdir(FOAM_DIR)):
        print("SKIP: OpenFOAM (Debian package openfoam) is not installed: checkMesh/moveDynamicMesh not found")
        sys.exit(77)
    rep = export_report(exportdir)
    unit_mm = {"m": 1000.0, "cm": 10.0, "mm": 1.0}.get(rep["units"]["lengths_written"], 1000.0)
    work = tempfile.mkdtemp(prefix="c4d-foam-")
    try:
        case = os.path.join(work, "case")
        shutil.copytree(os.path.join(exportdir, "openfoam"), case)
        cd = os.path.join(case, "system", "controlDict")
        text = open(cd).read()
        open(cd, "w").write(re.sub(r"writeInterval\s+\d+;", "writeInterval   1;", text))
        log = foam(["checkMesh"], case, os.path.join(work, "checkMesh.log"))
        assert "Mesh OK." in log, "checkMesh fails on the cavity:\n" + log[-3000:]
        cells = re.search(r"cells:\s+(\d+)", log).group(1)
        print(f"openfoam: checkMesh: Mesh OK ({cells} cells)")
        move = foam(["moveDynamicMesh"], case, os.path.join(work, "moveDynamicMesh.log"))
        times = time_dirs(case)
        expected = len(rep["steps"])
        assert len(times) == expected, f"moveDynamicMesh wrote {len(times)} times, the export has {expected}"
        # moveDynamicMesh checks the mesh after every step itself.
        per_step = [int(n) for n in re.findall(r"Number of negative volume cells: (\d+)", move)]
        print(f"openfoam: moveDynamicMesh (displacementLaplacian) through {expected} times ({times[-1][0]} s): "
              f"{len(per_step)} times with negative-volume cells, at most {max(per_step, default=0)} cells")
        foam_motion_ok = not per_step
        # The moved wall against the export's boundaryData and against the frames.
        frames = read_frames(outdir)
        nverts = frames.shape[1]
        wall = wall_only_vertices(exportdir, nverts)
        bd = os.path.join(case, "constant", "boundaryData")
        x0 = read_vectors(os.path.join(case, "constant", "polyMesh", "points"))[:nverts] * unit_mm
        idx = {tuple(v): i for i, v in enumerate(np.round(x0, 9))}
        patches = []
        for p in sorted(os.listdir(bd)):
            bp = read_vectors(os.path.join(bd, p, "points")) * unit_mm
            ids = np.array([idx[tuple(v)] for v in np.round(bp, 9)])  # the surface vertices at those coordinates
            tdirs = {float(d): d for d in os.listdir(os.path.join(bd, p)) if d != "points"}
            patches.append((p, bp, ids, tdirs))
        worst_bd, worst_frames = 0.0, 0.0
        for k, (t, name) in enumerate(times):
            x = (read_vectors(os.path.join(case, name, "polyMesh", "points"))[:nverts] * unit_mm) if k > 0 else x0
            ref = catmull_rom(frames, rep["frames"]["times_ms"], rep["steps"][k]["t_s"])
            worst_frames = max(worst_frames, float(np.abs(x[wall] - ref[wall]).max()))
            for p, bp, ids, tdirs in patches:
                d = read_vectors(os.path.join(bd, p, tdirs[min(tdirs, key=lambda s: abs(s - t))], "pointDisplacement"))
                worst_bd = max(worst_bd, float(np.abs(x[ids] - (bp + d * unit_mm)).max()))
        print(f"openfoam: moved surface vs the export's boundaryData: max {worst_bd:.3g} mm; wall vertices vs own "
              f"Catmull-Rom of OUTDIR: max {worst_frames:.3g} mm")
        assert worst_bd <= tol and worst_frames <= tol, "the moved wall is off"
        check_own_motion(exportdir, work, unit_mm, rep)
        if not foam_motion_ok:
            print("FOAM-MOTION-INVERTS: OpenFOAM's own displacementLaplacian inverted cells (see above)")
            sys.exit(3)
        print("OK")
    finally:
        shutil.rmtree(work, ignore_errors=True)


if __name__ == "__main__":
    main()
