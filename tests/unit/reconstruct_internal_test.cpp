// One-frame surface (Lim et al. 2014, "Constructing a 3D model of the First Cardiac Frame"):
// topology, conformity, volume, quality and invariance on stacks built in code.
#include "contour4d/surface/reconstruct.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <functional>

#include "contour4d/core/errors.h"
#include "contour4d/pipeline/input.h"
#include "contour4d/metrics/topology.h"
#include "cgal_self_intersections.h"
#include "surface/surface_tuning_internal.h"

namespace {

using c4d::Contour;
using c4d::Vec2;
using c4d::Vec3;

// A shape of slice z: a list of 2D polygons (CCW outer, any orientation accepted).
using Polys = std::vector<std::vector<Vec2>>;

// The library's surface, with the default tuning or with a step switched off (white-box: SurfaceTuning).
c4d::TriangleMesh frame_of(const c4d::Sequence& seq, int frame, const c4d::SurfaceOptions& o,
                           c4d::SurfaceReport* rep = nullptr) {
  return c4d::reconstruct_frame(seq, frame, o, rep);
}
c4d::TriangleMesh frame_of(const c4d::Sequence& seq, int frame, const c4d::detail::SurfaceParams& p,
                           c4d::SurfaceReport* rep = nullptr) {
  return c4d::detail::reconstruct_frame_tuned(seq, frame, p, rep);
}
c4d::detail::SurfaceParams defaults() { return c4d::detail::surface_params({}); }
using Shape = std::function<std::vector<std::vector<Vec2>>(double z)>;

std::vector<Vec2> ellipse(double cx, double cy, double a, double b, int n, double wobble = 0.0) {
  std::vector<Vec2> p;
  for (int i = 0; i < n; ++i) {
    const double t = 2.0 * M_PI * i / n;
    const double s = 1.0 + wobble * (0.6 * std::sin(3 * t + 0.4) + 0.4 * std::cos(5 * t));
    p.push_back({cx + s * a * std::cos(t), cy + s * b * std::sin(t)});
  }
  return p;
}

c4d::Sequence stack(const std::vector<double>& zs, const Shape& shape) {
  c4d::Sequence seq;
  seq.frames.resize(1);
  for (std::size_t i = 0; i < zs.size(); ++i) {
    c4d::Slice s;
    s.id = static_cast<int>(i);
    s.offset = zs[i];
    for (const auto& poly : shape(zs[i])) {
      Contour c;
      c.label = "lv";
      c.slice = s.id;
      for (const Vec2& q : poly) c.points.push_back({q.x, q.y, zs[i]});
      s.contours.push_back(c);
    }
    seq.frames[0].slices.push_back(s);
  }
  return seq;
}

std::vector<double> range(double z0, double z1, double dz) {
  std::vector<double> z;
  for (double v = z0; v <= z1 + 1e-9; v += dz) z.push_back(v);
  return z;
}

double point_segment(Vec3 p, Vec3 a, Vec3 b) {
  const Vec3 ab = b - a;
  double t = c4d::dot(p - a, ab) / std::max(1e-300, c4d::dot(ab, ab));
  t = std::clamp(t, 0.0, 1.0);
  return c4d::norm(p - (a + t * ab));
}

// Largest distance from the input contour vertices to the nearest mesh edge (contours are mesh edges,
// so this is ~0 when every input vertex is kept and the contour runs along edges).
double conformity_max(const c4d::Sequence& seq, const c4d::TriangleMesh& m) {
  double worst = 0.0;
  for (const auto& s : seq.frames[0].slices)
    for (const auto& c : s.contours)
      for (const Vec3& p : c.points) {
        double best = 1e300;
        for (const auto& t : m.triangles)
          for (int k = 0; k < 3; ++k)
            best = std::min(best, point_segment(p, m.positions[t[k]], m.positions[t[(k + 1) % 3]]));
        worst = std::max(worst, best);
      }
  return worst;
}

struct Angles {
  double min_deg = 180, share_40_80 = 0, share_below_25 = 0;
};

Angles angles(const c4d::TriangleMesh& m) {
  Angles a;
  std::size_t n = 0, good = 0, low = 0;
  for (const auto& t : m.triangles) {
    bool has_low = false;
    for (int k = 0; k < 3; ++k) {
      const Vec3 p = m.positions[t[k]], u = m.positions[t[(k + 1) % 3]] - p, v = m.positions[t[(k + 2) % 3]] - p;
      const double ang = std::acos(std::clamp(c4d::dot(u, v) / (c4d::norm(u) * c4d::norm(v)), -1.0, 1.0)) * 180 / M_PI;
      a.min_deg = std::min(a.min_deg, ang);
      ++n;
      if (ang >= 40 && ang <= 80) ++good;
      if (ang < 25) has_low = true;
    }
    if (has_low) ++low;
  }
  a.share_40_80 = static_cast<double>(good) / std::max<std::size_t>(1, n);
  a.share_below_25 = static_cast<double>(low) / std::max<std::size_t>(1, m.triangles.size());
  return a;
}

void expect_closed(const c4d::TriangleMesh& m, long euler, std::size_t components) {
  const c4d::TopologyReport c = c4d::check_topology(m);
  EXPECT_EQ(c.boundary_edges, 0u);
  EXPECT_EQ(c.nonmanifold_edges, 0u);
  EXPECT_EQ(c.nonmanifold_vertices, 0u);
  EXPECT_EQ(c.misoriented_edges, 0u);
  EXPECT_EQ(c.degenerate_triangles, 0u);
  EXPECT_EQ(c.euler, euler);
  EXPECT_EQ(c.components.size(), components);
  EXPECT_GT(c.signed_volume, 0.0);
  EXPECT_EQ(c.self_intersections, 0u);
}

// The tiled surface as it is: no remeshing, no rows, no fairing.
c4d::detail::SurfaceParams coarse() {
  c4d::detail::SurfaceParams o = defaults();
  o.remesh = false;
  o.rows = false;
  o.fairing = false;
  return o;
}

TEST(Reconstruct, CylinderIsClosedOutwardAndThroughTheContours) {
  const auto seq = stack(range(0, 20, 5), [](double) { return Polys{ellipse(0, 0, 10, 10, 63)}; });
  for (const auto& opt : {coarse(), defaults()}) {
    c4d::SurfaceReport rep;
    const auto m = frame_of(seq, 0, opt, &rep);
    expect_closed(m, 2, 1);
    EXPECT_TRUE(rep.closed);
    EXPECT_EQ(rep.caps, 2);
    EXPECT_EQ(rep.connections.size(), 4u);
    EXPECT_TRUE(rep.warnings.empty());
    // Volume: the prism of the 63-gon between the end slices plus two ends holding at most the 2.5 mm
    // cylinder the sections' trend gives (faired caps continue the vertical wall; the fill lifts their middle).
    const double prism = 0.5 * 63 * 100 * std::sin(2 * M_PI / 63) * 20;
    EXPECT_GT(c4d::signed_volume(m), prism);
    EXPECT_LT(c4d::signed_volume(m), prism + 2 * M_PI * 100 * 2.5 * 1.01);
    // The domes close within one slice spacing past the end planes.
    for (const Vec3& p : m.positions) {
      EXPECT_GE(p.z, -5.0);
      EXPECT_LE(p.z, 25.0);
    }
  }
}

TEST(Reconstruct, ContoursAreMeshEdges) {
  // Keep every input vertex (corner angle 0): conformity is exact.
  const auto seq =
      stack(range(0, 15, 5), [](double z) { return Polys{ellipse(0.2 * z, 0, 12 - 0.3 * z, 8, 70, 0.05)}; });
  c4d::detail::SurfaceParams o = defaults();
  o.corner_angle_deg = 0;
  const auto m = frame_of(seq, 0, o);
  expect_closed(m, 2, 1);
  EXPECT_LT(conformity_max(seq, m), 1e-9);
}

TEST(Reconstruct, SphereStackVolume) {
  const double R = 20;
  const auto seq = stack(range(-17.5, 17.5, 5), [&](double z) {
    return Polys{ellipse(0, 0, std::sqrt(R * R - z * z), std::sqrt(R * R - z * z), 128)};
  });
  c4d::SurfaceReport rep;
  const auto m = frame_of(seq, 0, c4d::SurfaceOptions{}, &rep);
  expect_closed(m, 2, 1);
  const double truth = 4.0 / 3.0 * M_PI * R * R * R;
  const double err = (c4d::signed_volume(m) - truth) / truth;
  const Angles a = angles(m);
  std::printf(
      "sphere R=20, 5 mm slices: volume error %.2f %%, %zu vertices, angles in 40-80: %.1f %%, "
      "triangles with an angle < 25: %.3f %%, min angle %.1f deg\n",
      100 * err, m.positions.size(), 100 * a.share_40_80, 100 * a.share_below_25, a.min_deg);
  EXPECT_LT(std::abs(err), 0.03);
  EXPECT_GT(a.min_deg, 5.0);
  EXPECT_GT(a.share_40_80, 0.7);
}

TEST(Reconstruct, BranchOneToTwoAndTwoToOne) {
  // A trunk (slices 0, 5) splitting into two legs (slices 10, 15); then the same upside down.
  const Shape split = [](double z) {
    if (z < 7) return Polys{ellipse(0, 0, 16, 8, 80)};
    return Polys{ellipse(-7, 0, 6, 6, 40), ellipse(7, 0, 6, 6, 40)};
  };
  const Shape merge = [&](double z) { return split(15 - z); };
  for (const Shape& shape : {split, merge}) {
    const auto seq = stack(range(0, 15, 5), shape);
    for (const auto& opt : {coarse(), defaults()}) {
      SCOPED_TRACE(opt.fairing ? "default options" : "coarse");
      c4d::SurfaceReport rep;
      const auto m = frame_of(seq, 0, opt, &rep);
      for (const auto& pr : c4d::testing::self_intersecting_pairs(m)) {
        for (std::uint32_t t : pr)
          for (auto v : m.triangles[t])
            std::printf(" (%.3f %.3f %.3f)", m.positions[v].x, m.positions[v].y, m.positions[v].z);
        std::printf("\n");
      }
      expect_closed(m, 2, 1);
      EXPECT_EQ(rep.branchings, 1);
      EXPECT_EQ(rep.caps, 3);
    }
  }
}

TEST(Reconstruct, ContoursTouchingAtOnePointAreMovedApart) {
  // A section exactly through a branch saddle: two circles sharing the point (0, 0) on slice 10.
  // Unseparated (min_contour_gap = 0) the tiled surface has 2 non-manifold edges and 3 vertices.
  const Shape shape = [](double z) {
    if (z < 7) return Polys{ellipse(0, 0, 16, 8, 80)};
    if (z < 12) return Polys{ellipse(-7, 0, 7, 7, 40), ellipse(7, 0, 7, 7, 40)};
    return Polys{ellipse(-8, 0, 6, 6, 40), ellipse(8, 0, 6, 6, 40)};
  };
  const auto seq = stack(range(0, 15, 5), shape);
  c4d::SurfaceReport rep;
  const auto m = frame_of(seq, 0, c4d::SurfaceOptions{}, &rep);
  expect_closed(m, 2, 1);
  bool warned = false;
  for (const auto& w : rep.warnings) warned = warned || w.find("contours touch") != std::string::npos;
  EXPECT_TRUE(warned);
  EXPECT_LT(conformity_max(seq, m), 0.05);  // points move by at most 0.01 mm; resampling adds its own
}

TEST(Reconstruct, StackOfAnnuliIsATorus) {
  const auto seq = stack(range(0, 20, 5), [](double) {
    auto hole = ellipse(0, 0, 7, 7, 40);
    std::reverse(hole.begin(), hole.end());
    return Polys{ellipse(0, 0, 18, 18, 96), hole};
  });
  for (const auto& opt : {coarse(), defaults()}) {
    c4d::SurfaceReport rep;
    const auto m = frame_of(seq, 0, opt, &rep);
    expect_closed(m, 0, 1);  // genus 1
    EXPECT_EQ(rep.caps, 2);  // ring caps, top and bottom
  }
}

TEST(Reconstruct, HoleThatEndsGetsItsOwnCap) {
  // A cup: a hole through the upper slices only.
  const auto seq = stack(range(0, 20, 5), [](double z) {
    Polys s{ellipse(0, 0, 18, 18, 96)};
    if (z > 7) s.push_back(ellipse(1, 0, 8, 8, 48));
    return s;
  });
  c4d::SurfaceReport rep;
  const auto m = frame_of(seq, 0, c4d::SurfaceOptions{}, &rep);
  expect_closed(m, 2, 1);
}

TEST(Reconstruct, SeparateStructuresAndSingleSlice) {
  const auto two = stack(range(0, 10, 5), [](double) {
    return Polys{ellipse(-30, 0, 8, 8, 40), ellipse(30, 0, 8, 8, 40)};
  });
  expect_closed(frame_of(two, 0, c4d::SurfaceOptions{}), 4, 2);
  const auto one = stack({0.0}, [](double) { return Polys{ellipse(0, 0, 10, 6, 50)}; });
  expect_closed(frame_of(one, 0, c4d::SurfaceOptions{}), 2, 1);
}

TEST(Reconstruct, OpenCapsLeaveTheEndsOpen) {
  const auto seq = stack(range(0, 20, 5), [](double) { return Polys{ellipse(0, 0, 10, 10, 63)}; });
  c4d::SurfaceOptions o;
  o.caps = c4d::CapStyle::Open;
  const auto m = frame_of(seq, 0, o);
  const auto c = c4d::check_topology(m, {.self_intersections = false});
  EXPECT_GT(c.boundary_edges, 0u);
  EXPECT_EQ(c.nonmanifold_edges, 0u);
  EXPECT_EQ(c.euler, 0);  // a tube
}

// Sorted positions of a mesh mapped by `back` (inverse transform), rounded comparison.
std::vector<Vec3> sorted_positions(const c4d::TriangleMesh& m, const std::function<Vec3(Vec3)>& back) {
  std::vector<Vec3> p;
  for (const Vec3& q : m.positions) p.push_back(back(q));
  std::sort(p.begin(), p.end(), [](Vec3 a, Vec3 b) {
    if (std::abs(a.z - b.z) > 1e-7) return a.z < b.z;
    if (std::abs(a.x - b.x) > 1e-7) return a.x < b.x;
    return a.y < b.y;
  });
  return p;
}

void expect_same_surface(const c4d::TriangleMesh& a, const c4d::TriangleMesh& b,
                         const std::function<Vec3(Vec3)>& back) {
  ASSERT_EQ(a.positions.size(), b.positions.size());
  ASSERT_EQ(a.triangles.size(), b.triangles.size());
  EXPECT_NEAR(c4d::signed_volume(a), c4d::signed_volume(b), 1e-6 * std::abs(c4d::signed_volume(a)));
  EXPECT_NEAR(c4d::surface_area(a), c4d::surface_area(b), 1e-6 * c4d::surface_area(a));
  const auto pa = sorted_positions(a, [](Vec3 q) { return q; }), pb = sorted_positions(b, back);
  double worst = 0;
  for (std::size_t i = 0; i < pa.size(); ++i) worst = std::max(worst, c4d::distance(pa[i], pb[i]));
  EXPECT_LT(worst, 1e-6);
}

c4d::Sequence irregular() {
  return stack(range(0, 20, 5), [](double z) {
    return Polys{ellipse(0.3 * z, -0.1 * z, 14 - 0.2 * z, 9 + 0.1 * z, 57 + static_cast<int>(z), 0.08)};
  });
}

// A ring (a contour with a hole) on three slices: its end caps are ring caps, faired with scale-aware
// terms (FairingOptions::scale_aware).
c4d::Sequence irregular_ring() {
  return stack(range(0, 10, 5), [](double z) {
    return Polys{ellipse(0.2 * z, 0.1 * z, 16 - 0.2 * z, 12, 95, 0.05),
                 ellipse(0.2 * z + 1, 0.1 * z, 7, 5 + 0.1 * z, 41, 0.05)};
  });
}

TEST(Reconstruct, InvariantToStartPointOrientationAndSliceOrder) {
  for (const auto& seq : {irregular(), irregular_ring()}) {
    for (const auto& opt : {coarse(), defaults()}) {
      const auto ref = frame_of(seq, 0, opt);
      expect_closed(ref, seq.frames[0].slices[0].contours.size() == 2 ? 0 : 2, 1);  // the ring: genus 1
      auto moved = seq;
      for (auto& s : moved.frames[0].slices)
        for (auto& c : s.contours) {
          std::reverse(c.points.begin(), c.points.end());
          std::rotate(c.points.begin(), c.points.begin() + 11, c.points.end());
        }
      std::reverse(moved.frames[0].slices.begin(), moved.frames[0].slices.end());
      expect_same_surface(ref, frame_of(moved, 0, opt), [](Vec3 q) { return q; });
    }
  }
}

TEST(Reconstruct, InvariantToRigidMotion) {
  // Rotation about a skew axis and a translation; the stack frame (normal, u, v) moves with it.
  const double c = std::cos(0.7), s = std::sin(0.7), c2 = std::cos(0.3), s2 = std::sin(0.3);
  auto R = [&](Vec3 p) {
    const Vec3 a{c * p.x - s * p.y, s * p.x + c * p.y, p.z};
    return Vec3{a.x, c2 * a.y - s2 * a.z, s2 * a.y + c2 * a.z};
  };
  auto Rinv = [&](Vec3 p) {
    const Vec3 a{p.x, c2 * p.y + s2 * p.z, -s2 * p.y + c2 * p.z};
    return Vec3{c * a.x + s * a.y, -s * a.x + c * a.y, a.z};
  };
  const Vec3 t{12.5, -40.25, 101.0};
  for (const auto& seq : {irregular(), irregular_ring()}) {
    auto moved = seq;
    moved.normal = R(seq.normal);
    moved.u = R(seq.u);
    moved.v = R(seq.v);
    for (auto& sl : moved.frames[0].slices) {
      sl.offset += c4d::dot(moved.normal, t);
      for (auto& ct : sl.contours)
        for (auto& p : ct.points) p = R(p) + t;
    }
    for (const auto& opt : {coarse(), defaults()}) {
      const auto ref = frame_of(seq, 0, opt);
      const auto out = frame_of(moved, 0, opt);
      expect_same_surface(ref, out, [&](Vec3 q) { return Rinv(q - t); });
    }
  }
}

TEST(Reconstruct, Speed) {
  // Not a timed assertion: prints the throughput the issue asks for (>= 100k output vertices/s).
  const double R = 40;
  const auto seq = stack(range(-37.5, 37.5, 5), [&](double z) {
    return Polys{ellipse(0, 0, std::sqrt(R * R - z * z), 0.8 * std::sqrt(R * R - z * z), 200, 0.03)};
  });
  c4d::SurfaceOptions o;
  o.check_self_intersections = false;
  const auto t0 = std::chrono::steady_clock::now();
  const auto m = frame_of(seq, 0, o);
  const double sec = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  std::printf("speed: %zu vertices in %.3f s = %.0f vertices/s\n", m.positions.size(), sec, m.positions.size() / sec);
  expect_closed(m, 2, 1);
}

TEST(Reconstruct, BadInputThrows) {
  c4d::Sequence empty;
  EXPECT_THROW(frame_of(empty, 0, c4d::SurfaceOptions{}), c4d::InvalidInput);
  auto seq = stack({0.0, 5.0}, [](double) { return Polys{ellipse(0, 0, 5, 5, 20)}; });
  seq.frames[0].slices[1].contours[0].label = "rv";
  EXPECT_THROW(frame_of(seq, 0, c4d::SurfaceOptions{}), c4d::InvalidInput);
  c4d::SurfaceOptions o;
  o.label = "rv";
  expect_closed(frame_of(seq, 0, o), 2, 1);
  o.label = "la";
  EXPECT_THROW(frame_of(seq, 0, o), c4d::InvalidInput);
}

}  // namespace

