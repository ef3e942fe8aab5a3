// Properties of the topology-change step (Lim et al. 2014, "Handling 2D Contour Topological Changes"):
// direction heuristic, ridge detection, sine vertical deformation (eq. 10, Table 1), on the idealized
// left heart (ED, ES, ED), whose slice y = -2.5 splits from ED to ES and merges back.
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>

#include <gtest/gtest.h>

#include "contour4d/core/errors.h"
#include "contour4d/motion/section.h"
#include "contour4d/motion/vertical_deformation.h"
#include "contour4d/phantoms/phantom.h"

namespace c4d {
namespace {

const Slice& slice_of(const Sequence& seq, int frame, int id) {
  for (const Slice& s : seq.frames.at(frame).slices)
    if (s.id == id) return s;
  throw std::runtime_error("slice " + std::to_string(id) + " missing in frame " + std::to_string(frame));
}

std::vector<Vec3> points_of(const Slice& s) {
  std::vector<Vec3> out;
  for (const Contour& c : s.contours) out.insert(out.end(), c.points.begin(), c.points.end());
  return out;
}

double offset_of(const Sequence& seq, int id) {
  for (const Frame& f : seq.frames)
    for (const Slice& s : f.slices)
      if (s.id == id) return s.offset;
  return std::nan("");
}

std::vector<Vec2> project(const std::vector<Vec3>& pts, Vec3 u, Vec3 v) {
  std::vector<Vec2> out;
  for (Vec3 p : pts) out.push_back({dot(p, u), dot(p, v)});
  return out;
}

double distance_to_polygon(Vec2 q, const std::vector<Vec2>& poly) {
  double best = 1e300;
  for (std::size_t i = 0; i < poly.size(); ++i)
    best = std::min(best, segment_distance(q, poly[i], poly[(i + 1) % poly.size()]));
  return best;
}

// Everything the step produces for one frame pair of a left-heart phantom.
struct Case {
  Phantom ph;
  VerticalMotion motion;
  Ridge ridge;
  VerticalField field;
  std::vector<Vec3> A, B, C, incident_points;
  TriangleMesh mesh;  // the truth of the earlier frame
};

Case run_case(bool oblique, int t, int t1, const VerticalDeformationOptions& opt = {}) {
  Case c;
  PhantomOptions po;
  po.oblique = oblique;
  c.ph = make_phantom("left-heart", po);
  const Sequence& seq = c.ph.contours;
  const auto motions = vertical_motions(seq, t, t1, opt);
  if (motions.size() != 1) throw std::runtime_error("expected one changing slice");
  c.motion = motions[0];
  const Slice& inc = slice_of(seq, t, c.motion.incident_slice);
  const Slice& comp = slice_of(seq, t, c.motion.complement_slice);
  // A: the lone contour of the pair; B, C: the two of the other slice.
  const Slice& lone = inc.contours.size() == 1 ? inc : comp;
  const Slice& pair = inc.contours.size() == 1 ? comp : inc;
  if (lone.contours.size() != 1 || pair.contours.size() != 2) throw std::runtime_error("unexpected contour counts");
  c.A = lone.contours[0].points;
  c.B = pair.contours[0].points;
  c.C = pair.contours[1].points;
  c.incident_points = points_of(inc);
  c.mesh = c.ph.truth.at(t);
  c.ridge = detect_ridge(c.mesh, c.A, c.B, c.C, seq.normal, opt);
  if (!c.ridge.found) throw std::runtime_error("no ridge");
  c.field = make_vertical_field(seq, c.motion, c.ridge.points, c.incident_points, opt);
  return c;
}

// ---------------------------------------------------------------------------------------------
// Direction

// In the left-heart phantom, offsets grow with world y (towards the caps): the legs (two contours) lie
// above the saddle and the trunk below it; from ED to ES the saddle descends by one slice gap.
TEST(VerticalMotion, LeftHeartSplitThenMerge) {
  const Phantom ph = make_phantom("left-heart");
  const Sequence& seq = ph.contours;
  for (MotionRule rule : {MotionRule::Auto, MotionRule::Counts}) {
    VerticalDeformationOptions opt;
    opt.rule = rule;
    // ED -> ES: the saddle descends through one slice: a split, motion Down, complement above it
    // (the slice that already has the two leg contours at ED).
    const auto split = vertical_motions(seq, 0, 1, opt);
    ASSERT_EQ(split.size(), 1u);
    const VerticalMotion& s = split[0];
    EXPECT_EQ(s.event, ContourEvent::Split);
    EXPECT_EQ(s.contours_before, 1);
    EXPECT_EQ(s.contours_after, 2);
    EXPECT_EQ(s.direction, VerticalDirection::Down);
    EXPECT_TRUE(s.decided_by_counts);
    EXPECT_GT(offset_of(seq, s.complement_slice), offset_of(seq, s.incident_slice));
    EXPECT_EQ(slice_of(seq, 0, s.complement_slice).contours.size(), 2u);

    // ES -> ED: the same slice merges back as the saddle rises: Up, complement below (one contour).
    const auto merge = vertical_motions(seq, 1, 2, opt);
    ASSERT_EQ(merge.size(), 1u);
    const VerticalMotion& m = merge[0];
    EXPECT_EQ(m.event, ContourEvent::Merge);
    EXPECT_EQ(m.incident_slice, s.incident_slice);
    EXPECT_EQ(m.direction, VerticalDirection::Up);
    EXPECT_LT(offset_of(seq, m.complement_slice), offset_of(seq, m.incident_slice));
    EXPECT_EQ(slice_of(seq, 1, m.complement_slice).contours.size(), 1u);

    // Frame 1 -> 0 is the same merge (time reversal of the split).
    const auto back = vertical_motions(seq, 1, 0, opt);
    ASSERT_EQ(back.size(), 1u);
    EXPECT_EQ(back[0].direction, m.direction);
    EXPECT_EQ(back[0].complement_slice, m.complement_slice);
  }
}

// Why Auto prefers the counts: the paper's similarity rule, read with eqs. 5-6 as written, ties on
// the split (the ES sections on both sides lie inside the ED peanut: 1 vs 1) and picks the wrong
// side on the merge (both ES loops lie inside the ED trunk section: 2 vs 1.26 => "Down").
TEST(VerticalMotion, PaperSimilarityScoresOnTheLeftHeart) {
  const Phantom ph = make_phantom("left-heart");
  VerticalDeformationOptions opt;
  opt.rule = MotionRule::Similarity;
  const VerticalMotion s = vertical_motions(ph.contours, 0, 1, opt).at(0);
  EXPECT_NEAR(s.similarity_below, s.similarity_above, 1e-9);  // tie: the counts decide
  EXPECT_TRUE(s.decided_by_counts);
  EXPECT_EQ(s.direction, VerticalDirection::Down);
  const VerticalMotion m = vertical_motions(ph.contours, 1, 2, opt).at(0);
  EXPECT_GT(m.similarity_below, m.similarity_above);
  EXPECT_FALSE(m.decided_by_counts);
  EXPECT_EQ(m.direction, VerticalDirection::Down);  // the literal rule; the geometry says Up
}

TEST(VerticalMotion, NoChangeAndBadFrames) {
  const Phantom ph = make_phantom("left-heart");
  EXPECT_TRUE(vertical_motions(ph.contours, 0, 2).empty());  // ED -> ED
  const VerticalMotion m = vertical_motion_direction(ph.contours, 0, 2, ph.contours.frames[0].slices[3].id);
  EXPECT_EQ(m.event, ContourEvent::None);
  EXPECT_EQ(m.direction, VerticalDirection::None);
  EXPECT_THROW(vertical_motions(ph.contours, 0, 3), InvalidInput);
  EXPECT_THROW(vertical_motion_direction(ph.contours, -1, 0, 0), InvalidInput);
}

TEST(VerticalMotion, EllipsoidApexAppearsOrVanishesWithoutDirection) {
  const Phantom ph = make_phantom("ellipsoid");
  int seen = 0;
  for (std::size_t t = 0; t + 1 < ph.contours.frames.size(); ++t)
    for (const VerticalMotion& m : vertical_motions(ph.contours, int(t), int(t) + 1)) {
      ++seen;
      EXPECT_TRUE(m.event == ContourEvent::Appear || m.event == ContourEvent::Vanish);
      EXPECT_EQ(m.direction, VerticalDirection::None);
    }
  EXPECT_GT(seen, 0);
}

// ---------------------------------------------------------------------------------------------
// Ridge

TEST(Ridge, LiesBetweenTheTwoContoursThroughTheSaddle) {
  for (RidgePath path : {RidgePath::Greedy, RidgePath::Shortest}) {
    VerticalDeformationOptions opt;
    opt.path = path;
    const Case c = run_case(false, 0, 1, opt);
    const Sequence& seq = c.ph.contours;
    ASSERT_TRUE(c.ridge.ends.found);
    EXPECT_GE(c.ridge.ends.band_sizes.size(), 2u);
    EXPECT_NE(c.ridge.ends.index[0], c.ridge.ends.index[1]);
    const auto b2 = project(c.B, seq.u, seq.v), c2 = project(c.C, seq.u, seq.v);
    // End points and every ridge vertex: 2D distances to B and C equal within 10 %.
    for (Vec3 p : {c.ridge.ends.points[0], c.ridge.ends.points[1]}) {
      const Vec2 q{dot(p, seq.u), dot(p, seq.v)};
      const double db = distance_to_polygon(q, b2), dc = distance_to_polygon(q, c2);
      EXPECT_LE(std::abs(db - dc), 0.1 * std::max(db, dc));
    }
    for (Vec3 p : c.ridge.points) {
      const Vec2 q{dot(p, seq.u), dot(p, seq.v)};
      const double db = distance_to_polygon(q, b2), dc = distance_to_polygon(q, c2);
      EXPECT_LE(std::abs(db - dc), 0.1 * std::max(db, dc) + 1e-9) << "ridge vertex not between B and C";
    }
    // Within the slab between the two slices, and through the saddle (world origin at ED).
    const double h_inc = offset_of(seq, c.motion.incident_slice), h_comp = offset_of(seq, c.motion.complement_slice);
    const double gap = std::abs(h_inc - h_comp);
    double to_saddle = 1e300;
    for (Vec3 p : c.ridge.points) {
      EXPECT_GE(dot(p, seq.normal), std::min(h_inc, h_comp) - 0.25 * gap - 1e-9);
      EXPECT_LE(dot(p, seq.normal), std::max(h_inc, h_comp) + 0.25 * gap + 1e-9);
      to_saddle = std::min(to_saddle, norm(p));
    }
    EXPECT_LT(to_saddle, 1e-9);  // the truth mesh has a vertex at the saddle; the ridge passes through it
    // Consecutive ridge vertices share a mesh edge.
    for (std::size_t i = 0; i + 1 < c.ridge.vertices.size(); ++i) {
      bool edge = false;
      for (const Triangle& tr : c.mesh.triangles)
        for (int k = 0; k < 3; ++k)
          edge = edge || (tr[k] == c.ridge.vertices[i] && tr[(k + 1) % 3] == c.ridge.vertices[i + 1]) ||
                 (tr[k] == c.ridge.vertices[i + 1] && tr[(k + 1) % 3] == c.ridge.vertices[i]);
      EXPECT_TRUE(edge);
    }
  }
}

TEST(Ridge, EndPointsIgnoreStartPointAndOrientationOfA) {
  const Case c = run_case(false, 0, 1);
  const Plane pl = make_plane(c.A.front(), c.ph.contours.normal);
  const RidgeEnds ref = ridge_end_points(c.A, c.B, c.C, pl);
  ASSERT_TRUE(ref.found);
  auto same_set = [&](const RidgeEnds& e) {
    const bool direct = distance(e.points[0], ref.points[0]) < 1e-12 && distance(e.points[1], ref.points[1]) < 1e-12;
    const bool swapped = distance(e.points[0], ref.points[1]) < 1e-12 && distance(e.points[1], ref.points[0]) < 1e-12;
    return direct || swapped;
  };
  std::vector<Vec3> rotated = c.A;
  std::rotate(rotated.begin(), rotated.begin() + rotated.size() / 3, rotated.end());
  std::vector<Vec3> reversed(c.A.rbegin(), c.A.rend());
  EXPECT_TRUE(same_set(ridge_end_points(rotated, c.B, c.C, pl)));
  EXPECT_TRUE(same_set(ridge_end_points(reversed, c.B, c.C, pl)));
  EXPECT_TRUE(same_set(ridge_end_points(c.A, c.C, c.B, pl)));  // B and C swapped
  EXPECT_FALSE(ridge_end_points(c.A, c.B, c.B, pl).found);     // B = C: one band everywhere, no ridge
}

// ---------------------------------------------------------------------------------------------
// Vertical deformation (eq. 10)

double r_between(const VerticalField& f, double h) {  // R inside slices 1..6 (test's own interpolation)
  for (int k = 0; k < 5; ++k)
    if (h <= f.heights[k] && h >= f.heights[k + 1]) {
      const double s = (f.heights[k] - h) / (f.heights[k] - f.heights[k + 1]);
      return (1 - s) * f.r[k] + s * f.r[k + 1];
    }
  return 0.0;
}

TEST(VerticalDeformation, FieldFollowsTable1) {
  const VerticalDeformationOptions opt;
  for (auto [t, t1] : {std::pair{0, 1}, std::pair{1, 2}}) {
    const Case c = run_case(false, t, t1);
    const Sequence& seq = c.ph.contours;
    const bool up = c.motion.direction == VerticalDirection::Up;
    EXPECT_EQ(c.field.r, up ? opt.r_upward : opt.r_downward);
    const double h_inc = offset_of(seq, c.motion.incident_slice), h_comp = offset_of(seq, c.motion.complement_slice);
    EXPECT_NEAR(c.field.delta, std::abs(h_inc - h_comp), 1e-12);
    for (int k = 0; k < 5; ++k) EXPECT_NEAR(c.field.heights[k] - c.field.heights[k + 1], c.field.delta, 1e-9);
    // Table 1 positions: Up has the incident slice at 3 and the complement at 4; Down the reverse.
    EXPECT_NEAR(c.field.heights[2], up ? h_inc : h_comp, 1e-12);
    EXPECT_NEAR(c.field.heights[3], up ? h_comp : h_inc, 1e-12);
    EXPECT_GT(c.field.lambda, 0.0);
    // Every R of the span has the motion's sign; λ is reached by the furthest incident point (VD = 0 there).
    double smallest = 1e300;
    for (Vec3 p : c.incident_points) {
      EXPECT_GE(vertical_displacement(c.field, p) * (up ? 1 : -1), 0.0);
      smallest = std::min(smallest, std::abs(vertical_displacement(c.field, p)));
    }
    EXPECT_EQ(smallest, 0.0);
  }
}

TEST(VerticalDeformation, AlongNormalLargestAtRidgeZeroOutsideContinuous) {
  const Case c = run_case(false, 0, 1);
  const VerticalField& f = c.field;
  const Vec3 n = f.normal;
  std::vector<Vec3> moved = c.mesh.positions;
  apply_vertical_deformation(moved, f);
  const double lo = f.heights[5] - f.taper, hi = f.heights[0] + f.taper;
  int moved_count = 0;
  for (std::size_t i = 0; i < moved.size(); ++i) {
    const Vec3 d = moved[i] - c.mesh.positions[i];
    EXPECT_LT(norm(d - dot(d, n) * n), 1e-12);  // only along the stack normal
    const double h = dot(c.mesh.positions[i], n);
    if (h < lo || h > hi) {
      EXPECT_EQ(norm(d), 0.0);  // nothing outside the span
    }
    if (norm(d) > 0) ++moved_count;
    // Never more than R(h) δ, the value on the ridge (D = 0).
    if (h <= f.heights[0] && h >= f.heights[5]) {
      EXPECT_LE(std::abs(dot(d, n)), std::abs(r_between(f, h)) * f.delta + 1e-12);
    }
  }
  EXPECT_GT(moved_count, 0);
  // On the ridge: exactly R(h) δ.
  for (Vec3 p : c.ridge.points) {
    const double h = dot(p, n);
    EXPECT_NEAR(vertical_displacement(f, p), r_between(f, h) * f.delta, 1e-9);
  }
  // At fixed height, |VD| does not grow away from the ridge, and vanishes from λ on.
  const Vec3 mid = c.ridge.points[c.ridge.points.size() / 2];
  for (Vec3 w : {f.u, f.v, normalized(f.u + f.v)}) {
    double prev = std::abs(vertical_displacement(f, mid));
    for (int k = 1; k <= 400; ++k) {
      const double cur = std::abs(vertical_displacement(f, mid + (k * 0.005 * 1.5 * f.lambda) * w));
      EXPECT_LE(cur, prev + 1e-12);
      prev = cur;
    }
    EXPECT_EQ(vertical_displacement(f, mid + (1.5 * f.lambda) * w), 0.0);
  }
  // Continuous, and no fold along the normal (|dVD/dh| < 1), across slice planes and span ends.
  for (Vec3 base : {mid, mid + (0.3 * f.lambda) * f.u}) {
    const double step = 1e-3 * f.delta;
    const Vec3 start = base + (lo - f.delta - dot(base, n)) * n;
    double prev = vertical_displacement(f, start);
    for (int k = 1; k * step < hi - lo + 2 * f.delta; ++k) {
      const double cur = vertical_displacement(f, start + (k * step) * n);
      EXPECT_LT(std::abs(cur - prev), step);
      prev = cur;
    }
  }
  // Continuous across D = λ as well.
  double prev = vertical_displacement(f, mid);
  for (int k = 1; k <= 3000; ++k) {
    const double cur = vertical_displacement(f, mid + (k * 1e-3 * 0.5 * f.lambda) * f.u);
    EXPECT_LT(std::abs(cur - prev), 1e-2 * f.delta);
    prev = cur;
  }
}

// The point of the step: after it, the incident slice's section already has the next frame's count.
TEST(VerticalDeformation, InducesTheSplitAndTheMerge) {
  for (auto [t, t1] : {std::pair{0, 1}, std::pair{1, 2}}) {
    const Case c = run_case(false, t, t1);
    const Slice& inc = slice_of(c.ph.contours, t, c.motion.incident_slice);
    const Plane pl = slice_plane(c.ph.contours, inc);
    EXPECT_EQ(int(plane_section(c.mesh, pl).size()), c.motion.contours_before);
    TriangleMesh moved = c.mesh;
    apply_vertical_deformation(moved.positions, c.field);
    EXPECT_EQ(int(plane_section(moved, pl).size()), c.motion.contours_after) << "frames " << t << " -> " << t1;
    EXPECT_GT(signed_volume(moved), 0.0);
  }
}

// Every split and merge of the 20-frame left-heart cycle (legs up) and of the bifurcation (legs down):
// the direction from the default rule, the ridge and eq. 10 give the incident section the next count.
TEST(VerticalDeformation, InducesEveryTopologyChangeOfThePhantoms) {
  for (const char* name : {"left-heart-cycle", "bifurcation"}) {
    const Phantom ph = make_phantom(name);
    const Sequence& seq = ph.contours;
    int handled = 0;
    for (int t = 0; t + 1 < int(seq.frames.size()); ++t)
      for (const VerticalMotion& m : vertical_motions(seq, t, t + 1)) {
        if (m.event != ContourEvent::Split && m.event != ContourEvent::Merge) continue;
        ASSERT_NE(m.direction, VerticalDirection::None) << name << " frame " << t;
        const Slice& inc = slice_of(seq, t, m.incident_slice);
        const Slice& comp = slice_of(seq, t, m.complement_slice);
        const Slice& lone = inc.contours.size() == 1 ? inc : comp;
        const Slice& pair = inc.contours.size() == 1 ? comp : inc;
        ASSERT_EQ(lone.contours.size(), 1u);
        ASSERT_EQ(pair.contours.size(), 2u);
        const Ridge r = detect_ridge(ph.truth[t], lone.contours[0].points, pair.contours[0].points,
                                     pair.contours[1].points, seq.normal);
        ASSERT_TRUE(r.found) << name << " frame " << t;
        const VerticalField f = make_vertical_field(seq, m, r.points, points_of(inc));
        TriangleMesh moved = ph.truth[t];
        apply_vertical_deformation(moved.positions, f);
        EXPECT_EQ(int(plane_section(moved, slice_plane(seq, inc)).size()), m.contours_after) << name << " frame " << t;
        ++handled;
      }
    EXPECT_EQ(handled, 2) << name;  // one split and one merge per cycle
  }
}

TEST(VerticalDeformation, InvariantToRigidMotion) {
  for (auto [t, t1] : {std::pair{0, 1}, std::pair{1, 2}}) {
    const Case a = run_case(false, t, t1);
    const Case b = run_case(true, t, t1);
    EXPECT_EQ(a.motion.event, b.motion.event);
    EXPECT_EQ(a.motion.direction, b.motion.direction);
    EXPECT_EQ(a.motion.incident_slice, b.motion.incident_slice);
    EXPECT_EQ(a.motion.complement_slice, b.motion.complement_slice);
    ASSERT_EQ(a.mesh.positions.size(), b.mesh.positions.size());
    EXPECT_EQ(a.ridge.vertices, b.ridge.vertices);
    EXPECT_NEAR(a.field.lambda, b.field.lambda, 1e-6);
    const auto R = oblique_rotation();
    std::vector<Vec3> pa = a.mesh.positions, pb = b.mesh.positions;
    apply_vertical_deformation(pa, a.field);
    apply_vertical_deformation(pb, b.field);
    double worst = 0;
    for (std::size_t i = 0; i < pa.size(); ++i) {
      const Vec3 da = pa[i] - a.mesh.positions[i], db = pb[i] - b.mesh.positions[i];
      const Vec3 rda{dot(R[0], da), dot(R[1], da), dot(R[2], da)};
      worst = std::max(worst, distance(rda, db));
    }
    EXPECT_LT(worst, 1e-5);
  }
}

TEST(VerticalDeformation, RejectsMissingInputs) {
  const Case c = run_case(false, 0, 1);
  VerticalMotion none = c.motion;
  none.direction = VerticalDirection::None;
  EXPECT_THROW(make_vertical_field(c.ph.contours, none, c.ridge.points, c.incident_points), InvalidInput);
  EXPECT_THROW(make_vertical_field(c.ph.contours, c.motion, {}, c.incident_points), InvalidInput);
  VerticalMotion far = c.motion;
  far.complement_slice = c.ph.contours.frames[0].slices.front().id;
  EXPECT_THROW(make_vertical_field(c.ph.contours, far, c.ridge.points, c.incident_points), InvalidInput);
}

}  // namespace
}  // namespace c4d
