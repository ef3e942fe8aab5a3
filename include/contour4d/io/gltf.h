#pragma once
//! \file gltf.h
//! \brief glTF 2.0 binary export (model.glb) of a 4D mesh: the frame-0 mesh, one morph target per
//! frame (displacement from frame 0) and a weights animation over the frame times.
//!
//! Units and axes as glTF requires: metres (mm × 0.001), Y up. Patient LPS maps to glTF by the
//! rotation (x, y, z)_glTF = (L, S, −P) = (x_LPS, z_LPS, −y_LPS): superior is up, anterior faces the
//! viewer (+Z), the patient's left is +X. By default a plain file every glTF reader loads (ParaView's
//! vtkGLTFReader, Blender, three.js): float positions and normals, and per frame float position and
//! normal displacements. GltfOptions::quantized writes the compact variant instead: KHR_mesh_quantization
//! (uint16 base, int16 morph targets, no normals) with the dequantisation in the node's scale and
//! translation, for readers that support the extension.

#include <filesystem>
#include <string>

#include "contour4d/core/mesh.h"

namespace c4d {

//! Options of write_gltf.
struct GltfOptions {
  bool step = false;               //!< STEP animation (hold each frame) instead of LINEAR
  bool lps_to_y_up = true;         //!< rotate patient LPS to glTF's Y-up (false: keep the axes)
  bool quantized = false;          //!< KHR_mesh_quantization: about a third of the size, fewer readers, no normals
  std::string name = "contour4d";  //!< mesh and node name
};

//! The bytes of a .glb file. \throw InvalidInput (BadMesh) on an empty or inconsistent sequence.
std::string gltf_glb_bytes(const MeshSequence& seq, const GltfOptions& options = {});

//! Writes a .glb file atomically. \throw InvalidInput (BadMesh), IoError (OutputNotWritable).
void write_gltf(const std::filesystem::path& path, const MeshSequence& seq, const GltfOptions& options = {});

}  // namespace c4d
