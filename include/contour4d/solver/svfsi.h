#pragma once
//! \file svfsi.h
//! \brief The hand-off to svFSI / svMultiPhysics: a SimVascular mesh-complete folder, a prescribed displacement
//! file per face and a minimal solver.xml that uses them (docs/export.md, "svFSI").
//!
//! FOLDER/mesh-complete/mesh-complete.mesh.vtu        tets, GlobalNodeID (points, 1-based), GlobalElementID,
//!                                                     ModelRegionID (cells)
//! FOLDER/mesh-complete/mesh-complete.exterior.vtp    every boundary triangle: GlobalNodeID, GlobalElementID
//!                                                     (the tet it bounds), ModelFaceID (1 wall, 2… the ends)
//! FOLDER/mesh-complete/walls_combined.vtp            the wall alone, same arrays
//! FOLDER/mesh-complete/mesh-surfaces/NAME.vtp        each face (wall, base, …), same arrays
//! FOLDER/NAME_displacement.dat                       the face's displacement from t = 0 at every output time
//! FOLDER/solver.xml                                  fluid (ALE: FSI equation, fluid domain only) + mesh motion

#include <string>

#include "contour4d/io/output_dir.h"
#include "contour4d/solver/handoff.h"

namespace c4d {

//! Writes the svFSI folder of `h` into `out`/`folder`; lengths in `length_scale` units of mm, times in s.
void write_svfsi(const OutputDir& out, const std::string& folder, const Handoff& h, double length_scale = 0.001);

//! The displacement file of the vertices `vertices` (sorted surface vertex ids; their global ids are id + 1) in
//! svFSI's "temporal and spatial values" layout: "3 T N", then the T times (s) one per line, then per vertex its
//! global id on a line and T lines of "dx dy dz" (displacement from t = 0), written to `path` as it is made.
//! \throw IoError (OutputNotWritable).
void write_svfsi_displacement(const std::filesystem::path& path, const Handoff& h,
                              const std::vector<std::uint32_t>& vertices, double length_scale);

}  // namespace c4d
