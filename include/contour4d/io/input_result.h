#pragma once
//! \file input_result.h
//! \brief What a reader gives: the contours, where their times come from, the repairs made and notes for
//! the user. Every reader returns it; pipeline/input.h picks the reader.

#include <string>
#include <vector>

#include "contour4d/core/contour_repair.h"
#include "contour4d/core/stack.h"

namespace c4d {

//! What was read, and notes for the user (which slices and frames were used or skipped, why).
struct InputResult {
  Sequence sequence;
  std::string format;                  //!< "contour4d-json", "gpfile", ...
  std::vector<std::string> notes;      //!< human-readable lines for the summary
  std::string timing;                  //!< where frame times come from: "data", "--frame-ms", "--cycle-ms",
                                       //!< "single frame" or "unknown" (frames numbered 0, 1, 2, ... ms)
  std::vector<ContourRepair> repairs;  //!< contour flaws fixed on reading (InputOptions::strict = false)
};

}  // namespace c4d
