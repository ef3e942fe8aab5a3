#pragma once
//! \file stack.h
//! \brief Slices, frames and sequences (Lim et al., "Model Definition", eqs. 2–4) and the
//! validation that turns loose contours into a stack of parallel planes.

#include <string>
#include <vector>

#include "contour4d/core/contour.h"
#include "contour4d/core/plane.h"

namespace c4d {

//! The contours lying on one plane in one frame (eq. 2).
struct Slice {
  int id = 0;                     //!< slice id from the input: the same plane in every frame
  double offset = 0.0;            //!< signed position of the plane along Sequence::normal (mm)
  std::vector<Contour> contours;  //!< contours of this slice, input order
};

//! The slices of one time step, sorted by increasing offset (eq. 3).
struct Frame {
  double time_ms = 0.0;       //!< acquisition time of the frame (ms); frame index × 1 ms when unknown
  std::vector<Slice> slices;  //!< slices holding at least one contour, by increasing offset
};

//! A validated stack of parallel slices over time (eq. 4).
struct Sequence {
  std::string units = "mm";   //!< length unit of every coordinate
  std::string space = "LPS";  //!< patient coordinate convention of the input ("LPS", "RAS" or "unknown")
  Vec3 normal{0, 0, 1};       //!< unit stack normal, pointing from the first slice to the last
  Vec3 u{1, 0, 0};            //!< in-plane axis shared by all slices
  Vec3 v{0, 1, 0};            //!< in-plane axis shared by all slices (u × v = normal)
  std::vector<Frame> frames;  //!< frames in time order
  std::string source;         //!< file or folder the sequence was read from (for messages)
};

//! Plane of slice `s` of sequence `seq` (origin on the stack axis at the slice's offset).
Plane slice_plane(const Sequence& seq, const Slice& s);

//! Options for validating a stack of contours.
struct StackOptions {
  double plane_tolerance = 0.05;      //!< max distance (mm) of a contour point from its slice plane
  double parallel_tolerance_deg = 1;  //!< max angle between slice normals (degrees)
  double min_area = 1e-6;             //!< contours with |area| below this (mm²) are rejected
  double min_plane_gap = 0.1;         //!< two slice ids closer than this (mm) are "one plane"
};

//! One contour as read from a file, before validation: frame index, where it came from (for messages).
struct RawContour {
  int frame = 0;    //!< frame index (0-based)
  Contour contour;  //!< label, slice id, points
  int line = 0;     //!< 1-based line of the file where the contour starts (0: unknown)
  int index = 0;    //!< 0-based index of the contour within its frame in the file
};

//! Builds a validated Sequence: derives the stack normal from the contours (area-weighted polygon
//! normals), checks every contour (finite, >= 3 distinct points, non-zero area, simple), every
//! slice (coplanar, one plane per slice id, one slice id per plane), the stack (slices parallel)
//! and every frame (at least one contour). `frame_count` frames are created (times from
//! `times_ms` when given, else index × 1 ms).
//! \throw InvalidInput naming `source` and the frame, slice and contour (and line when known).
Sequence build_sequence(const std::vector<RawContour>& contours, int frame_count, const std::vector<double>& times_ms,
                        const std::string& source, const StackOptions& options = {});

//! The distinct labels of a sequence, sorted.
std::vector<std::string> labels(const Sequence& seq);

//! A copy of `seq` keeping only contours whose label is `label`.
//! \throw InvalidInput (ErrorCode::UnknownLabel) when no contour has that label; the message
//! lists the labels present.
Sequence select_label(const Sequence& seq, const std::string& label);

}  // namespace c4d
