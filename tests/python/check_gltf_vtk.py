#!/usr/bin/python3
"""Loads a model.glb with python3-vtk9's vtkGLTFReader (ParaView's glTF reader) and checks every frame.

usage: check_gltf_vtk.py MODEL.glb FRAMES POINTS   (POINTS -1: frame 0's count, the same in every frame)
Each animation time step (one per frame) must load with all POINTS points, normals included, and the
frames must differ (the morph targets are applied). Exits non-zero with a message otherwise.
"""
import json
import struct
import sys

try:
    from vtkmodules.vtkIOGeometry import vtkGLTFReader
    from vtkmodules.vtkCommonDataModel import vtkDataObject
    from vtkmodules.vtkCommonExecutionModel import vtkStreamingDemandDrivenPipeline
except ImportError as e:
    sys.exit(f"python3-vtk9 is missing ({e}): run scripts/setup.sh")
try:
    from vtkmodules.util.numpy_support import vtk_to_numpy
except ImportError as e:
    sys.exit(f"numpy support of python3-vtk9 is missing ({e})")

path, frames, points = sys.argv[1], int(sys.argv[2]), int(sys.argv[3])


def key_times(glb):
    """The first animation's key times (s), read from the file itself (JSON and BIN chunks)."""
    with open(glb, "rb") as f:
        data = f.read()
    (json_len,) = struct.unpack_from("<I", data, 12)
    doc = json.loads(data[20:20 + json_len])
    binary = data[20 + json_len + 8:]
    accessor = doc["accessors"][doc["animations"][0]["samplers"][0]["input"]]
    view = doc["bufferViews"][accessor["bufferView"]]
    start = view.get("byteOffset", 0) + accessor.get("byteOffset", 0)
    return list(struct.unpack_from(f"<{accessor['count']}f", binary, start))


keys = key_times(path)
if len(keys) != frames:
    sys.exit(f"{path}: {len(keys)} key times, expected {frames}")
reader = vtkGLTFReader()
reader.SetFileName(path)
reader.UpdateInformation()
if reader.GetNumberOfAnimations() < 1:
    sys.exit(f"{path}: vtkGLTFReader finds no animation")
reader.EnableAnimation(0)
reader.UpdateInformation()
info = reader.GetOutputInformation(0)
key = vtkStreamingDemandDrivenPipeline.TIME_STEPS()
times = [info.Get(key, i) for i in range(info.Length(key))] if info.Has(key) else []
if not times:
    sys.exit(f"{path}: vtkGLTFReader offers no time steps")


def first_polydata(obj):
    """The first leaf of the reader's multiblock output."""
    it = obj.NewIterator()
    it.InitTraversal()
    while not it.IsDoneWithTraversal():
        leaf = it.GetCurrentDataObject()
        if leaf is not None and leaf.GetNumberOfPoints() > 0:
            return leaf
        it.GoToNextItem()
    return None


shapes = []
for t in keys:  # the reader applies the animation at the time asked for
    reader.UpdateTimeStep(t)
    mesh = first_polydata(reader.GetOutput())
    if mesh is None:
        sys.exit(f"{path}: time {t}: no points loaded")
    if points < 0:
        points = mesh.GetNumberOfPoints()
    if mesh.GetNumberOfPoints() != points:
        sys.exit(f"{path}: time {t}: {mesh.GetNumberOfPoints()} points, expected {points}")
    if mesh.GetPointData().GetNormals() is None:
        sys.exit(f"{path}: time {t}: no normals")
    shapes.append(vtk_to_numpy(mesh.GetPoints().GetData()).copy())
moved = max(float(abs(s - shapes[0]).max()) for s in shapes)
if frames > 1 and not moved > 0:
    sys.exit(f"{path}: every time step has frame 0's points: the morph targets were not applied")
print(f"check_gltf_vtk: {path}: {frames} frames at their key times, {points} points each, "
      f"largest move {moved * 1000:.2f} mm")
