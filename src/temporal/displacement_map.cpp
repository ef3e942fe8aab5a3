// Base mesh + per-triangle displacement maps for tessellated playback.
//
// References:
//  - L. Miara et al., "New Method for 4D Reconstruction of Medical Images", §III.D–E: one base mesh
//    and a displacement map per time step, refined on the GPU by the tessellation unit.
//  - A. Vlachos, J. Peters, C. Boyd, J. L. Mitchell 2001, "Curved PN triangles": the cubic patch
//    from three corners and their normals (the shaders in src/render/patch_renderer.cpp repeat it).
//  - T. Möller, B. Trumbore 1997, "Fast, minimum storage ray/triangle intersection".
//  - A. Kapoulkine, meshoptimizer: meshopt_simplify (Garland & Heckbert quadrics) for the base mesh.
//
// Why the displacement is baked per frame: the fine mesh does not move rigidly with the base (the
// contours change shape), so one static map would drift; Miara et al. also keep one map per time.
#include "contour4d/temporal/displacement_map.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <string>

#include <meshoptimizer.h>
#include <tbb/parallel_for.h>

#include "contour4d/core/errors.h"
#include "contour4d/core/normals.h"

namespace c4d {
namespace {

// The cubic PN patch at weights w (sum 1) and its linearly interpolated unit normal.
void pn_eval(const Vec3 P[3], const Vec3 N[3], const double w[3], Vec3& pos, Vec3& nrm) {
  auto b = [&](int i, int j) { return (1.0 / 3.0) * (2.0 * P[i] + P[j] - dot(P[j] - P[i], N[i]) * N[i]); };
  const Vec3 b01 = b(0, 1), b10 = b(1, 0), b12 = b(1, 2), b21 = b(2, 1), b20 = b(2, 0), b02 = b(0, 2);
  const Vec3 E = (1.0 / 6.0) * (b01 + b10 + b12 + b21 + b20 + b02);
  const Vec3 V = (1.0 / 3.0) * (P[0] + P[1] + P[2]);
  const Vec3 b111 = E + 0.5 * (E - V);
  pos = w[0] * w[0] * w[0] * P[0] + w[1] * w[1] * w[1] * P[1] + w[2] * w[2] * w[2] * P[2] +
        3.0 * (w[0] * w[0] * w[1] * b01 + w[1] * w[1] * w[0] * b10 + w[1] * w[1] * w[2] * b12 +
               w[2] * w[2] * w[1] * b21 + w[2] * w[2] * w[0] * b20 + w[0] * w[0] * w[2] * b02) +
        6.0 * w[0] * w[1] * w[2] * b111;
  const Vec3 n = w[0] * N[0] + w[1] * N[1] + w[2] * N[2];
  const double l = norm(n);
  nrm = l > 0 ? (1.0 / l) * n : Vec3{0, 0, 1};
}

// Linear interpolation on the lattice of one triangle's map.
double lattice_value(const float* d, int g, double b1, double b2) {
  const double x = std::clamp(b1, 0.0, 1.0) * g, y = std::clamp(b2, 0.0, 1.0) * g;
  int i = std::min(static_cast<int>(std::floor(x)), g), j = std::min(static_cast<int>(std::floor(y)), g);
  if (i + j >= g) {  // on the far edge or rounding past it
    j = std::min(j, g);
    i = std::max(0, g - j);
    return d[patch_sample_index(g, i, j)];
  }
  const double fx = x - i, fy = y - j;
  if (fx + fy <= 1.0)
    return (1 - fx - fy) * d[patch_sample_index(g, i, j)] + fx * d[patch_sample_index(g, i + 1, j)] +
           fy * d[patch_sample_index(g, i, j + 1)];
  return (fx + fy - 1) * d[patch_sample_index(g, i + 1, j + 1)] + (1 - fy) * d[patch_sample_index(g, i + 1, j)] +
         (1 - fx) * d[patch_sample_index(g, i, j + 1)];
}

// Uniform grid over the triangles of one frame, for the normal-line queries of the bake.
struct TriangleGrid {
  Vec3 lo{};
  double cell = 1.0;
  int nx = 1, ny = 1, nz = 1;
  std::vector<std::uint32_t> start, items;

