// Compact 4D model: base mesh + motion of few control vertices + bounded sparse corrections.
//
// References:
//  - L. Miara, S. Benomar Elmdeghri, M. O. Cherkaoui Malki, "New Method for 4D Reconstruction of
//    Medical Images", §III.D–E and Table I: one base mesh, per-frame displacement data, small storage.
//  - A. Kapoulkine, meshoptimizer: vertex-cache/fetch reordering, index and vertex codecs, and
//    meshopt_simplify (Garland & Heckbert 1997 quadrics) for the base (control) vertices.
//  - D. Levin 1998, "The approximation power of moving least-squares": linear-precision MLS weights,
//    so affine motion (pulsation, small twist) is carried exactly by the control vertices.
//
// Why not a per-triangle displacement map: our fine meshes come from contour tiling, not from
// subdividing a base mesh, so a barycentric grid cannot restore their exact vertices. The fine frame
// 0 is stored once instead; the motion, which is smooth, is what the few control vertices carry.
#include "contour4d/temporal/compact.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numeric>
#include <string>

#include <Eigen/Dense>
#include <meshoptimizer.h>
#include <tbb/parallel_for.h>

#include "contour4d/core/errors.h"
#include "contour4d/core/normals.h"

namespace c4d {
namespace {

[[noreturn]] void bad(const std::string& what, const std::string& hint, int frame = -1) {
  Location where;
  where.frame = frame;
  throw InvalidInput(ErrorCode::BadMesh, where, what, hint);
}

void put_varint(std::vector<std::uint8_t>& out, std::uint64_t v) {
  while (v >= 0x80) {
    out.push_back(static_cast<std::uint8_t>(v | 0x80));
    v >>= 7;
  }
  out.push_back(static_cast<std::uint8_t>(v));
}

std::uint64_t get_varint(const std::vector<std::uint8_t>& in, std::size_t& pos) {
  std::uint64_t v = 0;
  for (int shift = 0; shift < 64; shift += 7) {
    if (pos >= in.size()) bad("truncated correction stream", "the file is damaged: pack it again");
    const std::uint8_t b = in[pos++];
    v |= static_cast<std::uint64_t>(b & 0x7f) << shift;
    if ((b & 0x80) == 0) return v;
  }
  bad("overlong varint in correction stream", "the file is damaged: pack it again");
}

std::uint64_t zigzag(std::int64_t v) {
  return (static_cast<std::uint64_t>(v) << 1) ^ static_cast<std::uint64_t>(v >> 63);
}
std::int64_t unzigzag(std::uint64_t v) { return static_cast<std::int64_t>(v >> 1) ^ -static_cast<std::int64_t>(v & 1); }

void validate(const MeshSequence& seq) {
  if (seq.positions.empty()) bad("the mesh sequence has no frames", "reconstruct a 4D mesh first");
  const std::size_t n = seq.positions[0].size();
  if (n == 0 || seq.triangles.empty()) bad("the mesh sequence is empty", "reconstruct a 4D mesh first");
  if (n > std::numeric_limits<std::uint32_t>::max() / 2) bad("too many vertices", "split the mesh");
  for (std::size_t f = 0; f < seq.positions.size(); ++f) {
    if (seq.positions[f].size() != n)
      bad("frame has " + std::to_string(seq.positions[f].size()) + " vertices, frame 0 has " + std::to_string(n),
          "all frames of a 4D mesh must share vertices and triangles", static_cast<int>(f));
    for (const Vec3& p : seq.positions[f])
      if (!is_finite(p)) bad("non-finite vertex coordinate", "check the reconstruction", static_cast<int>(f));
  }
  for (const Triangle& t : seq.triangles)
    for (std::uint32_t i : t)
      if (i >= n) bad("triangle index " + std::to_string(i) + " out of range", "the triangle list is corrupt");
  if (!seq.times_ms.empty() && seq.times_ms.size() != seq.positions.size())
    bad("times_ms has " + std::to_string(seq.times_ms.size()) + " entries for " + std::to_string(seq.positions.size()) +
            " frames",
        "give one time per frame");
}

// Deterministic prediction of every vertex of one frame from the control displacements.
void predict(const std::vector<Vec3>& base, const ControlWeights& w, const std::vector<Vec3>& control_disp,
             std::vector<Vec3>& out) {
  out.resize(base.size());
  const std::size_t k = static_cast<std::size_t>(w.k);
  for (std::size_t v = 0; v < base.size(); ++v) {
    Vec3 d{};
    for (std::size_t j = 0; j < k; ++j) d += static_cast<double>(w.weights[v * k + j]) * control_disp[w.ids[v * k + j]];
    out[v] = base[v] + d;
  }
}

// Closest-point distance from p to triangle abc (Ericson, Real-Time Collision Detection §5.1.5).
double point_triangle_distance(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 ab = b - a, ac = c - a, ap = p - a;
  const double d1 = dot(ab, ap), d2 = dot(ac, ap);
  if (d1 <= 0 && d2 <= 0) return norm(ap);
  const Vec3 bp = p - b;
  const double d3 = dot(ab, bp), d4 = dot(ac, bp);
  if (d3 >= 0 && d4 <= d3) return norm(bp);
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return distance(p, a + (d1 / (d1 - d3)) * ab);
  const Vec3 cp = p - c;
  const double d5 = dot(ab, cp), d6 = dot(ac, cp);
  if (d6 >= 0 && d5 <= d6) return norm(cp);
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return distance(p, a + (d2 / (d2 - d6)) * ac);
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0)
    return distance(p, b + ((d4 - d3) / ((d4 - d3) + (d5 - d6))) * (c - b));
  const double den = va + vb + vc;
  if (!(std::abs(den) > 0)) return std::min({norm(ap), norm(bp), norm(cp)});  // degenerate triangle
  return distance(p, a + (vb / den) * ab + (vc / den) * ac);
}

// Triangles within two rings of every vertex (CSR): the part of a frame's surface a vertex may
// slide over. A distance to this subset bounds the distance to the whole surface from above.
struct TriangleRings {
  std::vector<std::uint32_t> start, tris;
};

TriangleRings triangle_rings(std::size_t nv, const std::vector<Triangle>& triangles) {
  std::vector<std::vector<std::uint32_t>> incident(nv);
  for (std::size_t t = 0; t < triangles.size(); ++t)
    for (std::uint32_t v : triangles[t]) incident[v].push_back(static_cast<std::uint32_t>(t));
  TriangleRings r;
  r.start.push_back(0);
  std::vector<std::uint32_t> set;
  for (std::size_t v = 0; v < nv; ++v) {
    set.clear();
    for (std::uint32_t t : incident[v])
      for (std::uint32_t u : triangles[t]) set.insert(set.end(), incident[u].begin(), incident[u].end());
    std::sort(set.begin(), set.end());
    set.erase(std::unique(set.begin(), set.end()), set.end());
    r.tris.insert(r.tris.end(), set.begin(), set.end());
    r.start.push_back(static_cast<std::uint32_t>(r.tris.size()));
  }
  return r;
}

double ring_distance(const TriangleRings& r, const std::vector<Triangle>& triangles, const std::vector<Vec3>& surface,
                     std::size_t v, const Vec3& p) {
  double best = std::numeric_limits<double>::infinity();
  for (std::uint32_t i = r.start[v]; i < r.start[v + 1]; ++i) {
    const Triangle& t = triangles[r.tris[i]];
    best = std::min(best, point_triangle_distance(p, surface[t[0]], surface[t[1]], surface[t[2]]));
  }
  return best;
}

std::vector<Vec3> decode_positions(const CompactModel& m) {
  std::vector<std::uint16_t> q(static_cast<std::size_t>(m.vertex_count) * 4);
  if (meshopt_decodeVertexBuffer(q.data(), m.vertex_count, 8, m.positions.data(), m.positions.size()) != 0)
    bad("corrupt position stream", "the file is damaged: pack it again");
  std::vector<Vec3> p(m.vertex_count);
  for (std::size_t v = 0; v < p.size(); ++v)
    p[v] = {m.origin[0] + q[4 * v] * m.grid_step, m.origin[1] + q[4 * v + 1] * m.grid_step,
            m.origin[2] + q[4 * v + 2] * m.grid_step};
  return p;
}

std::vector<Vec3> decode_motion(const CompactModel& m, std::size_t frame) {
  // Decoded whole once per call; callers cache (decode is done once per model in compact_decode).
  const std::size_t nc = m.control.size();
  std::vector<std::int16_t> q(nc * m.frame_count * 4);
  if (nc > 0 && meshopt_decodeVertexBuffer(q.data(), nc * m.frame_count, 8, m.motion.data(), m.motion.size()) != 0)
    bad("corrupt motion stream", "the file is damaged: pack it again");
  std::vector<Vec3> d(nc);
  for (std::size_t c = 0; c < nc; ++c) {
    const std::size_t r = (c * m.frame_count + frame) * 4;
    d[c] = {q[r] * m.motion_step, q[r + 1] * m.motion_step, q[r + 2] * m.motion_step};
  }
  return d;
}

// The triangles' corner indices, flat.
std::vector<std::uint32_t> flat_indices(const std::vector<Triangle>& triangles) {
  std::vector<std::uint32_t> idx(triangles.size() * 3);
  for (std::size_t t = 0; t < triangles.size(); ++t)
    for (int c = 0; c < 3; ++c) idx[3 * t + c] = triangles[t][c];
  return idx;
}

// Reorders for locality (the codecs compress deltas between neighbours): rewrites idx in the new
// ids and returns order[new] = old (the identity without `reorder`).
std::vector<std::uint32_t> reorder_vertices(std::vector<std::uint32_t>& idx, std::size_t nv, bool reorder) {
  std::vector<std::uint32_t> order(nv);  // order[new] = old
  std::iota(order.begin(), order.end(), 0u);
  if (reorder) {
    std::vector<std::uint32_t> tmp(idx.size());
    meshopt_optimizeVertexCache(tmp.data(), idx.data(), idx.size(), nv);
    std::vector<std::uint32_t> remap(nv);
    const std::size_t used = meshopt_optimizeVertexFetchRemap(remap.data(), tmp.data(), tmp.size(), nv);
    std::uint32_t next = static_cast<std::uint32_t>(used);
    for (std::size_t v = 0; v < nv; ++v)
      if (remap[v] == ~0u) remap[v] = next++;  // unreferenced vertices go last
    for (std::size_t v = 0; v < nv; ++v) order[remap[v]] = static_cast<std::uint32_t>(v);
    for (std::size_t i = 0; i < idx.size(); ++i) idx[i] = remap[tmp[i]];
  }
  return order;
}

// Every frame's positions in the new vertex order.
std::vector<std::vector<Vec3>> reordered_positions(const MeshSequence& seq, const std::vector<std::uint32_t>& order) {
  const std::size_t nv = order.size();
  std::vector<std::vector<Vec3>> P(seq.positions.size(), std::vector<Vec3>(nv));
  for (std::size_t f = 0; f < seq.positions.size(); ++f)
    for (std::size_t v = 0; v < nv; ++v) P[f][v] = seq.positions[f][order[v]];
  return P;
}

// The model's counts, times (frame index x 1 ms when not given), tolerance and neighbours.
CompactModel model_header(const MeshSequence& seq, const CompactOptions& opt) {
  const std::size_t nf = seq.positions.size();
  CompactModel m;
  m.vertex_count = static_cast<std::uint32_t>(seq.positions[0].size());
  m.triangle_count = static_cast<std::uint32_t>(seq.triangles.size());
  m.frame_count = static_cast<std::uint32_t>(nf);
  m.times_ms = seq.times_ms;
  if (m.times_ms.empty())
    for (std::size_t f = 0; f < nf; ++f) m.times_ms.push_back(static_cast<double>(f));
  m.tolerance = opt.tolerance;
  m.neighbours = static_cast<std::uint32_t>(std::clamp(opt.neighbours, 1, kMaxCompactNeighbours));
  return m;
}

// Frame 0 on a grid: per-coordinate error <= step/2, Euclidean <= tolerance/2. Sets m.grid_step,
// m.origin and m.positions.
void encode_frame0(CompactModel& m, const std::vector<Vec3>& p0, double tolerance) {
  const std::size_t nv = p0.size();
  Vec3 lo = p0[0], hi = p0[0];
  for (const Vec3& p : p0)
    for (int c = 0; c < 3; ++c) {
      lo[c] = std::min(lo[c], p[c]);
      hi[c] = std::max(hi[c], p[c]);
    }
  const double extent = std::max({hi.x - lo.x, hi.y - lo.y, hi.z - lo.z});
  m.grid_step = std::max(tolerance / std::sqrt(3.0), extent / 65535.0);
  for (int c = 0; c < 3; ++c) m.origin[c] = lo[c];
  std::vector<std::uint16_t> q0(nv * 4, 0);
  for (std::size_t v = 0; v < nv; ++v)
    for (int c = 0; c < 3; ++c)
      q0[4 * v + c] = static_cast<std::uint16_t>(std::clamp(std::lround((p0[v][c] - lo[c]) / m.grid_step), 0L, 65535L));
  m.positions.resize(meshopt_encodeVertexBufferBound(nv, 8));
  m.positions.resize(meshopt_encodeVertexBuffer(m.positions.data(), m.positions.size(), q0.data(), nv, 8));
}

// Control vertices: those meshopt_simplify keeps of the (reordered) frame-0 mesh; every vertex for
// a small mesh or a degenerate simplification.
std::vector<std::uint32_t> control_vertices(const std::vector<Vec3>& p0, const std::vector<std::uint32_t>& idx,
                                            const CompactOptions& opt) {
  const std::size_t nv = p0.size();
  std::vector<std::uint32_t> control;
  if (nv <= opt.control_vertices + 3) {
    control.resize(nv);
    std::iota(control.begin(), control.end(), 0u);
    return control;
  }
  std::vector<float> fp(nv * 3);
  for (std::size_t v = 0; v < nv; ++v)
    for (int c = 0; c < 3; ++c) fp[3 * v + c] = static_cast<float>(p0[v][c]);
  std::vector<std::uint32_t> simple(idx.size());
  const std::size_t target = std::max<std::size_t>(12, opt.control_vertices * 6);
  simple.resize(meshopt_simplify(simple.data(), idx.data(), idx.size(), fp.data(), nv, 12, target, 1.0f, 0, nullptr));
  std::vector<char> keep(nv, 0);
  for (std::uint32_t i : simple) keep[i] = 1;
  for (std::size_t v = 0; v < nv; ++v)
    if (keep[v]) control.push_back(static_cast<std::uint32_t>(v));
  if (control.size() < 4) {  // degenerate simplification: fall back to every vertex
    control.resize(nv);
    std::iota(control.begin(), control.end(), 0u);
  }
  return control;
}

// Control displacements relative to the decoded frame 0 (`base`), int16 per coordinate. Sets
// m.motion_step and m.motion.
void encode_motion(CompactModel& m, const std::vector<std::vector<Vec3>>& P, const std::vector<Vec3>& base,
                   double tolerance) {
  const std::size_t nf = P.size(), nc = m.control.size();
  double maxd = 0.0;
  for (std::size_t f = 0; f < nf; ++f)
    for (std::uint32_t c : m.control)
      for (int i = 0; i < 3; ++i) maxd = std::max(maxd, std::abs(P[f][c][i] - base[c][i]));
  m.motion_step = std::max(tolerance / 4.0, maxd / 32000.0);
  std::vector<std::int16_t> qm(nc * nf * 4, 0);
  for (std::size_t c = 0; c < nc; ++c)
    for (std::size_t f = 0; f < nf; ++f)
      for (int i = 0; i < 3; ++i)
        qm[(c * nf + f) * 4 + i] =
            static_cast<std::int16_t>(std::lround((P[f][m.control[c]][i] - base[m.control[c]][i]) / m.motion_step));
  m.motion.resize(meshopt_encodeVertexBufferBound(nc * nf, 8));
  m.motion.resize(meshopt_encodeVertexBuffer(m.motion.data(), m.motion.size(), qm.data(), nc * nf, 8));
}

// The triangles as the decoder will see them (the index codec may rotate corners), so that both
// compute the same normals.
std::vector<Triangle> decoded_triangles(const CompactModel& m, std::size_t index_count) {
  std::vector<std::uint32_t> didx(index_count);
  if (meshopt_decodeIndexBuffer(didx.data(), didx.size(), 4, m.indices.data(), m.indices.size()) != 0)
    bad("index codec round trip failed", "report this as a bug");
  std::vector<Triangle> tris(didx.size() / 3);
  for (std::size_t t = 0; t < tris.size(); ++t) tris[t] = {didx[3 * t], didx[3 * t + 1], didx[3 * t + 2]};
  return tris;
}

// What the corrections compare against: the decoder's triangles and their rings, the residual grid,
// the accepted error and whether it is measured to the surface.
struct Corrector {
  const std::vector<Triangle>& tris;
  const TriangleRings& rings;
  double residual_step = 0.0;
  double accept = 0.0;  // 0.9 x tolerance: margin for floating-point differences between machines
  bool surface = false;
};

// One frame's correction stream (count, then per corrected vertex its id step and residuals):
// moves pred where it misses `target` by more than the accepted error; adds the count to `corrected`.
std::vector<std::uint8_t> frame_corrections(const Corrector& k, const std::vector<Vec3>& target,
                                            const std::vector<Vec3>& normals, std::vector<Vec3>& pred,
                                            std::size_t& corrected) {
  std::vector<std::uint8_t> corr;
  std::vector<std::uint8_t> body;
  std::uint64_t count = 0;
  std::size_t last = 0;
  for (std::size_t v = 0; v < target.size(); ++v) {
    if (k.surface) {
      if (ring_distance(k.rings, k.tris, target, v, pred[v]) <= k.accept) continue;
      // One scalar along the predicted normal when that brings the vertex onto the surface.
      const std::int64_t r = std::llround(dot(target[v] - pred[v], normals[v]) / k.residual_step);
      const Vec3 cand = pred[v] + (static_cast<double>(r) * k.residual_step) * normals[v];
      if (r != 0 && ring_distance(k.rings, k.tris, target, v, cand) <= k.accept) {
        put_varint(body, 2 * (v - last));
        put_varint(body, zigzag(r));
        pred[v] = cand;
        last = v;
        ++count;
        continue;
      }
    } else if (distance(pred[v], target[v]) <= k.accept) {
      continue;
    }
    std::array<std::int64_t, 3> r{};
    for (int i = 0; i < 3; ++i) r[i] = std::llround((target[v][i] - pred[v][i]) / k.residual_step);
    put_varint(body, k.surface ? 2 * (v - last) + 1 : v - last);
    last = v;
    for (int i = 0; i < 3; ++i) {
      put_varint(body, zigzag(r[i]));
      pred[v][i] += static_cast<double>(r[i]) * k.residual_step;
    }
    ++count;
  }
  put_varint(corr, count);
  corr.insert(corr.end(), body.begin(), body.end());
  corrected += count;
  return corr;
}

// Adds one frame's errors (decoded `pred` against `target`) to st; sum2 gathers the squared distances.
void add_frame_errors(const Corrector& k, const std::vector<Vec3>& target, const std::vector<Vec3>& pred,
                      CompactStats& st, double& sum2) {
  for (std::size_t v = 0; v < target.size(); ++v) {
    const double e = distance(pred[v], target[v]);
    st.max_error = std::max(st.max_error, e);
    sum2 += e * e;
    st.max_surface_error = std::max(st.max_surface_error, ring_distance(k.rings, k.tris, target, v, pred[v]));
    st.max_surface_error_back = std::max(st.max_surface_error_back, ring_distance(k.rings, k.tris, pred, v, target[v]));
  }
}

// Corrections where the interpolated motion misses the input by more than the tolerance (with a
// margin for floating-point differences between machines): sets m.residual_step, m.error and
// m.corrections; returns the error statistics.
CompactStats encode_corrections(CompactModel& m, const std::vector<std::vector<Vec3>>& P, const std::vector<Vec3>& base,
                                std::size_t index_count, const CompactOptions& opt) {
  const std::size_t nv = base.size(), nf = P.size();
  m.residual_step = 2.0 * opt.tolerance / std::sqrt(3.0) * 0.98;
  const ControlWeights w = control_weights(base, m.control, static_cast<int>(m.neighbours));
  CompactStats st;
  double sum2 = 0.0;
  m.error = opt.error;
  const std::vector<Triangle> tris = decoded_triangles(m, index_count);
  const TriangleRings rings = triangle_rings(nv, tris);
  const Corrector k{tris, rings, m.residual_step, 0.9 * opt.tolerance, opt.error == CompactError::Surface};
  std::vector<Vec3> pred, normals;
  for (std::size_t f = 0; f < nf; ++f) {
    const std::vector<Vec3> disp = decode_motion(m, f);
    predict(base, w, disp, pred);
    if (k.surface) normals = area_weighted_normals(pred, tris, Vec3{});
    m.corrections.push_back(frame_corrections(k, P[f], normals, pred, st.corrected_vertices));
    add_frame_errors(k, P[f], pred, st, sum2);
  }
  st.rms_error = std::sqrt(sum2 / static_cast<double>(nv * nf));
  return st;
}

}  // namespace

