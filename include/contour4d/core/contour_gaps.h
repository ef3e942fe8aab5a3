#pragma once
//! \file contour_gaps.h
//! \brief Slices contoured in some frames only. A contour left out of one frame of a cine study (an omission of the
//! reader or of an automatic tool) is filled from the same slice's contours in the frames before and after it: a
//! cardiac cycle moves a slice's contour smoothly, while the slices around it are 8–16 mm away.

#include <string>
#include <vector>

#include "contour4d/core/stack.h"

namespace c4d {

//! One contour filled in time.
struct ContourFill {
  int frame = 0;       //!< 0-based frame that lacked it
  int slice = 0;       //!< slice id
  std::string label;   //!< its structure
  int from_frame = 0;  //!< the frames it was interpolated between (equal: copied from that frame)
  int to_frame = 0;
  double weight = 0;  //!< share of `to_frame` in the blend (0: all from_frame)
};

//! Fills the contour of `label` on a slice in each frame that lacks it, when (a) that slice holds exactly one
//! contour of the label in a frame before and a different frame after it (cyclically), at most a third of the
//! cycle apart (a two-phase study's other phase is not interpolation), (b) in the frame that lacks it, slices with the label lie on both
//! sides of it (an omission inside the structure, not its end: a structure's end moving across a slice plane in
//! mid-cycle is left as it is), and (c) the blend is a simple polygon. The fill blends the nearest frames before
//! and after (cyclically) that have it, both resampled to the same count by arc length, with the start and
//! orientation that match them best, weighted by frame distance. Every label of `seq` is done in turn.
std::vector<ContourFill> fill_contour_gaps(Sequence& seq);

}  // namespace c4d
