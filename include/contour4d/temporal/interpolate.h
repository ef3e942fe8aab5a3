#pragma once
//! \file interpolate.h
//! \brief Positions between frames (Miara et al. §III.E, "Construction of the 4D mesh and
//! interpolation"): linear, or periodic Catmull-Rom for a cardiac or breathing cycle.

#include <array>
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

//! What interpolate_positions combines at a time: position = Σ weight[k] · positions[frame[k]] over the first
//! `count` terms, summed in this order (count 1: the frame itself, 2: linear, 4: Catmull-Rom).
struct TimeWeights {
  std::array<std::size_t, 4> frame{};
  std::array<double, 4> weight{};
  int count = 1;
};

//! The frames and weights of time t (ms) in `mode` (see interpolate_positions); the weights sum to 1. For
//! quantities that depend linearly on the positions (displacements, their harmonic extension into a volume).
//! \throw InvalidInput (BadMesh) on no times or times that do not increase.
TimeWeights time_weights(const std::vector<double>& times_ms, double t_ms, TimeInterpolation mode,
                         double period_ms = 0.0);

//! Σ w.weight[k] · frames[w.frame[k]][v] for one vertex v, term after term in the weights' order.
inline Vec3 combine_vertex(const std::vector<std::vector<Vec3>>& frames, const TimeWeights& w, std::size_t v) {
  Vec3 x = w.weight[0] * frames[w.frame[0]][v];
  for (std::size_t k = 1; k < static_cast<std::size_t>(w.count); ++k) x = x + w.weight[k] * frames[w.frame[k]][v];
  return x;
}

//! Σ w.weight[k] · frames[w.frame[k]] per vertex, term after term in the weights' order (interpolate_positions'
//! sum), for any per-frame vertex data that moves linearly with the positions (displacements included).
std::vector<Vec3> combine_frames(const std::vector<std::vector<Vec3>>& frames, const TimeWeights& w);

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
