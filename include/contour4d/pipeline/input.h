#pragma once
//! \file input.h
//! \brief One entry point for every contour input: picks the reader from what INPUT is.

#include <filesystem>
#include <string>
#include <vector>

#include "contour4d/core/stack.h"
#include "contour4d/io/input_result.h"

namespace c4d {

//! How to read an input.
struct InputOptions {
  std::vector<std::string> contour_types;  //!< GPFile contour types to keep; empty = SAX_LV_ENDOCARDIAL
  std::string label;                       //!< keep only this label; for label images a number ("3") or a preset
                                           //!< name ("lv"), for an RT structure set an ROI's label, name or number.
                                           //!< Empty: every label, except that a Sunnybrook folder gives its
                                           //!< endocardium (lv-endo); "all": every label of every format
  std::string label_preset;                //!< label images: "acdc", "mnms" or "" (labels named by number)
  int slice_axis = -1;                     //!< label images: voxel axis of the slices; -1: largest spacing
  std::string space = "LPS";               //!< output coordinates of DICOM-derived inputs: "LPS" or "RAS"
  StackOptions stack;                      //!< validation tolerances
  double frame_ms = 0.0;                   //!< time between frames (ms) for inputs without times of their own
                                           //!< (GPFile, label images); 0: not given
  double cycle_ms = 0.0;                   //!< the same as a cycle length: frame f at f × cycle_ms / frames
  double contour_tolerance_mm = -1.0;      //!< how far smoothing may move a contour (mm): negative: half the pixel
                                           //!< size of the images they were traced on (GPFile, Sunnybrook; inputs
                                           //!< without one are exact); 0: exact, not smoothed (--exact-contours)
  bool align_slices = false;               //!< move each slice in its plane onto the long-axis contours that cross
                                           //!< it, else so the contours' centroids follow a smooth long axis
                                           //!< (breath-hold shifts; slice_alignment.h)
  bool strict = false;                     //!< refuse flawed contours (exit codes 15, 16, 19) instead of repairing
                                           //!< them (contour_repair.h; contour JSON and GPFile folders), and leave
                                           //!< contours missing from some frames out (contour_gaps.h)
};

//! Reads a .json contour file, a GPFile folder (a folder with GPFile_*.txt, or its parent), a
//! Sunnybrook-style patient folder (i-contours/, o-contours/, DICOM images), a DICOM RT structure set
//! (a .dcm file or any file marked DICM, or a folder of DICOM files holding exactly one; any other DICOM
//! file fails with Format, saying what it is), or label images (NIfTI, NRRD, MetaImage: one 4D file, one
//! file per frame, a folder or a name pattern).
//! \throw IoError / InvalidInput with context.
InputResult read_contours(const std::filesystem::path& input, const InputOptions& options = {});

//! The same for contours given in memory (a script's arrays): repaired unless options.strict, validated
//! by build_sequence, the label kept, frame times from `times_ms` (one per frame; empty: none of their
//! own, then options.frame_ms or cycle_ms). `source` names them in messages. Format "contours-in-memory".
//! \throw InvalidInput with the frame, slice and contour index of a bad contour.
InputResult read_contour_list(std::vector<RawContour> contours, int frame_count, const std::vector<double>& times_ms,
                              const std::string& source, const InputOptions& options = {});

}  // namespace c4d
