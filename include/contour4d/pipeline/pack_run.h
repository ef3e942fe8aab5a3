#pragma once
//! \file pack_run.h
//! \brief The packing run behind `contour4d pack` / `unpack` and the Python module: a mesh sequence to
//! model.c4d bytes (and the glTF beside it), and back, with the optional resampling in time.

#include <cstddef>
#include <string>

#include "contour4d/core/mesh.h"
#include "contour4d/temporal/compact.h"

namespace c4d {

//! What a user sets for packing (the command line's names in brackets; defaults as there).
struct PackRunOptions {
  double tolerance = 0.05;             //!< [--tolerance] max error of any vertex in any frame (mm)
  double normal_p99 = 1.5;             //!< [--normal-p99] bound on the facet-normal error, worst frame's p99 (deg)
  double step = 0.0125;                //!< [--step] coarsest grid step tried (mm)
  std::size_t resample = 0;            //!< [--resample] frames after resampling in time; 0: keep
  std::string interp = "catmull-rom";  //!< [--interp] "catmull-rom" (periodic), "linear" or "step"
  bool gltf = true;                    //!< [--no-gltf] also make the .glb
  bool gltf_step = false;              //!< [--gltf-step] STEP animation in the .glb instead of LINEAR
  bool gltf_quantized = false;         //!< [--gltf-quantized] KHR_mesh_quantization .glb (smaller; fewer readers)
};

//! What packing gives: the file contents and the figures the command line prints.
struct PackRun {
  MeshSequence input;  //!< the sequence packed (after resampling)
  CompactModel model;
  CompactStats stats;
  std::string c4d;                 //!< model.c4d's bytes (zstd-compressed)
  std::size_t raw_payload = 0;     //!< the payload before compression (bytes)
  std::size_t stored_payload = 0;  //!< the payload as stored (bytes)
  std::string glb;                 //!< model.glb's bytes; empty unless PackRunOptions::gltf
};

//! `seq` resampled to `frames` frames with `interp` ("catmull-rom", "linear" or "step"); 0: unchanged.
MeshSequence resample_if(MeshSequence seq, std::size_t frames, const std::string& interp);

//! Encodes `seq` (resampled first when asked). Nothing is written.
//! \throw InvalidInput (BadMesh) as compact_encode does.
PackRun pack_run(const MeshSequence& seq, const PackRunOptions& options = {});

}  // namespace c4d
