// The hand-off's shared helpers: positions at the output times (the periodic Catmull-Rom of time_steps.h),
// the parts of each face, units.
#include "contour4d/solver/handoff.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "contour4d/core/errors.h"

namespace c4d {

std::vector<Vec3> surface_at(const Handoff& h, std::size_t step) {
  return combine_frames(h.surface.seq.positions, step_weights(h.surface.seq, h.steps.times_s.at(step)));
}

std::vector<TimeWeights> all_step_weights(const Handoff& h) {
  std::vector<TimeWeights> w;
  w.reserve(h.steps.times_s.size());
  for (double t : h.steps.times_s) w.push_back(step_weights(h.surface.seq, t));
  return w;
}

FacePart face_part(const Handoff& h, int face) {
  FacePart p;
  std::vector<char> used(h.surface.seq.positions.front().size(), 0);
  for (std::uint32_t t = 0; t < h.surface.face.size(); ++t)
    if (h.surface.face[t] == face) {
      p.triangles.push_back(t);
      for (std::uint32_t v : h.surface.seq.triangles[t]) used[v] = 1;
    }
  for (std::uint32_t v = 0; v < used.size(); ++v)
    if (used[v]) p.vertices.push_back(v);
  return p;
}

double length_scale(const std::string& unit) {
  if (unit == "m") return 0.001;
  if (unit == "cm") return 0.1;
  if (unit == "mm") return 1.0;
  throw InvalidInput(ErrorCode::Usage, {}, "unknown length unit '" + unit + "'", "use m, cm or mm");
}

int length_decimals(double scale) { return 9 + static_cast<int>(std::lround(-std::log10(scale))); }

}  // namespace c4d
