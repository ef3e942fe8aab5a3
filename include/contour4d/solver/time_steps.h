#pragma once
//! \file time_steps.h
//! \brief The solver's time steps over the cycle: how many, and where each falls between the reconstructed
//! frames (the periodic Catmull-Rom of `render` and `unpack --interp catmull-rom`, temporal/interpolate.h).

#include <cstddef>
#include <vector>

#include "contour4d/core/mesh.h"
#include "contour4d/temporal/interpolate.h"

namespace c4d {

//! How the cycle is cut into solver steps (the command line's names in brackets). Give steps or dt, not both.
struct TimeStepOptions {
  std::size_t steps = 0;  //!< [--steps] steps per cycle; 0 with dt_s 0: 100
  double dt_s = 0.0;      //!< [--dt] step (s); must divide the cycle (to 1e-6 of it)
  int cycles = 1;         //!< [--cycles] cycles written one after the other
};

//! The output times: step i at i · dt_s, i = 0 … steps_per_cycle · cycles (the last repeats the first state).
struct TimeSteps {
  double period_s = 0.0;            //!< the cycle (s)
  std::size_t steps_per_cycle = 0;  //!< steps in one cycle
  double dt_s = 0.0;                //!< the step (s)
  std::vector<double> times_s;      //!< output times from 0 (s)
};

//! The steps of a cycle of `period_s` seconds.
//! \throw InvalidInput (Usage) for both or neither consistent steps and dt, a dt that does not divide the cycle
//! (the message names the nearest that do), cycles < 1.
TimeSteps make_time_steps(double period_s, const TimeStepOptions& options);

//! Where output time `t_s` (s after frame 0) falls between the frames of `seq` (periodic Catmull-Rom over the
//! cycle of seq.times_ms, cycle_period()).
TimeWeights step_weights(const MeshSequence& seq, double t_s);

}  // namespace c4d