ControlWeights control_weights(const std::vector<Vec3>& positions, const std::vector<std::uint32_t>& control,
                               int neighbours) {
  ControlWeights w;
  const std::size_t nc = control.size();
  w.k = static_cast<int>(
      std::min<std::size_t>(static_cast<std::size_t>(std::clamp(neighbours, 1, kMaxCompactNeighbours)), nc));
  const std::size_t k = static_cast<std::size_t>(w.k);
  w.ids.assign(positions.size() * k, 0);
  w.weights.assign(positions.size() * k, 0.0f);
  if (k == 0) return w;
  std::vector<Vec3> cp(nc);
  for (std::size_t c = 0; c < nc; ++c) cp[c] = positions[control[c]];
  tbb::parallel_for(
      std::size_t{0}, positions.size(), std::size_t{256},
      [&](std::size_t v0) {
        const std::size_t v1 = std::min(positions.size(), v0 + 256);
        std::vector<std::pair<double, std::uint32_t>> best;
        for (std::size_t v = v0; v < v1; ++v) {
          const Vec3 x = positions[v];
          best.clear();
          // k nearest control vertices, ties broken by id (deterministic).
          for (std::size_t c = 0; c < nc; ++c) {
            const Vec3 e = cp[c] - x;
            const std::pair<double, std::uint32_t> cand{dot(e, e), static_cast<std::uint32_t>(c)};
            if (best.size() < k) {
              best.push_back(cand);
              std::push_heap(best.begin(), best.end());
            } else if (cand < best.front()) {
              std::pop_heap(best.begin(), best.end());
              best.back() = cand;
              std::push_heap(best.begin(), best.end());
            }
          }
          std::sort(best.begin(), best.end());
          if (best.front().first == 0.0) {  // x is a control vertex: carry it exactly
            w.ids[v * k] = best.front().second;
            w.weights[v * k] = 1.0f;
            for (std::size_t j = 1; j < k; ++j) w.ids[v * k + j] = best[j].second;
            continue;
          }
          const double h2 = 0.25 * best.back().first + 1e-12;
          Eigen::Matrix4d M = Eigen::Matrix4d::Zero();
          std::array<Eigen::Vector4d, kMaxCompactNeighbours> b;
          std::array<double, kMaxCompactNeighbours> wt{};
          for (std::size_t j = 0; j < k; ++j) {
            const Vec3 e = cp[best[j].second] - x;
            b[j] = Eigen::Vector4d(1.0, e.x, e.y, e.z);
            wt[j] = 1.0 / (best[j].first + h2);
            M += wt[j] * b[j] * b[j].transpose();
          }
          // A small ridge on the gradient: control vertices near a surface are almost coplanar.
          const double ridge = 1e-3 * (M(1, 1) + M(2, 2) + M(3, 3)) / 3.0 + 1e-300;
          for (int i = 1; i < 4; ++i) M(i, i) += ridge;
          const Eigen::Vector4d a = M.ldlt().solve(Eigen::Vector4d::UnitX());
          for (std::size_t j = 0; j < k; ++j) {
            w.ids[v * k + j] = best[j].second;
            w.weights[v * k + j] = static_cast<float>(wt[j] * a.dot(b[j]));
          }
        }
      },
      tbb::simple_partitioner());
  return w;
}

