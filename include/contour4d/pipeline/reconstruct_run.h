#pragma once
//! \file reconstruct_run.h
//! \brief The end-to-end reconstruction run behind `contour4d reconstruct` and the Python module: the
//! options a user sets, the reconstruction of one frame or all, the checks of every frame, the report.
//!
//! Reading the input and writing the outputs stay with the caller, so the command line can check the
//! destination before the work and a script can keep the result in memory.

#include <functional>
#include <string>

#include "contour4d/core/mesh.h"
#include "contour4d/pipeline/input.h"
#include "contour4d/io/mesh_output.h"
#include "contour4d/io/output_dir.h"
#include "contour4d/metrics/result_check.h"
#include "contour4d/motion/reconstruct4d.h"

namespace c4d {

//! What a user sets for one reconstruction (the command line's names in brackets; defaults as there).
struct ReconstructRunOptions {
  int frame = -1;                       //!< [--frame] reconstruct this frame only; -1: every frame
  std::string label;                    //!< [--label] the structure (contour inputs; label images select on reading)
  double edge = SurfaceOptions{}.edge;  //!< [--edge] target edge length (mm)
  std::string cap = "rounded";          //!< [--cap] end caps: "rounded", "flat" or "open"
  std::string method =
      "auto";             //!< [--method] all frames: "auto", "rebuild", "rbf-project", "carry" or "rbf" (the paper's)
  int threads = 0;        //!< [--threads] worker threads, 0: all cores; the output does not depend on it
  bool vertical = false;  //!< [--vertical-deformation] Lim et al.'s vertical deformation
  std::string tiling = "bands";                                     //!< [--tiling] "bands" or "delaunay" (Lim et al.'s)
  double volume_tolerance = ResultCheckOptions{}.volume_tolerance;  //!< [--volume-tolerance] output check
};

//! What a run gives: the meshes, the checks of every frame and the report (report.json's text).
struct ReconstructRun {
  MeshSequence result;  //!< every frame (one for ReconstructRunOptions::frame), the same triangles
  ResultCheck check;    //!< the checks of every frame; the caller writes nothing when !check.ok()
  std::string report;   //!< report.json (2-space indented JSON, ending in a newline)
  std::string input;    //!< the input's name, for messages
};

//! Called with the stage, the work done and the total (frames), for progress bars.
using ProgressFn = std::function<void(const char* stage, int done, int total)>;

//! Called with a line for the user (the all-frames fallback, topology events, sub-meshes).
using RunMessage = std::function<void(const std::string& line)>;

//! Reconstructs `read` (one frame or all) as `contour4d reconstruct` does: the default all-frames morph,
//! and where it fails its checks every frame carried from frame 0 instead (kept when valid). Every frame
//! is checked; the report holds the options, repairs, frame times, per-frame figures, checks and, when
//! every frame passed, the volumes and EDV/ESV/EF. Nothing is written.
//! \throw InvalidInput (ErrorCode::Usage) for a frame out of range; the errors of reconstruct_4d.
ReconstructRun reconstruct_run(const InputResult& read, const std::string& input_name,
                               const ReconstructRunOptions& options, const ProgressFn& progress = {},
                               const RunMessage& say = {});

//! \throw SolverError (ErrorCode::InvalidResult) naming the first failing frame when !run.check.ok(), with `hint`.
void throw_if_failed(const ReconstructRun& run, const std::string& hint);

//! Writes a valid run into `out` (mesh.pvd, frames/ in `formats`, report.json) and commits it.
//! \throw SolverError (ErrorCode::InvalidResult) naming the first failing frame when !run.check.ok():
//! nothing is written then; with a non-empty `keep_failed` the failed result goes there, marked FAILED.
void write_run(OutputDir& out, const ReconstructRun& run, const MeshFormats& formats = {},
               const std::string& keep_failed = {});

}  // namespace c4d
