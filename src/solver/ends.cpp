// The ends of a reconstructed structure and the flat flow faces made of them. The caps are those of the
// one-frame surface (Lim et al. 2014, "Reconstruction from Segmented Contour Lines": a cap closes each end
// contour); they are found again on the finished mesh from the slice planes its contour vertices lie on. A
// chosen cap is flattened by W. T. Tutte's barycentric embedding ("How to draw a graph", Proc. London Math. Soc.
// 1963): each inner vertex at the mean of its neighbours with the border fixed on the plane, which cannot fold
// for a convex border (Floater 2003, "One-to-one piecewise linear mappings over triangulations") and is checked
// triangle by triangle otherwise, a few folded triangles of a border with pixel dents unfolded within the plane.
// It is linear in the border, so it commutes with the interpolation in time. Where a frame's border lies off one
// plane (a base whose contour vanishes in systole), the wall band up to the next contour takes up the border's
// move onto the plane by a harmonic extension along the normal, not its first row of triangles alone.
#include "contour4d/solver/ends.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <numeric>
#include <set>
#include <sstream>

#include <Eigen/Eigenvalues>
#include <Eigen/SparseCore>
#include <fmt/format.h>

#include "contour4d/core/errors.h"
#include "contour4d/core/sparse_solve.h"
#include "contour4d/metrics/topology.h"

