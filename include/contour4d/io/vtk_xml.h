#pragma once
//! \file vtk_xml.h
//! \brief VTK XML PolyData (.vtp, raw binary appended data) and ParaView collections (.pvd),
//! written without VTK and read back by VTK's own readers (tests use python3-vtk9).

#include <filesystem>
#include <string>
#include <vector>

#include "contour4d/core/mesh.h"

namespace c4d {

//! A .vtp file's content for `mesh`: Float64 points (mm), Int64 connectivity and offsets, little
//! endian, UInt64 headers, no compression. Deterministic: the same mesh gives the same bytes.
std::string format_vtp(const TriangleMesh& mesh);

//! Parses a .vtp written by format_vtp (appended raw or ascii DataArrays of triangles).
//! \throw IoError (BadMesh) naming `source` and what is wrong.
TriangleMesh parse_vtp(const std::string& content, const std::string& source);

//! One entry of a .pvd collection.
struct PvdEntry {
  double time_ms = 0.0;  //!< timestep attribute (ms)
  std::string file;      //!< path relative to the .pvd
};

//! A .pvd collection listing one dataset per timestep.
std::string format_pvd(const std::vector<PvdEntry>& entries);

//! Parses a .pvd's DataSet entries. \throw IoError (BadMesh).
std::vector<PvdEntry> parse_pvd(const std::string& content, const std::string& source);

}  // namespace c4d
