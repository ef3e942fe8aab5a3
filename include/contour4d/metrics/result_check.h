#pragma once
//! \file result_check.h
//! \brief The last gate before anything is written: every frame of a reconstruction is checked as a
//! closed, manifold, outward surface without self-intersections, with the same triangles in every frame
//! and a volume consistent with Simpson's discs of the same contours. A frame that fails is named with
//! its fault; the CLI then exits with ErrorCode::InvalidResult and writes nothing.

#include <cstddef>
#include <string>
#include <vector>

#include "contour4d/core/mesh.h"
#include "contour4d/core/stack.h"

namespace c4d {

//! Options of check_result.
struct ResultCheckOptions {
  bool closed = true;              //!< the surface must be closed (false for CapStyle::Open: open ends allowed,
                                   //!< and the volume is not compared)
  bool self_intersections = true;  //!< run the triangle-triangle intersection test (exact predicates)
  //! Largest |mesh volume − Simpson's volume| accepted, as a share of the volume the outer contours enclose by
  //! Simpson's discs (the same for contours without holes). Simpson's discs (area × slice thickness, half a gap
  //! beyond each end slice) and a smooth surface through the same contours differ by the caps and the
  //! curvature between slices, a few percent of what each sheet encloses (more where holes close between
  //! slices; measured figures: docs/results.md). A wall (a myocardium: contours with holes) differs from its
  //! discs by as much as a full cavity does, but against a much smaller volume: its end discs reach half a gap
  //! beyond the end slices, where the wall itself ends within a few mm of them (biv-me at 17.7 mm slices: the
  //! wall 98.7 ml against discs of 111.3 ml, −11 % of the wall, −4.7 % of the 270 ml its outer contours
  //! enclose, while the endocardium and epicardium alone are within −1.9 … +2.6 % of theirs). A collapsed or
  //! inside-out frame is far out either way.
  double volume_tolerance = 0.10;
};

//! What check_result found in one frame.
struct FrameCheck {
  int frame = 0;
  double volume = 0.0;                 //!< signed volume of the mesh (mm³)
  double simpson_volume = 0.0;         //!< Simpson's discs of the frame's contours (mm³; 0 when not compared)
  double simpson_outer_volume = 0.0;   //!< the same with the outer contours alone (holes not subtracted; mm³)
  std::size_t self_intersections = 0;  //!< crossing triangle pairs
  std::vector<std::string> faults;     //!< one sentence per fault; empty when the frame is valid
  bool ok() const { return faults.empty(); }
};

//! Every frame's check, in frame order.
struct ResultCheck {
  std::vector<FrameCheck> frames;
  bool ok() const;
  //! "frame 3: 120 crossing triangle pairs; volume 0.0 ml against 64.6 ml by Simpson's discs" for the
  //! first failing frame, with the count of the others; empty when every frame is valid.
  std::string summary() const;
};

//! Checks every frame of `result` (frames in parallel; the result does not depend on the thread
//! count). `contours` holds the contours the frames were built from (one structure), one frame per
//! result frame, for Simpson's discs; an empty sequence skips the volume comparison.
ResultCheck check_result(const MeshSequence& result, const Sequence& contours, const ResultCheckOptions& options = {});

}  // namespace c4d
