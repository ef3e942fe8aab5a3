// The solver hand-off's pieces on shapes built in code: time steps, the weights every output time uses, tet
// quality measures, the cavity mesh (its boundary the surface, unchanged) and its motion with the wall (no
// inverted tet, the cavity's volume the surface's, the same bits whatever the thread count).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>

#include "contour4d/core/errors.h"
#include "contour4d/metrics/crease.h"
#include "contour4d/metrics/tet_quality.h"
#include "contour4d/metrics/topology.h"
#include "contour4d/phantoms/phantom.h"
#include "contour4d/pipeline/export_run.h"
#include "contour4d/surface/reconstruct.h"
#include "contour4d/solver/cavity_mesh.h"
#include "contour4d/solver/cavity_motion.h"
#include "contour4d/solver/ends.h"
#include "contour4d/solver/tet_untangle.h"
#include "contour4d/solver/time_steps.h"
#include "contour4d/temporal/interpolate.h"
#include "contour4d/temporal/sequence.h"

namespace c4d {
namespace {

TEST(TimeSteps, StepsAndDtCutTheCycle) {
  const TimeSteps a = make_time_steps(0.8, {40, 0.0, 2});
  EXPECT_EQ(a.steps_per_cycle, 40u);
  EXPECT_DOUBLE_EQ(a.dt_s, 0.02);
  ASSERT_EQ(a.times_s.size(), 81u);  // two cycles, both ends included
  EXPECT_DOUBLE_EQ(a.times_s.back(), 1.6);
  const TimeSteps b = make_time_steps(0.8, {0, 0.001, 1});
  EXPECT_EQ(b.steps_per_cycle, 800u);
  EXPECT_EQ(make_time_steps(0.8, {}).steps_per_cycle, 100u);  // the default
}

TEST(TimeSteps, BadOptionsAreUsageErrors) {
  try {
    make_time_steps(0.829, {0, 0.002, 1});  // 414.5 steps
    FAIL() << "no throw";
  } catch (const InvalidInput& e) {
    EXPECT_EQ(e.code(), ErrorCode::Usage);
    EXPECT_NE(std::string(e.what()).find("does not divide"), std::string::npos);
  }
  EXPECT_THROW(make_time_steps(0.8, {10, 0.01, 1}), InvalidInput);
  EXPECT_THROW(make_time_steps(0.8, {10, 0.0, 0}), InvalidInput);
}

TEST(TimeSteps, WeightsGiveInterpolatePositionsBitForBit) {
  const MeshSequence seq = synthetic_beating_mesh(1, 7);
  for (double t : {0.0, 0.0371, 0.5, 0.9999, 1.3}) {
    const auto a = combine_frames(seq.positions, step_weights(seq, t));
    const auto b = interpolate_positions(seq, seq.times_ms.front() + 1000.0 * t, TimeInterpolation::CatmullRomPeriodic);
    ASSERT_EQ(a.size(), b.size());
    for (std::size_t v = 0; v < a.size(); ++v) {
      EXPECT_EQ(a[v].x, b[v].x);
      EXPECT_EQ(a[v].y, b[v].y);
      EXPECT_EQ(a[v].z, b[v].z);
    }
  }
  // At a frame's time the frame itself, exactly; over the wrap periodic.
  EXPECT_EQ(combine_frames(seq.positions, step_weights(seq, 0.0))[5].x, seq.positions[0][5].x);
}

TEST(TetQuality, RegularTetIsTheIdeal) {
  const Vec3 a{1, 1, 1}, b{1, -1, -1}, c{-1, 1, -1}, d{-1, -1, 1};
  const Vec3 p[4] = {a, b, c, d};
  const double v = tet_volume(a, b, c, d);
  const bool flip = v < 0;
  const Vec3 q2 = flip ? p[3] : p[2], q3 = flip ? p[2] : p[3];
  EXPECT_NEAR(tet_aspect_ratio(a, b, q2, q3), 1.0, 1e-12);
  EXPECT_NEAR(tet_min_dihedral_deg(a, b, q2, q3), std::acos(1.0 / 3.0) * 180.0 / std::numbers::pi, 1e-9);
  const TetQuality q = measure_tets({a, b, q2, q3}, {{0, 1, 2, 3}});
  EXPECT_EQ(q.inverted, 0u);
  EXPECT_NEAR(q.volume_mm3, 8.0 / 3.0, 1e-12);
  const TetQuality inv = measure_tets({a, b, q3, q2}, {{0, 1, 2, 3}});
  EXPECT_EQ(inv.inverted, 1u);
  EXPECT_LT(inv.min_volume_mm3, 0.0);
}

class Cavity : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    seq_ = new MeshSequence(synthetic_beating_mesh(2, 10));
    mesh_ = new TetMesh(mesh_cavity(seq_->frame(0)));
  }
  static void TearDownTestSuite() {
    delete seq_;
    delete mesh_;
  }
  static MeshSequence* seq_;
  static TetMesh* mesh_;
};
MeshSequence* Cavity::seq_ = nullptr;
TetMesh* Cavity::mesh_ = nullptr;

