// Compact 4D model: frame 0 on a fine grid, then every frame's move on the same grid, each vertex's move
// predicted from its already-decoded neighbours' moves.
//
// References:
//  - L. Miara, S. Benomar Elmdeghri, M. O. Cherkaoui Malki, "New Method for 4D Reconstruction of
//    Medical Images", §III.D–E and Table I: one base mesh, per-frame displacement data, small storage.
//  - A. Kapoulkine, meshoptimizer: vertex-cache/fetch reordering, index and vertex codecs.
//
// Why every vertex of every frame on one grid, and no smooth motion basis: the smooth bases we measured
// (docs/compact.md: control vertices with moving-least-squares weights, the principal components of the
// trajectories) miss the frame-specific detail of a contour-stack surface by 0.03–0.1 mm RMS, which tilts
// the facet normals of 1 mm triangles by 2–5° at the 99th percentile: visible creases and cracks in
// playback. On one fine grid the error is bounded per vertex and the decoded surfaces shade like the input.
#include "contour4d/temporal/compact.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <string>

#include <meshoptimizer.h>
#include <tbb/parallel_for.h>

#include "contour4d/core/errors.h"

namespace c4d {
namespace {

constexpr std::size_t kVertexBytes = 16;  // int32 x, y, z, 0 per vertex in the codec
// Largest grid coordinate kept (int32 with room for the frame-to-frame moves).
constexpr double kMaxGridUnits = 1.0e9;
// A vertex codec stream of n bytes never decodes to more than this many bytes per byte of it (meshopt's
// vertex codec spends at least 2 bits per 16 bytes of a vertex attribute byte group, plus its tail):
// counts beyond it are refused before anything is allocated.
constexpr std::size_t kMaxVertexCodecRatio = 64;
// Most vertex-frames a model may decode to (6 GiB of positions): a damaged count is refused, not allocated.
constexpr std::uint64_t kMaxVertexFrames = std::uint64_t{1} << 28;

[[noreturn]] void bad(const std::string& what, const std::string& hint, int frame = -1) {
  Location where;
  where.frame = frame;
  throw InvalidInput(ErrorCode::BadMesh, where, what, hint);
}

[[noreturn]] void damaged(const std::string& what, int frame = -1) {
  bad(what, "the file is damaged: pack it again", frame);
}

void validate(const MeshSequence& seq) {
  if (seq.positions.empty()) bad("the mesh sequence has no frames", "reconstruct a 4D mesh first");
  const std::size_t n = seq.positions[0].size();
  if (n == 0 || seq.triangles.empty()) bad("the mesh sequence is empty", "reconstruct a 4D mesh first");
  if (n > std::numeric_limits<std::uint32_t>::max() / kVertexBytes) bad("too many vertices", "split the mesh");
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

// The model's counts and times (frame index x 1 ms when not given).
CompactModel model_header(const MeshSequence& seq) {
  const std::size_t nf = seq.positions.size();
  CompactModel m;
  m.vertex_count = static_cast<std::uint32_t>(seq.positions[0].size());
  m.triangle_count = static_cast<std::uint32_t>(seq.triangles.size());
  m.frame_count = static_cast<std::uint32_t>(nf);
  m.times_ms = seq.times_ms;
  if (m.times_ms.empty())
    for (std::size_t f = 0; f < nf; ++f) m.times_ms.push_back(static_cast<double>(f));
  return m;
}

// The grid: origin at the corner below every vertex of every frame, the given step.
void set_grid(CompactModel& m, const MeshSequence& seq, double step) {
  m.step = step;
  m.tolerance = m.step * std::sqrt(3.0) / 2.0;
  Vec3 lo = seq.positions[0][0], hi = lo;
  for (const auto& frame : seq.positions)
    for (const Vec3& p : frame)
      for (int c = 0; c < 3; ++c) {
        lo[c] = std::min(lo[c], p[c]);
        hi[c] = std::max(hi[c], p[c]);
      }
  for (int c = 0; c < 3; ++c) {
    m.origin[c] = lo[c];
    if ((hi[c] - lo[c]) / m.step > kMaxGridUnits)
      bad("the mesh spans " + std::to_string(hi[c] - lo[c]) + " mm, too far for a grid of " + std::to_string(m.step) +
              " mm",
          "pack with a larger --tolerance, or check the units of the input");
  }
}

// Positions of one frame in grid units, vertex-major x, y, z, 0.
std::vector<std::int32_t> to_grid(const CompactModel& m, const std::vector<Vec3>& p,
                                  const std::vector<std::uint32_t>& order) {
  std::vector<std::int32_t> q(order.size() * 4, 0);
  for (std::size_t v = 0; v < order.size(); ++v)
    for (int c = 0; c < 3; ++c)
      q[4 * v + c] = static_cast<std::int32_t>(std::llround((p[order[v]][c] - m.origin[c]) / m.step));
  return q;
}

std::vector<std::uint8_t> encode_vertices(const std::vector<std::int32_t>& q) {
  const std::size_t n = q.size() / 4;
  std::vector<std::uint8_t> out(meshopt_encodeVertexBufferBound(n, kVertexBytes));
  out.resize(meshopt_encodeVertexBuffer(out.data(), out.size(), q.data(), n, kVertexBytes));
  return out;
}

std::vector<std::int32_t> decode_vertices(const std::vector<std::uint8_t>& in, std::size_t n) {
  if (n * kVertexBytes > in.size() * kMaxVertexCodecRatio + 4096)
    damaged("a vertex stream of " + std::to_string(in.size()) + " bytes cannot hold " + std::to_string(n) + " vertices",
            0);
  std::vector<std::int32_t> q(n * 4);
  if (meshopt_decodeVertexBuffer(q.data(), n, kVertexBytes, in.data(), in.size()) != 0)
    damaged("corrupt position stream", 0);
  return q;
}

// Each vertex's neighbours with a smaller id (CSR): the vertices a decoder has when it reaches it.
struct EarlierNeighbours {
  std::vector<std::uint32_t> start;  // n + 1
  std::vector<std::uint32_t> ids;
};

EarlierNeighbours earlier_neighbours(std::size_t n, const std::vector<std::uint32_t>& idx) {
  std::vector<std::pair<std::uint32_t, std::uint32_t>> edges;  // (later, earlier)
  edges.reserve(idx.size());
  for (std::size_t t = 0; t + 2 < idx.size(); t += 3)
    for (int c = 0; c < 3; ++c) {
      const std::uint32_t a = idx[t + c], b = idx[t + (c + 1) % 3];
      if (a != b) edges.emplace_back(std::max(a, b), std::min(a, b));
    }
  std::sort(edges.begin(), edges.end());
  edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
  EarlierNeighbours nb;
  nb.start.assign(n + 1, 0);
  for (const auto& e : edges) ++nb.start[e.first + 1];
  for (std::size_t v = 0; v < n; ++v) nb.start[v + 1] += nb.start[v];
  nb.ids.reserve(edges.size());
  for (const auto& e : edges) nb.ids.push_back(e.second);
  return nb;
}

// a / k rounded to the nearest integer, halves away from zero (k > 0): the same on every machine.
std::int64_t div_round(std::int64_t a, std::int64_t k) {
  return a >= 0 ? (2 * a + k) / (2 * k) : -((-2 * a + k) / (2 * k));
}

// The move of vertex v predicted from its earlier neighbours' moves (component c of x, y, z, 0 rows).
std::int64_t predicted_move(const EarlierNeighbours& nb, const std::vector<std::int64_t>& move, std::size_t v, int c) {
  const std::uint32_t b = nb.start[v], e = nb.start[v + 1];
  if (b == e) return 0;
  std::int64_t sum = 0;
  for (std::uint32_t i = b; i < e; ++i)
    sum += move[4 * static_cast<std::size_t>(nb.ids[i]) + static_cast<std::size_t>(c)];
  return div_round(sum, static_cast<std::int64_t>(e - b));
}

// Largest residual magnitude a motion stream may hold (grid units): far beyond any mesh on a 1e9-unit grid.
constexpr std::uint64_t kMaxResidual = std::uint64_t{1} << 40;

// One frame's moves (grid units, x, y, z, 0 rows) as zigzag varints of their residuals against the
// earlier-neighbour prediction, all x first, then y, then z (the payload's zstd does the rest).
std::vector<std::uint8_t> encode_moves(const EarlierNeighbours& nb, const std::vector<std::int64_t>& move) {
  std::vector<std::uint8_t> out;
  const std::size_t n = move.size() / 4;
  out.reserve(3 * n);
  for (int c = 0; c < 3; ++c)
    for (std::size_t v = 0; v < n; ++v) {
      const std::int64_t r = move[4 * v + static_cast<std::size_t>(c)] - predicted_move(nb, move, v, c);
      std::uint64_t z = (static_cast<std::uint64_t>(r) << 1) ^ static_cast<std::uint64_t>(r >> 63);
      while (z >= 0x80) {
        out.push_back(static_cast<std::uint8_t>(z | 0x80));
        z >>= 7;
      }
      out.push_back(static_cast<std::uint8_t>(z));
    }
  return out;
}

std::vector<std::int64_t> decode_moves(const EarlierNeighbours& nb, const std::vector<std::uint8_t>& in, std::size_t n,
                                       int frame) {
  std::vector<std::int64_t> move(4 * n, 0);
  std::size_t pos = 0;
  for (int c = 0; c < 3; ++c)
    for (std::size_t v = 0; v < n; ++v) {
      std::uint64_t z = 0;
      for (int shift = 0;; shift += 7) {
        if (pos >= in.size()) damaged("truncated motion stream", frame);
        if (shift > 42) damaged("a move too large in the motion stream", frame);
        const std::uint8_t b = in[pos++];
        z |= static_cast<std::uint64_t>(b & 0x7f) << shift;
        if ((b & 0x80) == 0) break;
      }
      if (z > 2 * kMaxResidual) damaged("a move too large in the motion stream", frame);
      const std::int64_t r = static_cast<std::int64_t>(z >> 1) ^ -static_cast<std::int64_t>(z & 1);
      move[4 * v + static_cast<std::size_t>(c)] = r + predicted_move(nb, move, v, c);
    }
  if (pos != in.size()) damaged("trailing bytes in the motion stream", frame);
  return move;
}

// The decoded positions of grid coordinates q (x, y, z, 0 per vertex).
std::vector<Vec3> from_grid(const CompactModel& m, const std::vector<std::int64_t>& q) {
  std::vector<Vec3> p(q.size() / 4);
  for (std::size_t v = 0; v < p.size(); ++v)
    for (int c = 0; c < 3; ++c) p[v][c] = m.origin[c] + static_cast<double>(q[4 * v + c]) * m.step;
  return p;
}

// Angle (degrees) between the facet normals of two meshes with the same triangles, per triangle.
std::vector<double> normal_angles(const std::vector<Vec3>& a, const std::vector<Vec3>& b,
                                  const std::vector<Triangle>& tris) {
  std::vector<double> out(tris.size());
  for (std::size_t t = 0; t < tris.size(); ++t) {
    const Triangle& tr = tris[t];
    const Vec3 na = cross(a[tr[1]] - a[tr[0]], a[tr[2]] - a[tr[0]]);
    const Vec3 nb = cross(b[tr[1]] - b[tr[0]], b[tr[2]] - b[tr[0]]);
    out[t] = std::atan2(norm(cross(na, nb)), dot(na, nb)) * 180.0 / M_PI;
  }
  return out;
}

// Vertex and normal errors of the decoded sequence against the input (in the input's vertex order).
CompactStats measure(const MeshSequence& in, const MeshSequence& out, const std::vector<std::uint32_t>& order) {
  CompactStats st;
  const std::size_t nf = in.positions.size(), nv = order.size();
  std::vector<double> max_e(nf, 0.0), sum_e2(nf, 0.0), p99(nf, 0.0), amax(nf, 0.0);
  tbb::parallel_for(std::size_t{0}, nf, [&](std::size_t f) {
    std::vector<Vec3> back(nv);
    for (std::size_t v = 0; v < nv; ++v) {
      back[order[v]] = out.positions[f][v];
      const double e = distance(out.positions[f][v], in.positions[f][order[v]]);
      max_e[f] = std::max(max_e[f], e);
      sum_e2[f] += e * e;
    }
    std::vector<double> a = normal_angles(back, in.positions[f], in.triangles);
    amax[f] = *std::max_element(a.begin(), a.end());
    const std::size_t k = std::min(a.size() - 1, static_cast<std::size_t>(0.99 * static_cast<double>(a.size())));
    std::nth_element(a.begin(), a.begin() + static_cast<std::ptrdiff_t>(k), a.end());
    p99[f] = a[k];
  });
  double sum = 0.0;
  for (std::size_t f = 0; f < nf; ++f) {  // in frame order: the same sums at any thread count
    st.max_error = std::max(st.max_error, max_e[f]);
    st.normal_p99 = std::max(st.normal_p99, p99[f]);
    st.normal_max = std::max(st.normal_max, amax[f]);
    sum += sum_e2[f];
  }
  st.rms_error = std::sqrt(sum / static_cast<double>(nf * nv));
  return st;
}

// Sets m's grid of `step` mm and its positions and motion on it (m holds the header and the triangles).
void encode_on_grid(CompactModel& m, const MeshSequence& seq, const EarlierNeighbours& nb,
                    const std::vector<std::uint32_t>& order, double step) {
  const std::size_t nf = seq.positions.size();
  set_grid(m, seq, step);
  std::vector<std::vector<std::int32_t>> grid(nf);
  tbb::parallel_for(std::size_t{0}, nf, [&](std::size_t f) { grid[f] = to_grid(m, seq.positions[f], order); });
  m.positions = encode_vertices(grid[0]);
  m.motion.resize(nf - 1);
  tbb::parallel_for(std::size_t{1}, nf, [&](std::size_t f) {
    std::vector<std::int64_t> move(grid[f].size());
    for (std::size_t i = 0; i < move.size(); ++i) move[i] = static_cast<std::int64_t>(grid[f][i]) - grid[f - 1][i];
    m.motion[f - 1] = encode_moves(nb, move);
  });
}

// Finest grid tried: an error of a micrometre tilts no facet of a contour-stack mesh visibly.
constexpr double kMinStep = 0.001;
// Grids tried at most: the normal error is close to proportional to the step, so the second one nearly always
// meets the bound.
constexpr int kMaxGrids = 4;

}  // namespace

CompactModel compact_encode(const MeshSequence& seq, const CompactOptions& opt,
                            std::vector<std::uint32_t>* vertex_order, CompactStats* stats) {
  validate(seq);
  if (!(opt.tolerance > 0.0) || !(opt.step > 0.0) || !(opt.normal_p99 > 0.0))
    throw InvalidInput(ErrorCode::Usage, {}, "the tolerance, the normal bound and the grid step must be positive",
                       "use e.g. --tolerance 0.05 (the default)");
  const std::size_t nv = seq.positions[0].size();
  std::vector<std::uint32_t> idx = flat_indices(seq.triangles);
  const std::vector<std::uint32_t> order = reorder_vertices(idx, nv, opt.reorder);  // rewrites idx
  CompactModel m = model_header(seq);
  m.indices.resize(meshopt_encodeIndexBufferBound(idx.size(), nv));
  m.indices.resize(meshopt_encodeIndexBuffer(m.indices.data(), m.indices.size(), idx.data(), idx.size()));
  const EarlierNeighbours nb = earlier_neighbours(nv, idx);

  double step = std::min(opt.step, 2.0 * opt.tolerance / std::sqrt(3.0));
  CompactStats st;
  for (int grid = 0; grid < kMaxGrids; ++grid) {
    encode_on_grid(m, seq, nb, order, step);
    st = measure(seq, compact_decode(m), order);
    if (st.normal_p99 <= opt.normal_p99 || step <= kMinStep) break;
    step = std::max(kMinStep, step * 0.9 * opt.normal_p99 / st.normal_p99);
  }
  st.index_bytes = m.indices.size();
  st.position_bytes = m.positions.size();
  for (const auto& b : m.motion) st.motion_bytes += b.size();
  if (stats) *stats = st;
  if (vertex_order) *vertex_order = order;
  return m;
}

MeshSequence compact_decode(const CompactModel& m) {
  if (m.vertex_count == 0 || m.triangle_count == 0 || m.frame_count == 0) damaged("empty compact model");
  if (m.times_ms.size() != m.frame_count || m.motion.size() + 1 != m.frame_count)
    damaged("the frame count does not match the time and motion lists");
  if (!(m.step > 0.0) || !std::isfinite(m.step) || !std::isfinite(m.origin[0]) || !std::isfinite(m.origin[1]) ||
      !std::isfinite(m.origin[2]))
    damaged("invalid grid");
  if (m.triangle_count > m.indices.size())  // the index codec spends at least one byte per triangle
    damaged("an index stream of " + std::to_string(m.indices.size()) + " bytes cannot hold " +
            std::to_string(m.triangle_count) + " triangles");
  if (static_cast<std::uint64_t>(m.vertex_count) * m.frame_count > kMaxVertexFrames)
    damaged(std::to_string(m.vertex_count) + " vertices in " + std::to_string(m.frame_count) +
            " frames are more than this build decodes");
  MeshSequence seq;
  std::vector<std::uint32_t> idx(static_cast<std::size_t>(m.triangle_count) * 3);
  if (meshopt_decodeIndexBuffer(idx.data(), idx.size(), 4, m.indices.data(), m.indices.size()) != 0)
    damaged("corrupt index stream");
  seq.triangles.resize(m.triangle_count);
  for (std::size_t t = 0; t < seq.triangles.size(); ++t)
    for (int c = 0; c < 3; ++c) {
      if (idx[3 * t + c] >= m.vertex_count) damaged("triangle index out of range");
      seq.triangles[t][c] = idx[3 * t + c];
    }
  seq.times_ms = m.times_ms;
  seq.positions.resize(m.frame_count);
  const std::vector<std::int32_t> q0 = decode_vertices(m.positions, m.vertex_count);
  std::vector<std::int64_t> q(q0.begin(), q0.end());  // 64-bit sums: a damaged stream cannot overflow
  seq.positions[0] = from_grid(m, q);
  const EarlierNeighbours nb = earlier_neighbours(m.vertex_count, idx);
  for (std::size_t f = 1; f < m.frame_count; ++f) {
    if (m.motion[f - 1].size() < 3 * static_cast<std::size_t>(m.vertex_count))  // a byte per value at least
      damaged("a motion stream of " + std::to_string(m.motion[f - 1].size()) + " bytes cannot hold " +
                  std::to_string(m.vertex_count) + " vertices",
              static_cast<int>(f));
    const std::vector<std::int64_t> move = decode_moves(nb, m.motion[f - 1], m.vertex_count, static_cast<int>(f));
    for (std::size_t i = 0; i < q.size(); ++i) q[i] += move[i];
    seq.positions[f] = from_grid(m, q);
  }
  return seq;
}

}  // namespace c4d
