#pragma once
//! \file sunnybrook.h
//! \brief Contours drawn on DICOM images, Sunnybrook Cardiac Data layout: pixel-coordinate
//! contour text files beside the DICOM images they were drawn on (docs/images.md).

#include <filesystem>
#include <string>

#include "contour4d/core/stack.h"
#include "contour4d/io/input_result.h"

namespace c4d {

//! Which Sunnybrook contours to read.
enum class SunnybrookContours {
  Endocardium,  //!< i-contours, label "lv-endo"
  Epicardium,   //!< o-contours, label "lv-epi"
  Both,         //!< both, labelled as above
};

//! How to read a Sunnybrook patient folder.
struct SunnybrookOptions {
  SunnybrookContours contours = SunnybrookContours::Endocardium;  //!< which contour files
  std::string space = "LPS";  //!< output coordinates: "LPS" (DICOM patient space) or "RAS" (x and y negated)
  StackOptions stack;         //!< validation tolerances for build_sequence
};

//! True when `folder` has an i-contours/ or o-contours/ folder with *-manual.txt files.
bool is_sunnybrook_folder(const std::filesystem::path& folder);

//! Reads a patient folder (i-contours/, o-contours/, and the DICOM images in dicoms_contoured/,
//! dicoms/ or the folder itself, named N.dcm or IM-0001-NNNN.dcm). Pixel (c, r) of image N lies at
//! ImagePositionPatient + c·Δc·X + r·Δr·Y (LPS mm); phase = (N − 1) mod P, slice id = (N − 1) div P,
//! P = CardiacNumberOfImages (0018,1090), 20 when absent. Frames are the phases that carry
//! contours, in phase order, timed by the mean TriggerTime (0018,1060) of their images (else
//! phase × 1 ms).
//! \throw IoError (FileNotFound: no folder / no contour files; MissingCompanion: a contour's
//! DICOM image is missing; Parse: a malformed contour line or unreadable DICOM; Format: DICOM
//! without geometry tags) / InvalidInput from build_sequence.
InputResult read_sunnybrook(const std::filesystem::path& folder, const SunnybrookOptions& options = {});

}  // namespace c4d