namespace c4d {
namespace {

constexpr double kPlaneTolerance = 1e-5;      // mm: a vertex this close to a slice plane lies on it
constexpr std::size_t kMinPlaneVertices = 6;  // vertices on one offset that make a slice plane

using Edge = std::pair<std::uint32_t, std::uint32_t>;
Edge edge_key(std::uint32_t a, std::uint32_t b) { return {std::min(a, b), std::max(a, b)}; }

// The offsets along the normal where at least kMinPlaneVertices vertices lie (the slice planes), ascending.
std::vector<double> slice_planes(std::vector<double> offsets) {
  std::sort(offsets.begin(), offsets.end());
  std::vector<double> planes;
  for (std::size_t i = 0; i < offsets.size();) {
    std::size_t j = i + 1;
    while (j < offsets.size() && offsets[j] - offsets[j - 1] <= kPlaneTolerance) ++j;
    if (j - i >= kMinPlaneVertices)
      planes.push_back(std::accumulate(offsets.begin() + i, offsets.begin() + j, 0.0) / static_cast<double>(j - i));
    i = j;
  }
  return planes;
}

// A cap on a plane with slices beyond it reaches at most this share of the gap to the next one.
constexpr double kCapShareOfGap = 0.95;

// Index of the plane `s` lies on, or -1.
int plane_of(const std::vector<double>& planes, double s) {
  const auto it = std::lower_bound(planes.begin(), planes.end(), s - kPlaneTolerance);
  if (it != planes.end() && std::abs(*it - s) <= kPlaneTolerance) return static_cast<int>(it - planes.begin());
  return -1;
}

struct Adjacency {
  std::map<Edge, std::vector<std::uint32_t>> edge_triangles;
};

Adjacency adjacency(const std::vector<Triangle>& triangles) {
  Adjacency a;
  for (std::uint32_t t = 0; t < triangles.size(); ++t)
    for (int k = 0; k < 3; ++k) a.edge_triangles[edge_key(triangles[t][k], triangles[t][(k + 1) % 3])].push_back(t);
  return a;
}

// The triangles on side `side` of plane `d`: every corner on or beyond it, and one beyond, or all on it and
// facing along side·normal (a flat lid).
std::vector<char> beyond(const TriangleMesh& mesh, const std::vector<double>& s, double d, int side,
                         const Vec3& normal) {
  std::vector<char> in(mesh.triangles.size(), 0);
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    const Triangle& tri = mesh.triangles[t];
    bool behind = false, past = false;
    for (std::uint32_t v : tri) {
      const double h = side * (s[v] - d);
      behind = behind || h < -kPlaneTolerance;
      past = past || h > kPlaneTolerance;
    }
    if (behind) continue;
    if (past) {
      in[t] = 1;
      continue;
    }
    const Vec3 n =
        cross(mesh.positions[tri[1]] - mesh.positions[tri[0]], mesh.positions[tri[2]] - mesh.positions[tri[0]]);
    in[t] = side * dot(n, normal) > 0.0 ? 1 : 0;
  }
  return in;
}

// The connected patches of flagged triangles (through shared edges).
std::vector<std::vector<std::uint32_t>> patches(const std::vector<Triangle>& triangles, const Adjacency& adj,
                                                const std::vector<char>& in) {
  std::vector<int> seen(triangles.size(), 0);
  std::vector<std::vector<std::uint32_t>> out;
  for (std::uint32_t t0 = 0; t0 < triangles.size(); ++t0) {
    if (!in[t0] || seen[t0]) continue;
    std::vector<std::uint32_t> patch{t0}, stack{t0};
    seen[t0] = 1;
    while (!stack.empty()) {
      const std::uint32_t t = stack.back();
      stack.pop_back();
      for (int k = 0; k < 3; ++k)
        for (std::uint32_t u : adj.edge_triangles.at(edge_key(triangles[t][k], triangles[t][(k + 1) % 3])))
          if (in[u] && !seen[u]) {
            seen[u] = 1;
            patch.push_back(u);
            stack.push_back(u);
          }
    }
    std::sort(patch.begin(), patch.end());
    out.push_back(std::move(patch));
  }
  return out;
}

// The patch as an end of plane `p`: its border edges all lie in the plane and it reaches at most `max_extent`
// beyond it.
bool as_end(const TriangleMesh& mesh, const std::vector<double>& s, const std::vector<double>& planes, int p, int side,
            double max_extent, const Vec3& normal, const std::vector<std::uint32_t>& patch, SurfaceEnd& end) {
  std::set<Edge> inside;  // directed edges of the patch
  std::set<std::uint32_t> vertices;
  for (std::uint32_t t : patch)
    for (int k = 0; k < 3; ++k) {
      inside.insert({mesh.triangles[t][k], mesh.triangles[t][(k + 1) % 3]});
      vertices.insert(mesh.triangles[t][k]);
    }
  const double d = planes[static_cast<std::size_t>(p)];
  for (std::uint32_t v : vertices)
    if (side * (s[v] - d) > max_extent + kPlaneTolerance) return false;
  std::vector<Edge> border;  // directed edges whose twin is not in the patch
  for (const Edge& e : inside)
    if (!inside.count({e.second, e.first})) {
      if (plane_of(planes, s[e.first]) != p || plane_of(planes, s[e.second]) != p) return false;
      border.push_back(e);
    }
  if (border.empty()) return false;  // a closed component, not a cap
  Vec3 area;
  std::set<std::uint32_t> on_border;
  for (const Edge& e : border) {
    area += 0.5 * cross(mesh.positions[e.first], mesh.positions[e.second]);
    on_border.insert(e.first);
    on_border.insert(e.second);
  }
  // Loops: components of the border graph.
  std::map<std::uint32_t, std::uint32_t> parent;
  for (std::uint32_t v : on_border) parent[v] = v;
  auto root = [&](std::uint32_t v) {
    while (parent[v] != v) v = parent[v] = parent[parent[v]];
    return v;
  };
  for (const Edge& e : border) parent[root(e.first)] = root(e.second);
  int loops = 0;
  Vec3 centroid;
  for (std::uint32_t v : on_border) {
    loops += root(v) == v ? 1 : 0;
    centroid += mesh.positions[v];
  }
  end.side = side;
  end.offset_mm = planes[static_cast<std::size_t>(p)];
  end.area_mm2 = side * dot(area, normal);
  end.centroid = (1.0 / static_cast<double>(on_border.size())) * centroid;
  end.triangles = patch;
  end.border.assign(on_border.begin(), on_border.end());
  end.inner.clear();
  for (std::uint32_t v : vertices)
    if (!on_border.count(v)) end.inner.push_back(v);
  end.loops = loops;
  return true;
}

void name_ends(std::vector<SurfaceEnd>& ends) {
  std::size_t base = 0, apex = 0;
  for (const SurfaceEnd& e : ends) (e.base ? base : apex) += 1;
  std::size_t b = 0, a = 0;
  for (SurfaceEnd& e : ends) {
    if (e.base) {
      ++b;
      e.name = base == 1 ? "base" : base == 2 ? (b == 1 ? "inlet" : "outlet") : fmt::format("base{}", b);
    } else {
      ++a;
      e.name = apex == 1 ? "apex" : fmt::format("apex{}", a);
    }
  }
}

// Clusters of sorted offsets whose neighbours are at most `gap` apart, of at least `min_count` vertices.
std::vector<std::vector<std::uint32_t>> offset_clusters(const std::vector<Vec3>& x, const Vec3& n, double gap,
                                                        std::size_t min_count) {
  std::vector<std::uint32_t> order(x.size());
  std::iota(order.begin(), order.end(), 0u);
  std::vector<double> s(x.size());
  for (std::size_t v = 0; v < x.size(); ++v) s[v] = dot(n, x[v]);
  std::sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) { return s[a] < s[b]; });
  std::vector<std::vector<std::uint32_t>> out;
  for (std::size_t i = 0; i < order.size();) {
    std::size_t j = i + 1;
    while (j < order.size() && s[order[j]] - s[order[j - 1]] <= gap) ++j;
    if (j - i >= min_count) out.emplace_back(order.begin() + i, order.begin() + j);
    i = j;
  }
  return out;
}

}  // namespace

