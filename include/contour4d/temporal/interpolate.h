#pragma once
//! \file interpolate.h
//! \brief Positions between frames (Miara et al. §III.E, "Construction of the 4D mesh and
//! interpolation"): linear, or periodic Catmull-Rom for a cardiac or breathing cycle.

#include <cstddef>
#include <vector>

#include "contour4d/core/mesh.h"

namespace c4d {

//! How positions move between two frames.
enum class TimeInterpolation {
  Step,                //!< hold the previous frame
  Linear,              //!< straight line between neighbouring frames
  CatmullRomPeriodic,  //!< C1 cubic through all frames; the last frame wraps to the first (a cycle)
};

//! Where time t (ms) falls: frames i0 < i1 (or i1 = 0 across the wrap) and the fraction u in [0, 1).
//! `period_ms` is the cycle length (<= 0: times_ms.back() - times_ms.front() + the mean frame step).
struct TimeSample {
  std::size_t i0 = 0;
  std::size_t i1 = 0;
  double u = 0.0;
};
//! \pre times_ms increasing, not empty. Non-periodic modes clamp t to [first, last].
TimeSample locate_time(const std::vector<double>& times_ms, double t_ms, bool periodic, double period_ms = 0.0);

//! Cycle length used by the periodic mode (ms).
double cycle_period(const std::vector<double>& times_ms, double period_ms = 0.0);

//! Catmull-Rom weights of frames i-1, i, i+1, i+2 at fraction u (uniform parameterisation).
void catmull_rom_weights(double u, double w[4]);

//! Vertex positions of the sequence at time t (ms).
//! \throw InvalidInput (BadMesh) on an empty sequence or times that do not increase.
std::vector<Vec3> interpolate_positions(const MeshSequence& seq, double t_ms, TimeInterpolation mode,
                                        double period_ms = 0.0);

//! The sequence resampled to `frames` evenly spaced times: over [first, last] for Step/Linear, over
//! one period (without repeating the first frame) for CatmullRomPeriodic.
//! \throw InvalidInput (Usage) when frames == 0.
MeshSequence resample_sequence(const MeshSequence& seq, std::size_t frames, TimeInterpolation mode,
                               double period_ms = 0.0);

}  // namespace c4d