TEST_F(Cavity, BoundaryIsTheSurfaceUnchanged) {
  const TetMesh& m = *mesh_;
  ASSERT_EQ(m.surface_nodes, seq_->positions[0].size());
  EXPECT_GT(m.nodes.size(), m.surface_nodes);  // inner nodes from the quality bound
  EXPECT_EQ(m.boundary, seq_->triangles);
  for (std::size_t v = 0; v < m.surface_nodes; ++v) EXPECT_EQ(m.nodes[v].x, seq_->positions[0][v].x);
  const TetQuality q = measure_tets(m.nodes, m.tets);
  EXPECT_EQ(q.inverted, 0u);
  EXPECT_NEAR(q.volume_mm3, signed_volume(seq_->frame(0)), 1e-9 * q.volume_mm3);
  EXPECT_GT(q.min_dihedral_deg, 5.0);
  for (std::size_t t = 0; t < m.boundary.size(); ++t) {
    const Tet& k = m.tets[m.boundary_tet[t]];
    int shared = 0;
    for (std::uint32_t v : m.boundary[t]) shared += std::count(k.begin(), k.end(), v) > 0 ? 1 : 0;
    EXPECT_EQ(shared, 3);
  }
}

TEST_F(Cavity, MovesWithTheWallWithoutInvertingAndKeepsItsVolume) {
  const TimeSteps steps = make_time_steps(1.0, {50, 0.0, 1});
  const CavityMotion m = cavity_motion(*mesh_, *seq_, steps.times_s, {2});
  EXPECT_EQ(m.extension, Extension::Harmonic);
  ASSERT_EQ(m.steps.size(), steps.times_s.size());
  for (std::size_t i = 0; i < m.steps.size(); ++i) {
    EXPECT_EQ(m.steps[i].inverted, 0u);
    const double surface =
        signed_volume({combine_frames(seq_->positions, step_weights(*seq_, steps.times_s[i])), seq_->triangles});
    EXPECT_NEAR(m.steps[i].volume_mm3, surface, 1e-9 * surface);
  }
  // The inner nodes at a key frame are the harmonic extension of that frame's wall: they solve the system.
  const auto nodes = cavity_nodes_at(*mesh_, *seq_, m, step_weights(*seq_, 0.3));
  for (std::size_t v = 0; v < mesh_->surface_nodes; ++v) EXPECT_EQ(nodes[v].x, seq_->positions[3][v].x);
  EXPECT_GT(m.min_dihedral_deg, 1.0);
}

// A family of tangles: the wall of a random key frame, the inner nodes in a ball of 3 mean edge lengths around a
// random node kicked by up to 0.9 edge lengths per axis (seeded), so that tens of tets invert. Untangling against frame 0's shapes leaves none
// inverted, moves only inner nodes, and gives the same bits when run twice.
TEST_F(Cavity, RandomTanglesAreUntangled) {
  const TetMesh& m = *mesh_;
  const NodeStars stars = node_stars(m.nodes.size(), m.tets);
  for (unsigned seed = 0; seed < 6; ++seed) {
    std::mt19937 rng(seed);
    const std::size_t frame = 1 + rng() % (seq_->positions.size() - 1);
    std::vector<Vec3> x = seq_->positions[frame];
    x.insert(x.end(), m.nodes.begin() + static_cast<std::ptrdiff_t>(m.surface_nodes), m.nodes.end());
    double edge = 0.0;  // the mean edge length of the tets
    for (const Tet& q : m.tets) edge += norm(m.nodes[q[1]] - m.nodes[q[0]]) / static_cast<double>(m.tets.size());
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    const Vec3 centre = x[m.surface_nodes + rng() % (m.nodes.size() - m.surface_nodes)];
    for (std::size_t v = m.surface_nodes; v < x.size(); ++v)
      if (norm(x[v] - centre) < 3.0 * edge) x[v] = x[v] + 0.9 * edge * Vec3{u(rng), u(rng), u(rng)};
    ASSERT_GT(measure_tets(x, m.tets).inverted, 3u) << "seed " << seed;
    std::vector<Vec3> again = x;
    EXPECT_GT(untangle_tets(x, m.nodes, m.tets, m.surface_nodes, stars), 0u);
    EXPECT_EQ(measure_tets(x, m.tets).inverted, 0u) << "seed " << seed;
    for (std::size_t v = 0; v < m.surface_nodes; ++v) EXPECT_EQ(x[v].x, seq_->positions[frame][v].x);
    untangle_tets(again, m.nodes, m.tets, m.surface_nodes, stars);
    for (std::size_t v = 0; v < x.size(); ++v) ASSERT_EQ(x[v].x, again[v].x);
  }
}

