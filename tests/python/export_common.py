# SPDX-License-Identifier: GPL-3.0-or-later
"""Shared helpers of the `contour4d export` checks: an independent reading of a reconstruction folder and an
independent periodic Catmull-Rom of its frames (written from the formula, not from contour4d's code)."""
import json
import os
import xml.etree.ElementTree as ET

import numpy as np
import vtk
from vtk.util.numpy_support import vtk_to_numpy


def read_vtp_points(path):
    r = vtk.vtkXMLPolyDataReader()
    r.SetFileName(path)
    r.Update()
    return vtk_to_numpy(r.GetOutput().GetPoints().GetData()).astype(float)


def read_frames(outdir):
    """The frames of a reconstruction folder (mesh.pvd): positions (mm) per frame."""
    root = ET.parse(os.path.join(outdir, "mesh.pvd")).getroot()
    files = [d.get("file") for d in root.iter("DataSet")]
    return np.array([read_vtp_points(os.path.join(outdir, f)) for f in files])


def catmull_rom(frames, times_ms, t_s):
    """Uniform periodic Catmull-Rom through the frames at t_s seconds after frame 0 (period: span + mean step)."""
    times = np.asarray(times_ms, float)
    n = len(times)
    period = (times[-1] - times[0]) * n / (n - 1)
    t = times[0] + (1000.0 * t_s - 0.0) % period
    if t >= times[-1]:
        i0, i1 = n - 1, 0
        u = (t - times[-1]) / (times[0] + period - times[-1])
    else:
        i1 = int(np.searchsorted(times, t, side="right"))
        i0 = i1 - 1
        u = (t - times[i0]) / (times[i1] - times[i0])
    if u == 0.0:
        return frames[i0]
    a, d = (i0 - 1) % n, (i1 + 1) % n
    w = [0.5 * (-u**3 + 2 * u**2 - u), 0.5 * (3 * u**3 - 5 * u**2 + 2), 0.5 * (-3 * u**3 + 4 * u**2 + u),
         0.5 * (u**3 - u**2)]
    return w[0] * frames[a] + w[1] * frames[i0] + w[2] * frames[i1] + w[3] * frames[d]


def export_report(exportdir):
    with open(os.path.join(exportdir, "export.json")) as f:
        return json.load(f)


def face_ids(exportdir):
    """Per surface triangle its face id (0 wall) and the surface triangles, from cavity/surface.vtp."""
    r = vtk.vtkXMLPolyDataReader()
    r.SetFileName(os.path.join(exportdir, "cavity", "surface.vtp"))
    r.Update()
    pd = r.GetOutput()
    faces = vtk_to_numpy(pd.GetCellData().GetArray("FaceID"))
    conn = vtk_to_numpy(pd.GetPolys().GetConnectivityArray()).reshape(-1, 3)
    return faces, conn


def wall_only_vertices(exportdir, nverts):
    """Vertices on no opened end and off its band (export.json's ends[].band_vertices: the wall that takes up the
    border's move onto the plane): their positions are the reconstruction's, untouched by the flattening."""
    faces, conn = face_ids(exportdir)
    on_end = np.zeros(nverts, bool)
    on_end[conn[faces > 0].ravel()] = True
    with open(os.path.join(exportdir, "export.json")) as f:
        for end in json.load(f)["ends"]:
            on_end[np.asarray(end.get("band_vertices", []), dtype=int)] = True
    return np.where(~on_end)[0]
