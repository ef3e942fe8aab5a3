#pragma once
//! \file plane.h
//! \brief An oriented plane with an orthonormal in-plane frame, to map world points to slice
//! coordinates and back.

#include "contour4d/core/vec.h"

namespace c4d {

//! A slice plane in world space (mm). `u`, `v`, `normal` form a right-handed orthonormal frame
//! (u × v = normal); `origin` is a point of the plane.
struct Plane {
  Vec3 origin;
  Vec3 normal{0, 0, 1};
  Vec3 u{1, 0, 0};
  Vec3 v{0, 1, 0};
};

//! Plane through `origin` with unit normal `normal`; u and v are chosen deterministically from the
//! normal alone, so every slice of a stack shares the same in-plane axes.
Plane make_plane(Vec3 origin, Vec3 normal);

//! Signed distance of p from the plane along its normal (mm).
inline double signed_distance(const Plane& pl, Vec3 p) { return dot(p - pl.origin, pl.normal); }

//! Orthogonal projection of p into the plane's (u, v) coordinates (mm).
inline Vec2 to_plane(const Plane& pl, Vec3 p) {
  const Vec3 d = p - pl.origin;
  return {dot(d, pl.u), dot(d, pl.v)};
}

//! World point of plane coordinates q at height h above the plane (mm).
inline Vec3 from_plane(const Plane& pl, Vec2 q, double h = 0.0) {
  return pl.origin + q.x * pl.u + q.y * pl.v + h * pl.normal;
}

}  // namespace c4d