Vec3 refine_normal(const TriangleMesh& mesh, const Vec3& guess) {
  Vec3 n = normalized(guess);
  // Wide clusters first (the rounding tilt), then tight ones (stray wall vertices left out).
  for (double gap : {2e-4, 2e-5, 2e-6, 2e-7}) {
    Vec3 sum;
    for (const auto& cluster : offset_clusters(mesh.positions, n, gap, 4 * kMinPlaneVertices)) {
      Vec3 c;
      for (std::uint32_t v : cluster) c += mesh.positions[v];
      c = (1.0 / static_cast<double>(cluster.size())) * c;
      Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
      for (std::uint32_t v : cluster) {
        const Vec3 d = mesh.positions[v] - c;
        const Eigen::Vector3d e(d.x, d.y, d.z);
        cov += e * e.transpose();
      }
      const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(cov);
      if (eig.eigenvalues()(1) <= 0.0) continue;  // collinear points: no plane
      const Eigen::Vector3d e = eig.eigenvectors().col(0);
      Vec3 m{e(0), e(1), e(2)};
      if (dot(m, n) < 0.0) m = -m;
      if (dot(m, n) < std::cos(0.01)) continue;  // not a slice plane (a cluster of wall vertices)
      sum += static_cast<double>(cluster.size()) * m;
    }
    if (norm(sum) > 0.0) n = normalized(sum);
  }
  return n;
}

std::vector<SurfaceEnd> find_ends(const TriangleMesh& mesh, const Vec3& normal) {
  std::vector<double> s(mesh.positions.size());
  for (std::size_t v = 0; v < s.size(); ++v) s[v] = dot(normal, mesh.positions[v]);
  const std::vector<double> planes = slice_planes(s);
  const Adjacency adj = adjacency(mesh.triangles);
  std::vector<SurfaceEnd> found;
  for (std::size_t p = 0; p < planes.size(); ++p)
    for (int side : {1, -1}) {
      // Beyond the last plane on this side only caps lie, however tall their domes; beyond any other plane the
      // rest of the mesh does too, reaching the next plane ahead, so a cap there stays short of it.
      const bool ahead = side > 0 ? p + 1 < planes.size() : p > 0;
      const double max_extent = ahead ? kCapShareOfGap * std::abs(planes[p] - planes[side > 0 ? p + 1 : p - 1])
                                      : std::numeric_limits<double>::infinity();
      for (const auto& patch : patches(mesh.triangles, adj, beyond(mesh, s, planes[p], side, normal))) {
        SurfaceEnd end;
        if (as_end(mesh, s, planes, static_cast<int>(p), side, max_extent, normal, patch, end))
          found.push_back(std::move(end));
      }
    }
  // A dome clamped flat at half the spacing puts many vertices on one offset (a plane of its own): its flat top
  // is found as a cap too, inside the real one. Keep the largest of overlapping caps.
  std::stable_sort(found.begin(), found.end(),
                   [](const SurfaceEnd& a, const SurfaceEnd& b) { return a.triangles.size() > b.triangles.size(); });
  std::vector<char> taken(mesh.triangles.size(), 0);
  std::vector<SurfaceEnd> ends;
  for (SurfaceEnd& e : found) {
    if (std::any_of(e.triangles.begin(), e.triangles.end(), [&](std::uint32_t t) { return taken[t] != 0; })) continue;
    for (std::uint32_t t : e.triangles) taken[t] = 1;
    ends.push_back(std::move(e));
  }
  double up = 0.0, down = 0.0;
  for (const SurfaceEnd& e : ends) (e.side > 0 ? up : down) += e.area_mm2;
  for (SurfaceEnd& e : ends) e.base = (e.side > 0) == (up >= down);
  std::stable_sort(ends.begin(), ends.end(), [](const SurfaceEnd& a, const SurfaceEnd& b) {
    if (a.base != b.base) return a.base;
    return a.area_mm2 > b.area_mm2;
  });
  name_ends(ends);
  return ends;
}

