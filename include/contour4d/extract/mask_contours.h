#pragma once
//! \file mask_contours.h
//! \brief Label images → a Sequence of contours: per label, per slice along the slice axis,
//! marching squares at sub-pixel precision, smoothing and even resampling (Miara et al. §III.B;
//! docs/images.md).

#include <filesystem>
#include <string>
#include <vector>

#include "contour4d/core/stack.h"
#include "contour4d/io/images.h"
#include "contour4d/io/input_result.h"

namespace c4d {

//! How the pixel staircase of a traced mask is smoothed (docs/images.md).
enum class StaircaseSmoothing {
  EdgeFit,  //!< fit_mask_staircase: local weighted parabolas through the sub-pixel edge (no curvature bias)
  Taubin,   //!< taubin_passes Taubin λ|μ passes on each chain
  None      //!< the raw marching-squares chain
};

//! How contours are extracted from label images.
struct MaskExtractOptions {
  std::vector<std::string>
      labels;  //!< labels to extract, by number ("3") or by preset name ("lv"); empty: every non-zero label present
  std::string
      preset;  //!< label names: "acdc" (rv=1, myo=2, lv=3), "mnms" (lv=1, myo=2, rv=3) or "" (labels named by number)
  int slice_axis =
      -1;  //!< voxel axis (0, 1, 2) the slices are stacked along; -1: the axis with the largest spacing (ties: the last)
  std::string space = "LPS";  //!< output coordinates: "LPS" (as the image) or "RAS" (x and y negated)
  double presmooth_sigma_px =
      0.0;  //!< Gaussian σ (pixels) applied to each label's 0/1 mask before marching squares; 0: the raw mask
  StaircaseSmoothing staircase = StaircaseSmoothing::
      EdgeFit;  //!< smoothing of the pixel staircase (EdgeFit needs presmooth_sigma_px = 0, else Taubin is used)
  int taubin_passes =
      10;  //!< Taubin λ|μ passes on each chain (StaircaseSmoothing::Taubin, or after a presmoothed mask); 0: none
  double resample_mm =
      1.0;             //!< spacing (mm) of the evenly resampled contour points; 0: keep the marching-squares vertices
  int min_points = 8;  //!< at least this many points per resampled contour
  StackOptions stack;  //!< validation tolerances for build_sequence
};

//! The label value of every requested label (in option order; every present non-zero label when
//! none is requested), and its name (the preset's name, else the number).
//! \throw InvalidInput (Usage: unknown preset; UnknownLabel: a name not in the preset or a label
//! absent from every frame; the message lists the labels present).
std::vector<std::pair<int, std::string>> resolve_labels(const LabelSeries& series, const MaskExtractOptions& options);

//! Contours of `series`: slice id = voxel index along the slice axis, contour label = label name,
//! outer boundaries and holes, several components per slice; built with build_sequence.
//! Deterministic whatever the thread count (slices run in parallel with TBB).
//! \throw InvalidInput as resolve_labels and build_sequence (EmptyFrame when a frame lacks every
//! requested label).
Sequence extract_mask_contours(const LabelSeries& series, const MaskExtractOptions& options = {});

//! read_label_series(input) then extract_mask_contours; format "label-image", notes for the
//! summary (files, slice axis, labels, contour counts).
InputResult read_label_image_contours(const std::filesystem::path& input, const MaskExtractOptions& options = {});

}  // namespace c4d