// A wall turned inside out (a frame mirrored through its centre) cannot hold a valid cavity: the motion throws
// InvertedElement, naming the time and both extensions, instead of returning folded tets.
TEST_F(Cavity, AWallTurnedInsideOutIsRefused) {
  MeshSequence seq = *seq_;
  Vec3 c;
  for (const Vec3& p : seq.positions[2]) c += p;
  c = (1.0 / static_cast<double>(seq.positions[2].size())) * c;
  for (Vec3& p : seq.positions[2]) p = c + Vec3{-(p - c).x, (p - c).y, (p - c).z};
  try {
    cavity_motion(*mesh_, seq, make_time_steps(1.0, {10, 0.0, 1}).times_s, {2});
    FAIL() << "no throw";
  } catch (const SolverError& e) {
    EXPECT_EQ(e.code(), ErrorCode::InvertedElement);
    EXPECT_NE(std::string(e.what()).find("harmonic extension"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("stiffened extension"), std::string::npos) << e.what();
  }
}

TEST_F(Cavity, ThreadCountDoesNotChangeABit) {
  const TimeSteps steps = make_time_steps(1.0, {20, 0.0, 1});
  const CavityMotion one = cavity_motion(*mesh_, *seq_, steps.times_s, {1});
  const CavityMotion two = cavity_motion(*mesh_, *seq_, steps.times_s, {2});
  for (std::size_t i = 0; i < one.steps.size(); ++i) {
    EXPECT_EQ(one.steps[i].volume_mm3, two.steps[i].volume_mm3);
    EXPECT_EQ(one.steps[i].min_dihedral_deg, two.steps[i].min_dihedral_deg);
    EXPECT_EQ(one.steps[i].max_aspect_ratio, two.steps[i].max_aspect_ratio);
  }
}

// A family of bases whose border leaves its plane: the ellipsoid phantom's one-frame surface, copied into 6
// frames, each frame's base region (the cap, the border, and the wall tapering to nothing 4 mm in) bent along the
// normal by a random wave of 2-5 mm and 1-3 periods around the border, and the whole frame scaled by a random
// 0.8-1.1 (seeded). Every frame's base comes out flat, unfolded and uncrossed, the wall off the band exactly as given,
// and the moving cavity valid at every step.
TEST(FlatEnds, RandomBentBordersAreFlattenedThroughTheirBand) {
  const Phantom ph = make_phantom("ellipsoid", {});
  const TriangleMesh m0 = reconstruct_frame(ph.contours, 0);
  const Vec3 n = ph.contours.normal;
  const std::vector<SurfaceEnd> ends = find_ends(m0, n);
  ASSERT_FALSE(ends.empty());
  const std::vector<int> base = choose_ends(ends, "base");
  ASSERT_EQ(base.size(), 1u);
  const SurfaceEnd& end = ends[static_cast<std::size_t>(base[0])];
  const Vec3 centre = end.centroid;
  const Vec3 a = normalized(cross(n, std::abs(n.x) < 0.9 ? Vec3{1, 0, 0} : Vec3{0, 1, 0})), b = cross(n, a);
  for (unsigned seed = 0; seed < 4; ++seed) {
    SCOPED_TRACE(seed);
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    MeshSequence seq;
    seq.triangles = m0.triangles;
    for (int f = 0; f < 6; ++f) {
      seq.times_ms.push_back(100.0 * f);
      std::vector<Vec3> x = m0.positions;
      if (f > 0) {
        const double amplitude = 2.0 + 3.0 * u(rng), phase = 6.3 * u(rng), scale = 0.8 + 0.3 * u(rng);
        const int waves = 1 + static_cast<int>(rng() % 3);
        for (Vec3& p : x) {
          const double h = end.side * (dot(n, p) - end.offset_mm);      // > 0 beyond the base plane
          const double reach = std::clamp(1.0 - (-h) / 4.0, 0.0, 1.0);  // 1 at and beyond the plane, 0 at 4 mm in
          const Vec3 r = p - centre;
          const double angle = std::atan2(dot(r, b), dot(r, a));
          p = p + reach * amplitude * std::sin(waves * angle + phase) * n;
          p = centre + scale * (p - centre);
        }
      }
      seq.positions.push_back(std::move(x));
    }
    for (std::size_t f = 0; f < seq.positions.size(); ++f)
      ASSERT_EQ(count_self_intersections({seq.positions[f], seq.triangles}), 0u) << "the bent input crosses";
    const FacedSequence faced = open_ends(seq, n, ends, base);
    EXPECT_TRUE(faced.not_flat_frames[0].empty());
    std::vector<char> off_band(seq.positions.front().size(), 1);
    for (std::uint32_t v : end.border) off_band[v] = 0;
    for (std::uint32_t v : end.inner) off_band[v] = 0;
    for (std::uint32_t v : faced.band[0]) off_band[v] = 0;
    for (std::size_t f = 0; f < seq.positions.size(); ++f) {
      const std::vector<Vec3>& x = faced.seq.positions[f];
      EXPECT_EQ(count_self_intersections({x, faced.seq.triangles}), 0u) << "frame " << f;
      const double plane = faced.plane_offset_mm[f];
      for (std::uint32_t t : end.triangles) {
        const Triangle& tri = faced.seq.triangles[t];
        EXPECT_GT(end.side * dot(cross(x[tri[1]] - x[tri[0]], x[tri[2]] - x[tri[0]]), n), 0.0) << "frame " << f;
        for (std::uint32_t v : tri) EXPECT_NEAR(dot(n, x[v]), plane, 1e-9);
      }
      for (std::size_t v = 0; v < x.size(); ++v) {
        if (!off_band[v]) continue;
        ASSERT_EQ(x[v].x, seq.positions[f][v].x) << "frame " << f << " vertex " << v;
      }
    }
    const TetMesh cavity = mesh_cavity(faced.seq.frame(0));
    const CavityMotion motion = cavity_motion(cavity, faced.seq, make_time_steps(0.6, {30, 0.0, 1}).times_s, {2});
    for (const TetQuality& q : motion.steps) EXPECT_EQ(q.inverted, 0u);
  }
}

// A wall folded back on itself in one frame (two triangles sharing an edge turned onto each other, a fin that
// crosses nothing): sharpest_fold finds it near 180° where the unfolded frames stay far below, and export_run
// refuses the sequence with InvertedElement (exit 31) naming the frame, before any cavity is meshed.
TEST(FlatEnds, AWallFoldedBackOnItselfIsRefusedByName) {
  const Phantom ph = make_phantom("ellipsoid", {});
  const TriangleMesh m0 = reconstruct_frame(ph.contours, 0);
  ExportInput in;
  in.folder = "folded";
  in.normal = ph.contours.normal;
  in.seq.triangles = m0.triangles;
  for (int f = 0; f < 3; ++f) {
    in.seq.positions.push_back(m0.positions);
    in.seq.times_ms.push_back(100.0 * f);
  }
  EXPECT_LT(sharpest_fold(m0).angle_deg, 90.0);
  // Triangle 0 (a, b, c) and its neighbour across a-b (b, a, d): d moved onto c's side of a-b.
  const Triangle t0 = m0.triangles[0];
  const std::uint32_t a = t0[0], b = t0[1], c = t0[2];
  std::uint32_t d = a;
  for (const Triangle& t : m0.triangles)
    for (int k = 0; k < 3; ++k)
      if (t[static_cast<std::size_t>(k)] == b && t[static_cast<std::size_t>((k + 1) % 3)] == a)
        d = t[static_cast<std::size_t>((k + 2) % 3)];
  ASSERT_NE(d, a);
  const Vec3 mid = 0.5 * (m0.positions[a] + m0.positions[b]);
  in.seq.positions[2][d] = mid + 0.8 * (m0.positions[c] - mid);
  EXPECT_GT(sharpest_fold(in.seq.frame(2)).angle_deg, 170.0);
  ExportRunOptions o;
  o.targets = {"vampy"};
  o.steps = {10, 0.0, 1};
  try {
    export_run(in, o);
    FAIL() << "no throw";
  } catch (const SolverError& e) {
    EXPECT_EQ(e.code(), ErrorCode::InvertedElement);
    EXPECT_NE(std::string(e.what()).find("frame 2: the wall folds back on itself"), std::string::npos) << e.what();
  }
}

TEST(CavityMesh, SelfIntersectingSurfaceFailsWithItsOwnCode) {
  TriangleMesh m = synthetic_beating_mesh(1, 1).frame(0);
  m.positions[0] = m.positions[0] * -1.5;  // pull one vertex out through the opposite side
  try {
    mesh_cavity(m);
    FAIL() << "no throw";
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ErrorCode::VolumeMeshFailed);
  }
}

}  // namespace
}  // namespace c4d
