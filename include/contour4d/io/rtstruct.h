#pragma once
//! \file rtstruct.h
//! \brief DICOM RT structure sets (RTSTRUCT), the contour exchange of radiotherapy and clinical systems:
//! each ROI's closed planar contours in patient space, each ROI a label (docs/formats.md, "DICOM RTSTRUCT").

#include <filesystem>
#include <string>

#include "contour4d/core/stack.h"
#include "contour4d/io/input_result.h"

namespace c4d {

//! How to read an RT structure set.
struct RtStructOptions {
  std::string label;          //!< the ROI to read: its label (roi_label), its ROIName (any case) or its ROINumber;
                              //!< "" or "all": every ROI with contours
  std::string space = "LPS";  //!< output coordinates: "LPS" (DICOM patient space) or "RAS" (x and y negated)
  StackOptions stack;         //!< validation tolerances for build_sequence
  bool repair = true;         //!< fix contour flaws (contour_repair.h) instead of refusing them
};

//! What a DICOM file is, from its header: SOP Class UID (0008,0016) and Modality (0008,0060).
struct DicomKind {
  std::string sop_class_uid;  //!< e.g. "1.2.840.10008.5.1.4.1.1.481.3"; empty when absent
  std::string sop_class;      //!< its name in words, e.g. "RT Structure Set Storage"; the UID when unknown
  std::string modality;       //!< e.g. "RTSTRUCT", "CT"; empty when absent
  bool rtstruct = false;      //!< RT Structure Set Storage, or no SOP class and Modality RTSTRUCT
};

//! True when `file` starts like a DICOM Part 10 file ("DICM" at byte 128). Never throws.
bool is_dicom_file(const std::filesystem::path& file);

//! The kind of the DICOM file `file`, read without its pixel data.
//! \throw IoError (FileNotFound, EmptyFile, Parse: not readable as DICOM).
DicomKind dicom_kind(const std::filesystem::path& file);

//! The label of an ROI: its name in lower case, each run of other characters than letters and digits made
//! one '-', trimmed ("Lung L" -> "lung-l", "PTV_70 Gy" -> "ptv-70-gy"); "roi-N" (N = ROINumber) when nothing
//! is left, and "all" becomes "all-N" ("all" asks for every structure).
std::string roi_label(const std::string& roi_name, int roi_number);

//! Reads an RT structure set: StructureSetROISequence (ROI number, name, frame of reference),
//! ROIContourSequence (per ROI its CLOSED_PLANAR contours: ContourData, mm, patient LPS),
//! RTROIObservationsSequence (RTROIInterpretedType, in the notes) and ReferencedFrameOfReferenceSequence
//! (the frame of reference each ROI is drawn in, and the referenced series, in the notes). One frame (time
//! 0); contours are grouped into slices by their plane (offset along the mean contour normal, planes within
//! `stack.min_plane_gap` are one slice), slice ids 0, 1, ... along it. Each ROI's contours are labelled
//! roi_label(ROIName, ROINumber). POINT and OPEN_* contours are left out (noted); with every ROI asked,
//! an ROI without closed contours is left out (noted) unless none has any. Format "dicom-rtstruct".
//! \throw IoError: FileNotFound, EmptyFile, Parse (not DICOM, truncated, undecodable numbers), Format (not an
//! RT structure set: the message says what it is; ContourData not in triplets or unlike
//! NumberOfContourPoints; ContourGeometricType missing; a contour of an ROI that is not defined; ROIs in
//! different frames of reference read together). InvalidInput: MissingGeometry (an ROI without a frame of
//! reference, or one ReferencedFrameOfReferenceSequence does not list), EmptyStructure (the ROI asked for, or
//! every ROI, has no closed planar contour; no ROI at all), UnknownLabel (`label` names no ROI), and
//! build_sequence's codes, the message naming the ROI and its contour.
InputResult read_rtstruct(const std::filesystem::path& file, const RtStructOptions& options = {});

}  // namespace c4d
