#pragma once
//! \file export_run.h
//! \brief The export run behind `contour4d export`: a reconstruction's output folder to the inputs of flow
//! solvers (svFSI / svMultiPhysics, OpenFOAM, VaMPy / OasisMove), docs/export.md.
//!
//! Reading and every check come first (load_export_input), then the work (export_run: faces, time steps,
//! cavity mesh and its motion, all checked), then the writing (write_export), so a bad input or a cavity that
//! would fold writes nothing.

#include <filesystem>
#include <string>
#include <vector>

#include "contour4d/core/mesh.h"
#include "contour4d/io/output_dir.h"
#include "contour4d/solver/cavity_mesh.h"
#include "contour4d/solver/ends.h"
#include "contour4d/solver/handoff.h"
#include "contour4d/solver/time_steps.h"

namespace c4d {

//! What a user sets (the command line's names in brackets; defaults as there).
struct ExportRunOptions {
  std::vector<std::string> targets;  //!< [--to] "svfsi", "openfoam", "vampy" (several allowed)
  TimeStepOptions steps;             //!< [--steps, --dt, --cycles]
  double frame_ms = 0.0;             //!< [--frame-ms] time between frames when the folder's times are unknown
  double cycle_ms = 0.0;             //!< [--cycle-ms] the same as a cycle length (frame f at f × cycle / frames)
  std::string open = "base";         //!< [--open] ends made flat faces: base, apex, all, none or end numbers
  std::vector<std::string> names;    //!< [--names] names of the opened ends, in order (default: ends.h's)
  std::string units;                 //!< [--units] m, cm or mm for every target; "": each target's own (docs)
  CavityMeshOptions cavity;          //!< [--tet-quality, --max-tet-volume] the volume mesh
  int threads = 0;                   //!< [--threads] 0: all cores; the output does not depend on it
  bool cavity_steps = false;         //!< [--cavity-steps] also write the moving cavity at every step (.vtu, .pvd)
};

//! A checked output folder: the sequence with its real times and the stack normal.
struct ExportInput {
  std::filesystem::path folder;
  MeshSequence seq;          //!< frames with correspondence; times_ms the real times
  Vec3 normal;               //!< the slices' normal (report.json's stack_normal, refined on the mesh)
  std::string times_source;  //!< where the times come from: the report's source, "--frame-ms", "--cycle-ms"
};

//! Reads and checks OUTDIR (mesh.pvd and report.json written by `contour4d reconstruct`).
//! \throw IoError (FileNotFound, BadMesh); InvalidInput (BadMesh: frames without correspondence;
//! TooFewFrames: one frame; OpenSurface: holes in the surface; UnknownFrameTimes: no real times and neither
//! --frame-ms nor --cycle-ms; MissingCompanion: no report.json).
ExportInput load_export_input(const std::filesystem::path& folder, const ExportRunOptions& options);

//! The ends of the input's frame 0 (for listing them).
std::vector<SurfaceEnd> export_ends(const ExportInput& input);

//! Everything to write, checked.
struct ExportRun {
  std::vector<SurfaceEnd> ends;  //!< every end found
  std::vector<int> opened;       //!< the ends made faces
  Handoff handoff;
  std::vector<double> surface_volume_mm3;  //!< the exported surface's volume at every output time
  double max_volume_difference = 0.0;      //!< max |cavity − surface| / surface over the output times
  std::string report;                      //!< export.json
};

//! Opens the chosen ends, cuts the cycle into steps, meshes the cavity and moves it. Nothing is written.
//! \throw InvalidInput (Usage: options; InvertedElement: a flat face folds); SolverError (VolumeMeshFailed,
//! InvertedElement: the wall folds back on itself at a key frame or output time, or the moving cavity folds at
//! some time with both extensions).
ExportRun export_run(const ExportInput& input, const ExportRunOptions& options);

//! Writes each target into `out`/<target>/, the frame-0 cavity into `out`/cavity/ and export.json.
void write_export(const OutputDir& out, const ExportRun& run, const ExportRunOptions& options);

}  // namespace c4d