std::vector<int> choose_ends(const std::vector<SurfaceEnd>& ends, const std::string& which) {
  std::vector<int> chosen;
  if (which == "none") return chosen;
  for (std::size_t i = 0; i < ends.size(); ++i)
    if (which == "all" || (which == "base" && ends[i].base) || (which == "apex" && !ends[i].base))
      chosen.push_back(static_cast<int>(i));
  if (which == "all" || which == "base" || which == "apex") return chosen;
  std::stringstream in(which);
  std::string item;
  while (std::getline(in, item, ',')) {
    std::size_t used = 0;
    int k = 0;
    try {
      k = std::stoi(item, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (used != item.size() || k < 1 || k > static_cast<int>(ends.size()))
      throw InvalidInput(
          ErrorCode::Usage, {},
          fmt::format("--open {}: '{}' is not base, apex, all, none or an end number 1..{}", which, item, ends.size()),
          "the ends are listed by `contour4d export OUTDIR --list-ends`");
    if (std::find(chosen.begin(), chosen.end(), k - 1) == chosen.end()) chosen.push_back(k - 1);
  }
  std::sort(chosen.begin(), chosen.end());
  return chosen;
}

namespace {

// Factorises deg(i) y_i − Σ_{j in the set} y_j for the vertices of a set (`local[v]` their index in it, −1 for
// others): the uniform graph Laplacian with the rest held fixed (lower triangle).
bool factor_uniform_laplacian(SparseLdlt& ldlt, const std::vector<std::vector<std::uint32_t>>& rings,
                              const std::vector<std::uint32_t>& vertices, const std::vector<int>& local) {
  const int n = static_cast<int>(vertices.size());
  std::vector<Eigen::Triplet<double>> entries;
  for (int i = 0; i < n; ++i) {
    const auto& ring = rings[vertices[static_cast<std::size_t>(i)]];
    entries.emplace_back(i, i, static_cast<double>(ring.size()));
    for (std::uint32_t j : ring)
      if (local[j] >= 0 && local[j] < i) entries.emplace_back(i, local[j], -1.0);
  }
  Eigen::SparseMatrix<double> a(n, n);
  a.setFromTriplets(entries.begin(), entries.end());
  return factor_lower(ldlt, a);
}

// The wall vertices between an end's border and the next slice plane (frame 0): reached from the border without
// passing the cap or a vertex on a slice plane. Sorted.
std::vector<std::uint32_t> basal_band(const MeshSequence& seq, const Vec3& normal, const SurfaceEnd& end,
                                      const std::vector<std::vector<std::uint32_t>>& rings) {
  const std::vector<Vec3>& x0 = seq.positions.front();
  std::vector<double> s(x0.size());
  for (std::size_t v = 0; v < x0.size(); ++v) s[v] = dot(normal, x0[v]);
  const std::vector<double> planes = slice_planes(s);
  std::vector<char> seen(x0.size(), 0);
  for (std::uint32_t v : end.border) seen[v] = 1;
  for (std::uint32_t v : end.inner) seen[v] = 1;
  std::vector<std::uint32_t> band, stack(end.border.begin(), end.border.end());
  while (!stack.empty()) {
    const std::uint32_t v = stack.back();
    stack.pop_back();
    for (std::uint32_t u : rings[v]) {
      if (seen[u]) continue;
      seen[u] = 1;
      if (plane_of(planes, s[u]) >= 0) continue;
      band.push_back(u);
      stack.push_back(u);
    }
  }
  std::sort(band.begin(), band.end());
  return band;
}

// Lays the border of `end` on each frame's plane (the mean offset of the border there) and moves the wall band
// beyond it (basal_band) along the normal by the harmonic extension of the border's moves (uniform weights,
// zero at the next contour): the border's spread over the plane is taken up by the whole band, not by its first
// row of triangles. One factorisation for every frame.
void lay_border_on_planes(MeshSequence& out, const Vec3& normal, const SurfaceEnd& end,
                          const std::vector<std::uint32_t>& band, const std::vector<std::vector<std::uint32_t>>& rings,
                          std::vector<double>& offsets) {
  const std::size_t nv = out.positions.front().size(), frames = out.positions.size();
  std::vector<double> shift(nv, 0.0);  // per vertex, in the current frame: the border's move along the normal
  std::vector<int> local(nv, -1);
  for (std::size_t i = 0; i < band.size(); ++i) local[band[i]] = static_cast<int>(i);
  const int n = static_cast<int>(band.size());
  SparseLdlt ldlt;
  if (n > 0 && !factor_uniform_laplacian(ldlt, rings, band, local))
    throw SolverError(ErrorCode::Internal, {}, "the wall band's system is singular");
  std::vector<double> b(static_cast<std::size_t>(n)), y(b.size());
  for (std::size_t f = 0; f < frames; ++f) {
    std::vector<Vec3>& x = out.positions[f];
    double d = 0.0;
    for (std::uint32_t v : end.border) d += dot(normal, x[v]);
    d /= static_cast<double>(end.border.size());
    offsets.push_back(d);
    for (std::uint32_t v : end.border) {
      shift[v] = d - dot(normal, x[v]);
      x[v] = x[v] + shift[v] * normal;
    }
    if (n == 0) continue;
    for (int i = 0; i < n; ++i) {
      b[static_cast<std::size_t>(i)] = 0.0;
      for (std::uint32_t j : rings[band[static_cast<std::size_t>(i)]])
        if (local[j] < 0) b[static_cast<std::size_t>(i)] += shift[j];
    }
    ldlt.solve(b.data(), y.data(), 1);
    for (int i = 0; i < n; ++i) {
      const std::uint32_t v = band[static_cast<std::size_t>(i)];
      x[v] = x[v] + y[static_cast<std::size_t>(i)] * normal;
    }
    for (std::uint32_t v : end.border) shift[v] = 0.0;
  }
}

// Twice the area of triangle `tri` facing along side · normal (negative: folded).
double facing(const std::vector<Vec3>& x, const Triangle& tri, int side, const Vec3& normal) {
  return side * dot(cross(x[tri[1]] - x[tri[0]], x[tri[2]] - x[tri[0]]), normal);
}

// Moves the inner vertices of a flat face's folded triangles within its plane until none folds (a few sweeps):
// each steps to where the smallest of its triangles grows (along normal × the opposite edge), the step halved
// when that does not raise it: the vertex moves into the kernel of its planar star. A border with small dents
// (pixel steps) folds Tutte's embedding at a few triangles only.
void unfold_face(std::vector<Vec3>& x, const std::vector<Triangle>& triangles, const SurfaceEnd& end,
                 const Vec3& normal, const std::vector<std::vector<std::uint32_t>>& faces_of) {
  constexpr int kSweeps = 20, kSteps = 40;
  auto lowest = [&](std::uint32_t v, Vec3& up) {
    double low = HUGE_VAL;
    for (std::uint32_t t : faces_of[v]) {
      const Triangle& tri = triangles[t];
      const double a = facing(x, tri, end.side, normal);
      if (a < low) {
        const int k = static_cast<int>(std::find(tri.begin(), tri.end(), v) - tri.begin());
        low = a;
        up = static_cast<double>(end.side) * cross(normal, x[tri[(k + 2) % 3]] - x[tri[(k + 1) % 3]]);
      }
    }
    return low;
  };
  for (int sweep = 0; sweep < kSweeps; ++sweep) {
    bool folded = false;
    for (std::uint32_t v : end.inner) {
      Vec3 up;
      double low = lowest(v, up);
      if (low > 0.0) continue;
      folded = true;
      double edge = 0.0;
      for (std::uint32_t t : faces_of[v])
        for (std::uint32_t u : triangles[t]) edge = std::max(edge, norm(x[u] - x[v]));
      double step = 0.25 * edge;
      for (int it = 0; it < kSteps && step > 1e-9 * edge && norm(up) > 0.0; ++it) {
        const Vec3 old = x[v];
        x[v] = old + (step / norm(up)) * up;
        Vec3 up2;
        const double low2 = lowest(v, up2);
        if (low2 > low) {
          low = low2;
          up = up2;
        } else {
          x[v] = old;
          step *= 0.5;
        }
      }
    }
    if (!folded) return;
  }
}

// True when a triangle flagged in `only` crosses another in frame `f` of `seq`.
bool crosses(const MeshSequence& seq, std::size_t f, const std::vector<char>& only) {
  return count_self_intersections_of({seq.positions[f], seq.triangles}, only) > 0;
}

// Flattens one end in every frame of `out` (a copy of the input sequence).
void flatten_end(MeshSequence& out, const Vec3& normal, const SurfaceEnd& end, const std::string& name,
                 const std::vector<std::vector<std::uint32_t>>& rings, const std::vector<std::uint32_t>& band,
                 double& ring_moved, double& band_moved, std::vector<double>& offsets, std::vector<int>& not_flat) {
  const std::size_t nv = out.positions.front().size(), frames = out.positions.size();
  std::vector<std::uint32_t> part = end.border;  // the vertices moved, to restore a frame whose flat face fails
  part.insert(part.end(), end.inner.begin(), end.inner.end());
  part.insert(part.end(), band.begin(), band.end());
  std::vector<std::vector<Vec3>> before(frames);
  for (std::size_t f = 0; f < frames; ++f)
    for (std::uint32_t v : part) before[f].push_back(out.positions[f][v]);
  std::vector<int> local(nv, -1);
  for (std::size_t i = 0; i < end.inner.size(); ++i) local[end.inner[i]] = static_cast<int>(i);
  std::vector<char> on_border(nv, 0);
  for (std::uint32_t v : end.border) on_border[v] = 1;
  lay_border_on_planes(out, normal, end, band, rings, offsets);
  const int n = static_cast<int>(end.inner.size());
  if (n > 0) {
    // Tutte: deg(i) x_i − Σ_inner x_j = Σ_border x_j, one factorisation, 3 columns per frame.
    SparseLdlt ldlt;
    if (!factor_uniform_laplacian(ldlt, rings, end.inner, local))
      throw SolverError(ErrorCode::Internal, {}, fmt::format("end '{}': the flat-face system is singular", name));
    const int columns = static_cast<int>(3 * frames);
    std::vector<double> b(static_cast<std::size_t>(n) * static_cast<std::size_t>(columns), 0.0), x(b.size());
    for (std::size_t f = 0; f < frames; ++f)
      for (int i = 0; i < n; ++i) {
        Vec3 sum;
        for (std::uint32_t j : rings[end.inner[static_cast<std::size_t>(i)]])
          if (on_border[j]) sum += out.positions[f][j];
        const std::size_t col = 3 * f, row = static_cast<std::size_t>(i), ld = static_cast<std::size_t>(n);
        b[(col + 0) * ld + row] = sum.x;
        b[(col + 1) * ld + row] = sum.y;
        b[(col + 2) * ld + row] = sum.z;
      }
    ldlt.solve(b.data(), x.data(), columns);
    for (std::size_t f = 0; f < frames; ++f)
      for (int i = 0; i < n; ++i) {
        const std::size_t col = 3 * f, row = static_cast<std::size_t>(i), ld = static_cast<std::size_t>(n);
        Vec3 p{x[(col + 0) * ld + row], x[(col + 1) * ld + row], x[(col + 2) * ld + row]};
        p = p - (dot(normal, p) - offsets[offsets.size() - frames + f]) * normal;  // rounding off the plane
        out.positions[f][end.inner[row]] = p;
      }
  }
  // A flat face must not fold: every triangle faces out of the cavity, along side · normal; nor may it or the
  // moved band cross the wall. Where it would (the frame-0 border far from one plane in that frame: a base that
  // moved to another slice), the frame keeps the end and the band as reconstructed, the end a face of its own.
  std::vector<char> moved(nv, 0), moved_triangles(out.triangles.size(), 0);
  for (std::uint32_t v : part) moved[v] = 1;
  for (std::size_t t = 0; t < out.triangles.size(); ++t)
    for (std::uint32_t v : out.triangles[t]) moved_triangles[t] = moved_triangles[t] || moved[v];
  std::vector<std::vector<std::uint32_t>> faces_of(nv);
  for (std::uint32_t t : end.triangles)
    for (std::uint32_t v : out.triangles[t]) faces_of[v].push_back(t);
  for (std::size_t f = 0; f < frames; ++f) {
    unfold_face(out.positions[f], out.triangles, end, normal, faces_of);
    const std::vector<Vec3>& x = out.positions[f];
    const bool folds = std::any_of(end.triangles.begin(), end.triangles.end(), [&](std::uint32_t t) {
      return facing(x, out.triangles[t], end.side, normal) <= 0.0;
    });
    if (folds || crosses(out, f, moved_triangles)) {
      for (std::size_t i = 0; i < part.size(); ++i) out.positions[f][part[i]] = before[f][i];
      not_flat.push_back(static_cast<int>(f));
      continue;
    }
    for (std::size_t i = 0; i < end.border.size(); ++i)
      ring_moved = std::max(ring_moved, norm(out.positions[f][part[i]] - before[f][i]));
    for (std::size_t i = part.size() - band.size(); i < part.size(); ++i)
      band_moved = std::max(band_moved, norm(out.positions[f][part[i]] - before[f][i]));
  }
  if (not_flat.size() == frames)
    throw InvalidInput(ErrorCode::InvertedElement, {},
                       fmt::format("the flat face of end '{}' folds in every frame: its border is too far from convex "
                                   "for a flat face",
                                   name),
                       "keep this end closed (--open without it)");
}

}  // namespace

FacedSequence open_ends(const MeshSequence& seq, const Vec3& normal, const std::vector<SurfaceEnd>& ends,
                        const std::vector<int>& open, const std::vector<std::string>& names) {
  FacedSequence r;
  r.seq = seq;
  r.face.assign(seq.triangles.size(), 0);
  r.names = {"wall"};
  const auto rings = vertex_neighbours(seq.positions.front().size(), seq.triangles);
  if (open.size() > 250)
    throw InvalidInput(ErrorCode::Usage, {}, fmt::format("{} ends to open: at most 250 faces", open.size()));
  for (std::size_t k = 0; k < open.size(); ++k) {
    const SurfaceEnd& end = ends.at(static_cast<std::size_t>(open[k]));
    const std::string name = k < names.size() ? names[k] : end.name;
    if (name.empty() || std::find(r.names.begin(), r.names.end(), name) != r.names.end() ||
        name.find_first_of(" /\\\t\"'") != std::string::npos)
      throw InvalidInput(ErrorCode::Usage, {},
                         fmt::format("face name '{}' is empty, repeated or not a plain word", name),
                         "give distinct names without spaces or slashes (--names base or --names inlet,outlet)");
    r.names.push_back(name);
    for (std::uint32_t t : end.triangles) r.face[t] = static_cast<std::uint8_t>(k + 1);
    double moved = 0.0, band_moved = 0.0;
    r.not_flat_frames.emplace_back();
    r.band.push_back(basal_band(r.seq, normal, end, rings));
    flatten_end(r.seq, normal, end, name, rings, r.band.back(), moved, band_moved, r.plane_offset_mm,
                r.not_flat_frames.back());
    r.ring_moved_mm.push_back(moved);
    r.band_moved_mm.push_back(band_moved);
  }
  return r;
}

}  // namespace c4d