CompactModel compact_encode(const MeshSequence& seq_in, const CompactOptions& opt,
                            std::vector<std::uint32_t>* vertex_order, CompactStats* stats) {
  validate(seq_in);
  if (!(opt.tolerance > 0.0)) bad("tolerance must be positive", "use e.g. 0.05 mm");
  const std::size_t nv = seq_in.positions[0].size();
  std::vector<std::uint32_t> idx = flat_indices(seq_in.triangles);
  const std::vector<std::uint32_t> order = reorder_vertices(idx, nv, opt.reorder);  // rewrites idx
  const std::vector<std::vector<Vec3>> P = reordered_positions(seq_in, order);

  CompactModel m = model_header(seq_in, opt);
  m.indices.resize(meshopt_encodeIndexBufferBound(idx.size(), nv));
  m.indices.resize(meshopt_encodeIndexBuffer(m.indices.data(), m.indices.size(), idx.data(), idx.size()));
  encode_frame0(m, P[0], opt.tolerance);
  const std::vector<Vec3> base = decode_positions(m);
  m.control = control_vertices(P[0], idx, opt);
  encode_motion(m, P, base, opt.tolerance);
  CompactStats st = encode_corrections(m, P, base, idx.size(), opt);

  st.index_bytes = m.indices.size();
  st.position_bytes = m.positions.size();
  st.motion_bytes = m.motion.size() + 4 * m.control.size();
  for (const auto& c : m.corrections) st.correction_bytes += c.size();
  if (stats) *stats = st;
  if (vertex_order) *vertex_order = order;
  return m;
}

