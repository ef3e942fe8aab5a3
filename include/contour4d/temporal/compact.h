#pragma once
//! \file compact.h
//! \brief Compact 4D model (Miara et al. §III.D–E, Table I: one mesh stored once, per-frame
//! displacement data): the fine mesh of frame 0 and every frame's displacement, all on one fine grid,
//! so that the decoded meshes are the input meshes to a fraction of their edge length and their
//! shading matches (docs/compact.md gives the layout and the alternatives measured).
//!
//! Layout of the model:
//!  - the triangles (meshopt index codec) and frame 0's positions on a grid of `step` mm (meshopt
//!    vertex codec of int32 x,y,z,0), vertices and triangles reordered for locality;
//!  - per frame f >= 1, every vertex's move on that grid since frame f − 1, as its residual against the
//!    rounded mean move of its neighbours with smaller ids (which the decoder has already restored:
//!    neighbouring vertices move alike, so most residuals are a few grid steps), zigzag varints, all x,
//!    then all y, then all z.
//! Every decoded vertex is within step·√3/2 mm (Euclidean) of the same input vertex, in every frame. The
//! encoder measures the decoded facet normals against the input's and refines the grid until they meet
//! CompactOptions::normal_p99 (each refinement scales the step by the ratio of bound to measure).
//! The decoded positions are the GPU's data (render/renderer.h): frame 0 and the displacement of every
//! frame, uploaded once and blended per time in the vertex shader.

#include <cstdint>
#include <vector>

#include "contour4d/core/mesh.h"

namespace c4d {

//! Options of compact_encode.
struct CompactOptions {
  double tolerance = 0.05;  //!< bound on the distance of each decoded vertex to the same input vertex (mm)
  double normal_p99 = 1.5;  //!< bound on the worst frame's 99th percentile of the angle between decoded and
                            //!< input facet normals (degrees): what keeps the shading free of creases and cracks
  double step = 0.0125;     //!< the coarsest grid step tried (mm); a finer one is used where the tolerance
                            //!< (step·√3/2 <= tolerance) or the normal bound needs it (small triangles)
  bool reorder = true;      //!< reorder vertices and triangles for compression (permutes ids)
};

//! A compact 4D model: plain data, the payload of model.c4d (temporal/model_c4d.h). Positions in the input
//! space (mm, LPS for DICOM data).
struct CompactModel {
  std::uint32_t vertex_count = 0;
  std::uint32_t triangle_count = 0;
  std::uint32_t frame_count = 0;
  std::vector<double> times_ms;                   //!< time of each frame (ms)
  double origin[3] = {0, 0, 0};                   //!< grid origin (mm): the corner below every frame
  double step = 0.0;                              //!< grid step (mm)
  double tolerance = 0.0;                         //!< the bound the encoder guaranteed (mm)
  std::vector<std::uint8_t> indices;              //!< meshopt_encodeIndexBuffer of the triangles
  std::vector<std::uint8_t> positions;            //!< meshopt_encodeVertexBuffer of int32 x,y,z,0 (grid units)
  std::vector<std::vector<std::uint8_t>> motion;  //!< per frame 1..F−1: the moves since the frame before
                                                  //!< (grid units), predicted residuals as zigzag varints
};

//! Sizes of the parts of an encoded model and its error, for reports (bytes, mm, degrees).
struct CompactStats {
  std::size_t index_bytes = 0;
  std::size_t position_bytes = 0;
  std::size_t motion_bytes = 0;
  double max_error = 0.0;   //!< max distance decoded vs input vertex (mm), all frames
  double rms_error = 0.0;   //!< RMS of that distance (mm)
  double normal_p99 = 0.0;  //!< worst frame's 99th percentile of the angle between decoded and input facet
                            //!< normals (degrees)
  double normal_max = 0.0;  //!< the largest such angle, all frames (degrees)
};

//! Encodes a mesh sequence. With options.reorder the model's vertex i is input vertex
//! `vertex_order[i]` (filled when not null).
//! \throw InvalidInput (BadMesh) on an empty sequence, frames of unequal size, out-of-range triangle
//! indices, non-finite coordinates, or coordinates too far apart for the grid; (Usage) on a
//! non-positive tolerance, normal bound or step.
CompactModel compact_encode(const MeshSequence& seq, const CompactOptions& options = {},
                            std::vector<std::uint32_t>* vertex_order = nullptr, CompactStats* stats = nullptr);

//! Decodes a model to the mesh sequence it stands for (vertex order of the model).
//! \throw InvalidInput (BadMesh) when a stream is corrupt or the counts are implausible for the streams.
MeshSequence compact_decode(const CompactModel& model);

}  // namespace c4d
