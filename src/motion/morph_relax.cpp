// Step 3 of the 4D morph (Lim et al. 2014, "4D Morphing of the Heart Model"; Miara et al. §III.E, which
// carries one mesh through the cycle): tangential relaxation. After the projection onto the frame's own
// surface, many cheap sweeps move every vertex in its tangent plane towards the mean of its ring (the
// uniform "umbrella" Laplacian) blended with an equilateral pull, with heavy-ball momentum; each round of
// sweeps ends with an exact projection. Vertices on a contour move along it. Beside slices whose contours
// split or merged, the umbrella weights edges by their chord height (MorphSteps::saddle_curvature), so
// the vertices gather where the surface bends. docs/algorithms/morph.md, "Relaxation".
#include <algorithm>
#include <atomic>
#include <cmath>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "morph_work_internal.h"
#include "simd/packed_math_internal.h"
#include "simd_avx_internal.h"
#include "sweep_lanes_internal.h"

namespace c4d::detail {
namespace {

constexpr int kRelaxRounds = 2;     // rounds per try (× MorphTry::sweep_factor), each ended by an exact
                                    // re-projection (4 gave up to 2.6 points more of 40–80° for a fifth more time)
constexpr int kRelaxSweeps = 100;   // sweeps per round (with momentum, as good as 1600 plain Jacobi sweeps)
constexpr double kRelaxStep = 0.5;  // fraction of the tangential move per sweep
constexpr double kRelaxMomentum = 0.9;  // heavy-ball momentum of the sweeps: speeds up the slow, smooth modes
                                        // about tenfold, so far fewer sweeps reach the same state
constexpr double kShapeWeight = 0.5;    // share of the equilateral pull (each triangle draws the vertex towards the
                                        // apex of the equilateral triangle on its opposite edge) against the
// umbrella: undoes the anisotropy that contraction leaves and the umbrella keeps
constexpr std::size_t kSweepBlock = 512;  // positions per parallel block of a sweep

// Vertices per relaxation sweep step (MorphSteps::sweep_lanes): 0 the widest this CPU runs (4 with
// AVX, else 2 with SSE2), else the request limited to that; 1 without SSE2.
int sweep_width(int requested) {
#if defined(__SSE2__)
  static const bool quad = avx_available();
  const int widest = quad ? 4 : 2;
  if (requested <= 0) return widest;
  return requested >= 4 ? widest : (requested >= 2 ? 2 : 1);
#else
  (void)requested;
  return 1;
#endif
}

// The vertices in breadth-first order over the mesh's edges (each component from its lowest vertex;
// neighbours in ring order): new position → vertex. Neighbours get nearby positions.
std::vector<std::uint32_t> breadth_first_order(const std::vector<std::size_t>& ring_start,
                                               const std::vector<std::uint32_t>& ring_index) {
  const std::size_t nv = ring_start.size() - 1;
  std::vector<std::uint32_t> order;
  order.reserve(nv);
  std::vector<char> seen(nv, 0);
  for (std::size_t s = 0; s < nv; ++s) {
    if (seen[s]) continue;
    seen[s] = 1;
    std::size_t k = order.size();
    order.push_back(static_cast<std::uint32_t>(s));
    for (; k < order.size(); ++k) {
      const std::uint32_t v = order[k];
      for (std::size_t r = ring_start[v]; r < ring_start[v + 1]; ++r)
        if (!seen[ring_index[r]]) {
          seen[ring_index[r]] = 1;
          order.push_back(ring_index[r]);
        }
    }
  }
  return order;
}

// The free positions of each block of kSweepBlock (those with a ring), with as many neighbours and opposite
// edges next to each other, so that a group of lanes spends no lane waiting out a longer ring (each vertex's
// step does not depend on its group or on the order within the block).
void group_free_positions(RelaxLayout& L, std::size_t nv) {
  const std::size_t blocks = (nv + kSweepBlock - 1) / kSweepBlock;
  L.free_k.reserve(nv);
  L.block_start.assign(blocks + 1, 0);
  auto shape_of = [&](std::size_t k) {
    return std::pair(L.ring_start[k + 1] - L.ring_start[k], L.opp_start[k + 1] - L.opp_start[k]);
  };
  for (std::size_t b = 0; b < blocks; ++b) {
    const std::size_t first = L.free_k.size();
    for (std::size_t k = kSweepBlock * b; k < std::min(nv, kSweepBlock * (b + 1)); ++k)
      if (L.ring_start[k + 1] != L.ring_start[k]) L.free_k.push_back(k);
    if (L.lanes > 1)
      std::stable_sort(L.free_k.begin() + static_cast<std::ptrdiff_t>(first), L.free_k.end(),
                       [&](std::size_t a, std::size_t c) { return shape_of(a) < shape_of(c); });
    L.block_start[b + 1] = L.free_k.size();
  }
}

// One vertex's sweep step (position i): its new velocity and position (before sliding). Umbrella move
// (weighted in saddle zones), blended with the equilateral pull: the mean of the apexes of equilateral
// triangles raised, in the tangent plane, on the edges (j, k) opposite the vertex: midpoint + √3/2 · n × e ·
// |e| / |n × e|. sweep_lanes_internal.h repeats these operations lane by lane.
void sweep_one(const SweepArrays& s, std::size_t i, Vec3* vel, Vec3* moved) {
  const Vec3 xi = s.xs[i], n = s.ns[i];
  const std::uint32_t* ring = s.ring_index + s.ring_start[i];
  const std::size_t m = s.ring_start[i + 1] - s.ring_start[i];
  Vec3 c{}, g{}, mid{};
  const bool weighted = s.zone[i];
  double wsum = 0;
  for (std::size_t k = 0; k < m; ++k) {
    const Vec3 e = s.xs[ring[k]] - xi;
    double w = 1.0;
    // Chord height of the edge over the surface, from the two normals (L²/8R on a sphere).
    if (weighted) w += (std::abs(dot(e, n)) + std::abs(dot(e, s.ns[ring[k]]))) / (8.0 * s.curv_dev);
    wsum += w;
    c += w * e;
  }
  // Two triangles at a time: one division and one square root instruction for both (simd/packed_math_internal.h:
  // the same bits as the scalar ones); the sums keep the triangles' order.
  std::size_t k = s.opp_start[i];
  const std::size_t k_end = s.opp_start[i + 1];
  auto edge = [&](std::size_t j, Vec3& e, double& ee, double& s2) {
    const Vec3 a = s.xs[s.opp_index[2 * j]] - xi, b = s.xs[s.opp_index[2 * j + 1]] - xi;
    e = b - a;
    mid += a + b;
    ee = dot(e, e);
    const double ne = dot(n, e);
    s2 = ee - ne * ne;
  };
  for (; k + 1 < k_end; k += 2) {
    Vec3 e0, e1;
    double ee0, s20, ee1, s21;
    edge(k, e0, ee0, s20);
    edge(k + 1, e1, ee1, s21);
    double f[2];
    sqrt_of_ratios2(ee0, s20, ee1, s21, f);
    if (s20 > 1e-300) g += f[0] * e0;
    if (s21 > 1e-300) g += f[1] * e1;
  }
  if (k < k_end) {
    Vec3 e0;
    double ee0, s20;
    edge(k, e0, ee0, s20);
    if (s20 > 1e-300) g += std::sqrt(ee0 / s20) * e0;
  }
  const double inv = 1.0 / static_cast<double>(m);
  if (weighted) c = (static_cast<double>(m) / wsum) * c;  // the weighted mean, as m × mean (saddle zones)
  Vec3 d = (Vec3{} + c) * inv;                            // +0 + c: a −0 becomes +0, as in the lanes
  const double no = static_cast<double>(s.opp_start[i + 1] - s.opp_start[i]);
  const Vec3 pull = (0.5 * mid + 0.8660254037844386 * cross(n, g)) / std::max(1.0, no);
  d = (1.0 - s.shape_weight) * d + s.shape_weight * pull;
  d -= dot(d, n) * n;
  vel[i] = s.beta * vel[i] + s.step * d;
  moved[i] = xi + vel[i];
}

// One Jacobi sweep (each position written from the sweep's start, s.xs): every free position's step into
// vel and moved, in groups of the layout's lanes, those on a contour slid along it. Returns the largest
// squared move (a maximum: the same in any order).
double sweep(const MorphWork& w, FrameWork& f, const SweepArrays& s, const std::vector<char>& slides_k,
             std::vector<Vec3>& vel, std::vector<Vec3>& moved) {
  const RelaxLayout& L = w.layout;
  const int lanes = L.lanes;
  std::atomic<double> largest{0.0};
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, L.block_start.size() - 1, 1),
                    [&](const tbb::blocked_range<std::size_t>& range) {
                      double biggest = 0.0;
                      auto finish = [&](std::size_t i) {
                        if (slides_k[i]) {
                          moved[i] = slide(f, L.order[i], moved[i]);
                          vel[i] = moved[i] - s.xs[i];
                        }
                        biggest = std::max(biggest, dot(vel[i], vel[i]));
                      };
                      auto step = [&](int width, const std::size_t* idx) {
                        if (width == 4)
                          sweep_quad(s, idx, vel.data(), moved.data());
#if defined(__SSE2__)
                        else if (width == 2)
                          sweep_lanes<Sse2Lanes>(s, idx, vel.data(), moved.data());
#endif
                        else
                          sweep_one(s, idx[0], vel.data(), moved.data());
                        for (int k = 0; k < width; ++k) finish(idx[k]);
                      };
                      // Each block's free positions in groups of `lanes`, the last few two at a time or alone.
                      std::size_t group[4];
                      int count = 0;
                      for (std::size_t b = range.begin(); b != range.end(); ++b) {
                        for (std::size_t j = L.block_start[b]; j < L.block_start[b + 1]; ++j) {
                          group[count++] = L.free_k[j];
                          if (count == lanes) {
                            step(lanes, group);
                            count = 0;
                          }
                        }
                        int done = 0;
                        if (count >= 2 && lanes > 1) {
                          step(2, group);
                          done = 2;
                        }
                        for (; done < count; ++done) step(1, group + done);
                        count = 0;
                      }
                      double seen = largest.load();
                      while (biggest > seen && !largest.compare_exchange_weak(seen, biggest)) {}
                    });
  return largest.load();
}

