// The output gate (result_check.h): every fault a broken frame can have is named with its frame, and a
// valid sequence passes, whatever the thread count.
#include <cmath>
#include <limits>
#include <utility>

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include "contour4d/metrics/result_check.h"
#include "metrics_fixtures.h"

namespace c4d {
namespace {

constexpr int kRings = 15, kPerRing = 64;

// Two frames of a sphere of radius 20 mm made of latitude rings, with its rings as the contours.
struct Case {
  MeshSequence result;
  Sequence contours;
};

Case sphere_case() {
  const TriangleMesh m = test::ring_sphere(20.0, kRings, kPerRing);
  Case c;
  c.result.triangles = m.triangles;
  c.result.positions = {m.positions, m.positions};
  c.result.times_ms = {0, 1};
  const Frame f = test::ring_contours(m, kRings, kPerRing);
  c.contours = test::z_sequence({f, f});
  return c;
}

bool mentions(const FrameCheck& c, const std::string& word) {
  for (const std::string& f : c.faults)
    if (f.find(word) != std::string::npos) return true;
  return false;
}

TEST(ResultCheck, ValidSequencePasses) {
  const Case c = sphere_case();
  const ResultCheck r = check_result(c.result, c.contours);
  EXPECT_TRUE(r.ok()) << r.summary();
  ASSERT_EQ(r.frames.size(), 2u);
  EXPECT_GT(r.frames[1].simpson_volume, 0.0);
  EXPECT_NEAR(r.frames[1].volume / r.frames[1].simpson_volume, 1.0, 0.05);
  EXPECT_TRUE(r.summary().empty());
}

TEST(ResultCheck, InsideOutFrameIsNamed) {
  Case c = sphere_case();
  for (Triangle& t : c.result.triangles) std::swap(t[1], t[2]);
  const ResultCheck r = check_result(c.result, c.contours);
  EXPECT_FALSE(r.ok());
  EXPECT_TRUE(mentions(r.frames[0], "inward"));
  EXPECT_NE(r.summary().find("frame 0"), std::string::npos);
}

TEST(ResultCheck, CollapsedFrameFailsTheVolumeBound) {
  Case c = sphere_case();
  for (Vec3& p : c.result.positions[1]) p = 0.6 * p;  // a fifth of the volume, still a valid surface
  const ResultCheck r = check_result(c.result, c.contours);
  EXPECT_TRUE(r.frames[0].ok());
  EXPECT_FALSE(r.frames[1].ok());
  EXPECT_TRUE(mentions(r.frames[1], "Simpson"));
  EXPECT_EQ(r.summary().rfind("frame 1:", 0), 0u) << r.summary();
  // Without contours there is nothing to compare the volume with.
  EXPECT_TRUE(check_result(c.result, Sequence{}).ok());
}

// A wall: the sphere of radius 20 with a cavity of radius `inner` (its rings reversed), and the sphere's rings as
// outer contours with circles of the cavity radius at the same heights as holes.
Case wall_case(double inner) {
  const TriangleMesh outer = test::ring_sphere(20.0, kRings, kPerRing);
  TriangleMesh cavity = test::ring_sphere(inner, kRings, kPerRing);
  Case c;
  c.result.triangles = outer.triangles;
  const auto offset = static_cast<std::uint32_t>(outer.positions.size());
  for (Triangle t : cavity.triangles) c.result.triangles.push_back({t[0] + offset, t[2] + offset, t[1] + offset});
  std::vector<Vec3> x = outer.positions;
  x.insert(x.end(), cavity.positions.begin(), cavity.positions.end());
  c.result.positions = {x};
  c.result.times_ms = {0};
  Frame f = test::ring_contours(outer, kRings, kPerRing);
  for (Slice& sl : f.slices) {
    const double z = sl.contours.front().points.front().z;
    if (std::abs(z) >= 15.0) continue;
    Contour hole;
    const double r = std::sqrt(15.0 * 15.0 - z * z);
    for (int k = 0; k < kPerRing; ++k) {
      const double a = 2 * 3.14159265358979323846 * k / kPerRing;
      hole.points.push_back({r * std::cos(a), r * std::sin(a), z});
    }
    sl.contours.push_back(hole);
  }
  c.contours = test::z_sequence({f});
  return c;
}

TEST(ResultCheck, AWallIsWeighedAgainstTheVolumeItsOuterContoursEnclose) {
  // The wall between radius 15 and 20 passes; its discs subtract the holes, and the outer discs do not.
  const ResultCheck ok = check_result(wall_case(15.0).result, wall_case(15.0).contours);
  EXPECT_TRUE(ok.ok()) << ok.summary();
  ASSERT_EQ(ok.frames.size(), 1u);
  EXPECT_GT(ok.frames[0].simpson_outer_volume, 1.5 * ok.frames[0].simpson_volume);
  // A wall that collapsed (its cavity grown to radius 19.5, a tenth of the wall left) is far out and named.
  const Case collapsed = wall_case(19.5);
  const ResultCheck r = check_result(collapsed.result, collapsed.contours);
  EXPECT_FALSE(r.ok());
  EXPECT_TRUE(mentions(r.frames[0], "its outer contours enclose")) << r.summary();
}

TEST(ResultCheck, HoleIsAFaultUnlessEndsAreOpen) {
  Case c = sphere_case();
  c.result.triangles.pop_back();
  EXPECT_TRUE(mentions(check_result(c.result, c.contours).frames[1], "not closed"));
  ResultCheckOptions open;
  open.closed = false;
  EXPECT_TRUE(check_result(c.result, c.contours, open).ok());
}

TEST(ResultCheck, CrossingTrianglesAreCounted) {
  Case c = sphere_case();
  // Pull one ring through the opposite side of the sphere: its triangles cross others.
  for (int j = 0; j < kPerRing / 4; ++j) {
    Vec3& p = c.result.positions[1][static_cast<std::size_t>(1 + 7 * kPerRing + j)];
    p = Vec3{-1.6 * p.x, -1.6 * p.y, p.z};
  }
  const ResultCheck r = check_result(c.result, c.contours);
  EXPECT_TRUE(r.frames[0].ok());
  EXPECT_GT(r.frames[1].self_intersections, 0u);
  EXPECT_TRUE(mentions(r.frames[1], "intersect"));
}

TEST(ResultCheck, NonFiniteOrMissingVerticesBreakCorrespondence) {
  Case c = sphere_case();
  c.result.positions[1][3].x = std::numeric_limits<double>::quiet_NaN();
  EXPECT_TRUE(mentions(check_result(c.result, c.contours).frames[1], "non-finite"));
  c.result.positions[1].pop_back();
  EXPECT_TRUE(mentions(check_result(c.result, c.contours).frames[1], "correspondence"));
}

TEST(ResultCheck, SameAnswerAtOneAndTwoThreads) {
  Case c = sphere_case();
  for (Vec3& p : c.result.positions[1]) p = 0.6 * p;
  std::string one, two;
  {
    tbb::global_control g(tbb::global_control::max_allowed_parallelism, 1);
    one = check_result(c.result, c.contours).summary();
  }
  {
    tbb::global_control g(tbb::global_control::max_allowed_parallelism, 2);
    two = check_result(c.result, c.contours).summary();
  }
  EXPECT_EQ(one, two);
}

}  // namespace
}  // namespace c4d
