// Tests of the analytic phantoms: closed oriented 2-manifold truths, exact sections (every contour
// vertex on the surface and its plane, every contour edge a truth edge), volumes against the
// analytic ones, the truth close to the analytic surface both ways, invariance under --oblique.
#include "contour4d/phantoms/phantom.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <random>
#include <set>
#include <unordered_map>

#include <sys/wait.h>
#include <unistd.h>

#include "contour4d/core/contour.h"
#include "contour4d/core/errors.h"
#include "contour4d/core/plane.h"
#include "contour4d/io/images.h"
#include "contour4d/phantoms/rasterize.h"

namespace c4d {
namespace {

using Edge = std::pair<std::uint32_t, std::uint32_t>;

//! Directed edge -> count.
std::map<Edge, int> directed_edges(const TriangleMesh& m) {
  std::map<Edge, int> e;
  for (const Triangle& t : m.triangles)
    for (int k = 0; k < 3; ++k) ++e[{t[k], t[(k + 1) % 3]}];
  return e;
}

//! Closed, consistently oriented, edge- and vertex-manifold, no degenerate triangle; returns
//! the Euler characteristic.
int check_closed_manifold(const TriangleMesh& m, const std::string& what) {
  const auto e = directed_edges(m);
  for (const auto& [edge, count] : e) {
    EXPECT_EQ(count, 1) << what << ": directed edge used twice";
    const auto it = e.find({edge.second, edge.first});
    EXPECT_TRUE(it != e.end() && it->second == 1) << what << ": edge without an opposite twin";
    if (count != 1 || it == e.end()) return -1000;
  }
  // Vertex links: the opposite edges of the triangles around a vertex form one cycle.
  std::vector<std::unordered_map<std::uint32_t, std::uint32_t>> link(m.positions.size());
  for (const Triangle& t : m.triangles)
    for (int k = 0; k < 3; ++k) link[t[k]][t[(k + 1) % 3]] = t[(k + 2) % 3];
  for (std::size_t v = 0; v < link.size(); ++v) {
    EXPECT_FALSE(link[v].empty()) << what << ": isolated vertex " << v;
    if (link[v].empty()) return -1000;
    std::size_t steps = 0;
    const std::uint32_t start = link[v].begin()->first;
    std::uint32_t cur = start;
    do {
      cur = link[v].at(cur);
      ++steps;
    } while (cur != start && steps <= link[v].size());
    EXPECT_EQ(steps, link[v].size()) << what << ": vertex " << v << " is not manifold";
    if (steps != link[v].size()) return -1000;
  }
  double max_len = 0;
  for (const Triangle& t : m.triangles)
    for (int k = 0; k < 3; ++k) max_len = std::max(max_len, distance(m.positions[t[k]], m.positions[t[(k + 1) % 3]]));
  for (const Triangle& t : m.triangles) {
    const Vec3 a = m.positions[t[0]], b = m.positions[t[1]], c = m.positions[t[2]];
    EXPECT_GT(norm(cross(b - a, c - a)), 1e-14 * max_len * max_len) << what << ": degenerate triangle";
  }
  EXPECT_GT(signed_volume(m), 0.0) << what << ": not outward";
  const auto V = static_cast<long>(m.positions.size()), E = static_cast<long>(e.size() / 2),
             F = static_cast<long>(m.triangles.size());
  return static_cast<int>(V - E + F);
}

//! Every contour edge is an edge of the truth mesh (so conformity is exact), and every vertex lies
//! on its slice plane and on the analytic surface.
void check_sections(const Phantom& ph) {
  for (std::size_t f = 0; f < ph.truth.size(); ++f) {
    const TriangleMesh& m = ph.truth[f];
    std::map<std::tuple<double, double, double>, std::uint32_t> index;
    for (std::uint32_t i = 0; i < m.positions.size(); ++i)
      index[{m.positions[i].x, m.positions[i].y, m.positions[i].z}] = i;
    const auto e = directed_edges(m);
    for (const Slice& s : ph.contours.frames[f].slices) {
      const Plane pl = slice_plane(ph.contours, s);
      for (const Contour& c : s.contours) {
        ASSERT_GE(c.points.size(), 8u);
        for (std::size_t k = 0; k < c.points.size(); ++k) {
          const Vec3 p = c.points[k], q = c.points[(k + 1) % c.points.size()];
          EXPECT_NEAR(signed_distance(pl, p), 0.0, 1e-9) << ph.name << " frame " << f << " slice " << s.id;
          EXPECT_NEAR(analytic_distance(ph, static_cast<int>(f), p), 0.0, 1e-6) << ph.name << " slice " << s.id;
          const auto ip = index.find({p.x, p.y, p.z}), iq = index.find({q.x, q.y, q.z});
          ASSERT_TRUE(ip != index.end() && iq != index.end()) << ph.name << ": contour vertex not a truth vertex";
          EXPECT_TRUE(e.count({ip->second, iq->second}) == 1) << ph.name << ": contour edge not a truth edge";
        }
      }
    }
  }
}

//! Closest distance from p to triangle abc (Ericson, Real-Time Collision Detection 5.1.5).
double point_triangle_distance(Vec3 p, Vec3 a, Vec3 b, Vec3 c) {
  const Vec3 ab = b - a, ac = c - a, ap = p - a;
  const double d1 = dot(ab, ap), d2 = dot(ac, ap);
  if (d1 <= 0 && d2 <= 0) return distance(p, a);
  const Vec3 bp = p - b;
  const double d3 = dot(ab, bp), d4 = dot(ac, bp);
  if (d3 >= 0 && d4 <= d3) return distance(p, b);
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return distance(p, a + (d1 / (d1 - d3)) * ab);
  const Vec3 cp = p - c;
  const double d5 = dot(ab, cp), d6 = dot(ac, cp);
  if (d6 >= 0 && d5 <= d6) return distance(p, c);
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return distance(p, a + (d2 / (d2 - d6)) * ac);
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0)
    return distance(p, b + ((d4 - d3) / ((d4 - d3) + (d5 - d6))) * (c - b));
  const double denom = 1 / (va + vb + vc);
  return distance(p, a + ab * (vb * denom) + ac * (vc * denom));
}

//! Distance from points to a mesh through a uniform grid of triangle boxes (for distances below
//! one cell).
struct MeshDistance {
  const TriangleMesh& m;
  double cell;
  std::map<std::tuple<long, long, long>, std::vector<std::uint32_t>> grid;
  MeshDistance(const TriangleMesh& mesh, double cell_mm) : m(mesh), cell(cell_mm) {
    for (std::uint32_t t = 0; t < m.triangles.size(); ++t) {
      Vec3 lo = m.positions[m.triangles[t][0]], hi = lo;
      for (int k = 1; k < 3; ++k) {
        const Vec3 p = m.positions[m.triangles[t][k]];
        for (std::size_t i = 0; i < 3; ++i) lo[i] = std::min(lo[i], p[i]), hi[i] = std::max(hi[i], p[i]);
      }
      for (long x = key(lo.x); x <= key(hi.x); ++x)
        for (long y = key(lo.y); y <= key(hi.y); ++y)
          for (long z = key(lo.z); z <= key(hi.z); ++z) grid[{x, y, z}].push_back(t);
    }
  }
  long key(double v) const { return static_cast<long>(std::floor(v / cell)); }
  double operator()(Vec3 p) const {
    double best = std::numeric_limits<double>::infinity();
    for (long x = key(p.x) - 1; x <= key(p.x) + 1; ++x)
      for (long y = key(p.y) - 1; y <= key(p.y) + 1; ++y)
        for (long z = key(p.z) - 1; z <= key(p.z) + 1; ++z) {
          const auto it = grid.find({x, y, z});
          if (it == grid.end()) continue;
          for (std::uint32_t t : it->second) {
            const Triangle& tr = m.triangles[t];
            best =
                std::min(best, point_triangle_distance(p, m.positions[tr[0]], m.positions[tr[1]], m.positions[tr[2]]));
          }
        }
    return best;
  }
};

std::size_t contour_count(const Frame& f) {
  std::size_t n = 0;
  for (const Slice& s : f.slices) n += s.contours.size();
  return n;
}

TEST(Phantoms, NamesAndUnknown) {
  const auto names = phantom_names();
  for (const char* n :
       {"ellipsoid", "bifurcation", "torus", "left-heart", "left-heart-cycle", "left-heart-ed", "left-heart-es"})
    EXPECT_NE(std::find(names.begin(), names.end(), n), names.end()) << n;
  try {
    make_phantom("no-such-shape");
    FAIL() << "expected InvalidInput";
  } catch (const InvalidInput& e) {
    EXPECT_EQ(e.code(), ErrorCode::Usage);
    EXPECT_NE(std::string(e.hint()).find("left-heart"), std::string::npos);
  }
  PhantomOptions bad;
  bad.spacing = 0;
  EXPECT_THROW(make_phantom("torus", bad), InvalidInput);
  bad = {};
  bad.truth_edge = 0;
  EXPECT_THROW(make_phantom("torus", bad), InvalidInput);
}

//! Topology, sections and volume of every phantom at a coarse truth (fast under sanitizers).
TEST(Phantoms, ClosedManifoldExactSections) {
  for (const std::string& name : phantom_names()) {
    PhantomOptions o;
    o.truth_edge = 1.0;
    o.frames = 4;
    const Phantom ph = make_phantom(name, o);
    ASSERT_EQ(ph.truth.size(), ph.contours.frames.size()) << name;
    ASSERT_EQ(ph.true_volume_mm3.size(), ph.truth.size()) << name;
    for (std::size_t f = 0; f < ph.truth.size(); ++f) {
      const int chi = check_closed_manifold(ph.truth[f], name + " frame " + std::to_string(f));
      EXPECT_EQ(chi, name == "torus" ? 0 : 2) << name << " frame " << f;
      EXPECT_NEAR(signed_volume(ph.truth[f]) / ph.true_volume_mm3[f], 1.0, 0.01) << name << " frame " << f;
    }
    check_sections(ph);
    EXPECT_LE(ph.slab_min, ph.contours.frames[0].slices.front().offset + 1e-9);
    EXPECT_GE(ph.slab_max, ph.contours.frames[0].slices.back().offset - 1e-9);
  }
}

TEST(Phantoms, VolumesAtDefaultResolution) {
  for (const std::string name : {"ellipsoid", "torus", "bifurcation", "left-heart-ed", "left-heart-es"}) {
    PhantomOptions o;
    o.frames = 2;
    const Phantom ph = make_phantom(name, o);
    for (std::size_t f = 0; f < ph.truth.size(); ++f) {
      EXPECT_NEAR(signed_volume(ph.truth[f]) / ph.true_volume_mm3[f], 1.0, 0.005) << name << " frame " << f;
      EXPECT_LT(ph.truth[f].triangles.size(), 300000u) << name;
    }
  }
}

TEST(Phantoms, AnalyticVolumes) {
  PhantomOptions o;
  o.frames = 2;  // ED and ES
  const Phantom e = make_phantom("ellipsoid", o);
  EXPECT_NEAR(e.true_volume_mm3[0], 4.0 / 3.0 * M_PI * 25 * 25 * 40, 1e-6);
  EXPECT_NEAR(e.true_volume_mm3[1], 4.0 / 3.0 * M_PI * 19 * 19 * 30, 1e-6);
  const Phantom t = make_phantom("torus", o);
  EXPECT_NEAR(t.true_volume_mm3[0], 2 * M_PI * M_PI * 30 * 12 * 12, 1e-6);
}

//! The truth mesh is close to the analytic surface both ways: random points on it are on the
//! surface, and exact surface points (vertices of a finer truth) are on it.
TEST(Phantoms, TruthApproximatesAnalyticSurface) {
  for (const std::string name : {"ellipsoid", "torus", "left-heart-ed", "left-heart-es", "bifurcation"}) {
    PhantomOptions o;
    o.frames = 2;
    const Phantom ph = make_phantom(name, o);
    o.truth_edge = 0.3;
    const Phantom fine = make_phantom(name, o);
    const TriangleMesh& m = ph.truth[0];
    std::mt19937 rng(42);
    std::uniform_real_distribution<double> u(0, 1);
    double worst = 0;
    for (int i = 0; i < 3000; ++i) {
      const Triangle& t = m.triangles[rng() % m.triangles.size()];
      double a = u(rng), b = u(rng);
      if (a + b > 1) a = 1 - a, b = 1 - b;
      const Vec3 p =
          m.positions[t[0]] + a * (m.positions[t[1]] - m.positions[t[0]]) + b * (m.positions[t[2]] - m.positions[t[0]]);
      worst = std::max(worst, std::abs(analytic_distance(ph, 0, p)));
    }
    EXPECT_LT(worst, 0.05) << name << ": truth -> analytic";
    const MeshDistance dist(m, 2.0);
    double worst_back = 0;
    for (std::size_t i = 0; i < fine.truth[0].positions.size(); i += 37)
      worst_back = std::max(worst_back, dist(fine.truth[0].positions[i]));
    EXPECT_LT(worst_back, 0.05) << name << ": analytic -> truth";
  }
}

TEST(Phantoms, ObliqueIsARigidMotion) {
  for (const std::string name : {"left-heart", "torus", "ellipsoid"}) {
    PhantomOptions o;
    o.truth_edge = 1.5;
    o.frames = 3;
    const Phantom a = make_phantom(name, o);
    o.oblique = true;
    const Phantom b = make_phantom(name, o);
    ASSERT_EQ(a.truth.size(), b.truth.size());
    for (std::size_t f = 0; f < a.truth.size(); ++f) {
      EXPECT_NEAR(signed_volume(b.truth[f]), signed_volume(a.truth[f]), 1e-6 * signed_volume(a.truth[f]));
      EXPECT_NEAR(a.true_volume_mm3[f], b.true_volume_mm3[f], 1e-6 * a.true_volume_mm3[f]);
      EXPECT_EQ(contour_count(a.contours.frames[f]), contour_count(b.contours.frames[f]));
      ASSERT_EQ(a.contours.frames[f].slices.size(), b.contours.frames[f].slices.size());
      for (std::size_t s = 0; s < a.contours.frames[f].slices.size(); ++s)
        EXPECT_NEAR(a.contours.frames[f].slices[s].offset - a.slab_min,
                    b.contours.frames[f].slices[s].offset - b.slab_min, 1e-9);
    }
    EXPECT_NEAR(a.slab_max - a.slab_min, b.slab_max - b.slab_min, 1e-9);
    check_sections(b);
  }
}

TEST(Phantoms, FramesAndSlices) {
  const Phantom lh = make_phantom("left-heart");
  ASSERT_EQ(lh.contours.frames.size(), 3u);
  EXPECT_EQ(lh.shape_parameters[0], lh.shape_parameters[2]);
  // Slices y = 32.5 - 5k along +y, none through the saddles at y = 0 and -5.
  EXPECT_NEAR(lh.contours.normal.y, 1.0, 1e-12);
  EXPECT_NEAR(lh.slab_max, 32.5, 1e-9);
  for (const Frame& f : lh.contours.frames)
    for (const Slice& s : f.slices) EXPECT_NEAR(std::remainder(s.offset - 2.5, 5.0), 0.0, 1e-9);
  // Above the saddle two contours per slice, below one.
  for (const Slice& s : lh.contours.frames[0].slices) EXPECT_EQ(s.contours.size(), s.offset > 0 ? 2u : 1u) << s.offset;
  for (const Slice& s : lh.contours.frames[1].slices) EXPECT_EQ(s.contours.size(), s.offset > -5 ? 2u : 1u) << s.offset;
  EXPECT_EQ(make_phantom("left-heart-ed").contours.frames.size(), 1u);
  EXPECT_EQ(make_phantom("left-heart-cycle").contours.frames.size(), 20u);
  PhantomOptions o;
  o.frames = 7;
  o.truth_edge = 2;
  EXPECT_EQ(make_phantom("ellipsoid", o).contours.frames.size(), 7u);
  // The torus gives rings with holes: two nested contours on every slice.
  const Phantom torus = make_phantom("torus", o);
  for (const Slice& s : torus.contours.frames[0].slices) EXPECT_EQ(s.contours.size(), 2u);
  // The ellipsoid loses its end slices as it shrinks.
  const Phantom e = make_phantom("ellipsoid", o);
  EXPECT_GT(e.contours.frames[0].slices.size(), e.contours.frames[3].slices.size());
}

TEST(Phantoms, SliceThroughSaddleGivesTwoTouchingLoops) {
  PhantomOptions o;
  o.offset = 0.0;  // a plane through the ED saddle
  o.truth_edge = 1.0;
  const Phantom ph = make_phantom("left-heart-ed", o);
  bool found = false;
  for (const Slice& s : ph.contours.frames[0].slices)
    if (std::abs(s.offset) < 1e-9) found = s.contours.size() == 2;
  EXPECT_TRUE(found);
  EXPECT_EQ(check_closed_manifold(ph.truth[0], "saddle slice"), 2);
  check_sections(ph);
}

TEST(Phantoms, Deterministic) {
  PhantomOptions o;
  o.truth_edge = 1.0;
  const Phantom a = make_phantom("left-heart", o), b = make_phantom("left-heart", o);
  for (std::size_t f = 0; f < a.truth.size(); ++f) {
    ASSERT_EQ(a.truth[f].positions.size(), b.truth[f].positions.size());
    for (std::size_t i = 0; i < a.truth[f].positions.size(); ++i)
      ASSERT_TRUE(a.truth[f].positions[i] == b.truth[f].positions[i]);
    EXPECT_EQ(a.truth[f].triangles, b.truth[f].triangles);
  }
}

TEST(Phantoms, Cli) {
  const auto dir = std::filesystem::temp_directory_path() / ("c4d_phantom_test_" + std::to_string(::getpid()));
  std::filesystem::remove_all(dir);
  const std::string cmd = std::string(C4D_CLI) + " phantom left-heart-es -o " + dir.string() + " > /dev/null";
  ASSERT_EQ(std::system(cmd.c_str()), 0) << cmd;
  for (const char* f : {"contours.json", "truth/mesh.pvd", "truth/frames/frame_000.vtp", "truth/frames/frame_000.obj",
                        "truth/truth.json"})
    EXPECT_TRUE(std::filesystem::exists(dir / f)) << f;
  const std::string list = std::string(C4D_CLI) + " phantom --list > /dev/null";
  EXPECT_EQ(std::system(list.c_str()), 0);
  const std::string bad = std::string(C4D_CLI) + " phantom nope -o " + dir.string() + " 2> /dev/null";
  EXPECT_EQ(WEXITSTATUS(std::system(bad.c_str())), static_cast<int>(ErrorCode::Usage));
  std::filesystem::remove_all(dir);
}

// The mask of a phantom: voxel k is slice id k (label pixels exactly on the slices that have
// contours), the direction matrix is a rotation, and the labelled area of each slice matches the
// exact section's area (a point-sampled mask's area error is a perimeter × a fraction of a pixel).
TEST(Rasterize, SlicesAreThePhantomsSlicesAndAreasMatch) {
  for (const char* name : {"left-heart-ed", "torus", "ellipsoid"}) {
    SCOPED_TRACE(name);
    PhantomOptions po;
    po.oblique = true;
    po.spacing = 8;
    po.frames = 2;
    const Phantom ph = make_phantom(name, po);
    const std::vector<LabelVolume> vols = rasterize_phantom(ph);
    ASSERT_EQ(vols.size(), ph.truth.size());
    const LabelVolume& v = vols[0];
    EXPECT_NEAR(v.spacing[2], 8.0, 1e-9);
    const auto& D = v.direction;
    const Vec3 ci{D[0], D[3], D[6]}, cj{D[1], D[4], D[7]}, ck{D[2], D[5], D[8]};
    EXPECT_NEAR(dot(cross(ci, cj), ck), 1.0, 1e-12);
    EXPECT_NEAR(std::abs(dot(ck, ph.contours.normal)), 1.0, 1e-12);
    const std::size_t plane = static_cast<std::size_t>(v.dims[0]) * static_cast<std::size_t>(v.dims[1]);
    for (int k = 0; k < v.dims[2]; ++k) {
      std::size_t count = 0;
      for (std::size_t i = 0; i < plane; ++i) count += v.labels[plane * static_cast<std::size_t>(k) + i] == 1;
      double area = 0, perimeter = 0;
      for (const Slice& s : ph.contours.frames[0].slices)
        if (s.id == k) {
          const Plane pl = make_plane(s.contours[0].points[0], ph.contours.normal);
          std::vector<std::vector<Vec2>> polys;
          for (const Contour& c : s.contours) {
            polys.emplace_back();
            for (const Vec3& p : c.points) polys.back().push_back(to_plane(pl, p));
            for (std::size_t i = 0; i < c.points.size(); ++i)
              perimeter += norm(c.points[(i + 1) % c.points.size()] - c.points[i]);
          }
          // A contour inside another is a hole (the torus): its area counts negative.
          for (std::size_t a = 0; a < polys.size(); ++a) {
            int depth = 0;
            for (std::size_t b = 0; b < polys.size(); ++b) {
              if (a == b) continue;
              bool in = false;
              const Vec2 q = polys[a][0];
              const auto& P = polys[b];
              for (std::size_t i = 0, j = P.size() - 1; i < P.size(); j = i++)
                if ((P[i].y > q.y) != (P[j].y > q.y) &&
                    q.x < (P[j].x - P[i].x) * (q.y - P[i].y) / (P[j].y - P[i].y) + P[i].x)
                  in = !in;
              depth += in;
            }
            area += (depth % 2 ? -1.0 : 1.0) * std::abs(signed_area(polys[a]));
          }
        }
      EXPECT_NEAR(static_cast<double>(count), area, 0.25 * perimeter + 2) << "slice " << k;
      // The slice plane of voxel k passes through the contours of slice id k.
      for (const Slice& s : ph.contours.frames[0].slices)
        if (s.id == k) {
          const Vec3 o{v.origin[0], v.origin[1], v.origin[2]};
          const Vec3 p = s.contours[0].points[0] - (o + (k * v.spacing[2]) * ck);
          EXPECT_NEAR(dot(p, ck), 0.0, 1e-6) << "slice " << k;
        }
    }
  }
}

TEST(Rasterize, DeterministicAndValidated) {
  PhantomOptions po;
  po.frames = 3;
  const Phantom ph = make_phantom("ellipsoid", po);
  EXPECT_EQ(rasterize_phantom(ph)[2].labels, rasterize_phantom(ph)[2].labels);
  RasterizeOptions bad;
  bad.pixel_x = 0;
  EXPECT_THROW(rasterize_phantom(ph, bad), InvalidInput);
  bad = {};
  bad.label = 0;
  EXPECT_THROW(rasterize_phantom(ph, bad), InvalidInput);
}

TEST(Rasterize, CliWritesA4DMask) {
  const auto dir = std::filesystem::temp_directory_path() / ("c4d_phantom_mask_" + std::to_string(::getpid()));
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  const std::string cmd = std::string(C4D_CLI) + " phantom ellipsoid --frames 4 --oblique -o " + (dir / "ph").string() +
                          " --mask " + (dir / "m.nii.gz").string() + " --mask-spacing 1.2,1,6 > /dev/null";
  ASSERT_EQ(std::system(cmd.c_str()), 0) << cmd;
  const std::vector<LabelVolume> m = read_label_image(dir / "m.nii.gz");
  ASSERT_EQ(m.size(), 4u);
  EXPECT_NEAR(m[0].spacing[0], 1.2, 1e-6);
  EXPECT_NEAR(m[0].spacing[2], 6.0, 1e-6);
  EXPECT_TRUE(std::filesystem::exists(dir / "ph" / "truth" / "mesh.pvd"));
  // Mask only; a bad extension is a usage error and writes nothing.
  const std::string only = std::string(C4D_CLI) + " phantom torus --mask " + (dir / "t.nrrd").string() + " > /dev/null";
  EXPECT_EQ(std::system(only.c_str()), 0);
  EXPECT_EQ(read_label_image(dir / "t.nrrd").size(), 10u);
  const std::string bad = std::string(C4D_CLI) + " phantom torus --mask " + (dir / "t.png").string() + " 2> /dev/null";
  EXPECT_EQ(WEXITSTATUS(std::system(bad.c_str())), static_cast<int>(ErrorCode::Usage));
  EXPECT_FALSE(std::filesystem::exists(dir / "t.png"));
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace c4d
