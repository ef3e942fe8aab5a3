#pragma once
//! \file mesh_output.h
//! \brief The output folder layout of a 4D mesh:
//!   OUTDIR/mesh.pvd                 ParaView time collection (timestep = time in ms)
//!   OUTDIR/frames/frame_000.vtp     VTK XML PolyData per frame
//!   OUTDIR/frames/frame_000.obj     the same mesh as OBJ (MeshFormats::obj; --format vtp,obj)
//!   OUTDIR/report.json              machine report (written by the caller)

#include <filesystem>
#include <string>
#include <vector>

#include "contour4d/core/mesh.h"
#include "contour4d/io/output_dir.h"

namespace c4d {

//! Per-frame meshes with their times; frames may differ in connectivity (e.g. phantom truth).
struct MeshFrames {
  std::vector<TriangleMesh> meshes;
  std::vector<double> times_ms;
};

//! The per-frame mesh files written besides VTP + mesh.pvd (always written: ParaView's time series).
struct MeshFormats {
  bool obj = false;  //!< frames/frame_NNN.obj too (MeshLab, Blender)
};

//! Parses a --format list such as "vtp", "vtp,obj" or "obj" (VTP is always written).
//! \throw InvalidInput (Usage) naming an unknown format.
MeshFormats parse_mesh_formats(const std::string& list);

//! Writes mesh.pvd and frames/ into a staged output folder. `comment` goes into each OBJ header.
void write_mesh_frames(const OutputDir& out, const MeshFrames& frames, const std::string& comment = {},
                       const MeshFormats& formats = {});

//! Same for a mesh sequence with correspondence.
void write_mesh_sequence(const OutputDir& out, const MeshSequence& seq, const std::string& comment = {},
                         const MeshFormats& formats = {});

//! Reads an output folder: mesh.pvd when present, else frames/frame_*.vtp, else frames/frame_*.obj,
//! in frame order. \throw IoError (FileNotFound, BadMesh) naming the file.
MeshFrames read_mesh_frames(const std::filesystem::path& dir);

}  // namespace c4d
