// Tests of stack validation (include/contour4d/core/stack.h): invariances of the derived stack and
// one test per rejected input.
#include "contour4d/core/stack.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "contour4d/core/errors.h"

namespace c4d {
namespace {

std::vector<Vec3> circle(Vec3 center, Vec3 n, double r, int count = 16, double phase = 0.0) {
  const Plane pl = make_plane(center, n);
  std::vector<Vec3> pts;
  for (int k = 0; k < count; ++k) {
    const double a = phase + 2 * std::numbers::pi * k / count;
    pts.push_back(from_plane(pl, {r * std::cos(a), 0.7 * r * std::sin(a)}));
  }
  return pts;
}

const Vec3 kNormal = normalized(Vec3{0.61, -0.49, 0.62});
const Vec3 kOrigin{-180.0, -100.0, -90.0};

//! 5 slices (ids 2..6) 10 mm apart along kNormal, 2 frames.
std::vector<RawContour> stack_contours() {
  std::vector<RawContour> raw;
  for (int f = 0; f < 2; ++f)
    for (int s = 0; s < 5; ++s) {
      RawContour rc;
      rc.frame = f;
      rc.index = s;
      rc.contour = {"lv", s + 2, circle(kOrigin + (10.0 * s) * kNormal, kNormal, 25.0 - 2 * s - f)};
      raw.push_back(rc);
    }
  return raw;
}

ErrorCode code_of(const std::vector<RawContour>& raw, int frames = 2, std::string* msg = nullptr) {
  try {
    build_sequence(raw, frames, {}, "stack.json");
  } catch (const Error& e) {
    if (msg) *msg = e.what();
    return e.code();
  }
  return static_cast<ErrorCode>(0);
}

TEST(Stack, DerivesObliqueNormalOffsetsAndOrder) {
  const Sequence seq = build_sequence(stack_contours(), 2, {}, "s");
  EXPECT_LT(distance(seq.normal, kNormal), 1e-9);  // ids increase along kNormal
  EXPECT_NEAR(dot(seq.u, seq.normal), 0.0, 1e-12);
  EXPECT_NEAR(dot(seq.v, seq.normal), 0.0, 1e-12);
  EXPECT_LT(distance(cross(seq.u, seq.v), seq.normal), 1e-12);
  ASSERT_EQ(seq.frames.size(), 2u);
  for (const Frame& f : seq.frames) {
    ASSERT_EQ(f.slices.size(), 5u);
    for (std::size_t k = 0; k < 5; ++k) {
      EXPECT_EQ(f.slices[k].id, static_cast<int>(k) + 2);
      EXPECT_NEAR(f.slices[k].offset, dot(kOrigin, kNormal) + 10.0 * k, 1e-9);
      const Plane pl = slice_plane(seq, f.slices[k]);
      for (const Vec3& p : f.slices[k].contours[0].points) EXPECT_NEAR(signed_distance(pl, p), 0.0, 1e-9);
    }
  }
  EXPECT_DOUBLE_EQ(seq.frames[1].time_ms, 1.0);
}

TEST(Stack, InvariantToInputOrderOrientationAndStartPoint) {
  const Sequence ref = build_sequence(stack_contours(), 2, {}, "s");
  std::vector<RawContour> raw = stack_contours();
  std::reverse(raw.begin(), raw.end());
  for (RawContour& rc : raw) {
    std::reverse(rc.contour.points.begin(), rc.contour.points.end());
    std::rotate(rc.contour.points.begin(), rc.contour.points.begin() + 5, rc.contour.points.end());
  }
  const Sequence seq = build_sequence(raw, 2, {}, "s");
  EXPECT_LT(distance(seq.normal, ref.normal), 1e-12);
  for (std::size_t f = 0; f < 2; ++f)
    for (std::size_t k = 0; k < 5; ++k) {
      EXPECT_EQ(seq.frames[f].slices[k].id, ref.frames[f].slices[k].id);
      EXPECT_NEAR(seq.frames[f].slices[k].offset, ref.frames[f].slices[k].offset, 1e-9);
    }
}

TEST(Stack, ReversedIdsFlipTheNormal) {
  std::vector<RawContour> raw = stack_contours();
  for (RawContour& rc : raw) rc.contour.slice = 10 - rc.contour.slice;
  const Sequence seq = build_sequence(raw, 2, {}, "s");
  EXPECT_LT(distance(seq.normal, -kNormal), 1e-9);
  EXPECT_EQ(seq.frames[0].slices.front().id, 4);  // ids 4..8 after the relabelling
}

TEST(Stack, RigidMotionMovesNormalAndKeepsSpacing) {
  // Rotation by 90 degrees about z plus a translation.
  auto move = [](Vec3 p) { return Vec3{-p.y + 3.0, p.x - 7.0, p.z + 11.0}; };
  std::vector<RawContour> raw = stack_contours();
  for (RawContour& rc : raw)
    for (Vec3& p : rc.contour.points) p = move(p);
  const Sequence ref = build_sequence(stack_contours(), 2, {}, "s");
  const Sequence seq = build_sequence(raw, 2, {}, "s");
  const Vec3 n = move(ref.normal) - move(Vec3{});
  EXPECT_LT(distance(seq.normal, n), 1e-9);
  for (std::size_t k = 1; k < 5; ++k)
    EXPECT_NEAR(seq.frames[0].slices[k].offset - seq.frames[0].slices[k - 1].offset, 10.0, 1e-9);
}

TEST(Stack, DropsClosingPointAndRepeats) {
  std::vector<RawContour> raw = stack_contours();
  auto& pts = raw[0].contour.points;
  const std::size_t n = pts.size();
  pts.insert(pts.begin() + 3, pts[3]);
  pts.push_back(pts.front());
  const Sequence seq = build_sequence(raw, 2, {}, "s");
  EXPECT_EQ(seq.frames[0].slices[0].contours[0].points.size(), n);
}

TEST(Stack, LabelsAndSelection) {
  std::vector<RawContour> raw = stack_contours();
  RawContour epi = raw[2];
  epi.contour.label = "epi";
  epi.index = 99;
  raw.push_back(epi);
  epi.frame = 1;
  raw.push_back(epi);
  const Sequence seq = build_sequence(raw, 2, {}, "s");
  EXPECT_EQ(labels(seq), (std::vector<std::string>{"epi", "lv"}));
  const Sequence only = select_label(seq, "epi");
  ASSERT_EQ(only.frames[0].slices.size(), 1u);
  EXPECT_EQ(only.frames[0].slices[0].id, 4);
  EXPECT_EQ(labels(only), std::vector<std::string>{"epi"});
  try {
    select_label(seq, "rv");
    FAIL();
  } catch (const InvalidInput& e) {
    EXPECT_EQ(e.code(), ErrorCode::UnknownLabel);
    EXPECT_NE(std::string(e.what()).find("\"epi\", \"lv\""), std::string::npos) << e.what();
  }
}

TEST(Stack, SelectLabelMissingInOneFrameIsEmptyFrame) {
  std::vector<RawContour> raw = stack_contours();
  RawContour epi = raw[2];
  epi.contour.label = "epi";
  raw.push_back(epi);  // frame 0 only
  const Sequence seq = build_sequence(raw, 2, {}, "s");
  try {
    select_label(seq, "epi");
    FAIL();
  } catch (const InvalidInput& e) {
    EXPECT_EQ(e.code(), ErrorCode::EmptyFrame);
    EXPECT_EQ(e.where().frame, 1);
  }
}

TEST(Stack, NonFinite) {
  std::vector<RawContour> raw = stack_contours();
  raw[3].contour.points[2].y = std::nan("");
  std::string msg;
  EXPECT_EQ(code_of(raw, 2, &msg), ErrorCode::NonFinite);
  EXPECT_NE(msg.find("frame 0, slice 5, contour 3"), std::string::npos) << msg;
}

TEST(Stack, TooFewDistinctPoints) {
  std::vector<RawContour> raw = stack_contours();
  raw[1].contour.points = {{0, 0, 0}, {1, 0, 0}, {0, 0, 0}, {1, 0, 0}};
  EXPECT_EQ(code_of(raw), ErrorCode::DegenerateContour);
}

TEST(Stack, ZeroArea) {
  std::vector<RawContour> raw = stack_contours();
  raw[1].contour.points = {{0, 0, 0}, {1, 1, 1}, {2, 2, 2}, {5, 5, 5}};
  EXPECT_EQ(code_of(raw), ErrorCode::DegenerateContour);
}

TEST(Stack, SelfIntersection) {
  std::vector<RawContour> raw = stack_contours();
  std::swap(raw[4].contour.points[2], raw[4].contour.points[9]);
  EXPECT_EQ(code_of(raw), ErrorCode::SelfIntersection);
}

TEST(Stack, NotCoplanarWithinAFrame) {
  std::vector<RawContour> raw = stack_contours();
  RawContour extra = raw[1];
  extra.index = 10;
  extra.contour.points = circle(kOrigin + 10.5 * kNormal + Vec3{60, 0, 0}, kNormal, 5.0);
  raw.push_back(extra);
  std::string msg;
  EXPECT_EQ(code_of(raw, 2, &msg), ErrorCode::NotCoplanar);
  EXPECT_NE(msg.find("slice 3"), std::string::npos) << msg;
}

TEST(Stack, SliceMovingBetweenFramesIsAnError) {
  std::vector<RawContour> raw = stack_contours();
  for (Vec3& p : raw[6].contour.points) p += 1.0 * kNormal;  // frame 1, slice 3
  std::string msg;
  EXPECT_EQ(code_of(raw, 2, &msg), ErrorCode::NotCoplanar);
  EXPECT_NE(msg.find("moves between frames"), std::string::npos) << msg;
}

TEST(Stack, NotParallel) {
  std::vector<RawContour> raw = stack_contours();
  const Vec3 tilted = normalized(kNormal + Vec3{0.2, 0.0, 0.0});
  raw[2].contour.points = circle(kOrigin + 20.0 * kNormal, tilted, 21.0);
  EXPECT_EQ(code_of(raw), ErrorCode::NotParallel);
}

TEST(Stack, DuplicatePlane) {
  std::vector<RawContour> raw = stack_contours();
  RawContour extra = raw[0];
  extra.index = 10;
  extra.contour.slice = 40;
  extra.contour.points = circle(kOrigin + Vec3{0, 0, 0} + 0.02 * kNormal + Vec3{80, 0, -80}, kNormal, 5.0);
  // Keep it on slice 2's plane: remove the component along the normal except 0.02 mm.
  for (Vec3& p : extra.contour.points) p -= dot(Vec3{80, 0, -80}, kNormal) * kNormal;
  raw.push_back(extra);
  std::string msg;
  EXPECT_EQ(code_of(raw, 2, &msg), ErrorCode::DuplicatePlane);
  EXPECT_NE(msg.find("slice ids 2 and 40"), std::string::npos) << msg;
}

TEST(Stack, EmptyFrame) {
  std::string msg;
  EXPECT_EQ(code_of(stack_contours(), 3, &msg), ErrorCode::EmptyFrame);
  EXPECT_NE(msg.find("frame 2"), std::string::npos) << msg;
  EXPECT_EQ(code_of({}, 0), ErrorCode::EmptyFrame);
}

TEST(Stack, SmallTiltedContourWithinTolerancePasses) {
  // A 0.5 mm contour tilted 3 degrees stays within plane_tolerance: not an error.
  std::vector<RawContour> raw = stack_contours();
  RawContour small = raw[0];
  small.index = 10;
  const Vec3 tilted = normalized(kNormal + Vec3{0.05, 0.0, 0.0});
  small.contour.points = circle(kOrigin + Vec3{0, 0, 0}, tilted, 0.3, 8);
  for (Vec3& p : small.contour.points) p += 40.0 * make_plane({}, kNormal).u;
  raw.push_back(small);
  EXPECT_NO_THROW(build_sequence(raw, 2, {}, "s"));
}

}  // namespace
}  // namespace c4d
