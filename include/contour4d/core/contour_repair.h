#pragma once
//! \file contour_repair.h
//! \brief Repair, don't refuse: the flaws contours drawn in clinical tools routinely have (open arcs,
//! loops and doubled-back tracing, spikes, repeated points, one- or two-point "contours", a re-acquired
//! slice on the plane of another) fixed before the stack is validated (build_sequence), each repair
//! recorded with where it was and how far points moved. `--strict` skips this and keeps the errors.

#include <string>
#include <vector>

#include "contour4d/core/stack.h"

namespace c4d {

//! One repair, for report.json and the summary.
struct ContourRepair {
  int frame = -1;       //!< 0-based frame (−1: every frame, a merge of slices)
  int slice = -1;       //!< slice id (after a merge: the id kept)
  int contour = -1;     //!< 0-based index of the contour within its frame in the input (−1: several)
  std::string kind;     //!< "duplicate-points", "spike", "open-arc-closed", "open-arc-dropped", "loop-removed",
                        //!< "too-few-points", "no-area", "slices-merged", "contour-filled-in-time"
                        //!< (contour_gaps.h)
  std::string detail;   //!< what was done, in words
  double moved_mm = 0;  //!< largest distance from a removed or dropped point to the contour kept (mm; 0: none)
};

//! Options of repair_contours.
struct RepairOptions {
  double duplicate_mm = 1e-3;        //!< consecutive points closer than this are one point
  double duplicate_fraction = 0.05;  //!< ... or closer than this fraction of the contour's median point spacing
  double spike_deg = 150.0;          //!< a point where the contour turns back by more than this is a spike (a corner of
                                     //!< a ventricle turns by 90–120°)
  double open_gap_factor = 4.0;      //!< a closing gap longer than this × the median point spacing is an open arc
  double min_plane_gap = 0.1;        //!< two slice ids whose planes are closer than this (mm) are one slice
};

//! Repairs `contours` in place (contours may be dropped or change slice id) and lists what was done.
//! Per contour: repeated points and spikes removed; a contour left with fewer than 3 points or no area
//! dropped; an open arc (closing gap much longer than its point spacing) kept when closing it along the
//! gap gives a simple polygon, else dropped; a contour that crosses itself replaced by its largest simple
//! loop (small loops and doubled-back stretches removed). Then slice ids lying on one plane are merged
//! into the later (larger) id, whose contours win in a frame where both have the same label.
//! Non-finite coordinates are left for build_sequence to refuse (that is corruption, not drawing).
std::vector<ContourRepair> repair_contours(std::vector<RawContour>& contours, const RepairOptions& options = {});

}  // namespace c4d
