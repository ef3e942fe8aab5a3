#pragma once
//! \file openfoam.h
//! \brief The hand-off to OpenFOAM: the cavity as a polyMesh with one patch per face, the prescribed point
//! displacement of every patch as boundaryData for a timeVaryingMappedFixedValue condition, and a case that
//! moves the mesh with a displacement-Laplacian motion solver (docs/export.md, "OpenFOAM").
//!
//! FOLDER/constant/polyMesh/{points,faces,owner,neighbour,boundary}   ASCII, tets as 4 triangular faces
//! FOLDER/constant/boundaryData/PATCH/points                         the patch's points at t = 0
//! FOLDER/constant/boundaryData/PATCH/TIME/pointDisplacement         their displacement at each output time
//! FOLDER/constant/{dynamicMeshDict,transportProperties,turbulenceProperties}
//! FOLDER/system/{controlDict,fvSchemes,fvSolution}                  pimpleFoam, one step per output time
//! FOLDER/0/{pointDisplacement,U,p}

#include <string>

#include "contour4d/io/output_dir.h"
#include "contour4d/solver/handoff.h"

namespace c4d {

//! Writes the OpenFOAM case of `h` into `out`/`folder`; lengths in `length_scale` units of mm (metres: 0.001),
//! times in s.
void write_openfoam(const OutputDir& out, const std::string& folder, const Handoff& h, double length_scale = 0.001);

}  // namespace c4d
