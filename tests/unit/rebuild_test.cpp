// The all-frames stage that builds every frame on one plan (rebuild.h, surface_plan.h), on families of random
// smooth blobs with random motion drawn from seeds: the same triangles in every frame by construction, each
// frame closed and free of crossings, each within a few hundredths of a millimetre of its own one-frame
// surface, the result independent of the contours' start points and orientation and of the thread count;
// frames whose contours change topology are named, an end contour that vanishes is carried onto the frame's
// own dome without folds, and a branching plan is refused.
#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include "contour4d/metrics/distance.h"
#include "contour4d/metrics/quality.h"
#include "contour4d/metrics/topology.h"
#include "contour4d/motion/rebuild.h"
#include "contour4d/motion/reconstruct4d.h"
#include "contour4d/surface/reconstruct.h"
#include "contour4d/surface/surface_plan.h"

namespace c4d {
namespace {

// A tilted stack of 5–8 slices 6–10 mm apart, each holding one smooth closed contour (an ellipse with two
// random harmonics), through 4–6 frames of contraction up to 30 % with a drift and a twist; every contour
// starts at a random point and runs either way.
Sequence blob_family(unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u01(0.0, 1.0);
  const int slices = 5 + static_cast<int>(u01(rng) * 4.0);
  const int frames = 4 + static_cast<int>(u01(rng) * 3.0);
  const double gap = 6.0 + 4.0 * u01(rng);
  const double tilt = 0.3 * u01(rng), turn = 2.0 * std::numbers::pi * u01(rng);
  Sequence seq;
  seq.normal = normalized(Vec3{std::sin(tilt) * std::cos(turn), std::sin(tilt) * std::sin(turn), std::cos(tilt)});
  seq.u = normalized(cross(Vec3{0, 1, 0}, seq.normal));
  seq.v = cross(seq.normal, seq.u);
  const double a = 18.0 + 8.0 * u01(rng), b = 14.0 + 6.0 * u01(rng);
  const double h2 = 0.12 * u01(rng), h3 = 0.06 * u01(rng), p2 = 6.0 * u01(rng), p3 = 6.0 * u01(rng);
  const double squeeze = 0.3 * u01(rng), drift = 3.0 * u01(rng), twist = 0.3 * u01(rng);
  for (int f = 0; f < frames; ++f) {
    Frame fr;
    fr.time_ms = 40.0 * f;
    const double phase = 0.5 * (1.0 - std::cos(2.0 * std::numbers::pi * f / frames));
    const double scale = 1.0 - squeeze * phase;
    for (int s = 0; s < slices; ++s) {
      Slice sl;
      sl.id = s;
      sl.offset = gap * s;
      // A profile that narrows towards both ends without closing inside the slab.
      const double z = (s + 0.5) / slices;
      const double profile = 0.45 + 0.55 * std::sin(std::numbers::pi * z);
      const int n = 48 + static_cast<int>(u01(rng) * 40.0);
      const int start = static_cast<int>(u01(rng) * n);
      const bool reverse = u01(rng) < 0.5;
      Contour c;
      c.slice = s;
      for (int k = 0; k < n; ++k) {
        const int j = reverse ? (start - k + n) % n : (start + k) % n;
        const double t = 2.0 * std::numbers::pi * j / n + twist * phase * z;
        const double r = 1.0 + h2 * std::cos(2 * t + p2) + h3 * std::cos(3 * t + p3);
        const double x = scale * profile * a * r * std::cos(t) + drift * phase;
        const double y = scale * profile * b * r * std::sin(t);
        c.points.push_back(sl.offset * seq.normal + x * seq.u + y * seq.v);
      }
      sl.contours.push_back(std::move(c));
      fr.slices.push_back(std::move(sl));
    }
    seq.frames.push_back(std::move(fr));
  }
  return seq;
}

double mean_distance_to_own(const TriangleMesh& mesh, const Sequence& seq, int frame) {
  const TriangleMesh own = reconstruct_frame(seq, frame);
  const SurfaceComparison c = compare_surfaces(mesh, own);
  return 0.5 * (c.whole.mesh_to_truth.mean + c.whole.truth_to_mesh.mean);
}

TEST(Rebuild, BlobFamilyIsOneMeshOfEachFramesOwnSurface) {
  const unsigned seeds = C4D_HEAVY_TESTS ? 6 : 1;  // the sanitizer build: one
  for (unsigned seed = 1; seed <= seeds; ++seed) {
    const Sequence seq = blob_family(seed);
    RebuildReport rep;
    const std::optional<MeshSequence> m = rebuild_frames(seq, {}, &rep);
    ASSERT_TRUE(m.has_value()) << "seed " << seed << ": " << rep.why_not;
    EXPECT_TRUE(rep.unfit.empty()) << "seed " << seed << ": " << (rep.unfit_why.empty() ? "" : rep.unfit_why[0]);
    for (std::size_t f = 0; f < seq.frames.size(); ++f) {
      ASSERT_EQ(m->positions[f].size(), m->positions[0].size()) << "seed " << seed;
      const TopologyReport t = check_topology(m->frame(f));
      EXPECT_TRUE(t.faults.empty()) << "seed " << seed << " frame " << f << ": "
                                    << (t.faults.empty() ? "" : t.faults[0]);
      EXPECT_GT(t.signed_volume, 0.0);
      EXPECT_LT(mean_distance_to_own(m->frame(f), seq, static_cast<int>(f)), 0.02) << "seed " << seed << " frame " << f;
    }
  }
}

TEST(Rebuild, InvariantToContourStartAndOrientation) {
  const Sequence seq = blob_family(11);
  Sequence turned = seq;
  for (Frame& f : turned.frames)
    for (Slice& s : f.slices)
      for (Contour& c : s.contours) {
        std::rotate(c.points.begin(), c.points.begin() + static_cast<std::ptrdiff_t>(c.points.size() / 3),
                    c.points.end());
        std::reverse(c.points.begin(), c.points.end());
      }
  const auto a = rebuild_frames(seq, {});
  const auto b = rebuild_frames(turned, {});
  ASSERT_TRUE(a && b);
  ASSERT_EQ(a->triangles.size(), b->triangles.size());
  for (std::size_t f = 0; f < seq.frames.size(); ++f) {
    const SurfaceComparison c = compare_surfaces(a->frame(f), b->frame(f));
    EXPECT_LT(c.whole.hausdorff, 0.05) << "frame " << f;
  }
}

TEST(Rebuild, ByteIdenticalAtOneAndTwoThreads) {
  const Sequence seq = blob_family(5);
  std::optional<MeshSequence> one, two;
  {
    tbb::global_control c(tbb::global_control::max_allowed_parallelism, 1);
    one = rebuild_frames(seq, {});
  }
  {
    tbb::global_control c(tbb::global_control::max_allowed_parallelism, 2);
    two = rebuild_frames(seq, {});
  }
  ASSERT_TRUE(one && two);
  EXPECT_EQ(one->triangles, two->triangles);
  EXPECT_EQ(one->positions, two->positions);
}

TEST(Rebuild, FramesWithAnotherTopologyAreNamed) {
  Sequence seq = blob_family(3);
  seq.frames[2].slices.pop_back();  // the top contour vanishes in frame 2
  RebuildReport rep;
  const auto m = rebuild_frames(seq, {}, &rep);
  ASSERT_TRUE(m.has_value());
  ASSERT_EQ(rep.unfit, std::vector<int>{2});
  EXPECT_NE(rep.unfit_why[0].find("slices"), std::string::npos) << rep.unfit_why[0];
  EXPECT_TRUE(m->positions[2].empty());
  EXPECT_FALSE(m->positions[1].empty());
}

TEST(Rebuild, EndContoursThatVanishAreCarriedOntoTheFramesOwnDome) {
  const unsigned seeds = C4D_HEAVY_TESTS ? 4 : 1;  // the sanitizer build: one
  for (unsigned seed = 1; seed <= seeds; ++seed) {
    Sequence seq = blob_family(20 + seed);
    // The top contour vanishes in the middle frames: an end moving back through its slice plane.
    for (std::size_t f = 1; f + 1 < seq.frames.size(); ++f) seq.frames[f].slices.pop_back();
    Reconstruct4DReport rep;
    const MeshSequence m = reconstruct_4d(seq, {}, &rep);
    ASSERT_EQ(rep.used, AllFramesMethod::Rebuild) << "seed " << seed << ": " << rep.rebuild.why_not;
    EXPECT_EQ(rep.rebuild.unfit.size(), seq.frames.size() - 2) << "seed " << seed;
    for (std::size_t f = 0; f < seq.frames.size(); ++f) {
      ASSERT_EQ(m.positions[f].size(), m.positions[0].size()) << "seed " << seed;
      const TopologyReport t = check_topology(m.frame(f), {.self_intersections = true});
      EXPECT_TRUE(t.faults.empty()) << "seed " << seed << " frame " << f << ": "
                                    << (t.faults.empty() ? "" : t.faults[0]);
      EXPECT_EQ(t.self_intersections, 0u) << "seed " << seed << " frame " << f;
      EXPECT_GT(t.signed_volume, 0.0);
      EXPECT_LT(mean_distance_to_own(m.frame(f), seq, static_cast<int>(f)), 0.05) << "seed " << seed << " frame " << f;
      EXPECT_GT(angle_quality(m.frame(f)).min_angle_deg, 5.0) << "seed " << seed << " frame " << f;
    }
  }
}

TEST(Rebuild, PlanOfABranchingIsUnusable) {
  Sequence seq = blob_family(4);
  // Two small contours side by side on the bottom slice of every frame: a 1→2 branching.
  for (Frame& f : seq.frames) {
    Slice& s = f.slices.front();
    Contour left = s.contours[0], right = s.contours[0];
    const Vec3 centre = s.offset * seq.normal;
    for (Vec3& p : left.points) p = centre + 0.3 * (p - centre) - 8.0 * seq.u;
    for (Vec3& p : right.points) p = centre + 0.3 * (p - centre) + 8.0 * seq.u;
    s.contours = {left, right};
  }
  RebuildReport rep;
  EXPECT_FALSE(rebuild_frames(seq, {}, &rep).has_value());
  EXPECT_FALSE(rep.why_not.empty());
}

TEST(SurfacePlan, AlignedSamplesFollowTheReferenceStart) {
  std::vector<Vec2> circle, ref;
  for (int k = 0; k < 60; ++k) {
    const double t = 2.0 * std::numbers::pi * k / 60.0;
    circle.push_back({10.0 * std::cos(t), 6.0 * std::sin(t)});
  }
  ref = resample_count(circle, 40, 0.25);  // starts a quarter of the way round
  const std::vector<Vec2> got = aligned_samples(circle, ref);
  ASSERT_EQ(got.size(), ref.size());
  for (std::size_t k = 0; k < ref.size(); ++k) EXPECT_LT(norm(got[k] - ref[k]), 1e-3) << k;
}

TEST(SurfacePlan, MeanValueWeightsReproduceAffineMaps) {
  const std::vector<std::vector<Vec2>> loops{{{0, 0}, {10, 0}, {12, 8}, {4, 11}, {-2, 6}},
                                             {{3, 3}, {3, 5}, {5, 5}, {5, 3}}};
  const Vec2 x{7.0, 4.0};
  const std::vector<double> w = mean_value_weights(x, loops);
  Vec2 back;
  double sum = 0.0;
  std::size_t i = 0;
  for (const auto& l : loops)
    for (const Vec2& p : l) {
      back = back + w[i] * p;
      sum += w[i++];
    }
  EXPECT_NEAR(sum, 1.0, 1e-12);
  EXPECT_LT(norm(back - x), 1e-9);
}

}  // namespace
}  // namespace c4d
