#pragma once
//! \file slice_alignment.h
//! \brief Breath-hold shifts: each short-axis slice of a cine study is acquired in its own breath-hold, so a
//! slice can sit a few millimetres off in its plane. Cardiac tools realign the slices so that the contours'
//! centroids follow a smooth long axis; align_slices does that, and says how far each slice moved.

#include <string>
#include <vector>

#include "contour4d/core/stack.h"

namespace c4d {

//! How far one slice was moved in its plane (the same move in every frame: one breath-hold per slice).
struct SliceShift {
  int slice = 0;         //!< slice id
  double offset_mm = 0;  //!< the slice plane's position along the stack normal (mm)
  Vec3 shift;            //!< the move, in the slice plane (mm, the input's coordinates)
  double shift_mm = 0;   //!< its length (mm)
  double weight = 1;     //!< the slice's weight in the robust fit (0: taken as an outlier, 1: fully trusted)
};

//! Options of align_slices.
struct SliceAlignmentOptions {
  std::string label;          //!< the structure whose centroids define the axis; empty: the label on the most
                              //!< slices (ties: the first by name), e.g. lv-endo
  int max_degree = 2;         //!< the axis: a polynomial in the slice offset of at most this degree (2: a gently
                              //!< bent ventricle); lowered to leave two slices more than coefficients (4 slices: a
                              //!< straight axis)
  double min_scale_mm = 0.5;  //!< floor of the robust fit's residual scale σ (mm); a slice's weight falls from 1 on
                              //!< the axis to 0 at 4.685 σ (2.3 mm at the floor), where it counts as shifted
  int iterations = 20;        //!< reweighting rounds of the robust (Tukey bisquare) fit
};

//! What align_slices did.
struct SliceAlignment {
  std::string label;               //!< the structure whose centroids were used
  int degree = 0;                  //!< degree of the fitted axis (−1: fewer than four slices, nothing moved)
  std::vector<SliceShift> shifts;  //!< one per slice id that holds `label`, by offset
};

//! Moves each slice of `seq` in its plane so that the centroid of its `label` contours (area-weighted, averaged
//! over the frames that have them) lies on a smooth axis: the robust least-squares polynomial fit of the
//! centroids against the slice offset. Every contour of a slice (every label, every frame) moves by the same
//! in-plane vector. With fewer than four slices nothing moves (degree −1).
SliceAlignment align_slices(Sequence& seq, const SliceAlignmentOptions& options = {});

}  // namespace c4d