// ---- Accuracy against analytic phantoms (issue 3 targets) ----
#include "contour4d/phantoms/phantom.h"

namespace {

struct Accuracy {
  double mean = 0, max = 0, volume_error = 0;
  std::size_t samples = 0;
  Angles angles;
  double conformity_mean = 0;
};

// Mean/max |analytic distance| over vertices and triangle centroids inside the slab, volume error
// against the true volume, angle statistics, conformity (input vertices to the nearest mesh edge).
Accuracy accuracy(const c4d::Phantom& ph, const c4d::TriangleMesh& m, bool conformity) {
  Accuracy a;
  const Vec3 n = ph.contours.normal;
  auto in_slab = [&](Vec3 p) {
    const double h = c4d::dot(n, p);
    return h >= ph.slab_min - 1e-9 && h <= ph.slab_max + 1e-9;
  };
  double sum = 0;
  auto take = [&](Vec3 p) {
    if (!in_slab(p)) return;
    const double d = std::abs(c4d::analytic_distance(ph, 0, p));
    sum += d;
    a.max = std::max(a.max, d);
    ++a.samples;
  };
  for (const Vec3& p : m.positions) take(p);
  for (const auto& t : m.triangles) take((m.positions[t[0]] + m.positions[t[1]] + m.positions[t[2]]) / 3.0);
  a.mean = sum / std::max<std::size_t>(1, a.samples);
  a.volume_error = (c4d::signed_volume(m) - ph.true_volume_mm3[0]) / ph.true_volume_mm3[0];
  a.angles = angles(m);
  if (conformity) {
    // Edges near each input vertex only (bucketed by slice height) keep this fast.
    double csum = 0;
    std::size_t cn = 0;
    for (const auto& s : ph.contours.frames[0].slices)
      for (const auto& c : s.contours)
        for (const Vec3& p : c.points) {
          double best = 1e300;
          for (const auto& t : m.triangles)
            for (int k = 0; k < 3; ++k) {
              const Vec3 a0 = m.positions[t[k]], a1 = m.positions[t[(k + 1) % 3]];
              if (std::abs(c4d::dot(n, a0) - s.offset) > 1e-6 || std::abs(c4d::dot(n, a1) - s.offset) > 1e-6) continue;
              best = std::min(best, point_segment(p, a0, a1));
            }
          csum += best;
          ++cn;
        }
    a.conformity_mean = csum / std::max<std::size_t>(1, cn);
  }
  return a;
}

// Both one-frame paths: interpolated rows (the default) and remeshed bands (SurfaceOptions::rows = false; the
// 4D run's frame 0).
TEST(ReconstructPhantoms, AccuracyVolumeAndQuality) {
  for (const bool rows : {true, false}) {
    for (const std::string name : {"ellipsoid", "left-heart-ed", "left-heart-es", "torus", "bifurcation"})
      for (bool oblique : {false, true}) {
        c4d::PhantomOptions po;
        po.oblique = oblique;
        const c4d::Phantom ph = c4d::make_phantom(name, po);
        c4d::SurfaceOptions so;
        so.rows = rows;
        c4d::SurfaceReport rep;
        const auto m = frame_of(ph.contours, 0, so, &rep);
        const Accuracy a = accuracy(ph, m, !oblique);
        std::printf(
            "%-5s %-14s %-7s: %6zu vertices, distance mean %.4f max %.3f mm, volume %+.2f %%, angles 40-80 %.1f %%, "
            "<25: %.3f %%, min %.1f deg, conformity mean %.4f mm%s\n",
            rows ? "rows" : "bands", name.c_str(), oblique ? "oblique" : "", m.positions.size(), a.mean, a.max,
            100 * a.volume_error, 100 * a.angles.share_40_80, 100 * a.angles.share_below_25, a.angles.min_deg,
            a.conformity_mean, rep.warnings.empty() ? "" : (" [" + rep.warnings[0] + "]").c_str());
        SCOPED_TRACE(name + (oblique ? " oblique" : "") + (rows ? " rows" : " bands"));
        EXPECT_TRUE(rep.closed);
        EXPECT_FALSE(rep.self_intersects);
        EXPECT_GT(rep.volume, 0.0);
        // Measured figures (docs/algorithms/one_frame_surface.md) with some headroom: regressions fail.
        if (name == "ellipsoid" || name.rfind("left-heart", 0) == 0) {
          EXPECT_LT(std::abs(a.volume_error), 0.01);  // issue 3: volume within 1 %
          EXPECT_LT(a.mean, 0.025);
          EXPECT_LT(a.max, 0.5);  // issue 3: max over the slab ≤ 0.5 mm (the saddle of the left heart included)
        } else if (name == "bifurcation") {
          EXPECT_LT(std::abs(a.volume_error), 0.02);  // issue 4's 2 % (filled caps and end bands: −1.3 %)
          EXPECT_LT(a.mean, 0.1);
        } else {  // the torus: its ring caps' coarser interior faired with scale-aware terms
          EXPECT_LT(std::abs(a.volume_error), 0.01);
          EXPECT_LT(a.mean, 0.03);
        }
        if (!oblique) {
          EXPECT_LT(a.conformity_mean, 0.01);  // against the original input contours
        }
        // No sliver anywhere, branchings and saddles included (issue 3: none below 10°, ≤ 0.01 % below 25°).
        EXPECT_GT(a.angles.min_deg, 25.0);
        EXPECT_LE(a.angles.share_below_25, 0.0001);
        EXPECT_GT(a.angles.share_40_80, 0.9);  // issue 3: at least 90 % of the angles in 40–80°
      }
  }
}

// SurfaceOptions::rows (the default): interpolated rows instead of remeshing the bands, then the faired
// surface remeshed (rows_final_remesh_iterations). Closed and well shaped (issue 3: at least 90 % of the angles
// in 40–80°; the left heart's ES frame keeps 91.8 % with CGAL's, 92.2 % with ours) with either remesher, on the phantoms and on biv-me's
// coarse, irregular real contours (17.7 mm slices), where the faired rows alone kept 68.7 % of their angles
// in 40–80° (rows_final_remesh_iterations = 0: the 4D run's later-frame targets).
TEST(ReconstructPhantoms, RowsPathIsClosedAndWellShaped) {
  auto check = [](const c4d::Sequence& seq, const std::string& name, long euler) {
    for (const c4d::RemeshEngine engine : {c4d::RemeshEngine::Cgal, c4d::RemeshEngine::Fast}) {
      c4d::detail::SurfaceParams so = defaults();
      so.rows = true;
      so.rows_remesher = engine;
      c4d::SurfaceReport rep;
      const auto m = frame_of(seq, 0, so, &rep);
      const Angles a = angles(m);
      SCOPED_TRACE(name + (engine == c4d::RemeshEngine::Fast ? " fast remesher" : " cgal"));
      std::printf("%-14s rows, %s: %6zu vertices, angles 40-80 %.1f %%, <25: %.4f %%, min %.1f deg\n", name.c_str(),
                  engine == c4d::RemeshEngine::Fast ? "fast" : "cgal", m.positions.size(), 100 * a.share_40_80,
                  100 * a.share_below_25, a.min_deg);
      EXPECT_TRUE(rep.closed);
      EXPECT_FALSE(rep.self_intersects);
      EXPECT_EQ(rep.euler, euler);
      EXPECT_GT(a.share_40_80, 0.90);
      EXPECT_LE(a.share_below_25, 0.0001);
      EXPECT_GT(a.min_deg, 20.0);
    }
  };
  for (const std::string name : {"left-heart-es", "torus", "bifurcation"})
    check(c4d::make_phantom(name, {}).contours, name, name == "torus" ? 0 : 2);
  const std::string dir = std::string(C4D_DATA_DIR) + "/bivme-patient1/guidepoints";
  ASSERT_TRUE(std::filesystem::is_directory(dir))
      << "real data folder missing: " << dir << " (see ../shared/data/README.md)";
  check(c4d::read_contours(dir).sequence, "biv-me frame 0", 2);
}

}  // namespace

