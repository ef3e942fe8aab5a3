#pragma once
//! \file input_result.h
//! \brief What a reader gives: the contours, where their times come from, the repairs made and notes for
//! the user. Every reader returns it; pipeline/input.h picks the reader.

#include <string>
#include <vector>

#include "contour4d/core/contour_repair.h"
#include "contour4d/core/contour_smoothing.h"
#include "contour4d/core/slice_alignment.h"
#include "contour4d/core/stack.h"

namespace c4d {

//! A slice contoured in some frames only: each frame is reconstructed from the slices it has.
struct SliceGap {
  int slice = 0;                    //!< slice id
  std::vector<int> missing_frames;  //!< 0-based frames without a contour on it
};

//! What was read, and notes for the user (which slices and frames were used or skipped, why).
struct InputResult {
  Sequence sequence;
  std::string format;                  //!< "contour4d-json", "gpfile", ...
  std::vector<std::string> notes;      //!< human-readable lines for the summary
  std::string timing;                  //!< where frame times come from: "data", "--frame-ms", "--cycle-ms",
                                       //!< "single frame" or "unknown" (frames numbered 0, 1, 2, ... ms)
  std::vector<ContourRepair> repairs;  //!< contour flaws fixed on reading (InputOptions::strict = false)
  double pixel_mm = 0.0;  //!< in-plane pixel size of the images the contours were traced on (mm); 0: none (exact
                          //!< contours, or contours fitted to a label mask's edge)
  double smoothing_tolerance_mm = 0.0;  //!< how far the contours were allowed to move when smoothed (0: not smoothed)
  std::string smoothing_source;         //!< where that tolerance came from, in words
  std::vector<ContourSmoothing> smoothing;      //!< what the smoothing did to each contour (contour_smoothing.h)
  std::vector<SliceGap> slices_in_some_frames;  //!< slices missing from some frames (by slice id)
  bool aligned = false;                         //!< the slices were moved in plane (InputOptions::align_slices)
  SliceAlignment alignment;                     //!< how far each slice moved (when `aligned`)
  std::vector<GuideCurve> long_axis;            //!< long-axis contours crossing the slices (GPFile folders), which
                                                //!< pin each slice for --align-slices
};

}  // namespace c4d
