// One disc laid onto another with the same border curve (disc_map.h): M. S. Floater, "Mean value
// coordinates" (CAGD 20, 2003) for each flattening, the border by arc length along the shared curve.
#include "contour4d/motion/disc_map.h"

#include <Eigen/Sparse>
#include <Eigen/SparseLU>

#include <array>
#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <utility>
#include <numbers>

#include "contour4d/core/errors.h"
#include "contour4d/motion/chains.h"

namespace c4d {

namespace {

// The angle at vertex a of triangle (a, b, c), in radians (0 when an edge is degenerate).
double corner_angle(Vec3 a, Vec3 b, Vec3 c) {
  const Vec3 u = b - a, v = c - a;
  const double nu = norm(u), nv = norm(v);
  if (nu <= 0 || nv <= 0) return 0.0;
  return std::acos(std::clamp(dot(u, v) / (nu * nv), -1.0, 1.0));
}

// Barycentric coordinates of p in the flat triangle (a, b, c); (−1, −1, −1) when it is degenerate.
std::array<double, 3> flat_barycentric(Vec2 p, Vec2 a, Vec2 b, Vec2 c) {
  const double d = (b.y - c.y) * (a.x - c.x) + (c.x - b.x) * (a.y - c.y);
  if (std::abs(d) < 1e-300) return {-1, -1, -1};
  const double l0 = ((b.y - c.y) * (p.x - c.x) + (c.x - b.x) * (p.y - c.y)) / d;
  const double l1 = ((c.y - a.y) * (p.x - c.x) + (a.x - c.x) * (p.y - c.y)) / d;
  return {l0, l1, 1.0 - l0 - l1};
}

// Triangles' border edges (used by one triangle) as a map from each edge's first vertex to its second, in the
// triangles' orientation; false when a vertex starts two border edges (not one simple loop per border).
bool border_edges(const std::vector<Triangle>& tris, std::map<std::uint32_t, std::uint32_t>& next) {
  std::map<std::pair<std::uint32_t, std::uint32_t>, int> uses;
  for (const Triangle& t : tris)
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t a = t[static_cast<std::size_t>(k)], b = t[static_cast<std::size_t>((k + 1) % 3)];
      ++uses[{std::min(a, b), std::max(a, b)}];
    }
  next.clear();
  for (const Triangle& t : tris)
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t a = t[static_cast<std::size_t>(k)], b = t[static_cast<std::size_t>((k + 1) % 3)];
      if (uses[{std::min(a, b), std::max(a, b)}] == 1 && !next.emplace(a, b).second) return false;
    }
  return true;
}

}  // namespace

bool is_disc(const std::vector<Triangle>& tris) {
  std::map<std::uint32_t, std::uint32_t> next;
  if (tris.empty() || !border_edges(tris, next) || next.empty()) return false;
  std::size_t loop = 1;
  for (std::uint32_t v = next.begin()->second; v != next.begin()->first; ++loop) {
    const auto it = next.find(v);
    if (it == next.end() || loop > next.size()) return false;
    v = it->second;
  }
  std::vector<std::uint32_t> vertices;
  std::map<std::pair<std::uint32_t, std::uint32_t>, int> edges;
  for (const Triangle& t : tris)
    for (int k = 0; k < 3; ++k) {
      vertices.push_back(t[static_cast<std::size_t>(k)]);
      const std::uint32_t a = t[static_cast<std::size_t>(k)], b = t[static_cast<std::size_t>((k + 1) % 3)];
      edges[{std::min(a, b), std::max(a, b)}] = 1;
    }
  std::sort(vertices.begin(), vertices.end());
  vertices.erase(std::unique(vertices.begin(), vertices.end()), vertices.end());
  return loop == next.size() &&
         static_cast<long>(vertices.size()) - static_cast<long>(edges.size()) + static_cast<long>(tris.size()) == 1;
}

