// Repair, don't refuse (contour_repair.h): each flaw of drawn contours has its repair, the repaired
// contours pass the stack's validation, every repair is listed, and a clean stack is left untouched.
#include "contour4d/core/contour_repair.h"

#include <cmath>
#include <numbers>
#include <string>

#include <gtest/gtest.h>

#include "contour4d/core/contour.h"
#include "contour4d/core/errors.h"

namespace c4d {
namespace {

// A circle of radius r on the plane z = z0, n points, counter-clockwise.
std::vector<Vec3> circle(double r, double z0, int n) {
  std::vector<Vec3> p;
  for (int k = 0; k < n; ++k) {
    const double a = 2 * std::numbers::pi * k / n;
    p.push_back({r * std::cos(a), r * std::sin(a), z0});
  }
  return p;
}

RawContour raw(int frame, int slice, std::vector<Vec3> points, int index = 0) {
  RawContour rc;
  rc.frame = frame;
  rc.index = index;
  rc.contour.label = "lv";
  rc.contour.slice = slice;
  rc.contour.points = std::move(points);
  return rc;
}

// Three slices of circles: a clean stack.
std::vector<RawContour> clean_stack() {
  return {raw(0, 0, circle(20, 0, 60)), raw(0, 1, circle(22, 8, 64)), raw(0, 2, circle(20, 16, 60))};
}

bool has(const std::vector<ContourRepair>& log, const std::string& kind) {
  for (const ContourRepair& r : log)
    if (r.kind == kind) return true;
  return false;
}

// The repaired stack must be one build_sequence accepts.
void expect_valid(const std::vector<RawContour>& contours) { EXPECT_NO_THROW(build_sequence(contours, 1, {}, "test")); }

TEST(ContourRepair, CleanStackUntouched) {
  std::vector<RawContour> c = clean_stack();
  const std::vector<RawContour> before = c;
  EXPECT_TRUE(repair_contours(c).empty());
  ASSERT_EQ(c.size(), before.size());
  for (std::size_t i = 0; i < c.size(); ++i) EXPECT_EQ(c[i].contour.points, before[i].contour.points);
}

TEST(ContourRepair, OpenArcIsClosedAlongItsGap) {
  std::vector<RawContour> c = clean_stack();
  std::vector<Vec3>& p = c[1].contour.points;
  p.erase(p.begin(), p.begin() + 18);  // a quarter missing: a 30 mm gap against 2 mm spacing
  const double area_before = std::abs(signed_area([&] {
    std::vector<Vec2> q;
    for (const Vec3& v : circle(22, 8, 64)) q.push_back({v.x, v.y});
    return q;
  }()));
  const auto log = repair_contours(c);
  EXPECT_TRUE(has(log, "open-arc-closed"));
  std::vector<Vec2> q;
  for (const Vec3& v : c[1].contour.points) q.push_back({v.x, v.y});
  EXPECT_FALSE(is_self_intersecting(q));
  EXPECT_NEAR(std::abs(signed_area(q)) / area_before, 1.0, 0.05);  // the curve continues the circle
  expect_valid(c);
}

TEST(ContourRepair, OpenArcWithATailAcrossItIsRepairedOrDropped) {
  std::vector<RawContour> c = clean_stack();
  // A C-shaped arc (20°..340°) whose tail runs on through the middle and out across the far side: either
  // the tail is peeled off as doubled-back tracing and the arc closed, or the contour is dropped.
  std::vector<Vec3> p;
  for (int k = 0; k <= 40; ++k) {
    const double a = (20.0 + 320.0 * k / 40) * std::numbers::pi / 180;
    p.push_back({22 * std::cos(a), 22 * std::sin(a), 8});
  }
  for (int k = 1; k <= 25; ++k) p.push_back({p[40].x - 2.0 * k, p[40].y + 0.3 * k, 8});
  c[1].contour.points = p;
  const auto log = repair_contours(c);
  EXPECT_FALSE(log.empty());
  if (c.size() == 3) {
    std::vector<Vec2> q;
    for (const Vec3& v : c[1].contour.points) q.push_back({v.x, v.y});
    EXPECT_FALSE(is_self_intersecting(q));
  } else {
    EXPECT_TRUE(has(log, "open-arc-dropped"));
  }
  expect_valid(c);
}

TEST(ContourRepair, SmallLoopRemovedLargestLoopKept) {
  std::vector<RawContour> c = clean_stack();
  std::vector<Vec3>& p = c[0].contour.points;
  // A figure-eight's small lobe at point 10: out across the contour and back, crossing it.
  const Vec3 a = p[10], b = p[11];
  std::vector<Vec3> lobe{a + Vec3{3, 1, 0}, a + Vec3{3, -3, 0}, b + Vec3{-3, 1, 0}};
  p.insert(p.begin() + 11, lobe.begin(), lobe.end());
  std::vector<Vec2> q0;
  for (const Vec3& v : p) q0.push_back({v.x, v.y});
  ASSERT_TRUE(is_self_intersecting(q0));
  const auto log = repair_contours(c);
  EXPECT_TRUE(has(log, "loop-removed"));
  expect_valid(c);
}

TEST(ContourRepair, SpikeAndDoubledBackTracingRemoved) {
  std::vector<RawContour> c = clean_stack();
  std::vector<Vec3>& p = c[2].contour.points;
  p.insert(p.begin() + 5, p[4] * 1.8);              // a spike 16 mm out
  p.insert(p.begin() + 30, {p[31], p[32], p[31]});  // traced forward and back over two points
  const auto log = repair_contours(c);
  EXPECT_TRUE(has(log, "spike"));
  std::vector<Vec2> q;
  for (const Vec3& v : c[2].contour.points) q.push_back({v.x, v.y});
  EXPECT_FALSE(is_self_intersecting(q));
  expect_valid(c);
}

TEST(ContourRepair, TooFewPointsDropped) {
  std::vector<RawContour> c = clean_stack();
  c.push_back(raw(0, 3, {{0, 0, 24}}, 3));
  c.push_back(raw(0, 4, {{0, 0, 32}, {1, 0, 32}}, 4));
  const auto log = repair_contours(c);
  EXPECT_EQ(c.size(), 3u);
  EXPECT_TRUE(has(log, "too-few-points"));
  expect_valid(c);
}

TEST(ContourRepair, SlicesOnOnePlaneMergedLaterWins) {
  std::vector<RawContour> c = clean_stack();
  c.push_back(raw(0, 1, circle(10, 8, 40), 3));  // frame 0 would now have two contours on slice 1 ...
  c.pop_back();
  c.push_back(raw(0, 7, circle(21, 8.01, 64), 3));  // ... no: a re-acquisition of slice 1's plane as slice 7
  c.push_back(raw(1, 1, circle(22, 8, 64), 0));     // frame 1 has only the old id
  c.push_back(raw(1, 0, circle(20, 0, 60), 1));
  EXPECT_THROW(build_sequence(c, 2, {}, "test"), InvalidInput);  // today: exit 19
  const auto log = repair_contours(c);
  EXPECT_TRUE(has(log, "slices-merged"));
  const Sequence seq = build_sequence(c, 2, {}, "test");
  for (const Frame& f : seq.frames)
    for (const Slice& s : f.slices) EXPECT_NE(s.id, 1);  // merged into 7
  // In frame 0, slice 7's own contour won (radius 21), the old one was dropped.
  for (const Slice& s : seq.frames[0].slices)
    if (s.id == 7) {
      ASSERT_EQ(s.contours.size(), 1u);
      EXPECT_NEAR(std::hypot(s.contours[0].points[0].x, s.contours[0].points[0].y), 21.0, 1e-9);
    }
}

TEST(ContourRepair, NonFiniteIsLeftForValidationToRefuse) {
  std::vector<RawContour> c = clean_stack();
  c[0].contour.points[3].x = std::nan("");
  repair_contours(c);
  try {
    build_sequence(c, 1, {}, "test");
    FAIL() << "a NaN coordinate must still be refused";
  } catch (const InvalidInput& e) {
    EXPECT_EQ(e.code(), ErrorCode::NonFinite);
  }
}

}  // namespace
}  // namespace c4d