// The paper's tiling (constrained Delaunay of the projected slices with CAT lifting points), wired
// in as SurfaceOptions::tiling: every phantom closed, outward, free of self-intersections, with the
// right genus, and no slice pair falling back to the band tiling.
TEST(ReconstructPhantoms, DelaunayTilingGivesClosedSurfaces) {
  for (const std::string name : {"ellipsoid", "left-heart-ed", "left-heart-es", "torus", "bifurcation"})
    for (bool oblique : {false, true}) {
      c4d::PhantomOptions po;
      po.oblique = oblique;
      const c4d::Phantom ph = c4d::make_phantom(name, po);
      c4d::SurfaceOptions so;
      so.tiling = c4d::Tiling::Delaunay;
      so.rows = false;  // every band by the paper's tiling, not only the branchings
      c4d::SurfaceReport rep;
      const auto m = frame_of(ph.contours, 0, so, &rep);
      const Accuracy a = accuracy(ph, m, false);
      SCOPED_TRACE(name + (oblique ? " oblique" : ""));
      std::printf(
          "%-14s %-7s delaunay: %6zu vertices, distance mean %.4f max %.3f mm, volume %+.2f %%, angles 40-80 "
          "%.1f %%, <25: %.3f %%, min %.1f deg\n",
          name.c_str(), oblique ? "oblique" : "", m.positions.size(), a.mean, a.max, 100 * a.volume_error,
          100 * a.angles.share_40_80, 100 * a.angles.share_below_25, a.angles.min_deg);
      EXPECT_TRUE(rep.closed);
      EXPECT_FALSE(rep.self_intersects);
      EXPECT_EQ(rep.euler, name == "torus" ? 0 : 2);
      for (const std::string& w : rep.warnings)
        EXPECT_EQ(w.find("Delaunay tiling not possible"), std::string::npos) << w;
      EXPECT_LT(std::abs(a.volume_error), name == "bifurcation" ? 0.05 : 0.01);
      EXPECT_GT(a.angles.min_deg, 15.0);
      EXPECT_GT(a.angles.share_40_80, 0.85);
    }
}