Disc disc_beyond(const TriangleMesh& mesh, const std::vector<Vec3>& contour, Vec3 dir) {
  constexpr double kOnPlane = 1e-5, kOnContour = 1e-3;  // mm
  double plane = 0;
  for (const Vec3& p : contour) plane += dot(p, dir);
  plane /= static_cast<double>(std::max<std::size_t>(1, contour.size()));
  const std::vector<Vec3>& y = mesh.positions;
  std::vector<std::uint32_t> parent(y.size());
  for (std::size_t v = 0; v < y.size(); ++v) parent[v] = static_cast<std::uint32_t>(v);
  auto root = [&](std::uint32_t v) {
    while (parent[v] != v) v = parent[v] = parent[parent[v]];
    return v;
  };
  std::vector<const Triangle*> beyond;
  for (const Triangle& t : mesh.triangles)
    if (dot(y[t[0]], dir) >= plane - kOnPlane && dot(y[t[1]], dir) >= plane - kOnPlane &&
        dot(y[t[2]], dir) >= plane - kOnPlane) {
      beyond.push_back(&t);
      parent[root(t[1])] = root(t[0]);
      parent[root(t[2])] = root(t[0]);
    }
  std::map<std::uint32_t, std::vector<Triangle>> parts;
  for (const Triangle* t : beyond) parts[root((*t)[0])].push_back(*t);
  for (auto& [r, tris] : parts) {
    std::map<std::uint32_t, std::uint32_t> next;
    if (!border_edges(tris, next) || next.empty()) continue;
    std::vector<Vec3> border_points;
    for (const auto& [a, b] : next) border_points.push_back(y[a]);
    bool on_contour = true;
    for (const Vec3& p : border_points) {
      std::int32_t hint = -1;
      on_contour = on_contour && norm(closest_on_loop(contour, p, hint) - p) <= kOnContour;
    }
    if (!on_contour || !is_disc(tris)) continue;
    Disc d;
    d.triangles = std::move(tris);
    d.border.push_back(next.begin()->first);
    for (std::uint32_t v = next.begin()->second; v != d.border.front(); v = next[v]) d.border.push_back(v);
    return d;
  }
  return {};
}

std::vector<Vec2> flatten_disc(const std::vector<Vec3>& x, const Disc& disc, const std::vector<double>& turns) {
  constexpr int kBorder = -2, kOutside = -1;
  std::vector<int> column(x.size(), kOutside);
  std::vector<Vec2> uv(x.size(), Vec2{0, 0});
  for (std::size_t k = 0; k < disc.border.size(); ++k) {
    const double a = 2.0 * std::numbers::pi * turns[k];
    column[disc.border[k]] = kBorder;
    uv[disc.border[k]] = Vec2{std::cos(a), std::sin(a)};
  }
  int inner = 0;
  for (const Triangle& t : disc.triangles)
    for (std::uint32_t v : t)
      if (column[v] == kOutside) column[v] = inner++;
  if (inner == 0) return uv;
  // Row i: Σ_j w_ij (u_i − u_j) = 0, w_ij = Σ over the triangles at edge ij of tan(γ/2) / |x_i − x_j|,
  // γ the triangle's angle at i (Floater 2003, eq. 5.1): positive weights.
  std::vector<Eigen::Triplet<double>> entries;
  Eigen::MatrixXd rhs = Eigen::MatrixXd::Zero(inner, 2);
  for (const Triangle& t : disc.triangles)
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t i = t[static_cast<std::size_t>(k)];
      const int row = column[i];
      if (row < 0) continue;
      const std::uint32_t j = t[static_cast<std::size_t>((k + 1) % 3)], l = t[static_cast<std::size_t>((k + 2) % 3)];
      const double half_tan = std::tan(0.5 * corner_angle(x[i], x[j], x[l]));
      for (std::uint32_t other : {j, l}) {
        const double w = half_tan / std::max(norm(x[other] - x[i]), 1e-12);
        entries.emplace_back(row, row, w);
        if (column[other] >= 0) {
          entries.emplace_back(row, column[other], -w);
        } else {
          rhs(row, 0) += w * uv[other].x;
          rhs(row, 1) += w * uv[other].y;
        }
      }
    }
  Eigen::SparseMatrix<double> a(inner, inner);
  a.setFromTriplets(entries.begin(), entries.end());
  a.makeCompressed();
  Eigen::SparseLU<Eigen::SparseMatrix<double>> lu;
  lu.compute(a);
  if (lu.info() != Eigen::Success)
    throw SolverError(ErrorCode::Internal, {}, "flatten_disc: the mean-value system cannot be factored");
  const Eigen::MatrixXd u = lu.solve(rhs);
  for (std::size_t v = 0; v < x.size(); ++v)
    if (column[v] >= 0) uv[v] = Vec2{u(column[v], 0), u(column[v], 1)};
  return uv;
}

