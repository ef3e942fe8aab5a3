// Optimisation-based smoothing of small angles (Freitag & Ollivier-Gooch, "Tetrahedral mesh
// improvement using swapping and smoothing", 1997, applied to triangles on a surface): the local
// quality step that Lim et al. 2014 ask for where triangle quality degrades ("Surface Smoothing and
// Refinement"; "4D Morphing of the Heart Model"). Laplacian-type relaxation makes the ring even, but
// where the surface is stretched one way and squeezed the other (a saddle forming as contours split)
// its equilibrium still leaves thin triangles; maximising the ring's smallest angle directly removes
// most of them. Only vertices of bad triangles move, so the rest of the mesh is untouched.
#include "contour4d/surface/angle_repair.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <optional>
#include <span>
#include <unordered_map>
#include <utility>
#include <vector>

#include "contour4d/metrics/topology.h"

namespace c4d {

namespace {

// The cosine of the smallest angle of triangle (a, b, c), clamped to [−1, 1]; 1 when degenerate.
double smallest_angle_cos(Vec3 a, Vec3 b, Vec3 c) {
  const double la = distance(b, c), lb = distance(c, a), lc = distance(a, b);
  if (!(la > 0 && lb > 0 && lc > 0)) return 1.0;
  // The smallest angle faces the shortest side.
  double s = la, p = lb, q = lc;
  if (p < s) std::swap(s, p);
  if (q < s) std::swap(s, q);
  return std::clamp((p * p + q * q - s * s) / (2 * p * q), -1.0, 1.0);
}

double cos_to_deg(double cosv) { return std::acos(cosv) * 180.0 / std::numbers::pi; }

}  // namespace

double min_angle_deg(Vec3 a, Vec3 b, Vec3 c) { return cos_to_deg(smallest_angle_cos(a, b, c)); }

namespace {

Vec3 face_normal(const std::vector<Vec3>& x, const Triangle& t) { return cross(x[t[1]] - x[t[0]], x[t[2]] - x[t[0]]); }

// Triangles binned by the cells their bounding boxes touch: the candidates that a moved vertex's
// triangles could cut through. A dense block of cells over the triangles' extent, each with its
// triangles in one flat array (count, prefix sum, fill: no hashing, no per-cell allocation); boxes
// beyond the block are clamped onto its border cells.
struct TriangleGrid {
  double cell = 1.0;
  std::int64_t lo[3] = {0, 0, 0}, size[3] = {0, 0, 0};
  std::vector<std::uint32_t> start;  // per cell, into items; one more at the end
  std::vector<std::uint32_t> items;  // triangles, cell by cell, each cell's in increasing order
  // The cell index along one axis, floor(v / cell) clamped far beyond any mesh (so that the conversion
  // stays defined); the floor by truncation, which equals std::floor on that range.
  std::int64_t at(double v) const {
    const double q = std::clamp(v / cell, -1e15, 1e15);
    auto t = static_cast<std::int64_t>(q);
    if (static_cast<double>(t) > q) --t;
    return t;
  }
  // The block's cells that the box [a, b] touches, as index ranges from[d]..to[d] per axis (clamped into
  // the block at both ends: a monotone map, so boxes that overlap meet a common cell, also a box that
  // moved out of the block since binning).
  struct Range {
    std::int64_t from[3], to[3];
  };
  Range range(Vec3 a, Vec3 b) const {
    auto in = [&](std::int64_t c, int d) { return std::clamp(c, lo[d], lo[d] + size[d] - 1); };
    return {{in(at(a.x), 0), in(at(a.y), 1), in(at(a.z), 2)}, {in(at(b.x), 0), in(at(b.y), 1), in(at(b.z), 2)}};
  }
  // Calls f(cell index) for every cell of a range.
  template <class F>
  void visit(const Range& r, F&& f) const {
    for (std::int64_t i = r.from[0]; i <= r.to[0]; ++i)
      for (std::int64_t j = r.from[1]; j <= r.to[1]; ++j)
        for (std::int64_t k = r.from[2]; k <= r.to[2]; ++k)
          f(static_cast<std::size_t>(((i - lo[0]) * size[1] + (j - lo[1])) * size[2] + (k - lo[2])));
  }
  // The same for the box [a, b].
  template <class F>
  void visit(Vec3 a, Vec3 b, F&& f) const {
    visit(range(a, b), f);
  }
};

void grow(Vec3& lo, Vec3& hi, Vec3 p) {
  lo = {std::min(lo.x, p.x), std::min(lo.y, p.y), std::min(lo.z, p.z)};
  hi = {std::max(hi.x, p.x), std::max(hi.y, p.y), std::max(hi.z, p.z)};
}

TriangleGrid bin_triangles(const std::vector<Vec3>& x, const std::vector<Triangle>& triangles) {
  TriangleGrid g;
  std::vector<double> lengths;
  lengths.reserve(triangles.size());
  for (const Triangle& t : triangles) lengths.push_back(distance(x[t[0]], x[t[1]]));
  if (!lengths.empty()) {
    std::nth_element(lengths.begin(), lengths.begin() + static_cast<std::ptrdiff_t>(lengths.size() / 2), lengths.end());
    g.cell = std::max(1e-6, 2.0 * lengths[lengths.size() / 2]);
  }
  // Each finite triangle's box, and the extent of them all.
  std::vector<std::array<Vec3, 2>> boxes(triangles.size());
  std::vector<char> finite(triangles.size(), 0);
  Vec3 all_lo{1e300, 1e300, 1e300}, all_hi{-1e300, -1e300, -1e300};
  for (std::size_t f = 0; f < triangles.size(); ++f) {
    Vec3 lo{1e300, 1e300, 1e300}, hi{-1e300, -1e300, -1e300};
    for (std::uint32_t w : triangles[f]) grow(lo, hi, x[w]);
    if (!is_finite(lo) || !is_finite(hi)) continue;
    boxes[f] = {lo, hi};
    finite[f] = 1;
    grow(all_lo, all_hi, lo);
    grow(all_lo, all_hi, hi);
  }
  if (!(all_lo.x <= all_hi.x)) return g;  // no finite triangle: an empty block
  // The cell doubles until the block holds at most 8 cells per triangle (or 4096): a coarser cell only
  // adds candidates, and the test on them is exact.
  for (;;) {
    g.lo[0] = g.at(all_lo.x), g.lo[1] = g.at(all_lo.y), g.lo[2] = g.at(all_lo.z);
    g.size[0] = g.at(all_hi.x) - g.lo[0] + 1, g.size[1] = g.at(all_hi.y) - g.lo[1] + 1,
    g.size[2] = g.at(all_hi.z) - g.lo[2] + 1;
    const double cells =
        static_cast<double>(g.size[0]) * static_cast<double>(g.size[1]) * static_cast<double>(g.size[2]);
    if (cells <= std::max(4096.0, 8.0 * static_cast<double>(triangles.size()))) break;
    g.cell *= 2.0;
  }
  const auto ncells = static_cast<std::size_t>(g.size[0] * g.size[1] * g.size[2]);
  g.start.assign(ncells + 1, 0);
  std::vector<TriangleGrid::Range> ranges(triangles.size());  // each triangle's cells, found once
  for (std::size_t f = 0; f < triangles.size(); ++f)
    if (finite[f]) {
      ranges[f] = g.range(boxes[f][0], boxes[f][1]);
      g.visit(ranges[f], [&](std::size_t c) { ++g.start[c + 1]; });
    }
  for (std::size_t c = 0; c < ncells; ++c) g.start[c + 1] += g.start[c];
  g.items.resize(g.start[ncells]);
  std::vector<std::uint32_t> fill(g.start.begin(), g.start.end() - 1);
  for (std::size_t f = 0; f < triangles.size(); ++f)
    if (finite[f]) g.visit(ranges[f], [&](std::size_t c) { g.items[fill[c]++] = static_cast<std::uint32_t>(f); });
  return g;
}

// Triangles moved since binning, listed once by each cell their boxes met when they moved (earlier
// places stay listed: a candidate too many is only tested).
using MovedCells = std::unordered_map<std::size_t, std::vector<std::uint32_t>>;

void list_moved(const std::vector<Vec3>& x, const std::vector<Triangle>& triangles, std::span<const std::uint32_t> fs,
                const TriangleGrid& grid, MovedCells& moved) {
  for (std::uint32_t f : fs) {
    Vec3 lo{1e300, 1e300, 1e300}, hi{-1e300, -1e300, -1e300};
    for (std::uint32_t w : triangles[f]) grow(lo, hi, x[w]);
    if (!is_finite(lo) || !is_finite(hi)) continue;
    grid.visit(lo, hi, [&](std::size_t c) {
      std::vector<std::uint32_t>& list = moved[c];
      if (std::find(list.begin(), list.end(), f) == list.end()) list.push_back(f);
    });
  }
}

// Candidates for ring_intersects: each triangle once (`seen` holds the call's stamp), and only those whose box
// meets the ring's (no other can cross it).
struct NearTriangles {
  std::vector<std::uint32_t> seen;  // per triangle, the stamp of the last call that listed it
  std::uint32_t stamp = 0;
  std::vector<std::uint32_t> list;
};

// True when one of `fs` (the triangles of a vertex at its new position) intersects a triangle of
// the grid or of `moved` other than through a shared vertex or edge.
bool ring_intersects(const std::vector<Vec3>& x, const std::vector<Triangle>& triangles,
                     std::span<const std::uint32_t> fs, const TriangleGrid& grid, const MovedCells& moved,
                     NearTriangles& near) {
  Vec3 lo{1e300, 1e300, 1e300}, hi{-1e300, -1e300, -1e300};
  for (std::uint32_t f : fs)
    for (std::uint32_t w : triangles[f]) grow(lo, hi, x[w]);
  near.seen.resize(triangles.size(), 0);
  if (++near.stamp == 0) {  // wrapped: forget every stamp
    std::fill(near.seen.begin(), near.seen.end(), 0);
    near.stamp = 1;
  }
  near.list.clear();
  auto consider = [&](std::uint32_t g) {
    if (g >= triangles.size() || near.seen[g] == near.stamp) return;
    near.seen[g] = near.stamp;
    Vec3 glo{1e300, 1e300, 1e300}, ghi{-1e300, -1e300, -1e300};
    for (std::uint32_t w : triangles[g])
      if (w < x.size()) grow(glo, ghi, x[w]);
    // Closed boxes; a box with a NaN corner is kept (intersects_any decides about it).
    if (glo.x > hi.x || ghi.x < lo.x || glo.y > hi.y || ghi.y < lo.y || glo.z > hi.z || ghi.z < lo.z) return;
    near.list.push_back(g);
  };
  // The triangles of the vertices being tried may have moved since binning: widen the box by half a cell.
  const Vec3 pad{0.5 * grid.cell, 0.5 * grid.cell, 0.5 * grid.cell};
  grid.visit(lo - pad, hi + pad, [&](std::size_t c) {
    for (std::uint32_t k = grid.start[c]; k < grid.start[c + 1]; ++k) consider(grid.items[k]);
    if (const auto it = moved.find(c); it != moved.end())
      for (std::uint32_t g : it->second) consider(g);
  });
  return intersects_any(x, triangles, std::vector<std::uint32_t>(fs.begin(), fs.end()), near.list);
}

// The eight steps of the search (cos, sin of d·π/4), worked out once.
const std::array<std::array<double, 2>, 8> kCompass = [] {
  std::array<std::array<double, 2>, 8> c{};
  for (int d = 0; d < 8; ++d) {
    const double a = d * std::numbers::pi / 4.0;
    c[static_cast<std::size_t>(d)] = {std::cos(a), std::sin(a)};
  }
  return c;
}();

// Below this smallest angle (degrees) a triangle is a sliver (see optimise).
constexpr double kSliverDeg = 5.0;

// The triangles of each vertex, in increasing order (CSR).
struct VertexTriangles {
  std::vector<std::uint32_t> start, items;
  VertexTriangles(std::size_t nv, const std::vector<Triangle>& triangles)
      : start(nv + 1, 0), items(3 * triangles.size()) {
    for (const Triangle& t : triangles)
      for (std::uint32_t v : t) ++start[v + 1];
    for (std::size_t v = 0; v < nv; ++v) start[v + 1] += start[v];
    std::vector<std::uint32_t> fill(start.begin(), start.end() - 1);
    for (std::size_t f = 0; f < triangles.size(); ++f)
      for (std::uint32_t v : triangles[f]) items[fill[v]++] = static_cast<std::uint32_t>(f);
  }
  std::span<const std::uint32_t> operator[](std::size_t v) const {
    return {items.data() + start[v], items.data() + start[v + 1]};
  }
};

std::size_t optimise(std::vector<Vec3>& positions, const std::vector<Triangle>& triangles, const VertexTriangles& ring,
                     const std::vector<char>& fixed, const SurfaceSnap& snap, const AngleRepairOptions& options) {
  const double cos_fold = 0.5;  // a ring triangle may turn by at most 60°
  std::size_t moves = 0;
  // Active set: after the first pass, a vertex is tried again only if it or a vertex of its ring
  // moved in the previous pass (else its ring is unchanged and the search would fail again).
  std::vector<char> moved(positions.size(), 1);
  // Binned once, when a move is first to be checked; the triangles moved since are listed beside it.
  std::optional<TriangleGrid> grid;
  MovedCells moved_cells;
  NearTriangles near;
  for (int pass = 0; pass < options.passes; ++pass) {
    std::vector<char> active(positions.size(), 0);
    for (std::size_t v = 0; v < positions.size(); ++v)
      if (moved[v])
        for (std::uint32_t f : ring[v])
          for (std::uint32_t w : triangles[f]) active[w] = 1;
    std::vector<std::uint32_t> todo;
    for (const Triangle& t : triangles)
      if ((active[t[0]] || active[t[1]] || active[t[2]]) &&
          min_angle_deg(positions[t[0]], positions[t[1]], positions[t[2]]) < options.target_deg)
        for (std::uint32_t v : t)
          if (!fixed[v] && active[v]) todo.push_back(v);
    std::fill(moved.begin(), moved.end(), 0);
    std::sort(todo.begin(), todo.end());
    todo.erase(std::unique(todo.begin(), todo.end()), todo.end());
    if (todo.empty()) break;
    std::size_t pass_moves = 0;
    for (std::uint32_t v : todo) {
      const std::span<const std::uint32_t> fs = ring[v];
      if (fs.empty()) continue;
      std::vector<Vec3> n0;
      Vec3 n{};
      double len = 0;
      int edges = 0;
      for (std::uint32_t f : fs) {
        n0.push_back(face_normal(positions, triangles[f]));
        n += n0.back();
        for (std::uint32_t w : triangles[f])
          if (w != v) {
            len += distance(positions[w], positions[v]);
            ++edges;
          }
      }
      if (norm(n) <= 0 || edges == 0) continue;
      n = normalized(n);
      len /= edges;
      // A sliver's own normal is noise (a 173° triangle turns over with a tiny move of its middle
      // vertex): the fold test of its triangles uses the vertex normal instead, so that opening it
      // towards the surface's side is allowed and opening it inside out is not.
      for (std::size_t k = 0; k < fs.size(); ++k) {
        const Triangle& t = triangles[fs[k]];
        if (min_angle_deg(positions[t[0]], positions[t[1]], positions[t[2]]) < kSliverDeg) n0[k] = n;
      }
      // Tangent basis.
      const Vec3 helper = std::abs(n.x) < 0.9 ? Vec3{1, 0, 0} : Vec3{0, 1, 0};
      const Vec3 e1 = normalized(cross(n, helper)), e2 = cross(n, e1);
      auto quality = [&](Vec3 p) {
        const Vec3 keep = positions[v];
        positions[v] = p;
        // The ring's smallest angle: one arccosine, of the largest cosine (the arccosine decreases).
        double largest_cos = -1.0;
        bool folds = false;
        for (std::size_t k = 0; k < fs.size() && !folds; ++k) {
          const Triangle& t = triangles[fs[k]];
          const Vec3 nk = face_normal(positions, t);
          const double a = norm(nk), b = norm(n0[k]);
          folds = !(a > 0) || dot(nk, n0[k]) < cos_fold * a * b;
          largest_cos = std::max(largest_cos, smallest_angle_cos(positions[t[0]], positions[t[1]], positions[t[2]]));
        }
        positions[v] = keep;
        return folds ? -1.0 : cos_to_deg(largest_cos);
      };
      Vec3 best = positions[v];
      double best_q = quality(best);
      const double start_q = best_q;
      double h = options.first_step * len;
      for (int step = 0; step < options.steps && h > 1e-4 * len; ++step) {
        Vec3 cand_best = best;
        double cand_q = best_q;
        for (const auto& [cd, sd] : kCompass) {
          const Vec3 want = best + h * (cd * e1 + sd * e2);
          const Vec3 c = snap(v, want);
          // A snap that lands far from the step went to another sheet of the surface (across a
          // narrow gap): never follow it.
          if (!is_finite(c) || distance(c, want) > 0.5 * h) continue;
          const double q = quality(c);
          if (q > cand_q + 1e-9) {
            cand_q = q;
            cand_best = c;
          }
        }
        if (cand_q > best_q) {
          best = cand_best;
          best_q = cand_q;
        } else {
          h *= 0.5;
        }
      }
      if (best_q > start_q + 1e-9) {
        // The ring at its new place may not cut through another part of the surface; else try
        // shorter moves towards it.
        const Vec3 from = positions[v];
        for (double f : {1.0, 0.5, 0.25}) {
          const Vec3 c = f == 1.0 ? best : snap(v, from + f * (best - from));
          if (!is_finite(c) || quality(c) <= start_q + 1e-9) continue;
          positions[v] = c;
          if (!grid) grid = bin_triangles(positions, triangles);
          if (!ring_intersects(positions, triangles, fs, *grid, moved_cells, near)) {
            ++pass_moves;
            moved[v] = 1;
            list_moved(positions, triangles, fs, *grid, moved_cells);
            break;
          }
          positions[v] = from;
        }
      }
    }
    moves += pass_moves;
    if (pass_moves == 0) break;
  }
  return moves;
}

}  // namespace

std::size_t repair_small_angles(std::vector<Vec3>& positions, const std::vector<Triangle>& triangles,
                                const std::vector<char>& fixed, const SurfaceSnap& snap,
                                const AngleRepairOptions& options) {
  const std::size_t nv = positions.size();
  const VertexTriangles ring(nv, triangles);
  std::vector<char> frozen(fixed.begin(), fixed.end());
  frozen.resize(nv, 0);
  return optimise(positions, triangles, ring, frozen, snap, options);
}

std::size_t untangle(std::vector<Vec3>& positions, const std::vector<Triangle>& triangles,
                     const std::vector<char>& fixed, const SurfaceSnap& snap, int rounds) {
  // The full intersection test costs more than the rest of a morphed frame: it runs only where a
  // triangle is a sliver (below 15°), the mark of a crowded, folding patch.
  bool suspect = false;
  for (const Triangle& t : triangles)
    if (min_angle_deg(positions[t[0]], positions[t[1]], positions[t[2]]) < 15.0) {
      suspect = true;
      break;
    }
  if (!suspect) return 0;
  const std::size_t nv = positions.size();
  const auto nb = vertex_neighbours(nv, triangles);
  std::size_t left = 0;
  for (int round = 0; round <= rounds; ++round) {
    const TriangleMesh mesh{positions, triangles};
    std::vector<std::pair<std::size_t, std::size_t>> pairs;
    left = count_self_intersections(mesh, &pairs, triangles.size());
    if (left == 0 || round == rounds) break;
    // The vertices of the intersecting triangles and two rings around them.
    std::vector<char> in(nv, 0);
    for (const auto& [i, j] : pairs)
      for (std::size_t f : {i, j})
        for (std::uint32_t v : triangles[f]) in[v] = 1;
    for (int layer = 0; layer < 2; ++layer) {
      std::vector<char> next = in;
      for (std::size_t v = 0; v < nv; ++v)
        if (in[v])
          for (std::uint32_t w : nb[v]) next[w] = 1;
      in = std::move(next);
    }
    std::vector<std::uint32_t> region;
    for (std::size_t v = 0; v < nv; ++v)
      if (in[v] && !(v < fixed.size() && fixed[v]) && !nb[v].empty()) region.push_back(static_cast<std::uint32_t>(v));
    // Umbrella steps within the surface: folded, crowded patches open up.
    for (int it = 0; it < 10; ++it) {
      std::vector<Vec3> next(region.size());
      for (std::size_t k = 0; k < region.size(); ++k) {
        const std::uint32_t v = region[k];
        Vec3 c{};
        for (std::uint32_t w : nb[v]) c += positions[w];
        next[k] = snap(v, c / static_cast<double>(nb[v].size()));
      }
      for (std::size_t k = 0; k < region.size(); ++k)
        if (is_finite(next[k])) positions[region[k]] = next[k];
    }
  }
  return left;
}

}  // namespace c4d
