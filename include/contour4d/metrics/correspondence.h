#pragma once
//! \file correspondence.h
//! \brief Vertex correspondence across frames: the same vertices and triangles in every frame
//! (Lim et al. 2014, "Vertex Correspondence"), and a geometric test for permuted vertices.

#include <string>
#include <vector>

#include "contour4d/core/mesh.h"

namespace c4d {

//! Thresholds of the shuffled-vertex test (see docs/evaluate.md for the reasoning).
struct CorrespondenceOptions {
  double suspicious_median_change_pct = 50.0;  //!< flag a frame whose median edge-length change exceeds this (%)
  double jump_factor = 4.0;                    //!< an edge "jumps" when it grows longer than this factor
  double suspicious_jump_pct = 1.0;            //!< flag a frame where more than this % of edges jump
};

//! Result of check_correspondence.
struct CorrespondenceReport {
  bool same_vertex_count = true;               //!< every frame has frame 0's vertex count
  bool same_triangles = true;                  //!< every frame has frame 0's triangle list, in order
  int first_differing_frame = -1;              //!< first frame that differs from frame 0 (-1: none)
  std::string difference;                      //!< how it differs, in words
  std::vector<double> median_edge_change_pct;  //!< per frame: median |l − l_ref| / l_ref over edges (%)
  std::vector<double> edge_jump_pct;           //!< per frame: % of edges grown longer than jump_factor
  std::vector<int> suspicious_frames;          //!< frames whose vertices look permuted
  std::vector<std::string> faults;             //!< one sentence per fault

  bool ok() const { return faults.empty(); }
};

//! Compares connectivity across frames, then, when it is shared, the length of every edge in each
//! frame with its reference length: the per-edge median over all frames (for two frames, frame 0).
//! A frame whose vertices were permuted turns edges into random chords of the surface, so its
//! median change is huge while true motion changes edge lengths by tens of percent at most.
CorrespondenceReport check_correspondence(const std::vector<TriangleMesh>& frames,
                                          const CorrespondenceOptions& options = {});

}  // namespace c4d
