#pragma once
//! \file sequence.h
//! \brief Getting a MeshSequence for the compact model and playback: from an output folder, from a
//! model.c4d, or a synthetic beating shape for tests and benchmarks.

#include <cstddef>
#include <filesystem>

#include "contour4d/core/mesh.h"
#include "contour4d/io/mesh_output.h"

namespace c4d {

//! A sequence from per-frame meshes that share one triangle list.
//! \throw InvalidInput (BadMesh) naming the first frame whose vertex count or triangles differ.
MeshSequence to_mesh_sequence(const MeshFrames& frames, const std::string& source = {});

//! Reads an output folder (OUTDIR with mesh.pvd or frames/) or a model.c4d file.
//! \throw IoError / InvalidInput as read_mesh_frames, read_model_c4d and to_mesh_sequence.
MeshSequence load_mesh_sequence(const std::filesystem::path& path);

//! A cardiac-like synthetic 4D mesh: an ellipsoid (semi-axes 30, 30, 45 mm, icosphere subdivided
//! `subdivisions` times: 20·4^s triangles) that pulsates with a cardiac volume curve (ejection then
//! filling), twists about its long axis and sways, over `frames` frames of a 1000 ms cycle.
MeshSequence synthetic_beating_mesh(int subdivisions, std::size_t frames = 20);

}  // namespace c4d