// `rounds` rounds of kRelaxSweeps sweeps in the tangent planes of the round's start (f.normals), each ended
// by an exact projection (vertices on a contour stay on it).
void relax_rounds(const MorphWork& w, FrameWork& f, const MorphTry& tr, int rounds) {
  const RelaxLayout& L = w.layout;
  const std::size_t nv = w.nv;
  const double curv_dev = tr.saddle_weights ? f.curv_dev : 0.0;
  // Everything the sweeps read, in the breadth-first order (position k is vertex order[k]).
  std::vector<char> slides_k(nv), zone_k(nv);
  for (std::size_t k = 0; k < nv; ++k) {
    const std::uint32_t i = L.order[k];
    slides_k[k] = f.on_contour[i];
    zone_k[k] = curv_dev > 0 && f.saddle_zone[i];
  }
  std::vector<Vec3> xs(nv), ns(nv), moved(nv), vel(nv);
  SweepArrays arrays;
  arrays.ns = ns.data();
  arrays.ring_start = L.ring_start.data();
  arrays.ring_index = L.ring_index.data();
  arrays.opp_start = L.opp_start.data();
  arrays.opp_index = L.opp_index.data();
  arrays.zone = zone_k.data();
  arrays.curv_dev = curv_dev;
  arrays.shape_weight = kShapeWeight;
  arrays.beta = kRelaxMomentum;
  arrays.step = kRelaxStep;
  for (int r = 0; r < rounds; ++r) {
    for (std::size_t k = 0; k < nv; ++k) {
      xs[k] = f.x[L.order[k]];
      ns[k] = f.normals[L.order[k]];
    }
    std::fill(vel.begin(), vel.end(), Vec3{});
    moved = xs;
    // A round ends early once the sweeps have settled (MorphTry::relax_settled; not in a retry).
    const double settled2 = std::pow(std::max(0.0, tr.relax_settled) * w.median_edge, 2);
    for (int pass = 0; pass < kRelaxSweeps; ++pass) {
      arrays.xs = xs.data();
      const double largest = sweep(w, f, arrays, slides_k, vel, moved);
      std::swap(xs, moved);
      if (settled2 > 0 && largest < settled2) break;
    }
    for (std::size_t k = 0; k < nv; ++k) f.x[L.order[k]] = xs[k];
    std::vector<Vec3> q = f.proj.project(f.x, &f.normals);
    for (std::size_t i = 0; i < nv; ++i)
      if (!f.on_contour[i]) f.x[i] = q[i];
  }
}

}  // namespace

