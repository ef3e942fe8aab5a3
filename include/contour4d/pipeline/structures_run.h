#pragma once
//! \file structures_run.h
//! \brief Several structures reconstructed in one run (`reconstruct --label all`): each into OUTDIR/<name>/
//! with its own report, and one combined report with the volumes, EF and wall mass of every structure.

#include <string>
#include <vector>

#include "contour4d/pipeline/reconstruct_run.h"
#include "contour4d/pipeline/structures.h"

namespace c4d {

//! One structure's run: its result, or the error that stopped it.
struct StructureRun {
  Structure structure;
  ReconstructRun run;  //!< empty when `error_code` is set
  int error_code = 0;  //!< the exit code of the failure (26: failed its checks), 0 when valid
  std::string error;   //!< the failure's message
};

//! Reconstructs every structure with the same options (each frame's label is the structure's). A failing
//! structure is recorded, never stops the others.
std::vector<StructureRun> reconstruct_structures(std::vector<Structure> structures, const std::string& input_name,
                                                 const ReconstructRunOptions& options, const ProgressFn& progress = {},
                                                 const RunMessage& say = {});

//! The combined report.json: per structure its frames, volume curve, ED/ES frames, EDV/ESV/EF, the wall's
//! mass per frame (kMyocardiumDensity), and the failures.
std::string structures_report(const std::vector<StructureRun>& runs, const std::string& input_name,
                              const std::vector<std::string>& notes);

//! Writes each valid structure into OUTDIR/<name>/ (mesh.pvd, frames/, report.json), the combined report
//! into OUTDIR/report.json, and commits.
void write_structures(OutputDir& out, const std::vector<StructureRun>& runs, const MeshFormats& formats,
                      const std::string& report);

}  // namespace c4d