std::vector<Vec3> lift_from_disc(const std::vector<Vec2>& where, const std::vector<Vec3>& x, const Disc& disc,
                                 const std::vector<Vec2>& uv) {
  // Triangles bucketed by their bounding boxes on a grid over [−1, 1]² (the flattened disc).
  const auto cells = static_cast<int>(std::clamp(std::sqrt(static_cast<double>(disc.triangles.size())), 1.0, 256.0));
  auto cell_of = [&](double c) { return std::clamp(static_cast<int>((c + 1.0) * 0.5 * cells), 0, cells - 1); };
  std::vector<std::vector<std::uint32_t>> grid(static_cast<std::size_t>(cells * cells));
  for (std::size_t k = 0; k < disc.triangles.size(); ++k) {
    const Triangle& t = disc.triangles[k];
    double lo_x = 2, lo_y = 2, hi_x = -2, hi_y = -2;
    for (std::uint32_t v : t) {
      lo_x = std::min(lo_x, uv[v].x), hi_x = std::max(hi_x, uv[v].x);
      lo_y = std::min(lo_y, uv[v].y), hi_y = std::max(hi_y, uv[v].y);
    }
    for (int gy = cell_of(lo_y); gy <= cell_of(hi_y); ++gy)
      for (int gx = cell_of(lo_x); gx <= cell_of(hi_x); ++gx)
        grid[static_cast<std::size_t>(gy * cells + gx)].push_back(static_cast<std::uint32_t>(k));
  }
  // The triangle whose smallest barycentric coordinate is largest: the one holding p, or the nearest.
  auto lift = [&](Vec2 p, const std::vector<std::uint32_t>& candidates) {
    double best = -std::numeric_limits<double>::infinity();
    std::array<double, 3> best_w{1, 0, 0};
    std::uint32_t best_t = 0;
    for (std::uint32_t k : candidates) {
      const Triangle& t = disc.triangles[k];
      const std::array<double, 3> w = flat_barycentric(p, uv[t[0]], uv[t[1]], uv[t[2]]);
      const double m = std::min({w[0], w[1], w[2]});
      if (m > best) best = m, best_w = w, best_t = k;
    }
    for (double& w : best_w) w = std::max(w, 0.0);
    const double s = best_w[0] + best_w[1] + best_w[2];
    const Triangle& t = disc.triangles[best_t];
    return (best_w[0] * x[t[0]] + best_w[1] * x[t[1]] + best_w[2] * x[t[2]]) / (s > 0 ? s : 1.0);
  };
  std::vector<std::uint32_t> all(disc.triangles.size());
  for (std::size_t k = 0; k < all.size(); ++k) all[k] = static_cast<std::uint32_t>(k);
  std::vector<Vec3> out;
  out.reserve(where.size());
  for (const Vec2 p : where) {
    const std::vector<std::uint32_t>& in_cell = grid[static_cast<std::size_t>(cell_of(p.y) * cells + cell_of(p.x))];
    bool inside = false;
    for (std::uint32_t k : in_cell) {
      const Triangle& t = disc.triangles[k];
      const std::array<double, 3> w = flat_barycentric(p, uv[t[0]], uv[t[1]], uv[t[2]]);
      inside = inside || std::min({w[0], w[1], w[2]}) >= -1e-9;
    }
    out.push_back(lift(p, inside ? in_cell : all));
  }
  return out;
}

std::vector<double> turns_along(const std::vector<Vec3>& loop, const std::vector<Vec3>& points) {
  const std::size_t n = loop.size();
  std::vector<double> start(n + 1, 0.0);
  for (std::size_t k = 0; k < n; ++k) start[k + 1] = start[k] + norm(loop[(k + 1) % n] - loop[k]);
  const double length = start[n];
  std::vector<double> out;
  out.reserve(points.size());
  for (const Vec3 p : points) {
    std::int32_t segment = -1;  // every segment tried (closest_on_loop), the closest one stored here
    const Vec3 q = closest_on_loop(loop, p, segment);
    const double at = start[static_cast<std::size_t>(segment)] + norm(q - loop[static_cast<std::size_t>(segment)]);
    out.push_back(length > 0 ? std::fmod(at / length, 1.0) : 0.0);
  }
  return out;
}

}  // namespace c4d
