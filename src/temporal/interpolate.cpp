// Interpolation between frames of a 4D mesh (Miara et al. §III.E: intermediate meshes between
// consecutive sequences for smooth display). Catmull-Rom: E. Catmull, R. Rom 1974, "A class of local
// interpolating splines"; uniform form, periodic over the cycle because cardiac and respiratory
// motion repeats.
#include "contour4d/temporal/interpolate.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "contour4d/core/errors.h"

namespace c4d {
namespace {

void check_times(const std::vector<double>& times) {
  if (times.empty())
    throw InvalidInput(ErrorCode::BadMesh, {}, "the sequence has no frames", "reconstruct a 4D mesh first");
  for (std::size_t i = 1; i < times.size(); ++i)
    if (!(times[i] > times[i - 1]))
      throw InvalidInput(ErrorCode::BadMesh, {{}, -1, static_cast<int>(i)},
                         "frame times do not increase (" + std::to_string(times[i - 1]) + " ms then " +
                             std::to_string(times[i]) + " ms)",
                         "give each frame a distinct, increasing time_ms");
}

}  // namespace

double cycle_period(const std::vector<double>& times, double period_ms) {
  if (period_ms > 0.0) return period_ms;
  if (times.size() < 2) return 1.0;
  const double span = times.back() - times.front();
  return span + span / static_cast<double>(times.size() - 1);
}

TimeSample locate_time(const std::vector<double>& times, double t, bool periodic, double period_ms) {
  TimeSample s;
  const std::size_t n = times.size();
  if (n <= 1) return s;
  if (periodic) {
    const double period = cycle_period(times, period_ms);
    double r = std::fmod(t - times.front(), period);
    if (r < 0) r += period;
    t = times.front() + r;
    if (t >= times.back()) {  // the wrap segment: last frame -> first frame
      const double len = times.front() + period - times.back();
      s.i0 = n - 1;
      s.i1 = 0;
      s.u = len > 0 ? std::clamp((t - times.back()) / len, 0.0, 1.0) : 0.0;
      return s;
    }
  } else {
    t = std::clamp(t, times.front(), times.back());
    if (t >= times.back()) {
      s.i0 = s.i1 = n - 1;
      return s;
    }
  }
  const std::size_t i1 = static_cast<std::size_t>(std::upper_bound(times.begin(), times.end(), t) - times.begin());
  s.i0 = i1 - 1;
  s.i1 = i1;
  s.u = (t - times[s.i0]) / (times[s.i1] - times[s.i0]);
  return s;
}

void catmull_rom_weights(double u, double w[4]) {
  const double u2 = u * u, u3 = u2 * u;
  w[0] = 0.5 * (-u3 + 2 * u2 - u);
  w[1] = 0.5 * (3 * u3 - 5 * u2 + 2);
  w[2] = 0.5 * (-3 * u3 + 4 * u2 + u);
  w[3] = 0.5 * (u3 - u2);
}

TimeWeights time_weights(const std::vector<double>& times, double t, TimeInterpolation mode, double period_ms) {
  check_times(times);
  const std::size_t n = times.size();
  const TimeSample s = locate_time(times, t, mode == TimeInterpolation::CatmullRomPeriodic, period_ms);
  TimeWeights w;
  w.frame[0] = s.i0;
  w.weight[0] = 1.0;
  if (mode == TimeInterpolation::Step || s.u == 0.0) return w;
  if (mode == TimeInterpolation::Linear) {
    w.count = 2;
    w.frame = {s.i0, s.i1, 0, 0};
    w.weight = {1.0 - s.u, s.u, 0.0, 0.0};
    return w;
  }
  w.count = 4;
  w.frame = {(s.i0 + n - 1) % n, s.i0, s.i1, (s.i1 + 1) % n};
  catmull_rom_weights(s.u, w.weight.data());
  return w;
}

std::vector<Vec3> combine_frames(const std::vector<std::vector<Vec3>>& frames, const TimeWeights& w) {
  const std::vector<Vec3>& first = frames[w.frame[0]];
  if (w.count == 1) return first;
  std::vector<Vec3> out(first.size());
  for (std::size_t v = 0; v < out.size(); ++v) out[v] = combine_vertex(frames, w, v);
  return out;
}

std::vector<Vec3> interpolate_positions(const MeshSequence& seq, double t, TimeInterpolation mode, double period_ms) {
  std::vector<double> times = seq.times_ms;
  if (times.empty())
    for (std::size_t f = 0; f < seq.positions.size(); ++f) times.push_back(static_cast<double>(f));
  check_times(times);
  if (times.size() != seq.positions.size())
    throw InvalidInput(ErrorCode::BadMesh, {}, "times_ms and positions differ in length", "give one time per frame");
  return combine_frames(seq.positions, time_weights(times, t, mode, period_ms));
}

MeshSequence resample_sequence(const MeshSequence& seq, std::size_t frames, TimeInterpolation mode, double period_ms) {
  if (frames == 0)
    throw InvalidInput(ErrorCode::Usage, {}, "cannot resample to 0 frames", "pass --resample N with N >= 1");
  std::vector<double> times = seq.times_ms;
  if (times.empty())
    for (std::size_t f = 0; f < seq.positions.size(); ++f) times.push_back(static_cast<double>(f));
  check_times(times);
  MeshSequence out;
  out.triangles = seq.triangles;
  const bool periodic = mode == TimeInterpolation::CatmullRomPeriodic;
  const double span = periodic ? cycle_period(times, period_ms) : times.back() - times.front();
  for (std::size_t i = 0; i < frames; ++i) {
    const double t = times.front() +
                     (periodic ? span * static_cast<double>(i) / static_cast<double>(frames)
                               : (frames == 1 ? 0.0 : span * static_cast<double>(i) / static_cast<double>(frames - 1)));
    out.times_ms.push_back(t);
    out.positions.push_back(interpolate_positions(seq, t, mode, period_ms));
  }
  return out;
}

}  // namespace c4d
