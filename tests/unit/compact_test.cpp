// Compact 4D model and model.c4d: error bound, round trips, rigid-motion invariance, corrupt files.
#include "contour4d/temporal/compact.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <string>

#include "contour4d/core/errors.h"
#include "contour4d/io/model_c4d.h"
#include "contour4d/temporal/displacement_map.h"
#include "contour4d/temporal/sequence.h"
#include "temporal_fixtures.h"

namespace c4d {
namespace {

// Distance from p to triangle abc by projection and edge clamping (test-local, independent of the
// library's implementation).
double tri_distance(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 n = cross(b - a, c - a);
  const double nn = dot(n, n);
  if (nn > 0) {
    const Vec3 q = p - (dot(p - a, n) / nn) * n;
    const double u = dot(cross(c - b, q - b), n), v = dot(cross(a - c, q - c), n), w = dot(cross(b - a, q - a), n);
    if (u >= 0 && v >= 0 && w >= 0) return distance(p, q);
  }
  auto seg = [&](const Vec3& x, const Vec3& y) {
    const Vec3 d = y - x;
    const double t = dot(d, d) > 0 ? std::clamp(dot(p - x, d) / dot(d, d), 0.0, 1.0) : 0.0;
    return distance(p, x + t * d);
  };
  return std::min({seg(a, b), seg(b, c), seg(c, a)});
}

double surface_distance(const Vec3& p, const std::vector<Vec3>& pos, const std::vector<Triangle>& tris) {
  double best = 1e300;
  for (const Triangle& t : tris) best = std::min(best, tri_distance(p, pos[t[0]], pos[t[1]], pos[t[2]]));
  return best;
}

// The beating shape with per-vertex noise: mostly along the surface (as vertices of a
// reconstruction slide), a little across it.
MeshSequence noisy_beating(int subdivisions, std::size_t frames) {
  MeshSequence seq = synthetic_beating_mesh(subdivisions, frames);
  std::mt19937 rng(7);
  std::normal_distribution<double> g(0.0, 1.0);
  for (std::size_t f = 1; f < frames; ++f)
    for (Vec3& p : seq.positions[f]) {
      const Vec3 n = normalized(Vec3{p.x / 900.0, p.y / 900.0, p.z / 2025.0});
      Vec3 r{g(rng), g(rng), g(rng)};
      r = r - dot(r, n) * n;
      p += 0.3 * r + 0.03 * g(rng) * n;
    }
  return seq;
}

double max_error(const MeshSequence& in, const MeshSequence& out, const std::vector<std::uint32_t>& order) {
  double e = 0.0;
  for (std::size_t f = 0; f < in.positions.size(); ++f)
    for (std::size_t v = 0; v < order.size(); ++v) e = std::max(e, distance(out.positions[f][v], in.positions[f][order[v]]));
  return e;
}

TEST(Compact, DecodedWithinToleranceAndSameConnectivity) {
  const MeshSequence seq = synthetic_beating_mesh(4, 12);  // 5120 triangles
  std::vector<std::uint32_t> order;
  CompactStats st;
  CompactOptions opt;
  opt.control_vertices = 150;
  const CompactModel m = compact_encode(seq, opt, &order, &st);
  const MeshSequence out = compact_decode(m);
  ASSERT_EQ(out.positions.size(), seq.positions.size());
  ASSERT_EQ(out.triangles.size(), seq.triangles.size());
  EXPECT_LE(max_error(seq, out, order), opt.tolerance);
  EXPECT_NEAR(st.max_error, max_error(seq, out, order), 1e-9);
  EXPECT_EQ(out.times_ms, seq.times_ms);
  // Same triangles up to the vertex permutation (and triangle order): compare as sorted sets.
  std::vector<std::array<std::uint32_t, 3>> a, b;
  for (const Triangle& t : seq.triangles) {
    std::array<std::uint32_t, 3> x = t;
    std::rotate(x.begin(), std::min_element(x.begin(), x.end()), x.end());
    a.push_back(x);
  }
  for (const Triangle& t : out.triangles) {
    std::array<std::uint32_t, 3> x{order[t[0]], order[t[1]], order[t[2]]};
    std::rotate(x.begin(), std::min_element(x.begin(), x.end()), x.end());
    b.push_back(x);
  }
  std::sort(a.begin(), a.end());
  std::sort(b.begin(), b.end());
  EXPECT_EQ(a, b);
  // Orientation kept: the volume of each frame matches.
  for (std::size_t f = 0; f < seq.positions.size(); ++f)
    EXPECT_NEAR(signed_volume(out.frame(f)), signed_volume(seq.frame(f)), 1e-3 * signed_volume(seq.frame(f)));
}

TEST(Compact, TighterToleranceHolds) {
  const MeshSequence seq = synthetic_beating_mesh(3, 8);
  for (double tol : {0.2, 0.05, 0.01}) {
    CompactOptions opt;
    opt.tolerance = tol;
    opt.control_vertices = 60;
    std::vector<std::uint32_t> order;
    const MeshSequence out = compact_decode(compact_encode(seq, opt, &order));
    EXPECT_LE(max_error(seq, out, order), tol) << "tolerance " << tol;
  }
}

TEST(Compact, WithoutReorderKeepsIds) {
  const MeshSequence seq = synthetic_beating_mesh(3, 6);
  CompactOptions opt;
  opt.reorder = false;
  const MeshSequence out = compact_decode(compact_encode(seq, opt));
  // The index codec may rotate a triangle's corners (winding kept) but keeps the triangle order.
  ASSERT_EQ(out.triangles.size(), seq.triangles.size());
  for (std::size_t t = 0; t < seq.triangles.size(); ++t) {
    Triangle a = seq.triangles[t], b = out.triangles[t];
    std::rotate(a.begin(), std::min_element(a.begin(), a.end()), a.end());
    std::rotate(b.begin(), std::min_element(b.begin(), b.end()), b.end());
    EXPECT_EQ(a, b) << t;
  }
  for (std::size_t f = 0; f < seq.positions.size(); ++f)
    for (std::size_t v = 0; v < seq.positions[f].size(); ++v) EXPECT_LE(distance(out.positions[f][v], seq.positions[f][v]), opt.tolerance);
}

TEST(Compact, RigidMotionInvariantError) {
  MeshSequence seq = synthetic_beating_mesh(3, 6);
  MeshSequence moved = seq;
  const double c = std::cos(0.7), s = std::sin(0.7);
  for (auto& frame : moved.positions)
    for (Vec3& p : frame) p = Vec3{c * p.x - s * p.z + 100.0, p.y - 50.0, s * p.x + c * p.z + 7.0};
  for (const MeshSequence* q : {&seq, &moved}) {
    std::vector<std::uint32_t> order;
    const MeshSequence out = compact_decode(compact_encode(*q, {}, &order));
    EXPECT_LE(max_error(*q, out, order), 0.05);
  }
}

TEST(Compact, DeterministicBytes) {
  const MeshSequence seq = synthetic_beating_mesh(3, 5);
  EXPECT_EQ(serialize_model_c4d(compact_encode(seq)), serialize_model_c4d(compact_encode(seq)));
}

TEST(Compact, FileRoundTripAndCorruption) {
  const MeshSequence seq = synthetic_beating_mesh(2, 4);
  const CompactModel m = compact_encode(seq);
  const std::string bytes = serialize_model_c4d(m);
  const CompactModel back = parse_model_c4d(bytes);
  EXPECT_EQ(serialize_model_c4d(back), bytes);
  // Every truncated prefix fails cleanly.
  for (std::size_t n = 0; n < bytes.size(); n += 7) EXPECT_THROW(parse_model_c4d(bytes.substr(0, n)), IoError) << n;
  // A flipped payload bit fails the checksum.
  std::string bad = bytes;
  bad[bad.size() / 2] = static_cast<char>(bad[bad.size() / 2] ^ 0x10);
  EXPECT_THROW(parse_model_c4d(bad), IoError);
  std::string wrong = bytes;
  wrong[0] = 'X';
  try {
    parse_model_c4d(wrong);
    FAIL();
  } catch (const IoError& e) {
    EXPECT_EQ(e.code(), ErrorCode::Format);
  }
}

// CompactError::Surface: every decoded vertex within the tolerance of its frame's input surface
// (checked here against all triangles), a smaller file than the vertex bound, and the mode survives
// the file round trip.
TEST(Compact, SurfaceErrorBoundHoldsAndIsSmaller) {
  const MeshSequence seq = noisy_beating(3, 6);
  CompactOptions opt;
  opt.control_vertices = 60;
  CompactStats sv, ss;
  const CompactModel mv = compact_encode(seq, opt, nullptr, &sv);
  opt.error = CompactError::Surface;
  std::vector<std::uint32_t> order;
  const CompactModel ms = compact_encode(seq, opt, &order, &ss);
  EXPECT_LE(ss.max_surface_error, opt.tolerance);
  EXPECT_LT(serialize_model_c4d(ms).size(), serialize_model_c4d(mv).size());
  const CompactModel back = parse_model_c4d(serialize_model_c4d(ms));
  EXPECT_EQ(back.error, CompactError::Surface);
  const MeshSequence out = compact_decode(back);
  std::vector<Vec3> input(order.size());
  std::vector<Triangle> tris = out.triangles;  // model ids; map the input into them
  double worst = 0.0;
  for (std::size_t f = 0; f < seq.positions.size(); ++f) {
    for (std::size_t v = 0; v < order.size(); ++v) input[v] = seq.positions[f][order[v]];
    for (const Vec3& p : out.positions[f]) worst = std::max(worst, surface_distance(p, input, tris));
  }
  EXPECT_LE(worst, opt.tolerance);
  EXPECT_GT(sv.corrected_vertices, 0u);
}

// Base mesh + displacement maps: the displaced lattice samples lie on the fine surface (they are
// its intersections with the patch normals), the smooth PN patches alone do not; the CPU
// tessellation has level² triangles per base triangle and shares edge vertices.
TEST(DisplacementMap, SamplesLieOnTheFineSurface) {
  const auto [seq, po, pm] = test::beating_patches(3, 3, 80, 4);
  ASSERT_GT(pm.triangles.size(), 40u);
  EXPECT_EQ(pm.missed, 0u);
  EXPECT_EQ(pm.displacement.size(), seq.positions.size() * pm.triangles.size() * patch_samples(po.grid));
  double on = 0.0, off = 0.0;
  for (std::size_t f = 0; f < seq.positions.size(); ++f)
    for (std::size_t t = 0; t < pm.triangles.size(); t += 3)
      for (int j = 0; j <= po.grid; ++j)
        for (int i = 0; i + j <= po.grid; ++i) {
          const double b1 = double(i) / po.grid, b2 = double(j) / po.grid;
          on = std::max(on, surface_distance(patch_point(pm, f, t, b1, b2), seq.positions[f], seq.triangles));
          off = std::max(off, surface_distance(patch_point(pm, f, t, b1, b2, false), seq.positions[f], seq.triangles));
        }
  EXPECT_LT(on, 1e-3);
  EXPECT_GT(off, 10 * on);
  const MeshSequence tess = tessellate_patches(pm, 3);
  EXPECT_EQ(tess.triangles.size(), pm.triangles.size() * 9);
  // Closed base mesh: V - E + F = 2 with shared edge vertices (E = 3F/2).
  const long long F = static_cast<long long>(tess.triangles.size()), V = static_cast<long long>(tess.positions[0].size());
  EXPECT_EQ(V - 3 * F / 2 + F, 2);
  EXPECT_THROW(build_patch_mesh(seq, PatchOptions{80, 0, 4.0}), InvalidInput);
}

TEST(Compact, RejectsInconsistentFrames) {
  MeshSequence seq = synthetic_beating_mesh(1, 3);
  seq.positions[2].pop_back();
  EXPECT_THROW(compact_encode(seq), InvalidInput);
  MeshFrames frames;
  const MeshSequence good = synthetic_beating_mesh(1, 2);
  frames.meshes = {good.frame(0), good.frame(1)};
  frames.meshes[1].triangles[0] = {0, 2, 1};
  frames.times_ms = {0, 1};
  EXPECT_THROW(to_mesh_sequence(frames, "x"), InvalidInput);
}

}  // namespace
}  // namespace c4d