MeshSequence compact_decode(const CompactModel& m) {
  if (m.vertex_count == 0 || m.triangle_count == 0 || m.frame_count == 0)
    bad("empty compact model", "pack a non-empty 4D mesh");
  if (m.times_ms.size() != m.frame_count || m.corrections.size() != m.frame_count)
    bad("frame count does not match the time and correction lists", "the file is damaged: pack it again");
  if (!(m.grid_step > 0.0) || !(m.motion_step > 0.0) || !(m.residual_step > 0.0) || m.neighbours == 0 ||
      m.neighbours > static_cast<std::uint32_t>(kMaxCompactNeighbours))
    bad("invalid quantisation parameters", "the file is damaged: pack it again");
  for (std::size_t c = 0; c < m.control.size(); ++c)
    if (m.control[c] >= m.vertex_count || (c > 0 && m.control[c] <= m.control[c - 1]))
      bad("invalid control vertex list", "the file is damaged: pack it again");
  MeshSequence seq;
  std::vector<std::uint32_t> idx(static_cast<std::size_t>(m.triangle_count) * 3);
  if (meshopt_decodeIndexBuffer(idx.data(), idx.size(), 4, m.indices.data(), m.indices.size()) != 0)
    bad("corrupt index stream", "the file is damaged: pack it again");
  seq.triangles.resize(m.triangle_count);
  for (std::size_t t = 0; t < seq.triangles.size(); ++t)
    for (int c = 0; c < 3; ++c) {
      if (idx[3 * t + c] >= m.vertex_count) bad("triangle index out of range", "the file is damaged: pack it again");
      seq.triangles[t][c] = idx[3 * t + c];
    }
  const std::vector<Vec3> base = decode_positions(m);
  const ControlWeights w = control_weights(base, m.control, static_cast<int>(m.neighbours));
  const std::size_t nc = m.control.size();
  std::vector<std::int16_t> q(nc * m.frame_count * 4);
  if (nc > 0 && meshopt_decodeVertexBuffer(q.data(), nc * m.frame_count, 8, m.motion.data(), m.motion.size()) != 0)
    bad("corrupt motion stream", "the file is damaged: pack it again");
  seq.times_ms = m.times_ms;
  seq.positions.resize(m.frame_count);
  const bool surface = m.error == CompactError::Surface;
  std::vector<Vec3> disp(nc), normals;
  for (std::size_t f = 0; f < m.frame_count; ++f) {
    for (std::size_t c = 0; c < nc; ++c) {
      const std::size_t r = (c * m.frame_count + f) * 4;
      disp[c] = {q[r] * m.motion_step, q[r + 1] * m.motion_step, q[r + 2] * m.motion_step};
    }
    predict(base, w, disp, seq.positions[f]);
    if (surface) normals = area_weighted_normals(seq.positions[f], seq.triangles, Vec3{});
    const std::vector<std::uint8_t>& corr = m.corrections[f];
    std::size_t pos = 0;
    const std::uint64_t count = get_varint(corr, pos);
    if (count > m.vertex_count) bad("too many corrections", "the file is damaged: pack it again", static_cast<int>(f));
    std::uint64_t v = 0;
    for (std::uint64_t i = 0; i < count; ++i) {
      const std::uint64_t code = get_varint(corr, pos);
      const bool full = !surface || (code & 1) != 0;
      v += surface ? code >> 1 : code;
      if (v >= m.vertex_count)
        bad("correction vertex out of range", "the file is damaged: pack it again", static_cast<int>(f));
      if (!full) {
        const double r = static_cast<double>(unzigzag(get_varint(corr, pos))) * m.residual_step;
        seq.positions[f][v] += r * normals[v];
        continue;
      }
      for (int c = 0; c < 3; ++c)
        seq.positions[f][v][c] += static_cast<double>(unzigzag(get_varint(corr, pos))) * m.residual_step;
    }
  }
  return seq;
}

}  // namespace c4d
