#!/usr/bin/python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Checks an svFSI export of `contour4d export` with readers of its own (python3-vtk9, python3-meshio, numpy).

usage: check_export_svfsi.py OUTDIR EXPORTDIR [TOL_MM]

- mesh-complete.mesh.vtu loads in VTK and in meshio (the same points, tets and ids), every .vtp in VTK (meshio 5.0
  has no PolyData reader); GlobalNodeID is 1..N and GlobalElementID 1..M
  in the volume; every face's GlobalNodeID names volume nodes at the same coordinates, and each face triangle is
  a face of the tet its GlobalElementID names.
- Every NAME_displacement.dat, read here from svFSI's layout and added to frame 0's coordinates of its nodes,
  reproduces at every time the wall that this script interpolates itself (periodic Catmull-Rom of OUTDIR's
  frames at export.json's frame times) within TOL_MM (default 1e-6 mm) on the vertices of no opened end, and
  the VaMPy surfaces when the export has them on every vertex; an opened end stays flat at every time.
"""
import glob
import os
import sys

import meshio
import numpy as np
import vtk
from vtk.util.numpy_support import vtk_to_numpy

from export_common import catmull_rom, export_report, read_frames, wall_only_vertices, read_vtp_points


def vtk_read(path):
    r = vtk.vtkXMLUnstructuredGridReader() if path.endswith(".vtu") else vtk.vtkXMLPolyDataReader()
    r.SetFileName(path)
    r.Update()
    return r.GetOutput()


def read_displacement(path):
    """svFSI's temporal and spatial values file: 'ndof nt nnodes', nt times, then per node: id, nt rows."""
    tokens = open(path).read().split()
    ndof, nt, nn = int(tokens[0]), int(tokens[1]), int(tokens[2])
    pos = 3
    times = np.array([float(x) for x in tokens[pos:pos + nt]])
    pos += nt
    ids, values = [], []
    for _ in range(nn):
        ids.append(int(tokens[pos]))
        pos += 1
        values.append(np.array([float(x) for x in tokens[pos:pos + nt * ndof]]).reshape(nt, ndof))
        pos += nt * ndof
    assert pos == len(tokens), f"{path}: {len(tokens) - pos} trailing values"
    return times, np.array(ids), np.array(values)  # values[node, time, dof]


def main():
    outdir, exportdir = sys.argv[1], sys.argv[2]
    tol = float(sys.argv[3]) if len(sys.argv) > 3 else 1e-6
    rep = export_report(exportdir)
    sv = os.path.join(exportdir, "svfsi")
    mc = os.path.join(sv, "mesh-complete")
    unit_mm = 1000.0  # svfsi lengths in metres unless --units says otherwise
    if rep["units"]["lengths_written"] in ("cm", "mm"):
        unit_mm = {"cm": 10.0, "mm": 1.0}[rep["units"]["lengths_written"]]

    vol = vtk_read(os.path.join(mc, "mesh-complete.mesh.vtu"))
    pts = vtk_to_numpy(vol.GetPoints().GetData())
    gid = vtk_to_numpy(vol.GetPointData().GetArray("GlobalNodeID"))
    eid = vtk_to_numpy(vol.GetCellData().GetArray("GlobalElementID"))
    assert (gid == np.arange(1, len(pts) + 1)).all(), "GlobalNodeID is not 1..N"
    assert (eid == np.arange(1, vol.GetNumberOfCells() + 1)).all(), "GlobalElementID is not 1..M"
    tets = vtk_to_numpy(vol.GetCells().GetConnectivityArray()).reshape(-1, 4)
    m = meshio.read(os.path.join(mc, "mesh-complete.mesh.vtu"))
    assert np.array_equal(m.points, pts) and np.array_equal(m.cells_dict["tetra"], tets), "meshio differs from VTK"
    assert np.array_equal(np.ravel(m.point_data["GlobalNodeID"]), gid), "meshio GlobalNodeID differs"
    tet_faces = {}
    for t, q in enumerate(tets):
        for k in range(4):
            tet_faces[tuple(sorted(np.delete(q, k)))] = t + 1
    # Every .vtp: ids match the volume.
    vtps = sorted(glob.glob(os.path.join(mc, "mesh-surfaces", "*.vtp"))) + [
        os.path.join(mc, "mesh-complete.exterior.vtp"), os.path.join(mc, "walls_combined.vtp")]
    for path in vtps:
        pd = vtk_read(path)
        fp = vtk_to_numpy(pd.GetPoints().GetData())
        fid = vtk_to_numpy(pd.GetPointData().GetArray("GlobalNodeID"))
        feid = vtk_to_numpy(pd.GetCellData().GetArray("GlobalElementID"))
        tris = vtk_to_numpy(pd.GetPolys().GetConnectivityArray()).reshape(-1, 3)
        assert np.array_equal(fp, pts[fid - 1]), f"{path}: GlobalNodeID points differ from the volume's"
        for tri, e in zip(tris, feid):
            assert tet_faces.get(tuple(sorted(fid[tri] - 1))) == e, f"{path}: a triangle is not a face of its element"
    # meshio 5.0 (Debian 12) has no PolyData (.vtp) reader: the .vtp files are read by VTK only.
    print(f"svfsi: {len(pts)} nodes, {len(tets)} tets (VTK and meshio agree), {len(vtps)} surface .vtp files "
          "(VTK; meshio 5.0 reads no .vtp): ids consistent")

    frames = read_frames(outdir)
    times_ms = rep["frames"]["times_ms"]
    nverts = frames.shape[1]
    wall = set(wall_only_vertices(exportdir, nverts).tolist())
    vampy = sorted(glob.glob(os.path.join(exportdir, "vampy", "model_moved_*.vtp")))
    worst_wall, worst_vampy, worst_flat, count = 0.0, 0.0, 0.0, 0
    for path in sorted(glob.glob(os.path.join(sv, "*_displacement.dat"))):
        name = os.path.basename(path)[:-len("_displacement.dat")]
        times, ids, disp = read_displacement(path)
        assert times[0] == 0.0 and np.all(np.diff(times) > 0), f"{path}: times do not start at 0 and increase"
        x0 = pts[ids - 1] * unit_mm
        keep = np.array([i - 1 in wall for i in ids])
        for k, t in enumerate(times):
            x = x0 + disp[:, k, :] * unit_mm
            ref = catmull_rom(frames, times_ms, t)[ids - 1]
            if keep.any():
                worst_wall = max(worst_wall, float(np.abs(x[keep] - ref[keep]).max()))
            if name != "wall":  # an opened end: flat at every time
                c = x - x.mean(axis=0)
                worst_flat = max(worst_flat, float(np.linalg.svd(c, compute_uv=False)[-1] / np.sqrt(len(c))))
            if vampy:
                vp = read_vtp_points(vampy[k])
                if k == 0 and name == "wall":
                    # vampy's model.vtp holds the wall's vertices in increasing id order.
                    assert len(vp) == len(ids)
                if name == "wall":
                    worst_vampy = max(worst_vampy, float(np.abs(vp - x).max()))
            count += 1
    print(f"svfsi displacement: {count} face-times; wall vertices vs own Catmull-Rom of OUTDIR: max {worst_wall:.3g} mm; "
          f"vs VaMPy surfaces: max {worst_vampy:.3g} mm; opened ends off their plane (RMS): max {worst_flat:.3g} mm")
    assert worst_wall <= tol, f"wall differs from the interpolated frames by {worst_wall} mm > {tol}"
    assert worst_vampy <= tol, f"svFSI and VaMPy walls differ by {worst_vampy} mm"
    assert worst_flat <= 1e-6, f"an opened end is not flat ({worst_flat} mm)"
    print("OK")


if __name__ == "__main__":
    main()
