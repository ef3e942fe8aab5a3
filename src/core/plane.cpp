#include "contour4d/core/plane.h"

#include <cmath>

namespace c4d {

Plane make_plane(Vec3 origin, Vec3 normal) {
  Plane pl;
  pl.origin = origin;
  pl.normal = normalized(normal);
  // Pick the world axis least aligned with the normal, so u is well conditioned and depends on
  // the normal alone (every slice of a stack gets the same u, v).
  const double ax = std::abs(pl.normal.x), ay = std::abs(pl.normal.y), az = std::abs(pl.normal.z);
  Vec3 helper = (ax <= ay && ax <= az) ? Vec3{1, 0, 0} : (ay <= az ? Vec3{0, 1, 0} : Vec3{0, 0, 1});
  pl.u = normalized(helper - dot(helper, pl.normal) * pl.normal);
  pl.v = cross(pl.normal, pl.u);
  return pl;
}

}  // namespace c4d