// The relaxation works on the vertices in breadth-first order: frame 0's numbering scatters neighbours
// (neighbours thousands of indices apart), so every sweep's gathers of the rings missed
// the cache. Its sweeps are Jacobi sweeps (each writes its own vertex from the last sweep's positions)
// and each ring keeps its neighbour order, so the order changes no result.
void build_relax_layout(MorphWork& w) {
  RelaxLayout& L = w.layout;
  const std::size_t nv = w.nv;
  L.order = breadth_first_order(w.ring_start, w.ring_index);
  std::vector<std::uint32_t> rank(nv);  // vertex → position
  for (std::size_t k = 0; k < nv; ++k) rank[L.order[k]] = static_cast<std::uint32_t>(k);
  L.ring_start.assign(nv + 1, 0);
  L.opp_start.assign(nv + 1, 0);
  L.ring_index.reserve(w.ring_index.size());
  L.opp_index.reserve(6 * w.frame0.triangles.size());
  for (std::size_t k = 0; k < nv; ++k) {
    const std::uint32_t i = L.order[k];
    for (std::uint32_t j : w.nb[i]) L.ring_index.push_back(rank[j]);
    L.ring_start[k + 1] = L.ring_index.size();
    for (std::uint32_t t : w.incident[i]) {
      const Triangle& tri = w.frame0.triangles[t];
      const std::size_t c = tri[0] == i ? 0 : tri[1] == i ? 1 : 2;
      L.opp_index.push_back(rank[tri[(c + 1) % 3]]);
      L.opp_index.push_back(rank[tri[(c + 2) % 3]]);
    }
    L.opp_start[k + 1] = L.opp_index.size() / 2;
  }
  L.lanes = sweep_width(w.steps.sweep_lanes);
  group_free_positions(L, nv);
}

// A try's relaxation: kRelaxRounds × MorphTry::sweep_factor rounds. A retry relaxes more rounds, not rounds
// sweep_factor times as long: within a round every vertex moves in the tangent plane it had at the round's
// start, and over 800 sweeps a crowded, strongly bent patch (a basal contour shrinking to a third in one
// frame) drifts off the surface and folds when projected back.
void relax(const MorphWork& w, FrameWork& f, const MorphTry& tr) {
  relax_rounds(w, f, tr, kRelaxRounds * tr.sweep_factor);
}

// One round (around the vertices a plane snap just put on contours).
void relax_round(const MorphWork& w, FrameWork& f, const MorphTry& tr) { relax_rounds(w, f, tr, 1); }

}  // namespace c4d::detail
