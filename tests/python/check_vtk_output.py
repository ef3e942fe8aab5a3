#!/usr/bin/python3
"""Loads an output folder with python3-vtk9's own readers (a real VTK client).

usage: check_vtk_output.py OUTDIR FRAMES POINTS TRIANGLES  (POINTS/TRIANGLES of frame 0; -1 = any)
The .pvd collection is parsed with VTK's XML parser (vtkXMLDataParser, as ParaView's PVD reader does;
python3-vtk9 ships no PVD reader) and every DataSet it lists is loaded with vtkXMLPolyDataReader.
Exits non-zero with a message when VTK cannot read the files or the counts differ.
"""
import os
import sys

try:
    from vtkmodules.vtkIOXML import vtkXMLPolyDataReader
    from vtkmodules.vtkIOXMLParser import vtkXMLDataParser
except ImportError as e:
    sys.exit(f"python3-vtk9 is missing ({e}): run scripts/setup.sh")

outdir, frames, points, tris = sys.argv[1], int(sys.argv[2]), int(sys.argv[3]), int(sys.argv[4])
pvd = os.path.join(outdir, "mesh.pvd")
parser = vtkXMLDataParser()
parser.SetFileName(pvd)
if not parser.Parse():
    sys.exit(f"{pvd}: VTK's XML parser rejects the file")
root = parser.GetRootElement()
if root.GetName() != "VTKFile" or root.GetAttribute("type") != "Collection":
    sys.exit(f"{pvd}: not a VTKFile of type Collection")
collection = root.FindNestedElementWithName("Collection")
datasets = [collection.GetNestedElement(i) for i in range(collection.GetNumberOfNestedElements())]
datasets = [d for d in datasets if d.GetName() == "DataSet"]
if len(datasets) != frames:
    sys.exit(f"{pvd}: {len(datasets)} DataSets, expected {frames}")
times = []
for f, d in enumerate(datasets):
    times.append(float(d.GetAttribute("timestep")))
    path = os.path.join(outdir, d.GetAttribute("file"))
    r = vtkXMLPolyDataReader()
    r.SetFileName(path)
    r.Update()
    if r.GetErrorCode() != 0:
        sys.exit(f"{path}: VTK reader error {r.GetErrorCode()}")
    pd = r.GetOutput()
    if f == 0 and points >= 0 and pd.GetNumberOfPoints() != points:
        sys.exit(f"{path}: {pd.GetNumberOfPoints()} points, expected {points}")
    if f == 0 and tris >= 0 and pd.GetNumberOfPolys() != tris:
        sys.exit(f"{path}: {pd.GetNumberOfPolys()} triangles, expected {tris}")
    if pd.GetNumberOfPolys() == 0:
        sys.exit(f"{path}: no triangles read")
if times != sorted(times):
    sys.exit(f"{pvd}: timesteps not increasing: {times}")
print(f"python3-vtk9 read {frames} frames; times {times}")
