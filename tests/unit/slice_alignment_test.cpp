// Breath-hold slice alignment (slice_alignment.h) on families of stacks with random seeds: ventricles with a
// gently bent long axis, random stack orientations, one or two slices shifted 2–5 mm in their plane in every
// frame. The shifted slices go back to within 0.3 mm of where they were, the others barely move, every move lies
// in its slice plane, and the result does not depend on the stack's orientation or the frames' order.
#include "contour4d/core/slice_alignment.h"

#include <cmath>
#include <algorithm>
#include <functional>
#include <numbers>
#include <random>

#include <gtest/gtest.h>

namespace c4d {
namespace {

struct Stack {
  Sequence seq;
  std::vector<Vec2> truth_centre;                  // per slice index: the centre before any shift (u, v)
  std::function<Vec3(int, double, double)> point;  // the ventricle: frame, offset z (mm), angle t about its axis
};

Vec3 unit(Vec3 a) { return a * (1.0 / std::sqrt(dot(a, a))); }

// A random orthonormal frame (u, v, normal).
void random_axes(std::mt19937& rng, Sequence& seq) {
  std::normal_distribution<double> g(0.0, 1.0);
  const Vec3 n = unit({g(rng), g(rng), g(rng)});
  const Vec3 e = std::abs(n.x) < 0.9 ? Vec3{1, 0, 0} : Vec3{0, 1, 0};
  seq.normal = n;
  seq.u = unit(cross(n, e));
  seq.v = cross(n, seq.u);
}

// `slices` slices 8 mm apart, the centre on a bent axis (quadratic in the offset), radii narrowing towards the
// apex and contracting over `frames` frames; each slice's points carry `extra` harmonics (irregular contours).
Stack bent_stack(std::mt19937& rng, int slices, int frames) {
  std::uniform_real_distribution<double> bend(-0.02, 0.02), tilt(-0.15, 0.15), harmonic(-0.06, 0.06), phase(0, 6.28);
  Stack s;
  random_axes(rng, s.seq);
  const double bu = bend(rng), bv = bend(rng), tu = tilt(rng), tv = tilt(rng), h = harmonic(rng), ph = phase(rng);
  const Vec3 n = s.seq.normal, u = s.seq.u, v = s.seq.v;
  s.point = [=](int f, double z, double t) {
    const double squeeze = 1.0 - 0.2 * std::sin(std::numbers::pi * f / std::max(frames, 2));
    const double k = (z + 4.0 * (slices - 1)) / 8.0;  // the slice index, continuous
    const Vec2 c{tu * z + bu * z * z, tv * z + bv * z * z};
    const double rr = squeeze * (10.0 + 20.0 * std::sqrt((k + 1) / slices)) * (1 + h * std::cos(3 * t + ph));
    return n * z + u * (c.x + rr * std::cos(t)) + v * (c.y + rr * std::sin(t));
  };
  for (int f = 0; f < frames; ++f) {
    Frame frame;
    frame.time_ms = 40.0 * f;
    for (int k = 0; k < slices; ++k) {
      const double z = 8.0 * k - 4.0 * (slices - 1);
      if (f == 0) s.truth_centre.push_back({tu * z + bu * z * z, tv * z + bv * z * z});
      Contour con;
      con.label = "lv-endo";
      con.slice = k;
      for (int i = 0; i < 48; ++i) con.points.push_back(s.point(f, z, 2 * std::numbers::pi * i / 48));
      frame.slices.push_back({k, z, {con}});
    }
    s.seq.frames.push_back(frame);
  }
  return s;
}

void shift_slice(Sequence& seq, int id, Vec3 d) {
  for (Frame& f : seq.frames)
    for (Slice& s : f.slices)
      if (s.id == id)
        for (Contour& c : s.contours)
          for (Vec3& p : c.points) p = p + d;
}

// The in-plane centre of slice `id` in frame 0 (mean of its points: the contours are regular).
Vec2 centre_of(const Sequence& seq, int id) {
  for (const Slice& s : seq.frames.front().slices)
    if (s.id == id) {
      Vec3 m{};
      for (const Vec3& p : s.contours.front().points) m = m + p;
      m = m * (1.0 / static_cast<double>(s.contours.front().points.size()));
      return {dot(m, seq.u), dot(m, seq.v)};
    }
  return {};
}

TEST(SliceAlignment, ShiftedSlicesGoBackOnFamilies) {
  for (int seed = 0; seed < 40; ++seed) {
    std::mt19937 rng(static_cast<unsigned>(seed));
    const int slices = 7 + seed % 8, frames = 1 + seed % 5;
    Stack s = bent_stack(rng, slices, frames);
    std::uniform_real_distribution<double> size(2.0, 5.0), angle(0, 2 * std::numbers::pi);
    std::uniform_int_distribution<int> pick(0, slices - 1);
    const int moved = pick(rng);
    const int moved2 = seed % 3 == 0 ? (moved + slices / 2) % slices : -1;
    for (int id : {moved, moved2}) {
      if (id < 0) continue;
      const double a = angle(rng), l = size(rng);
      shift_slice(s.seq, id, (s.seq.u * std::cos(a) + s.seq.v * std::sin(a)) * l);
    }
    const SliceAlignment al = align_slices(s.seq);
    ASSERT_EQ(al.label, "lv-endo");
    ASSERT_EQ(static_cast<int>(al.shifts.size()), slices) << "seed " << seed;
    EXPECT_EQ(al.degree, 2) << "seed " << seed;
    for (const SliceShift& sh : al.shifts) {
      EXPECT_NEAR(dot(sh.shift, s.seq.normal), 0.0, 1e-9) << "the move leaves the slice plane, seed " << seed;
      const Vec2 c = centre_of(s.seq, sh.slice);
      const Vec2 t = s.truth_centre[static_cast<std::size_t>(sh.slice)];
      const double off = std::hypot(c.x - t.x, c.y - t.y);
      const bool was_moved = sh.slice == moved || sh.slice == moved2;
      EXPECT_LT(off, was_moved ? 0.3 : 0.2) << "seed " << seed << " slice " << sh.slice << " moved " << sh.shift_mm;
      if (was_moved) {
        EXPECT_GT(sh.shift_mm, 1.7) << "seed " << seed;
      }
    }
  }
}

TEST(SliceAlignment, AnUnshiftedStackStaysPut) {
  for (int seed = 0; seed < 10; ++seed) {
    std::mt19937 rng(static_cast<unsigned>(100 + seed));
    Stack s = bent_stack(rng, 10, 3);
    const SliceAlignment al = align_slices(s.seq);
    for (const SliceShift& sh : al.shifts) EXPECT_LT(sh.shift_mm, 1e-6) << "seed " << seed;
  }
}

TEST(SliceAlignment, IndependentOfOrientationAndFrameOrder) {
  std::mt19937 rng(7);
  Stack a = bent_stack(rng, 9, 4);
  shift_slice(a.seq, 3, a.seq.u * 3.5);
  Sequence b = a.seq;
  std::reverse(b.frames.begin(), b.frames.end());
  // The same stack turned rigidly: a rotation about the normal (u, v turned by 40°) and a translation.
  Sequence c = a.seq;
  const double th = 0.7;
  const Vec3 u2 = c.u * std::cos(th) + c.v * std::sin(th), v2 = c.v * std::cos(th) - c.u * std::sin(th);
  for (Frame& f : c.frames)
    for (Slice& s : f.slices)
      for (Contour& con : s.contours)
        for (Vec3& p : con.points) {
          const double pu = dot(p, a.seq.u), pv = dot(p, a.seq.v), pn = dot(p, a.seq.normal);
          p = u2 * pu + v2 * pv + a.seq.normal * pn + Vec3{5, -3, 2};
        }
  const SliceAlignment ra = align_slices(a.seq), rb = align_slices(b), rc = align_slices(c);
  ASSERT_EQ(ra.shifts.size(), rb.shifts.size());
  ASSERT_EQ(ra.shifts.size(), rc.shifts.size());
  for (std::size_t i = 0; i < ra.shifts.size(); ++i) {
    EXPECT_NEAR(ra.shifts[i].shift_mm, rb.shifts[i].shift_mm, 1e-9);
    EXPECT_NEAR(ra.shifts[i].shift_mm, rc.shifts[i].shift_mm, 1e-6);
  }
}

// A long stack (a CT series has hundreds of slices): the robust start samples its slices, the shifted one
// still goes back.
TEST(SliceAlignment, LongStackIsHandled) {
  std::mt19937 rng(11);
  Stack s = bent_stack(rng, 150, 1);
  shift_slice(s.seq, 77, s.seq.v * 4.0);
  const SliceAlignment al = align_slices(s.seq);
  ASSERT_EQ(al.shifts.size(), 150u);
  const Vec2 c = centre_of(s.seq, 77), t = s.truth_centre[77];
  EXPECT_LT(std::hypot(c.x - t.x, c.y - t.y), 0.3);
}

TEST(SliceAlignment, TooFewSlicesMoveNothing) {
  std::mt19937 rng(3);
  Stack s = bent_stack(rng, 2, 2);
  const Sequence before = s.seq;
  const SliceAlignment al = align_slices(s.seq);
  EXPECT_EQ(al.degree, -1);
  EXPECT_TRUE(al.shifts.empty());
  EXPECT_EQ(s.seq.frames[1].slices[1].contours[0].points[5].x, before.frames[1].slices[1].contours[0].points[5].x);
}

// Long-axis views of the ventricle of `s`: for each angle a (radians), in every frame, the curve up one side of the
// plane through the axis at a and down the other, sampled every 0.25 mm of offset from half a gap below the first
// slice to half a gap above the last (biv-me's LAX contours, drawn on other images).
std::vector<GuideCurve> long_axis_views(const Stack& s, const std::vector<double>& angles) {
  std::vector<GuideCurve> out;
  const double lo = s.seq.frames.front().slices.front().offset - 4.0 + 0.1;
  const double hi = s.seq.frames.front().slices.back().offset + 4.0;
  for (std::size_t f = 0; f < s.seq.frames.size(); ++f)
    for (std::size_t k = 0; k < angles.size(); ++k) {
      GuideCurve c;
      c.frame = static_cast<int>(f);
      c.plane = 100 + static_cast<int>(k);
      c.label = "lax-lv-endo";
      for (double z = hi; z >= lo; z -= 0.25) c.points.push_back(s.point(static_cast<int>(f), z, angles[k]));
      for (double z = lo; z <= hi; z += 0.25)
        c.points.push_back(s.point(static_cast<int>(f), z, angles[k] + std::numbers::pi));
      out.push_back(std::move(c));
    }
  return out;
}

// With long-axis views (two or three, at contour vertex angles), every shifted slice goes back to within 0.05 mm
// and the others stay within 0.05 mm, on families of stacks with random seeds; each move lies in its slice plane.
TEST(SliceAlignmentOnLongAxis, ShiftedSlicesGoBackOnFamilies) {
  for (int seed = 0; seed < 24; ++seed) {
    std::mt19937 rng(static_cast<unsigned>(500 + seed));
    const int slices = 5 + seed % 8, frames = 1 + seed % 4;
    Stack s = bent_stack(rng, slices, frames);
    const double step = 2 * std::numbers::pi / 48;
    const std::vector<double> angles =
        seed % 2 ? std::vector<double>{0.0, 12 * step} : std::vector<double>{3 * step, 19 * step, 35 * step};
    const std::vector<GuideCurve> curves = long_axis_views(s, angles);
    std::uniform_real_distribution<double> size(2.0, 5.0), angle(0, 2 * std::numbers::pi);
    std::uniform_int_distribution<int> pick(0, slices - 1);
    const int moved = pick(rng), moved2 = seed % 3 == 0 ? (moved + slices / 2) % slices : -1;
    for (int id : {moved, moved2}) {
      if (id < 0) continue;
      const double a = angle(rng), l = size(rng);
      shift_slice(s.seq, id, (s.seq.u * std::cos(a) + s.seq.v * std::sin(a)) * l);
    }
    const SliceAlignment al = align_slices_to_curves(s.seq, curves);
    ASSERT_EQ(al.method, "long-axis");
    ASSERT_EQ(al.label, "lv-endo");
    ASSERT_EQ(static_cast<int>(al.shifts.size()), slices) << "seed " << seed;
    for (const SliceShift& sh : al.shifts) {
      EXPECT_EQ(sh.crossings, static_cast<int>(2 * angles.size()) * frames) << "seed " << seed;
      EXPECT_NEAR(dot(sh.shift, s.seq.normal), 0.0, 1e-9) << "the move leaves the slice plane, seed " << seed;
      const Vec2 c = centre_of(s.seq, sh.slice), t = s.truth_centre[static_cast<std::size_t>(sh.slice)];
      EXPECT_LT(std::hypot(c.x - t.x, c.y - t.y), 0.05) << "seed " << seed << " slice " << sh.slice;
    }
  }
}

// One view fixes a slice in one direction only (its crossings' normals all lie along its plane): nothing moves.
// Without curves of the structure, the centroids' axis is used.
TEST(SliceAlignmentOnLongAxis, OneViewMovesNothingAndNoViewFallsBack) {
  std::mt19937 rng(42);
  Stack s = bent_stack(rng, 8, 2);
  shift_slice(s.seq, 4, s.seq.u * 3.0);
  const Sequence before = s.seq;
  const SliceAlignment one = align_slices_to_curves(s.seq, long_axis_views(s, {0.0}));
  EXPECT_EQ(one.method, "long-axis");
  for (const SliceShift& sh : one.shifts) {
    EXPECT_EQ(sh.shift_mm, 0.0) << "slice " << sh.slice;
    EXPECT_EQ(sh.weight, 0.0);
  }
  EXPECT_EQ(s.seq.frames[1].slices[4].contours[0].points[7].x, before.frames[1].slices[4].contours[0].points[7].x);
  std::vector<GuideCurve> other = long_axis_views(s, {0.0, 1.0});
  for (GuideCurve& c : other) c.label = "lax-rv-endo";
  const SliceAlignment fallback = align_slices_to_curves(s.seq, other);
  EXPECT_EQ(fallback.method, "centroid-axis");
  EXPECT_GT(fallback.shifts[4].shift_mm, 2.0);
}

// The moves do not depend on where the study lies (a rotation about the stack normal and a translation of the
// contours and the views together), nor on the order of the views.
TEST(SliceAlignmentOnLongAxis, IndependentOfRigidMotionAndViewOrder) {
  std::mt19937 rng(9);
  Stack s = bent_stack(rng, 7, 3);
  shift_slice(s.seq, 2, s.seq.v * 2.5 - s.seq.u * 1.5);
  const double step = 2 * std::numbers::pi / 48;
  const std::vector<GuideCurve> curves = long_axis_views(s, {5 * step, 21 * step});
  const double th = 0.7;
  const Vec3 u2 = s.seq.u * std::cos(th) + s.seq.v * std::sin(th), v2 = s.seq.v * std::cos(th) - s.seq.u * std::sin(th);
  const auto turn = [&](Vec3 p) {
    return u2 * dot(p, s.seq.u) + v2 * dot(p, s.seq.v) + s.seq.normal * dot(p, s.seq.normal) + Vec3{5, -3, 2};
  };
  Sequence moved = s.seq;
  for (Frame& f : moved.frames)
    for (Slice& sl : f.slices) {
      sl.offset += dot(Vec3{5, -3, 2}, s.seq.normal);
      for (Contour& c : sl.contours)
        for (Vec3& p : c.points) p = turn(p);
    }
  std::vector<GuideCurve> moved_curves = curves;
  for (GuideCurve& c : moved_curves)
    for (Vec3& p : c.points) p = turn(p);
  std::reverse(moved_curves.begin(), moved_curves.end());
  Sequence a = s.seq;
  const SliceAlignment ra = align_slices_to_curves(a, curves), rb = align_slices_to_curves(moved, moved_curves);
  ASSERT_EQ(ra.shifts.size(), rb.shifts.size());
  for (std::size_t i = 0; i < ra.shifts.size(); ++i) {
    EXPECT_NEAR(ra.shifts[i].shift_mm, rb.shifts[i].shift_mm, 1e-6) << "slice " << ra.shifts[i].slice;
    EXPECT_EQ(ra.shifts[i].crossings, rb.shifts[i].crossings);
  }
  EXPECT_GT(ra.shifts[2].shift_mm, 2.5);
}

}  // namespace
}  // namespace c4d
