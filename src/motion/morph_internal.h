#pragma once
// The 4D morph's entry point with its steps switched one by one (morph.h's morph_sequence runs them all):
// white-box tests (tests/unit/morph_internal_test.cpp) measure each step against the morph without it.

#include <cstddef>
#include <functional>
#include <vector>

#include "contour4d/core/mesh.h"
#include "contour4d/core/stack.h"
#include "contour4d/motion/morph.h"

namespace c4d::detail {

// Which steps of RbfProject run, and how far (the defaults are morph_sequence's; docs/algorithms/morph.md
// gives the figures behind each).
struct MorphSteps {
  double slide_spacing = 0.75;      // > 0: frame-0 contour vertices of a contour matched in the later frame slide
                                    // along that frame's contour through the relaxation and the repair, at least this
                                    // × the median edge apart along it (where the contour shrank, the ones between
                                    // relax on the surface); 0: none (they relax on the surface)
  bool plane_snap = true;           // after the relaxation, on each edge crossing a matched contour's plane, the
                                    // endpoint nearest the plane goes onto the contour where its ring keeps its angles
  bool contour_fit = true;          // last, the guarded fit of the frame's mesh onto all its contours (contour_fit.h)
  double saddle_curvature = 0.05;   // relaxation beside a slice whose contours split or merged since frame 0: umbrella
                                    // weights 1 + h / (this × median edge), h the edge's chord height over the
                                    // surface: the vertices gather where a split saddle bends; 0: off
  int retry_attempts = 1;           // tries after the first while a frame misses the quality criteria
                                    // (morph.cpp, relax_with_retries)
  int crossing_retry_attempts = 1;  // tries after retry_attempts while the best try still has crossing triangles
  int sweep_lanes = 0;              // relaxation: vertices per sweep step (SIMD lanes): 0 the widest the CPU runs
                                    // (4 with AVX, else 2), 1, 2 or 4 (4 without AVX: 2); the same result bit for bit
};

using SurfaceOf = std::function<const TriangleMesh&(std::size_t)>;

// morph_sequence (morph.h) with `steps`.
MeshSequence morph_sequence(const Sequence& seq, const TriangleMesh& frame0, const SurfaceOf& surface,
                            const MorphOptions& options, const MorphSteps& steps, MorphReport* report = nullptr);

}  // namespace c4d::detail