  int clampi(double v, int n) const { return std::clamp(static_cast<int>(std::floor(v)), 0, n - 1); }
  std::size_t id(int x, int y, int z) const { return (static_cast<std::size_t>(z) * ny + y) * nx + x; }

  void build(const std::vector<Vec3>& p, const std::vector<Triangle>& tris, double cell_mm) {
    Vec3 hi = p[0];
    lo = p[0];
    for (const Vec3& q : p)
      for (int c = 0; c < 3; ++c) {
        lo[c] = std::min(lo[c], q[c]);
        hi[c] = std::max(hi[c], q[c]);
      }
    cell = cell_mm;
    const double ext = std::max({hi.x - lo.x, hi.y - lo.y, hi.z - lo.z});
    cell = std::max(cell, ext / 200.0);  // at most 200 cells a side
    nx = static_cast<int>((hi.x - lo.x) / cell) + 1;
    ny = static_cast<int>((hi.y - lo.y) / cell) + 1;
    nz = static_cast<int>((hi.z - lo.z) / cell) + 1;
    std::vector<std::uint32_t> count(static_cast<std::size_t>(nx) * ny * nz + 1, 0);
    auto range = [&](const Triangle& t, std::array<int, 6>& r) {
      for (int c = 0; c < 3; ++c) {
        // Dilated by half a cell: line_hit samples its segment every half cell, so a sample lies
        // within a quarter cell of any crossing and its cell then lists the triangle.
        const double a = std::min({p[t[0]][c], p[t[1]][c], p[t[2]][c]}) - 0.5 * cell;
        const double b = std::max({p[t[0]][c], p[t[1]][c], p[t[2]][c]}) + 0.5 * cell;
        const int n = c == 0 ? nx : (c == 1 ? ny : nz);
        r[2 * c] = clampi((a - lo[c]) / cell, n);
        r[2 * c + 1] = clampi((b - lo[c]) / cell, n);
      }
    };
    std::array<int, 6> r{};
    for (int pass = 0; pass < 2; ++pass) {
      if (pass == 1) {
        start.assign(count.size(), 0);
        for (std::size_t i = 1; i < count.size(); ++i) start[i] = start[i - 1] + count[i - 1];
        items.assign(start.back(), 0);
        std::fill(count.begin(), count.end(), 0);
      }
      for (std::size_t t = 0; t < tris.size(); ++t) {
        range(tris[t], r);
        for (int z = r[4]; z <= r[5]; ++z)
          for (int y = r[2]; y <= r[3]; ++y)
            for (int x = r[0]; x <= r[1]; ++x) {
              const std::size_t c = id(x, y, z);
              if (pass == 1) items[start[c] + count[c]] = static_cast<std::uint32_t>(t);
              ++count[c];
            }
      }
    }
  }
};

// Signed distance s (|s| <= search, smallest |s|) at which the line o + s·n meets a triangle.
bool line_hit(const TriangleGrid& g, const std::vector<Vec3>& p, const std::vector<Triangle>& tris, const Vec3& o,
              const Vec3& n, double search, double& s_best) {
  std::array<std::size_t, 64> cells{};
  std::size_t nc = 0;
  const int steps = std::min(63, static_cast<int>(std::ceil(2.0 * search / (0.5 * g.cell))));
  for (int k = 0; k <= steps; ++k) {
    const Vec3 q = o + (-search + 2.0 * search * k / std::max(steps, 1)) * n;
    const std::size_t c = g.id(g.clampi((q.x - g.lo.x) / g.cell, g.nx), g.clampi((q.y - g.lo.y) / g.cell, g.ny),
                               g.clampi((q.z - g.lo.z) / g.cell, g.nz));
    if (std::find(cells.begin(), cells.begin() + static_cast<std::ptrdiff_t>(nc), c) ==
        cells.begin() + static_cast<std::ptrdiff_t>(nc))
      cells[nc++] = c;
  }
  bool hit = false;
  s_best = std::numeric_limits<double>::infinity();
  for (std::size_t ci = 0; ci < nc; ++ci)
    for (std::uint32_t i = g.start[cells[ci]]; i < g.start[cells[ci] + 1]; ++i) {
      const Triangle& t = tris[g.items[i]];
      const Vec3 e1 = p[t[1]] - p[t[0]], e2 = p[t[2]] - p[t[0]];
      const Vec3 h = cross(n, e2);
      const double det = dot(e1, h);
      if (std::abs(det) < 1e-14) continue;
      const Vec3 sv = o - p[t[0]];
      const double u = dot(sv, h) / det;
      if (u < -1e-9 || u > 1 + 1e-9) continue;
      const Vec3 qv = cross(sv, e1);
      const double v = dot(n, qv) / det;
      if (v < -1e-9 || u + v > 1 + 1e-9) continue;
      const double s = dot(e2, qv) / det;
      if (std::abs(s) <= search && std::abs(s) < std::abs(s_best)) {
        s_best = s;
        hit = true;
      }
    }
  return hit;
}

}  // namespace

Vec3 patch_point(const PatchMesh& pm, std::size_t frame, std::size_t tri, double b1, double b2, bool displaced) {
  const Triangle& t = pm.triangles.at(tri);
  const Vec3 P[3] = {pm.positions.at(frame)[t[0]], pm.positions[frame][t[1]], pm.positions[frame][t[2]]};
  const Vec3 N[3] = {pm.normals.at(frame)[t[0]], pm.normals[frame][t[1]], pm.normals[frame][t[2]]};
  const double w[3] = {1.0 - b1 - b2, b1, b2};
  Vec3 pos, nrm;
  pn_eval(P, N, w, pos, nrm);
  if (!displaced || pm.grid <= 0) return pos;
  const std::size_t S = patch_samples(pm.grid);
  const float* d = pm.displacement.data() + (frame * pm.triangles.size() + tri) * S;
  return pos + lattice_value(d, pm.grid, b1, b2) * nrm;
}

PatchMesh build_patch_mesh(const MeshSequence& fine, const PatchOptions& opt) {
  if (fine.positions.empty() || fine.positions[0].empty() || fine.triangles.empty())
    throw InvalidInput(ErrorCode::BadMesh, {}, "empty mesh sequence", "reconstruct a 4D mesh first");
  if (opt.grid < 1 || opt.grid > 64)
    throw InvalidInput(ErrorCode::Usage, {}, "displacement grid " + std::to_string(opt.grid) + " out of range",
                       "use 1..64 lattice steps per edge");
  const std::size_t nv = fine.positions[0].size(), nf = fine.positions.size();
  for (std::size_t f = 0; f < nf; ++f)
    if (fine.positions[f].size() != nv)
      throw InvalidInput(ErrorCode::BadMesh, {{}, -1, static_cast<int>(f)}, "frames differ in vertex count",
                         "all frames of a 4D mesh share vertices and triangles");
  std::vector<std::uint32_t> idx;
  for (const Triangle& t : fine.triangles)
    for (std::uint32_t v : t) {
      if (v >= nv) throw InvalidInput(ErrorCode::BadMesh, {}, "triangle index out of range", "the mesh is corrupt");
      idx.push_back(v);
    }
  std::vector<float> fp(nv * 3);
  for (std::size_t v = 0; v < nv; ++v)
    for (int c = 0; c < 3; ++c) fp[3 * v + c] = static_cast<float>(fine.positions[0][v][c]);
  std::vector<std::uint32_t> simple(idx.size());
  if (opt.base_triangles * 3 < idx.size())
    simple.resize(meshopt_simplify(simple.data(), idx.data(), idx.size(), fp.data(), nv, 12, opt.base_triangles * 3,
                                   1.0f, 0, nullptr));
  else
    simple = idx;
  PatchMesh pm;
  pm.grid = opt.grid;
  pm.times_ms = fine.times_ms;
  if (pm.times_ms.size() != nf) {
    pm.times_ms.clear();
    for (std::size_t f = 0; f < nf; ++f) pm.times_ms.push_back(static_cast<double>(f));
  }
  std::vector<std::uint32_t> remap(nv, ~0u);
  for (std::uint32_t v : simple)
    if (remap[v] == ~0u) {
      remap[v] = static_cast<std::uint32_t>(pm.fine_ids.size());
      pm.fine_ids.push_back(v);
    }
  for (std::size_t i = 0; i + 2 < simple.size(); i += 3)
    pm.triangles.push_back({remap[simple[i]], remap[simple[i + 1]], remap[simple[i + 2]]});
  const std::size_t nt = pm.triangles.size(), S = patch_samples(opt.grid);
  pm.displacement.assign(nf * nt * S, 0.0f);
  double mean_edge = 0.0;
  for (const Triangle& t : fine.triangles) mean_edge += distance(fine.positions[0][t[0]], fine.positions[0][t[1]]);
  mean_edge /= static_cast<double>(fine.triangles.size());
  double base_edge = 0.0;
  for (const Triangle& t : pm.triangles)
    base_edge += distance(fine.positions[0][pm.fine_ids[t[0]]], fine.positions[0][pm.fine_ids[t[1]]]);
  base_edge /= static_cast<double>(std::max<std::size_t>(nt, 1));
  // A coarse base departs from the fine surface by a fraction of its edge length.
  const double search = std::max(opt.search_mm, base_edge);
  std::vector<std::size_t> missed(nf, 0);
  std::vector<double> maxd(nf, 0.0);
  for (std::size_t f = 0; f < nf; ++f) {
    const std::vector<Vec3>& P = fine.positions[f];
    const std::vector<Vec3> N = area_weighted_normals(P, fine.triangles, Vec3{0, 0, 1});
    std::vector<Vec3> bp(pm.fine_ids.size()), bn(pm.fine_ids.size());
    for (std::size_t b = 0; b < bp.size(); ++b) {
      bp[b] = P[pm.fine_ids[b]];
      bn[b] = N[pm.fine_ids[b]];
    }
    pm.positions.push_back(bp);
    pm.normals.push_back(bn);
    TriangleGrid grid;
    grid.build(P, fine.triangles, std::max(2.0 * mean_edge, search / 4.0));
    std::vector<std::size_t> miss_t(nt, 0);
    std::vector<double> max_t(nt, 0.0);
    tbb::parallel_for(std::size_t{0}, nt, [&](std::size_t t) {
      const Triangle& tri = pm.triangles[t];
      const Vec3 Pc[3] = {bp[tri[0]], bp[tri[1]], bp[tri[2]]};
      const Vec3 Nc[3] = {bn[tri[0]], bn[tri[1]], bn[tri[2]]};
      float* d = pm.displacement.data() + (f * nt + t) * S;
      for (int j = 0; j <= opt.grid; ++j)
        for (int i = 0; i + j <= opt.grid; ++i) {
          const double w[3] = {1.0 - static_cast<double>(i + j) / opt.grid, static_cast<double>(i) / opt.grid,
                               static_cast<double>(j) / opt.grid};
          Vec3 o, n;
          pn_eval(Pc, Nc, w, o, n);
          double s = 0.0;
          if (!line_hit(grid, P, fine.triangles, o, n, search, s)) {
            s = std::numeric_limits<double>::quiet_NaN();
            ++miss_t[t];
          } else {
            max_t[t] = std::max(max_t[t], std::abs(s));
          }
          d[patch_sample_index(opt.grid, i, j)] = static_cast<float>(s);
        }
      // A missed sample takes the mean of its lattice neighbours that hit (a hole in the map would
      // show as a pit of the patch's distance to the surface); none at all: 0.
      for (int pass = 0; pass <= opt.grid && miss_t[t] > 0; ++pass) {
        bool changed = false;
        for (int j = 0; j <= opt.grid; ++j)
          for (int i = 0; i + j <= opt.grid; ++i) {
            float& x = d[patch_sample_index(opt.grid, i, j)];
            if (!std::isnan(x)) continue;
            const int nb[6][2] = {{i + 1, j}, {i - 1, j}, {i, j + 1}, {i, j - 1}, {i + 1, j - 1}, {i - 1, j + 1}};
            double sum = 0.0;
            int cnt = 0;
            for (const auto& q : nb)
              if (q[0] >= 0 && q[1] >= 0 && q[0] + q[1] <= opt.grid) {
                const float y = d[patch_sample_index(opt.grid, q[0], q[1])];
                if (!std::isnan(y)) {
                  sum += y;
                  ++cnt;
                }
              }
            if (cnt > 0) {
              x = static_cast<float>(sum / cnt);
              changed = true;
            }
          }
        if (!changed) break;
      }
      for (std::size_t k = 0; k < S; ++k)
        if (std::isnan(d[k])) d[k] = 0.0f;
    });
    for (std::size_t t = 0; t < nt; ++t) {
      missed[f] += miss_t[t];
      maxd[f] = std::max(maxd[f], max_t[t]);
    }
  }
  for (std::size_t f = 0; f < nf; ++f) {
    pm.missed += missed[f];
    pm.max_abs_displacement = std::max(pm.max_abs_displacement, maxd[f]);
  }
  return pm;
}

MeshSequence tessellate_patches(const PatchMesh& pm, int level) {
  if (level < 1 || level > 64)
    throw InvalidInput(ErrorCode::Usage, {}, "tessellation level " + std::to_string(level) + " out of range",
                       "use 1..64");
  MeshSequence out;
  out.times_ms = pm.times_ms;
  // Lattice point (t, i, j) -> shared vertex: corners by base vertex, edge points by (edge, step).
  std::map<std::array<std::uint64_t, 3>, std::uint32_t> ids;
  struct Sample {
    std::uint32_t tri;
    double b1, b2;
  };
  std::vector<Sample> samples;
  const std::uint64_t L = static_cast<std::uint64_t>(level);
  auto vertex = [&](std::size_t t, int i, int j) {
    const Triangle& tri = pm.triangles[t];
    std::array<std::uint64_t, 3> key{};
    const int k = level - i - j;  // weight of corner 0, in steps
    auto edge = [&](std::uint32_t a, std::uint32_t b, std::uint64_t steps_from_a) {
      return a < b ? std::array<std::uint64_t, 3>{1, (std::uint64_t{a} << 32) | b, steps_from_a}
                   : std::array<std::uint64_t, 3>{1, (std::uint64_t{b} << 32) | a, L - steps_from_a};
    };
    if (i == 0 && j == 0)
      key = {0, tri[0], 0};
    else if (i == level)
      key = {0, tri[1], 0};
    else if (j == level)
      key = {0, tri[2], 0};
    else if (j == 0)
      key = edge(tri[0], tri[1], static_cast<std::uint64_t>(i));
    else if (i == 0)
      key = edge(tri[0], tri[2], static_cast<std::uint64_t>(j));
    else if (k == 0)
      key = edge(tri[1], tri[2], static_cast<std::uint64_t>(j));
    else
      key = {2, t, (static_cast<std::uint64_t>(i) << 32) | static_cast<std::uint64_t>(j)};
    auto [it, fresh] = ids.emplace(key, static_cast<std::uint32_t>(samples.size()));
    if (fresh)
      samples.push_back(
          {static_cast<std::uint32_t>(t), static_cast<double>(i) / level, static_cast<double>(j) / level});
    return it->second;
  };
  for (std::size_t t = 0; t < pm.triangles.size(); ++t)
    for (int j = 0; j < level; ++j)
      for (int i = 0; i + j < level; ++i) {
        out.triangles.push_back({vertex(t, i, j), vertex(t, i + 1, j), vertex(t, i, j + 1)});
        if (i + j + 2 <= level)
          out.triangles.push_back({vertex(t, i + 1, j), vertex(t, i + 1, j + 1), vertex(t, i, j + 1)});
      }
  out.positions.resize(pm.positions.size());
  for (std::size_t f = 0; f < pm.positions.size(); ++f) {
    out.positions[f].resize(samples.size());
    for (std::size_t s = 0; s < samples.size(); ++s)
      out.positions[f][s] = patch_point(pm, f, samples[s].tri, samples[s].b1, samples[s].b2);
  }
  return out;
}

}  // namespace c4d
