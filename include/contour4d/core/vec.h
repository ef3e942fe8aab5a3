#pragma once
//! \file vec.h
//! \brief Small value types for points and directions in world space (mm) and in slice planes.
//!
//! Plain aggregates with the arithmetic geometry code needs; Eigen stays out of core headers
//! (STYLE.md rule 5). Coordinates are millimetres in the input's patient space (LPS unless stated).

#include <cmath>
#include <cstddef>

namespace c4d {

//! A point or direction in a slice plane (mm), coordinates along the plane's u and v axes.
struct Vec2 {
  double x = 0.0;
  double y = 0.0;
};

//! A point or direction in 3D world space (mm).
struct Vec3 {
  double x = 0.0;
  double y = 0.0;
  double z = 0.0;

  double& operator[](std::size_t i) { return i == 0 ? x : (i == 1 ? y : z); }
  double operator[](std::size_t i) const { return i == 0 ? x : (i == 1 ? y : z); }
};

inline Vec2 operator+(Vec2 a, Vec2 b) { return {a.x + b.x, a.y + b.y}; }
inline Vec2 operator-(Vec2 a, Vec2 b) { return {a.x - b.x, a.y - b.y}; }
inline Vec2 operator*(double s, Vec2 a) { return {s * a.x, s * a.y}; }
inline Vec2 operator*(Vec2 a, double s) { return {s * a.x, s * a.y}; }
inline bool operator==(Vec2 a, Vec2 b) { return a.x == b.x && a.y == b.y; }
inline double dot(Vec2 a, Vec2 b) { return a.x * b.x + a.y * b.y; }
//! z component of the 3D cross product (twice the signed area of the triangle 0, a, b).
inline double cross(Vec2 a, Vec2 b) { return a.x * b.y - a.y * b.x; }
inline double norm(Vec2 a) { return std::sqrt(dot(a, a)); }

inline Vec3 operator+(Vec3 a, Vec3 b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
inline Vec3 operator-(Vec3 a, Vec3 b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
inline Vec3 operator-(Vec3 a) { return {-a.x, -a.y, -a.z}; }
inline Vec3 operator*(double s, Vec3 a) { return {s * a.x, s * a.y, s * a.z}; }
inline Vec3 operator*(Vec3 a, double s) { return {s * a.x, s * a.y, s * a.z}; }
inline Vec3 operator/(Vec3 a, double s) { return {a.x / s, a.y / s, a.z / s}; }
inline Vec3& operator+=(Vec3& a, Vec3 b) {
  a = a + b;
  return a;
}
inline Vec3& operator-=(Vec3& a, Vec3 b) {
  a = a - b;
  return a;
}
inline bool operator==(Vec3 a, Vec3 b) { return a.x == b.x && a.y == b.y && a.z == b.z; }
inline double dot(Vec3 a, Vec3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
inline Vec3 cross(Vec3 a, Vec3 b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }
inline double norm(Vec3 a) { return std::sqrt(dot(a, a)); }
//! The point of the segment a–b closest to p (Vec2 in the plane, Vec3 in space).
template <class V>
V closest_on_segment(V a, V b, V p) {
  const V ab = b - a;
  const double l2 = dot(ab, ab);
  double t = l2 > 0.0 ? dot(p - a, ab) / l2 : 0.0;
  t = t < 0.0 ? 0.0 : (t > 1.0 ? 1.0 : t);
  return a + t * ab;
}
//! Distance (mm) from point p to the segment a–b in the plane.
inline double segment_distance(Vec2 p, Vec2 a, Vec2 b) { return norm(p - closest_on_segment(a, b, p)); }
inline double distance(Vec3 a, Vec3 b) { return norm(a - b); }
//! Unit vector along a; returns a unchanged when its length is zero.
inline Vec3 normalized(Vec3 a) {
  const double n = norm(a);
  return n > 0.0 ? a / n : a;
}
inline bool is_finite(Vec3 a) { return std::isfinite(a.x) && std::isfinite(a.y) && std::isfinite(a.z); }

}  // namespace c4d
