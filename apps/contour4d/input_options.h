#pragma once
//! \file input_options.h
//! \brief The input flags shared by every subcommand that reads contours.

#include <CLI/CLI.hpp>

#include "contour4d/pipeline/input.h"

namespace c4d::cli {

//! Adds --type, --label, --labels, --slice-axis, --space, --frame-ms, --cycle-ms, --exact-contours,
//! --contour-tolerance and --strict, filling `o`.
//! With `labels`, --label is repeatable and may be "all" (reconstruct: several structures in one run).
inline void add_input_options(CLI::App* app, InputOptions& o, std::vector<std::string>* labels = nullptr) {
  app->add_option("--type", o.contour_types,
                  "GPFile contour types to keep (repeatable; default SAX_LV_ENDOCARDIAL), e.g. SAX_LV_EPICARDIAL");
  if (labels)
    app->add_option(
        "--label", *labels,
        "structure: a contour label (lv-endo, lv-epi), or for label images a number (3) or a preset name (lv), "
        "for an RT structure set an ROI's label (lung-l), name or number; "
        "repeatable, or all: every structure (and lv-wall, the myocardium, from lv-endo inside lv-epi), "
        "each into OUTDIR/<label>/");
  else
    app->add_option(
        "--label", o.label,
        "structure to keep: a contour label (lv-endo, lv-epi), or for label images a number (3) or a preset name "
        "(lv), for an RT structure set an ROI's label (lung-l), name or number; all: every structure (Sunnybrook "
        "folders give lv-endo unless asked)");
  app->add_option("--labels", o.label_preset,
                  "label-image preset naming the labels: acdc (RV=1, MYO=2, LV=3) or mnms (LV=1, MYO=2, RV=3)")
      ->check(CLI::IsMember({"acdc", "mnms"}));
  app->add_option("--slice-axis", o.slice_axis,
                  "label images: voxel axis 0, 1 or 2 along which slices are stacked "
                  "(default: the axis with the largest spacing)")
      ->check(CLI::Range(0, 2));
  app->add_option("--space", o.space,
                  "output space of image/DICOM inputs (RT structure sets too): lps (DICOM patient space) or ras")
      ->capture_default_str()
      ->transform(CLI::IsMember({"lps", "ras", "LPS", "RAS"}));
  app->add_option("--frame-ms", o.frame_ms,
                  "time between frames in ms, for inputs without frame times (GPFile, label images); DICOM trigger "
                  "times win where present")
      ->check(CLI::PositiveNumber);
  app->add_option("--cycle-ms", o.cycle_ms,
                  "the same given as the cardiac cycle length in ms (frames spread evenly over it)")
      ->check(CLI::PositiveNumber);
  auto* exact = app->add_flag_callback(
      "--exact-contours", [&o] { o.contour_tolerance_mm = 0.0; },
      "keep traced contours exactly as drawn (the surface then passes through every point and creases along "
      "each contour); the default smooths contours traced on images within half a pixel");
  app->add_option("--contour-tolerance", o.contour_tolerance_mm,
                  "how far (mm) smoothing may move a traced contour (default: half the pixel size of the images "
                  "they were traced on; exact inputs such as phantoms are not smoothed)")
      ->check(CLI::NonNegativeNumber)
      ->excludes(exact);
  app->add_flag("--align-slices", o.align_slices,
                "undo breath-hold shifts: move each slice in its plane onto the long-axis contours that cross it "
                "(GPFile folders with LAX contours), else so the contours' centroids follow a smooth long axis (a "
                "robust fit; each slice's move is listed in report.json \"slice_alignment\")");
  app->add_flag("--strict", o.strict,
                "refuse flawed contours (open arcs, loops, spikes, too few points, two slice ids on one plane) with "
                "their exit codes instead of repairing them (the default repairs each and lists it in the report)");
}

}  // namespace c4d::cli
