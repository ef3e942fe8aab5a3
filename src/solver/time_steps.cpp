// The solver's time steps: the cycle cut into equal steps in seconds, each placed between the reconstructed
// frames with the periodic Catmull-Rom spline of temporal/interpolate.h (E. Catmull, R. Rom 1974), C¹ over the
// wrap from the last frame to the first, so a solver that loops the cycle sees no jump in wall velocity.
#include "contour4d/solver/time_steps.h"

#include <cmath>
#include <string>

#include <fmt/format.h>

#include "contour4d/core/errors.h"

namespace c4d {
namespace {

constexpr std::size_t kDefaultSteps = 100;
constexpr double kDivideTolerance = 1e-6;  // of the cycle: how closely --dt must divide it

}  // namespace

TimeSteps make_time_steps(double period_s, const TimeStepOptions& options) {
  if (options.cycles < 1)
    throw InvalidInput(ErrorCode::Usage, {}, fmt::format("--cycles {} is not a positive count", options.cycles));
  if (options.steps > 0 && options.dt_s > 0.0)
    throw InvalidInput(ErrorCode::Usage, {}, "--steps and --dt both given", "give one of them");
  TimeSteps t;
  t.period_s = period_s;
  t.steps_per_cycle = options.steps > 0 ? options.steps : kDefaultSteps;
  if (options.dt_s > 0.0) {
    const double n = std::round(period_s / options.dt_s);
    if (n < 1.0 || std::abs(n * options.dt_s - period_s) > kDivideTolerance * period_s)
      throw InvalidInput(ErrorCode::Usage, {},
                         fmt::format("--dt {} s does not divide the cycle of {} s", options.dt_s, period_s),
                         fmt::format("use --dt {} or {} (or --steps N)", period_s / std::max(n, 1.0),
                                     period_s / (std::max(n, 1.0) + 1.0)));
    t.steps_per_cycle = static_cast<std::size_t>(n);
  }
  t.dt_s = period_s / static_cast<double>(t.steps_per_cycle);
  const std::size_t total = t.steps_per_cycle * static_cast<std::size_t>(options.cycles);
  t.times_s.reserve(total + 1);
  for (std::size_t i = 0; i <= total; ++i) t.times_s.push_back(t.dt_s * static_cast<double>(i));
  return t;
}

TimeWeights step_weights(const MeshSequence& seq, double t_s) {
  return time_weights(seq.times_ms, seq.times_ms.front() + 1000.0 * t_s, TimeInterpolation::CatmullRomPeriodic);
}

}  // namespace c4d
