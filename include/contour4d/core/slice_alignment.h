#pragma once
//! \file slice_alignment.h
//! \brief Breath-hold shifts: each short-axis slice of a cine study is acquired in its own breath-hold, so a
//! slice can sit a few millimetres off in its plane. Cardiac tools realign the slices: onto the long-axis
//! contours that cross them where the study has such contours (align_slices_to_curves), otherwise so that the
//! contours' centroids follow a smooth long axis (align_slices). Both say how far each slice moved.

#include <string>
#include <vector>

#include "contour4d/core/stack.h"

namespace c4d {

//! How far one slice was moved in its plane (the same move in every frame: one breath-hold per slice).
struct SliceShift {
  int slice = 0;           //!< slice id
  double offset_mm = 0;    //!< the slice plane's position along the stack normal (mm)
  Vec3 shift;              //!< the move, in the slice plane (mm, the input's coordinates)
  double shift_mm = 0;     //!< its length (mm)
  double weight = 1;       //!< the slice's weight in the robust fit (0: taken as an outlier, 1: fully trusted);
                           //!< on long-axis curves the share of its crossings trusted (0: the slice was not moved)
  int crossings = 0;       //!< align_slices_to_curves: long-axis crossings of the slice plane, all frames
  double residual_mm = 0;  //!< align_slices_to_curves: median distance of those crossings from the moved contours
};

//! A long-axis curve: an open polyline drawn on an image plane that crosses the short-axis slices (biv-me's
//! LAX_LV_ENDOCARDIAL contour of one view in one frame), in the sequence's coordinates (mm).
struct GuideCurve {
  int frame = 0;             //!< 0-based frame
  int plane = 0;             //!< the image plane it was drawn on (slice id of the input)
  std::string label;         //!< "lax-" + the label of the short-axis contours it meets (lax-lv-endo)
  std::vector<Vec3> points;  //!< in drawing order
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

//! What align_slices or align_slices_to_curves did.
struct SliceAlignment {
  std::string method;              //!< "centroid-axis" (align_slices) or "long-axis" (align_slices_to_curves)
  std::string label;               //!< the structure whose centroids (or contours) were used
  int degree = 0;                  //!< degree of the fitted axis (−1: fewer than four slices, nothing moved;
                                   //!< 0 on long-axis curves: no axis)
  std::vector<SliceShift> shifts;  //!< one per slice id that holds `label`, by offset
};

//! Moves each slice of `seq` in its plane so that the centroid of its `label` contours (area-weighted, averaged
//! over the frames that have them) lies on a smooth axis: the robust least-squares polynomial fit of the
//! centroids against the slice offset. Every contour of a slice (every label, every frame) moves by the same
//! in-plane vector. With fewer than four slices nothing moves (degree −1).
SliceAlignment align_slices(Sequence& seq, const SliceAlignmentOptions& options = {});

//! Moves each short-axis slice of `seq` in its plane onto the long-axis curves that cross it: where a curve
//! labelled "lax-" + L crosses a slice's plane in a frame, the crossing should lie on that frame's L contours of the
//! slice. Each slice gets the one in-plane move (the same in every frame) that brings its contours onto its
//! crossings of every frame and every label L with curves, by robust least squares (Gauss–Newton on the distances
//! to the contours, Tukey's bisquare weights). A slice with fewer than 4 crossings (or trusted weights adding up to
//! less than 3), or whose crossings do not fix both in-plane directions, is not moved (weight 0). Without curves for any label of `seq`, align_slices.
//! `label` (options.label) is reported as the labels used, joined by '+'.
SliceAlignment align_slices_to_curves(Sequence& seq, const std::vector<GuideCurve>& curves,
                                      const SliceAlignmentOptions& options = {});

}  // namespace c4d
