#pragma once
//! \file volume.h
//! \brief Volumes from contours by Simpson's method of discs, and the ejection fraction
//! (EDV, ESV, EF) of a volume curve.

#include <vector>

#include "contour4d/core/stack.h"

namespace c4d {

//! The area enclosed by the contours of one slice.
struct SliceArea {
  int slice = 0;            //!< slice id
  double offset = 0.0;      //!< mean of dot(point, normal) over the slice's contour points (mm)
  double area = 0.0;        //!< enclosed area (mm²): outer contours minus holes
  double outer_area = 0.0;  //!< the outer contours' area alone (mm²): holes not subtracted
};

//! Simpson's method of discs for one frame.
struct DiscVolume {
  double volume = 0.0;            //!< Σ area_i × thickness_i (mm³), see simpson_volumes
  double outer_volume = 0.0;      //!< the same with the outer contours' areas (holes not subtracted; mm³)
  double trapezoid_volume = 0.0;  //!< Σ (area_i + area_i+1) / 2 × gap_i between first and last slice (mm³)
  std::vector<SliceArea> slices;  //!< by increasing offset
};

//! Area (mm²) of the region enclosed by one slice's contours, in the (u, v) plane coordinates:
//! a contour inside an odd number of the slice's other contours is a hole and is subtracted.
//! `outer_area` (when given) gets the same without subtracting the holes.
double enclosed_area(const Slice& slice, Vec3 u, Vec3 v, double* outer_area = nullptr);

//! Disc volumes of every frame. Each slice is a disc (prism) of its enclosed area and thickness
//! equal to the distance between the midpoints to its neighbouring slices; the first and last
//! slices extend half a gap beyond their plane (for evenly spaced slices: area × spacing, the
//! classic rule). A frame with one slice uses the median gap of the whole sequence.
std::vector<DiscVolume> simpson_volumes(const Sequence& seq);

//! End-diastolic and end-systolic volumes and the ejection fraction of a volume curve.
struct EjectionFraction {
  double edv = 0.0;     //!< largest volume (mm³)
  double esv = 0.0;     //!< smallest volume (mm³)
  double ef_pct = 0.0;  //!< (EDV − ESV) / EDV × 100 (%); 0 when EDV <= 0
  int ed_frame = -1;    //!< frame of EDV (first one on ties)
  int es_frame = -1;    //!< frame of ESV (first one on ties)
};

//! EDV = max, ESV = min over the frames. Empty input gives frames -1 and zeros.
EjectionFraction ejection_fraction(const std::vector<double>& volumes);

}  // namespace c4d
