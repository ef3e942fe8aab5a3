#pragma once
//! \file gpfile.h
//! \brief Reader of biv-me / Cardiac Atlas "GPFile" guide-point folders (docs/formats.md): one
//! GPFile_NNN.txt per frame (x, y, z in mm, patient space LPS; contour type; slice id) plus
//! SliceInfoFile.txt with each slice's DICOM image plane.

#include <filesystem>
#include <string>
#include <vector>

#include "contour4d/core/contour_repair.h"
#include "contour4d/core/slice_alignment.h"
#include "contour4d/core/stack.h"

namespace c4d {

//! How to read a GPFile folder.
struct GpFileOptions {
  std::vector<std::string> contour_types;  //!< contour types to keep; empty = {"SAX_LV_ENDOCARDIAL"}. With both
                                           //!< SAX_RV_FREEWALL and SAX_RV_SEPTUM, each slice's two arcs are joined
                                           //!< into one contour labelled "rv-endo" (the RV endocardium)
  double parallel_tolerance_deg = 5.0;     //!< image planes within this angle of the short-axis one are kept
  StackOptions stack;                      //!< validation tolerances for build_sequence
  bool repair = true;                      //!< fix contour flaws (contour_repair.h) instead of refusing them
};

//! One slice of SliceInfoFile.txt: a DICOM image plane (mm, LPS).
struct GpFileSlice {
  int id = 0;             //!< slice id (column 5 of the GPFiles)
  std::string image;      //!< DICOM file name of the slice
  Vec3 position;          //!< ImagePositionPatient: centre of the first pixel (mm)
  Vec3 row;               //!< first ImageOrientationPatient triplet (unit direction along a row)
  Vec3 column;            //!< second ImageOrientationPatient triplet (unit direction along a column)
  Vec3 normal;            //!< row × column (unit)
  double pixel_mm = 0.0;  //!< PixelSpacing, the mean of its two values (mm); 0 when the line has none
  bool used = false;      //!< true when its contours went into the sequence
  std::string note;       //!< why it was skipped, when it was
};

//! What was read from a GPFile folder.
struct GpFileResult {
  Sequence sequence;                     //!< validated stack of the chosen contour types
  std::vector<GpFileSlice> slices;       //!< every slice of SliceInfoFile.txt, by id
  std::vector<int> slices_used;          //!< ids of the slices in the sequence
  std::vector<int> slices_skipped;       //!< ids of slices with chosen contours that were dropped
  std::vector<std::string> frame_files;  //!< file name of each frame
  std::vector<std::string> notes;        //!< human-readable lines: what was used, skipped, closed
  std::vector<ContourRepair> repairs;    //!< flaws fixed (GpFileOptions::repair)
  std::vector<GuideCurve> long_axis;     //!< every LAX_* contour (whatever the chosen types), one per frame, slice
                                         //!< and type, labelled by gpfile_label (lax-lv-endo): for --align-slices
};

//! User-facing label of a biv-me contour type: lower case, '-' for '_', "SAX_" dropped,
//! ENDOCARDIAL -> endo, EPICARDIAL -> epi (SAX_LV_ENDOCARDIAL -> "lv-endo",
//! SAX_RV_FREEWALL -> "rv-freewall", LAX_LV_EPICARDIAL -> "lax-lv-epi").
std::string gpfile_label(const std::string& contour_type);

//! Parses the texts of a GPFile folder: `frames[i]` is the text of the i-th GPFile (frame i),
//! `slice_info` that of SliceInfoFile.txt. `source` names the folder; `frame_names` (optional)
//! the frame files, for messages. Keeps the chosen contour types on the short-axis slices (image
//! normal parallel to the majority of slices carrying them); the points of one (slice, type) in
//! one frame form one contour, in file order. SAX_LV_EPICARDIAL, open in biv-me, is closed with
//! the SAX_RV_SEPTUM points of the same slice when present.
//! \throw IoError / InvalidInput naming the file, line, frame and slice.
GpFileResult parse_gpfile_texts(const std::vector<std::string>& frames, const std::string& slice_info,
                                const std::string& source, const GpFileOptions& options = {},
                                const std::vector<std::string>& frame_names = {});

//! Reads a GPFile folder (GPFile_*.txt in file-number order, plus SliceInfoFile.txt).
//! \throw IoError (FileNotFound when no GPFile_*.txt, MissingCompanion without SliceInfoFile.txt),
//! and as parse_gpfile_texts.
GpFileResult read_gpfile(const std::filesystem::path& folder, const GpFileOptions& options = {});

}  // namespace c4d
