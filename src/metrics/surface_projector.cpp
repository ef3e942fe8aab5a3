// Closest-point queries with CGAL's AABB tree (CGAL User Manual, "3D Fast Intersection and Distance
// Computation"), on a triangle soup kept alongside so the hit triangle's normal is known.
#include "contour4d/metrics/surface_projector.h"

#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <algorithm>
#include <limits>
#include <utility>
#include <vector>

#include "contour4d/metrics/surface_walk.h"

namespace c4d {
namespace {
using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Iterator = std::vector<K::Triangle_3>::const_iterator;
using Primitive = CGAL::AABB_triangle_primitive<K, Iterator>;
using Tree = CGAL::AABB_tree<CGAL::AABB_traits<K, Primitive>>;
}  // namespace

// Walks that end farther from their query than this fraction of their triangle's longest edge are
// checked by the tree (SurfaceProjector::walk).
constexpr double kWalkTrust = 0.05;

struct SurfaceProjector::Impl {
  std::vector<K::Triangle_3> triangles;
  std::vector<Vec3> normals;
  std::vector<std::uint32_t> source;  // index of each kept triangle in the mesh
  std::vector<std::int32_t> kept;     // per mesh triangle: its index among the kept ones, or -1
  SurfaceWalk walk;                   // over the kept triangles, in their order
  Tree tree;                          // built at the first query (CGAL builds it, and its k-d tree, lazily)
};

SurfaceProjector::SurfaceProjector(const TriangleMesh& s) : impl_(std::make_unique<Impl>()) {
  const std::size_t n = s.positions.size();
  impl_->triangles.reserve(s.triangles.size());
  impl_->kept.assign(s.triangles.size(), -1);
  TriangleMesh kept{s.positions, {}};
  for (const Triangle& t : s.triangles) {
    if (t[0] >= n || t[1] >= n || t[2] >= n) continue;
    const Vec3 a = s.positions[t[0]], b = s.positions[t[1]], c = s.positions[t[2]];
    if (!is_finite(a) || !is_finite(b) || !is_finite(c)) continue;
    // A zero-area triangle adds nothing to the surface and CGAL's closest-point construction is not
    // defined for it.
    if (!(norm(cross(b - a, c - a)) > 0.0)) continue;
    impl_->triangles.emplace_back(K::Point_3(a.x, a.y, a.z), K::Point_3(b.x, b.y, b.z), K::Point_3(c.x, c.y, c.z));
    impl_->normals.push_back(normalized(cross(b - a, c - a)));
    impl_->kept[static_cast<std::size_t>(&t - s.triangles.data())] = static_cast<std::int32_t>(impl_->source.size());
    impl_->source.push_back(static_cast<std::uint32_t>(&t - s.triangles.data()));
    kept.triangles.push_back(t);
  }
  if (impl_->triangles.empty()) return;
  impl_->walk = make_surface_walk(std::move(kept));
  impl_->tree.insert(impl_->triangles.begin(), impl_->triangles.end());
}

SurfaceProjector::~SurfaceProjector() = default;

bool SurfaceProjector::empty() const { return impl_->triangles.empty(); }

std::int32_t SurfaceProjector::mesh_triangle(std::int32_t hint) const {
  if (hint < 0 || static_cast<std::size_t>(hint) >= impl_->source.size()) return -1;
  return static_cast<std::int32_t>(impl_->source[static_cast<std::size_t>(hint)]);
}

std::int32_t SurfaceProjector::hint_of(std::int32_t triangle) const {
  if (triangle < 0 || static_cast<std::size_t>(triangle) >= impl_->kept.size()) return -1;
  return impl_->kept[static_cast<std::size_t>(triangle)];
}

Vec3 SurfaceProjector::walk(Vec3 p, Vec3* normal, std::int32_t* hint) const {
  if (empty() || *hint < 0 || static_cast<std::size_t>(*hint) >= impl_->triangles.size())
    return closest(p, normal, hint);
  const Vec3 q = walk_closest(impl_->walk, p, *hint);
  // A walk can stop in a local minimum of the distance, which shows as a walk that ended far from the
  // query (rare: a fraction of a millimetre away on edges of about one). A walk that ends farther than kWalkTrust of its triangle's longest edge is checked by the tree, searched
  // within the walk's distance.
  const Triangle& t = impl_->walk.triangles[static_cast<std::size_t>(*hint)];
  const Vec3 &a = impl_->walk.positions[t[0]], &b = impl_->walk.positions[t[1]], &c = impl_->walk.positions[t[2]];
  const double longest2 = std::max({dot(b - a, b - a), dot(c - b, c - b), dot(a - c, a - c)});
  if (dot(p - q, p - q) > kWalkTrust * kWalkTrust * longest2) return closest(p, normal, hint);
  if (normal) *normal = impl_->normals[static_cast<std::size_t>(*hint)];
  return q;
}

Vec3 SurfaceProjector::closest(Vec3 p, Vec3* normal) const {
  std::int32_t none = -1;
  return closest(p, normal, &none);
}

Vec3 SurfaceProjector::closest(Vec3 p, Vec3* normal, std::int32_t* hint) const {
  if (empty()) {
    const double nan = std::numeric_limits<double>::quiet_NaN();
    if (normal) *normal = {nan, nan, nan};
    return {nan, nan, nan};
  }
  const K::Point_3 q(p.x, p.y, p.z);
  Tree::Point_and_primitive_id hit;
  const auto h = *hint;
  if (h >= 0 && static_cast<std::size_t>(h) < impl_->triangles.size()) {
    // The hint's own closest point bounds the search radius from the start (no k-d tree lookup).
    const Iterator it = impl_->triangles.begin() + h;
    hit = impl_->tree.closest_point_and_primitive(q, {K::Construct_projected_point_3()(*it, q), it});
  } else {
    hit = impl_->tree.closest_point_and_primitive(q);
  }
  const auto index = static_cast<std::size_t>(hit.second - impl_->triangles.begin());
  *hint = static_cast<std::int32_t>(index);
  if (normal) *normal = impl_->normals[index];
  return {hit.first.x(), hit.first.y(), hit.first.z()};
}

}  // namespace c4d
