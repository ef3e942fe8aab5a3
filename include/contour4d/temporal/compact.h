#pragma once
//! \file compact.h
//! \brief Compact 4D model (Miara et al. §III.D–E, Table I): a fine mesh stored once, its motion
//! carried by a few control vertices, and sparse corrections that bound the error.
//!
//! Layout of the model (docs/compact.md):
//!  - the fine mesh of frame 0: connectivity (meshopt index codec) and positions quantised on a grid
//!    of step `grid_step` mm (meshopt vertex codec), vertices and triangles reordered for locality;
//!  - control vertices: a subset of the fine vertices (the vertices kept by meshopt_simplify, the
//!    "base mesh"), with their displacement from frame 0 in every frame, quantised at `motion_step`;
//!  - per fine vertex, linear moving-least-squares weights over its nearest control vertices, computed
//!    from the decoded frame 0 (not stored: encoder and decoder compute the same ones);
//!  - per frame, sparse corrections for the vertices whose interpolated position is farther than
//!    `tolerance` mm from the true one, quantised at `residual_step`.
//! With CompactError::Vertex every decoded vertex is within `tolerance` mm (Euclidean) of the same
//! input vertex, in every frame. With CompactError::Surface every decoded vertex is within
//! `tolerance` mm of the input frame's surface (its triangles around that vertex): motion along the
//! surface is free, most corrections are one scalar along the predicted vertex normal.

#include <cstdint>
#include <vector>

#include "contour4d/core/mesh.h"

namespace c4d {

//! What the encoder's tolerance bounds.
enum class CompactError {
  Vertex,   //!< distance of each decoded vertex to the same input vertex (keeps correspondence exact)
  Surface,  //!< distance of each decoded vertex to the input surface (Hausdorff-style, smaller file)
};

//! Options of compact_encode.
struct CompactOptions {
  double tolerance = 0.05;                    //!< max distance (mm) between decoded and input vertex, any frame
  std::size_t control_vertices = 600;         //!< target number of control vertices carrying the motion
  int neighbours = 8;                         //!< control vertices per fine vertex in the interpolation
  bool reorder = true;                        //!< reorder vertices and triangles for compression (permutes ids)
  CompactError error = CompactError::Vertex;  //!< what `tolerance` bounds
};

//! Number of control vertices a fine vertex's weights refer to (CompactModel::neighbours).
constexpr int kMaxCompactNeighbours = 16;

//! A compact 4D model: plain data, the payload of model.c4d (temporal/model_c4d.h). Positions in the input
//! space (mm, LPS for DICOM data).
struct CompactModel {
  std::uint32_t vertex_count = 0;
  std::uint32_t triangle_count = 0;
  std::uint32_t frame_count = 0;
  std::vector<double> times_ms;                        //!< time of each frame (ms)
  double origin[3] = {0, 0, 0};                        //!< grid origin (mm)
  double grid_step = 0.0;                              //!< frame-0 position quantum (mm)
  double motion_step = 0.0;                            //!< control displacement quantum (mm)
  double residual_step = 0.0;                          //!< correction quantum (mm)
  double tolerance = 0.0;                              //!< the bound the encoder guaranteed (mm)
  std::uint32_t neighbours = 0;                        //!< control vertices per fine vertex
  CompactError error = CompactError::Vertex;           //!< Surface: corrections may be scalars along the normal
  std::vector<std::uint8_t> indices;                   //!< meshopt_encodeIndexBuffer of the triangles
  std::vector<std::uint8_t> positions;                 //!< meshopt_encodeVertexBuffer of uint16 x,y,z,0 (grid units)
  std::vector<std::uint32_t> control;                  //!< ids of the control vertices, increasing
  std::vector<std::uint8_t> motion;                    //!< meshopt_encodeVertexBuffer of int16 x,y,z,0 per
                                                       //!< (control vertex, frame), control-major
  std::vector<std::vector<std::uint8_t>> corrections;  //!< per frame: varint-coded sparse corrections
                                                       //!< (Surface: gap·2 + full flag, then 3 or 1 values)
};

//! Sizes of the parts of an encoded model and its error, for reports (bytes, mm).
struct CompactStats {
  std::size_t index_bytes = 0;
  std::size_t position_bytes = 0;
  std::size_t motion_bytes = 0;
  std::size_t correction_bytes = 0;
  std::size_t corrected_vertices = 0;   //!< corrections over all frames
  double max_error = 0.0;               //!< max distance decoded vs input vertex (mm), all frames
  double rms_error = 0.0;               //!< RMS of that distance (mm)
  double max_surface_error = 0.0;       //!< max distance decoded vertex to input surface (mm)
  double max_surface_error_back = 0.0;  //!< max distance input vertex to decoded surface (mm)
};

//! Encodes a mesh sequence. With options.reorder the model's vertex i is input vertex
//! `vertex_order[i]` (filled when not null).
//! \throw InvalidInput (BadMesh) on an empty sequence, frames of unequal size, out-of-range triangle
//! indices, or non-finite coordinates.
CompactModel compact_encode(const MeshSequence& seq, const CompactOptions& options = {},
                            std::vector<std::uint32_t>* vertex_order = nullptr, CompactStats* stats = nullptr);

//! Decodes a model to the mesh sequence it stands for (vertex order of the model).
//! \throw InvalidInput (BadMesh) when a stream is corrupt.
MeshSequence compact_decode(const CompactModel& model);

//! The linear moving-least-squares weights of every fine vertex over its `neighbours` nearest
//! control vertices (frame-0 positions): `ids[v * k + j]`, `weights[v * k + j]`; a weighted sum of
//! the control displacements reproduces any affine displacement field. Deterministic.
struct ControlWeights {
  int k = 0;
  std::vector<std::uint32_t> ids;  //!< index into the control list
  std::vector<float> weights;
};
ControlWeights control_weights(const std::vector<Vec3>& positions, const std::vector<std::uint32_t>& control,
                               int neighbours);

}  // namespace c4d
